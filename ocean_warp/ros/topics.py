"""What every ROS topic of the simulated E-Boats holds: the one home of their names, types, frames and contents,
for the MCAP logs (:mod:`ocean_warp.envs.ros.mcap_log`) and for a ROS node. No ROS client library is imported: each
message is a plain dict of its ROS 2 fields (``header.stamp.sec`` / ``nanosec``, lowercase ``k`` of CameraInfo,
...), built from a :class:`~ocean_warp.envs.SailingEnv` on the host.

Namespaces. One boat sails under the seed twin's ``/eboat``; several under ``/eboat_0``, ``/eboat_1``, ...
(boat i in environment i), optionally below a prefix that tells runs apart (``ocean-warp eval`` records each
controller's runs under ``/<controller>``: ``/autopilot/eboat_3``). A boat's tf frames carry its namespace
without the leading slash (``eboat_3/base_link``, ``autopilot/eboat/base_link``), except the seed's single
``/eboat``, whose frames are the plain ``base_link``, ``odom``, ... of a one-robot tf tree.

Per boat, under its namespace (rates: one message each time the state is taken, once per decision in the
logs; the seed's own topics keep its ROS 1 names and its degrees, everything else is SI per REP 103):

==================================  ===============================  ==============================================
topic                               type                             content
==================================  ===============================  ==============================================
mission_control/observations        std_msgs/msg/Float32MultiArray   the seed's 9 values (:data:`SEED_OBSERVATION`)
control_interface/sail              std_msgs/msg/Float32             sheet command: largest boom angle [deg], 0-90
control_interface/rudder            std_msgs/msg/Float32             rudder command [deg], +-60, positive to port
control_interface/propulsion        std_msgs/msg/Int16               propeller level commanded, -5 ... 5
atmosferic_control/wind             geometry_msgs/msg/Point          true wind velocity, world ENU [m/s]
lidar/scan                          sensor_msgs/msg/LaserScan        a single-channel lidar's scan (with a lidar)
gps/fix                             sensor_msgs/msg/NavSatFix        the GNSS reading as WGS 84 (``geodesy``)
imu/data                            sensor_msgs/msg/Imu              attitude (truth), gyro and accelerometer
                                                                     readings (noisy, biased), body FLU
wind/true                           geometry_msgs/msg/Vector3Stamped true wind velocity in ``map`` [m/s]
wind/apparent                       geometry_msgs/msg/Vector3Stamped the vane and anemometer reading: apparent
                                                                     wind velocity in ``base_link`` [m/s]
current                             geometry_msgs/msg/Vector3Stamped the water's current at the surface where
                                                                     the boat sails (tide included) in ``map``
                                                                     [m/s]; zero in still water
camera/image_raw                    sensor_msgs/msg/Image            RGB, "rgb8" (with an RGB camera)
camera/camera_info                  sensor_msgs/msg/CameraInfo       its pinhole model
camera/depth/image_raw              sensor_msgs/msg/Image            depth along the optical axis [m], "32FC1"
camera/depth/camera_info            sensor_msgs/msg/CameraInfo       the same pinhole model
==================================  ===============================  ==============================================

The ROS node (``ocean-warp ros``, :mod:`ocean_warp.envs.ros.node`) also publishes, per boat, ``mission_control/episode``
(std_msgs/msg/Float32MultiArray, :data:`EPISODE_END`: one message each time an episode ends, with how it ended;
in the node's ``--record`` log too, :data:`NODE_TOPICS`).

Shared: ``/tf`` (tf2_msgs/msg/TFMessage: every boat's ``odom`` -> ``base_link``, its true pose), ``/tf_static``
(``map`` -> each boat's ``odom``, the identity: the simulator's truth has no drift, REP 105; ``base_link`` ->
``lidar_link`` and -> ``camera_link`` at the sensors' mounts, ``camera_link`` -> ``camera_optical_frame``) and
``/clock`` (rosgraph_msgs/msg/Clock: the simulated time, which stamps every message; the node publishes it
between decisions too, ``--clock-hz``). The time never runs back: the node's reset service restarts the boats,
and the clock goes on from one decision after the last time published (``time_offset_ns`` of :func:`snapshot`).

Frames (REP 103): ``map`` and ``odom`` are the simulator's world frame, ENU (x east, y north, z up; still water
at z = 0), ``base_link`` the boat's body frame, FLU (x forward, y to port, z up; the simulator's own), the
lidar's ``lidar_link`` its sensor frame (beams' azimuths counter-clockwise from its x), the camera's
``camera_link`` its link frame (x along the view) and ``camera_optical_frame`` the image's (z forward, x right,
y down). Where the values come from: the seed's observations, the seed's wind, true wind and tf from the
simulator's truth (as the seed's task sees it, ``envs/tasks/observation_blocks.seed_columns``), the current from the
simulator's truth too (no sensor measures it); the GNSS fix, the IMU's
rates and accelerations and the apparent wind from the noisy sensor readings (``ocean_warp.sensors``, held
between refreshes at the sensors' rates), with their configured standard deviations (times the boat's noise
factor) as covariances; the IMU's orientation is the true attitude (the simulated IMU has no attitude filter;
its covariance is left 0, "unknown" to ROS).
"""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np

from ocean_warp.fleet import END_REASONS, episode_end
from ocean_warp.frames import quaternion_from_roll_pitch_yaw, roll_pitch_yaw

from .geodesy import GUANABARA_BAY, GeodeticDatum, enu_to_geodetic

__all__ = [
    "GLOBAL_TOPICS",
    "bus_name",
    "SEED_NAMESPACE", "SEED_OBSERVATION", "BOAT_TOPICS", "TF", "TF_STATIC", "CLOCK", "MAP_FRAME", "Message",
    "BoatSnapshot", "boat_namespace", "frame_id", "snapshot", "joint_states", "stamp", "seed_observation_values",
    "EPISODE_TOPIC", "NODE_TOPICS", "EPISODE_END", "episode_messages", "episode_end_reason",
    "state_messages", "command_messages", "lidar_messages", "camera_messages", "static_messages", "clock_message",
    "env_lidar", "TYPES", "FLOAT32", "INT16", "FLOAT32_MULTI_ARRAY", "POINT", "VECTOR3_STAMPED", "NAV_SAT_FIX", "IMU",
    "LASER_SCAN", "IMAGE", "CAMERA_INFO", "TF_MESSAGE", "CLOCK_TYPE",
]

# --- names ---------------------------------------------------------------------------------------------
SEED_NAMESPACE = "/eboat"
"""The seed twin's namespace: a single boat's."""
MAP_FRAME = "map"
"""The world frame (ENU), shared by every boat."""

FLOAT32 = "std_msgs/msg/Float32"
INT16 = "std_msgs/msg/Int16"
FLOAT32_MULTI_ARRAY = "std_msgs/msg/Float32MultiArray"
POINT = "geometry_msgs/msg/Point"
VECTOR3_STAMPED = "geometry_msgs/msg/Vector3Stamped"
NAV_SAT_FIX = "sensor_msgs/msg/NavSatFix"
IMU = "sensor_msgs/msg/Imu"
LASER_SCAN = "sensor_msgs/msg/LaserScan"
IMAGE = "sensor_msgs/msg/Image"
CAMERA_INFO = "sensor_msgs/msg/CameraInfo"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"
CLOCK_TYPE = "rosgraph_msgs/msg/Clock"
TYPES = (FLOAT32, INT16, FLOAT32_MULTI_ARRAY, POINT, VECTOR3_STAMPED, NAV_SAT_FIX, IMU, LASER_SCAN, IMAGE,
         CAMERA_INFO, TF_MESSAGE, CLOCK_TYPE)
"""Every message type published (full ROS 2 names; definitions in ``message_definitions``)."""

BOAT_TOPICS = {
    "mission_control/observations": FLOAT32_MULTI_ARRAY,
    "control_interface/sail": FLOAT32,
    "control_interface/rudder": FLOAT32,
    "control_interface/propulsion": INT16,
    "atmosferic_control/wind": POINT,
    "lidar/scan": LASER_SCAN,
    "gps/fix": NAV_SAT_FIX,
    "imu/data": IMU,
    "wind/true": VECTOR3_STAMPED,
    "wind/apparent": VECTOR3_STAMPED,
    "current": VECTOR3_STAMPED,
    "camera/image_raw": IMAGE,
    "camera/camera_info": CAMERA_INFO,
    "camera/depth/image_raw": IMAGE,
    "camera/depth/camera_info": CAMERA_INFO,
}
"""Each boat's topics, relative to its namespace, and their types (the module's table says what they hold)."""
TF, TF_STATIC, CLOCK = "/tf", "/tf_static", "/clock"
GLOBAL_TOPICS = (TF, TF_STATIC, CLOCK)
"""Topics outside every namespace; a boat's topics are named relative to the node's namespace."""


def bus_name(topic: str) -> str:
    """The name a ROS publisher or subscriber gets for ``topic``: a global topic absolute, a boat's relative
    to the node's namespace (``/eboat/gps/fix`` -> ``eboat/gps/fix``, so ``__ns`` moves it)."""
    return topic if topic in GLOBAL_TOPICS else topic.lstrip("/")


EPISODE_TOPIC = "mission_control/episode"
NODE_TOPICS = {EPISODE_TOPIC: FLOAT32_MULTI_ARRAY}
"""Each boat's topics that only the ROS node publishes (and logs with ``--record``), relative to its namespace."""
EPISODE_END = ("success", "waypoints_reached", "decisions", "return", "status_flags", "end_reason", "boat", "time_s")
"""An episode's end (``mission_control/episode``), in order: 1 where the boat reached its last waypoint, else 0;
waypoints reached; decisions sailed; the reward summed over the episode; the simulator's status flags at the
end (0: none; ``ocean_warp.BoatStatus``: capsized, collided, ...); how it ended, the index of its reason in
``ocean_warp.fleet.END_REASONS`` (0 reached, 1 capsized, 2 collided, 3 flagged, 4 time-out, 5 lost: beyond
the lost distance, 125 m from the waypoint in the seed's task); the boat's index; the simulated time of the
end [s] (the message's clock, as float32). A boat whose episode ended starts the next one at once (a new start
is drawn)."""

SEED_OBSERVATION = ("distance_m", "bearing_deg", "speed_m_s", "apparent_wind_speed_m_s", "apparent_wind_angle_deg",
                    "boom_angle_deg", "rudder_angle_deg", "propeller_level", "roll_deg")
"""The seed's observation array, in order: planar distance to the waypoint [m]; its bearing from the bow [deg],
positive to port, in [-180, 180); surge speed [m/s]; apparent wind speed [m/s] and angle [deg] at the masthead
(where it comes from, from the bow, positive to port); boom angle [deg], positive with the boom to port;
rudder angle [deg], positive turning the boat to port; the propeller level the last decision applied; roll
[deg], positive heeling to starboard. All from the truth, as the seed task's ``seed_columns`` reads them."""

_OPTICAL_IN_LINK = (-0.5, 0.5, -0.5, 0.5)
"""camera_link -> camera_optical_frame (x, y, z, w): the optical z along the link's x, x along -y, y along -z."""
_NAME = re.compile(r"^(/[A-Za-z][A-Za-z0-9_]*)*$")


def boat_namespace(boat: int, boats: int, prefix: str = "") -> str:
    """The namespace of boat ``boat`` of ``boats``: ``/eboat`` for a single boat, else ``/eboat_<boat>``, below
    ``prefix`` ("" or an absolute ROS name such as ``/autopilot``); ``ValueError`` for a bad prefix."""
    if not isinstance(prefix, str) or not _NAME.match(prefix):
        raise ValueError(f"boat_namespace: prefix must be '' or an absolute ROS name such as '/autopilot' (letters, "
                         f"digits, '_', each part starting with a letter), got {prefix!r}")
    return f"{prefix}{SEED_NAMESPACE}" if boats == 1 else f"{prefix}{SEED_NAMESPACE}_{boat}"


def frame_id(namespace: str, frame: str) -> str:
    """A boat's tf frame ``frame`` (``base_link``, ``odom``, ...): plain under the seed's ``/eboat``, else
    prefixed with the namespace without its leading slash (``eboat_3/base_link``)."""
    return frame if namespace == SEED_NAMESPACE else f"{namespace[1:]}/{frame}"


def stamp(time_ns: int) -> dict:
    """A ``builtin_interfaces/Time`` of ``time_ns`` nanoseconds of simulated time."""
    return {"sec": int(time_ns // 1_000_000_000), "nanosec": int(time_ns % 1_000_000_000)}


def _header(time_ns: int, frame: str) -> dict:
    return {"stamp": stamp(time_ns), "frame_id": frame}


def _vector(values) -> dict:
    return {"x": float(values[0]), "y": float(values[1]), "z": float(values[2])}


def _quaternion(values) -> dict:
    return {"x": float(values[0]), "y": float(values[1]), "z": float(values[2]), "w": float(values[3])}


def _diagonal(variances) -> list[float]:
    """A row-major 3 x 3 covariance with ``variances`` on its diagonal."""
    return [float(v) for v in np.diag(np.asarray(variances, dtype=np.float64)).reshape(-1)]


@dataclasses.dataclass(frozen=True)
class Message:
    """One message: its topic (absolute), type (full ROS 2 name), the simulated time it refers to
    [ns] (its header stamp, or for a type without header its log time) and its fields."""

    topic: str
    type: str
    time_ns: int
    fields: dict


# --- the state, on the host ------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True, kw_only=True)
class BoatSnapshot:
    """Host copies (float64 numpy) of what the messages read of an environment's N boats at one time."""

    time_ns: int
    """Simulated time [ns], the simulator's clock rounded to the nanosecond."""
    position: np.ndarray
    """(N, 3) body origin, world ENU [m]."""
    orientation: np.ndarray
    """(N, 4) body (FLU) -> world quaternion x, y, z, w (normalised)."""
    velocity: np.ndarray
    """(N, 6) body-frame velocity [m/s] and angular velocity [rad/s] (Fossen's nu)."""
    target: np.ndarray
    """(N, 3) world position of each boat's current waypoint [m]."""
    wind_velocity: np.ndarray
    """(N, 3) true wind at the reference height, world frame [m/s]."""
    current_velocity: np.ndarray
    """(N, 3) the water's current at the surface, world frame [m/s] (zero in still water)."""
    truth: np.ndarray
    """(N, 16) exact sensor channels (``ocean_warp.CHANNEL_NAMES``)."""
    readings: np.ndarray
    """(N, 16) noisy sensor readings, same columns."""
    propeller_level: np.ndarray
    """(N,) the level the last decision applied."""
    noise_scale: np.ndarray
    """(N,) each boat's factor on its sensors' noise."""
    sensor_std: np.ndarray
    """(16,) each channel's configured noise standard deviation (in its unit)."""
    joint_names: tuple[str, ...] = ()
    """The vessel's joints, as a ``sensor_msgs/JointState`` names them (:func:`joint_states`): ``boom_angle`` and
    ``rudder_angle`` of the E-Boat, ``thruster_angle_0`` and ``_1`` of the WAM-V."""
    joint_angles: np.ndarray | None = None
    """(N, J) each boat's angle of each joint [rad], positive to port (a part turns by minus it about its z)."""
    boom_angle: dataclasses.InitVar[np.ndarray | None] = None
    """(N,) [rad]: a joint ``boom_angle`` given by name (added to the joints)."""
    rudder_angle: dataclasses.InitVar[np.ndarray | None] = None
    """(N,) [rad]: a joint ``rudder_angle`` given by name (added to the joints)."""

    def __post_init__(self, boom_angle, rudder_angle):
        names = tuple(self.joint_names)
        angles = np.zeros((self.count, 0)) if self.joint_angles is None \
            else np.asarray(self.joint_angles, dtype=np.float64).reshape(self.count, len(names))
        for name, value in (("boom_angle", boom_angle), ("rudder_angle", rudder_angle)):
            if value is not None and name not in names:
                names += (name,)
                angles = np.column_stack([angles, np.asarray(value, dtype=np.float64).reshape(-1)])
        object.__setattr__(self, "joint_names", names)
        object.__setattr__(self, "joint_angles", angles)

    @property
    def count(self) -> int:
        return self.position.shape[0]

    def joint(self, name: str) -> np.ndarray:
        """(N,) every boat's angle of joint ``name`` [rad]; NaN where the vessel has no such joint."""
        if name in self.joint_names:
            return self.joint_angles[:, self.joint_names.index(name)]
        return np.full(self.count, np.nan)


def joint_states(vessel, state) -> tuple[tuple[str, ...], np.ndarray]:
    """(names, (N, J) angles [rad]) of the joints of ``vessel``'s parts (``VesselPart.joint``) read from the
    simulator ``state``: a 1-D state array is one joint under its own name, column k of a 2-D one is
    ``<name>_<k>``; in the order the parts first name them."""
    names, columns = [], []
    for part in vessel.parts():
        if part.joint is None:
            continue
        values = np.asarray(getattr(state, part.joint).numpy(), dtype=np.float64)
        name = part.joint if values.ndim == 1 else f"{part.joint}_{part.joint_column}"
        if name not in names:
            names.append(name)
            columns.append(values if values.ndim == 1 else values[:, part.joint_column])
    count = state.position.shape[0]
    return tuple(names), (np.column_stack(columns) if columns else np.zeros((count, 0)))


def snapshot(env, time_offset_ns: int = 0) -> BoatSnapshot:
    """The state of ``env`` (a ``SailingEnv``, a ``VrxEnv``: its ``vessel`` and ``simulator``) now: after
    ``env.step()`` the boats as the next decision sees them (environments that ended already restarted), at the
    simulator's clock plus ``time_offset_ns`` (what a log or node adds to keep its time running on across resets);
    the vessel's common state and its joints (:func:`joint_states`)."""
    state = env.simulator.state
    host = lambda array: np.asarray(array.numpy(), dtype=np.float64)  # noqa: E731
    orientation = host(state.orientation)
    orientation /= np.linalg.norm(orientation, axis=1, keepdims=True)
    joint_names, joint_angles = joint_states(env.vessel, state)
    return BoatSnapshot(
        time_ns=int(round(float(state.time.numpy()[0]) * 1e9)) + int(time_offset_ns), position=host(state.position),
        orientation=orientation, velocity=host(state.velocity), target=host(env.target_world),
        wind_velocity=host(state.wind_velocity), current_velocity=host(state.current_velocity),
        truth=host(state.truth), readings=host(state.readings), joint_names=joint_names, joint_angles=joint_angles,
        propeller_level=host(env.propeller_level), noise_scale=host(state.noise_scale),
        sensor_std=np.asarray(env.simulator.sensors.config.channel_noise(), dtype=np.float64))


def _wrap_degrees(angle: np.ndarray) -> np.ndarray:
    """Angles [deg] wrapped into [-180, 180)."""
    return angle - 360.0 * np.floor((angle + 180.0) / 360.0)


def seed_observation_values(s: BoatSnapshot) -> np.ndarray:
    """(N, 9) the seed's observation array of every boat (:data:`SEED_OBSERVATION`: order and units)."""
    attitude = roll_pitch_yaw(s.orientation)
    to_target = s.target[:, :2] - s.position[:, :2]
    bearing = np.degrees(np.arctan2(to_target[:, 1], to_target[:, 0]) - attitude[:, 2])
    return np.column_stack([np.hypot(to_target[:, 0], to_target[:, 1]), _wrap_degrees(bearing), s.velocity[:, 0],
                            s.truth[:, 14], np.degrees(s.truth[:, 13]), np.degrees(s.joint("boom_angle")),
                            np.degrees(s.joint("rudder_angle")), s.propeller_level, np.degrees(attitude[:, 0])])


def state_messages(s: BoatSnapshot, *, prefix: str = "", datum: GeodeticDatum = GUANABARA_BAY) -> list[Message]:
    """The messages of the state ``s`` (no commands, sensors that see or static transforms): per boat the seed's
    observations and wind, the GNSS fix, the IMU, the true and apparent wind, the current; and ``/tf`` with every
    boat's pose. Each stamped at ``s.time_ns``."""
    t, n = s.time_ns, s.count
    observations = seed_observation_values(s)
    geodetic = enu_to_geodetic(s.readings[:, 0:3], datum)
    std, scale = s.sensor_std, s.noise_scale
    messages, transforms = [], []
    for boat in range(n):
        ns = boat_namespace(boat, n, prefix)
        base, odom = frame_id(ns, "base_link"), frame_id(ns, "odom")
        reading, noise = s.readings[boat], scale[boat] ** 2
        apparent = -reading[14] * np.array([math.cos(reading[13]), math.sin(reading[13]), 0.0])
        messages += [
            Message(f"{ns}/mission_control/observations", FLOAT32_MULTI_ARRAY, t, {
                "layout": {"dim": [{"label": "observation", "size": len(SEED_OBSERVATION),
                                    "stride": len(SEED_OBSERVATION)}], "data_offset": 0},
                "data": observations[boat].tolist()}),
            Message(f"{ns}/atmosferic_control/wind", POINT, t, _vector(s.wind_velocity[boat])),
            Message(f"{ns}/gps/fix", NAV_SAT_FIX, t, {
                "header": _header(t, base), "status": {"status": 0, "service": 1},  # STATUS_FIX, SERVICE_GPS
                "latitude": float(geodetic[boat, 0]), "longitude": float(geodetic[boat, 1]),
                "altitude": float(geodetic[boat, 2]), "position_covariance": _diagonal(std[0:3] ** 2 * noise),
                "position_covariance_type": 2}),  # COVARIANCE_TYPE_DIAGONAL_KNOWN
            Message(f"{ns}/imu/data", IMU, t, {
                "header": _header(t, base), "orientation": _quaternion(s.orientation[boat]),
                "orientation_covariance": [0.0] * 9, "angular_velocity": _vector(reading[9:12]),
                "angular_velocity_covariance": _diagonal(std[9:12] ** 2 * noise),
                "linear_acceleration": _vector(reading[6:9]),
                "linear_acceleration_covariance": _diagonal(std[6:9] ** 2 * noise)}),
            Message(f"{ns}/wind/true", VECTOR3_STAMPED, t,
                    {"header": _header(t, MAP_FRAME), "vector": _vector(s.wind_velocity[boat])}),
            Message(f"{ns}/wind/apparent", VECTOR3_STAMPED, t,
                    {"header": _header(t, base), "vector": _vector(apparent)}),
            Message(f"{ns}/current", VECTOR3_STAMPED, t,
                    {"header": _header(t, MAP_FRAME), "vector": _vector(s.current_velocity[boat])}),
        ]
        transforms.append(_transform(t, odom, base, s.position[boat], s.orientation[boat]))
    messages.append(Message(TF, TF_MESSAGE, t, {"transforms": transforms}))
    return messages


def _transform(time_ns: int, parent: str, child: str, translation, rotation) -> dict:
    """A ``geometry_msgs/TransformStamped``: ``child``'s pose in ``parent`` (translation [m], rotation x y z w)."""
    return {"header": _header(time_ns, parent), "child_frame_id": child,
            "transform": {"translation": _vector(translation), "rotation": _quaternion(rotation)}}


def command_messages(time_ns: int, rudder, sheet, propeller, *, prefix: str = "") -> list[Message]:
    """The seed's command topics of every boat: ``rudder`` and ``sheet`` (N,) commands [rad] and ``propeller``
    (N,) levels, as sent at ``time_ns`` (the start of the decision they steered)."""
    rudder, sheet, propeller = (np.asarray(v).reshape(-1) for v in (rudder, sheet, propeller))
    n, messages = rudder.size, []
    for boat in range(n):
        ns = boat_namespace(boat, n, prefix)
        messages += [Message(f"{ns}/control_interface/sail", FLOAT32, time_ns, {"data": math.degrees(sheet[boat])}),
                     Message(f"{ns}/control_interface/rudder", FLOAT32, time_ns,
                             {"data": math.degrees(rudder[boat])}),
                     Message(f"{ns}/control_interface/propulsion", INT16, time_ns, {"data": int(propeller[boat])})]
    return messages


# --- sensors that see ----------------------------------------------------------------------------------
def env_lidar(env):
    """The lidar ``env`` scans with when it makes its observation (its task's ``lidar``), or None."""
    course = getattr(env, "obstacles", None)
    return None if course is None else course.lidar


def lidar_messages(lidar, time_ns: int, *, scan_time: float, prefix: str = "") -> list[Message]:
    """``lidar/scan`` of every boat from ``lidar``'s last scan (a :class:`~ocean_warp.perception.Lidar`, boat i's
    sensor in row i): its beams' angles from its config, ``scan_time`` [s] between scans, and the ranges [m],
    +inf where a beam returned nothing (REP 117). A lidar of several channels gives none (a 3D scan is no
    LaserScan): an empty list."""
    from ocean_warp.kernels.ray_cast import HIT_NONE

    config = lidar.config
    if config.channels != 1:
        return []
    azimuth = config.azimuths()
    increment = float(azimuth[1] - azimuth[0]) if azimuth.size > 1 else 0.0
    ranges = lidar.range_array.numpy().astype(np.float32)
    ranges[lidar.kind_array.numpy() == int(HIT_NONE)] = np.inf
    n, messages = ranges.shape[0], []
    for boat in range(n):
        ns = boat_namespace(boat, n, prefix)
        messages.append(Message(f"{ns}/lidar/scan", LASER_SCAN, time_ns, {
            "header": _header(time_ns, frame_id(ns, "lidar_link")), "angle_min": float(azimuth[0]),
            "angle_max": float(azimuth[-1]), "angle_increment": increment, "time_increment": 0.0,
            "scan_time": float(scan_time), "range_min": config.min_range, "range_max": config.max_range,
            "ranges": ranges[boat].tolist(), "intensities": []}))
    return messages


def _camera_info(camera, time_ns: int, frame: str) -> dict:
    info = camera.camera_info()
    return {"header": _header(time_ns, frame), "height": info["height"], "width": info["width"],
            "distortion_model": info["distortion_model"], "d": list(info["D"]), "k": list(info["K"]),
            "r": list(info["R"]), "p": list(info["P"]), "binning_x": info["binning_x"],
            "binning_y": info["binning_y"], "roi": dict(info["roi"])}


def camera_messages(camera, boats: int, time_ns: int, *, prefix: str = "") -> list[Message]:
    """Each camera's images (RGB "rgb8", depth "32FC1" [m], as it renders them) and their CameraInfo, in its
    ``camera_optical_frame``, under the namespace of the boat it rides (``camera``: a
    :class:`~ocean_warp.perception.Camera`, camera c on boat ``camera.boats[c]`` of ``boats``)."""
    riders = camera.boats.numpy()
    config = camera.config
    images = []
    if config.rgb:
        images.append(("camera", "rgb8", 3, camera.rgb_array.numpy()))
    if config.depth:
        images.append(("camera/depth", "32FC1", 4, camera.depth_array.numpy().astype("<f4")))
    messages = []
    for c, boat in enumerate(riders):
        ns = boat_namespace(int(boat), boats, prefix)
        frame = frame_id(ns, "camera_optical_frame")
        for path, encoding, size, array in images:
            messages.append(Message(f"{ns}/{path}/image_raw", IMAGE, time_ns, {
                "header": _header(time_ns, frame), "height": config.height, "width": config.width,
                "encoding": encoding, "is_bigendian": 0, "step": config.width * size,
                "data": np.ascontiguousarray(array[c]).tobytes()}))  # depth little-endian ("<f4") on any host
            messages.append(Message(f"{ns}/{path}/camera_info", CAMERA_INFO, time_ns,
                                    _camera_info(camera, time_ns, frame)))
    return messages


def static_messages(boats: int, time_ns: int, *, prefix: str = "", odom: bool = True, lidar_config=None,
                    camera=None) -> Message:
    """``/tf_static`` of ``boats`` boats: with ``odom``, ``map`` -> each one's ``odom`` (the identity), and where
    given the mounts of a lidar (``lidar_config``, a ``LidarConfig``: ``base_link`` -> ``lidar_link``) and a
    camera (``camera``, a :class:`~ocean_warp.perception.Camera`: ``base_link`` -> ``camera_link`` ->
    ``camera_optical_frame``, for the boats it rides)."""
    transforms = []
    identity = (0.0, 0.0, 0.0, 1.0)
    camera_boats = set() if camera is None else {int(b) for b in camera.boats.numpy()}
    for boat in range(boats):
        ns = boat_namespace(boat, boats, prefix)
        base = frame_id(ns, "base_link")
        if odom:
            transforms.append(_transform(time_ns, MAP_FRAME, frame_id(ns, "odom"), (0.0, 0.0, 0.0), identity))
        if lidar_config is not None:
            transforms.append(_transform(time_ns, base, frame_id(ns, "lidar_link"), lidar_config.mount,
                                         quaternion_from_roll_pitch_yaw(lidar_config.mount_rpy)[0]))
        if boat in camera_boats:
            link = frame_id(ns, "camera_link")
            transforms.append(_transform(time_ns, base, link, camera.config.mount,
                                         quaternion_from_roll_pitch_yaw(camera.config.mount_rpy)[0]))
            transforms.append(_transform(time_ns, link, frame_id(ns, "camera_optical_frame"), (0.0, 0.0, 0.0),
                                         _OPTICAL_IN_LINK))
    return Message(TF_STATIC, TF_MESSAGE, time_ns, {"transforms": transforms})


def clock_message(time_ns: int) -> Message:
    """``/clock`` at ``time_ns`` of simulated time."""
    return Message(CLOCK, CLOCK_TYPE, time_ns, {"clock": stamp(time_ns)})


def episode_messages(time_ns: int, ended, success, waypoints, decisions, returns, status, time_out=None, *,
                     prefix: str = "") -> list[Message]:
    """``mission_control/episode`` (:data:`EPISODE_END`) of every boat whose episode ended at ``time_ns``:
    ``ended`` (N,) bool, and per boat (N,) ``success`` (1 or 0), ``waypoints`` reached, ``decisions`` sailed,
    ``returns`` (the summed reward), the simulator's ``status`` flags at the end and ``time_out`` (bool, the
    task's time limit reached; None: none was)."""
    ended = np.asarray(ended, dtype=bool).reshape(-1)
    n, messages = ended.size, []
    columns = [np.asarray(v, dtype=np.float64).reshape(-1) for v in (success, waypoints, decisions, returns, status)]
    timed_out = np.zeros(n, dtype=bool) if time_out is None else np.asarray(time_out, dtype=bool).reshape(-1)
    for boat in np.flatnonzero(ended):
        ns = boat_namespace(int(boat), n, prefix)
        reason = episode_end(columns[0][boat] == 1.0, bool(timed_out[boat]), int(columns[4][boat]))
        messages.append(Message(f"{ns}/{EPISODE_TOPIC}", FLOAT32_MULTI_ARRAY, time_ns, {
            "layout": {"dim": [{"label": "episode_end", "size": len(EPISODE_END), "stride": len(EPISODE_END)}],
                       "data_offset": 0},
            "data": [float(column[boat]) for column in columns]
            + [float(END_REASONS.index(reason)), float(boat), time_ns / 1e9]}))
    return messages


def episode_end_reason(message: Message) -> str:
    """The words of how the episode of a ``mission_control/episode`` message ended (:data:`END_REASONS`)."""
    return END_REASONS[int(message.fields["data"][EPISODE_END.index("end_reason")])]
