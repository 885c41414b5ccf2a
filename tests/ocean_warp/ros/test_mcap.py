"""The rosbag2 MCAP logs (``ocean_warp.envs.ros.mcap_log``, topics in ``ocean_warp.ros.topics``), read back with an
independent reader (``rosbags``) and checked against the environment's own numbers, numpy and geodesy written
here; ``ocean-warp demo`` and ``eval`` with ``--record`` end to end (CPU, four-point hull, a few seconds)."""

from __future__ import annotations

import csv
import dataclasses
import math
import os
import struct
import sys
from pathlib import Path

import numpy as np
import pytest
import torch

pytest.importorskip("mcap_ros2")
pytest.importorskip("rosbags")

from rosbags.highlevel import AnyReader  # noqa: E402
from rosbags.interfaces import MessageDefinitionFormat  # noqa: E402
from rosbags.typesys import Stores, get_typestore, get_types_from_msg  # noqa: E402

from ocean_warp.envs import SailingEnv  # noqa: E402
from ocean_warp.envs.sailing_env import environment_origins  # noqa: E402
from ocean_warp.envs.apps import evaluation  # noqa: E402
from ocean_warp.envs.tasks.obstacle_layout import ObstacleLayoutConfig  # noqa: E402
from ocean_warp.envs.tasks.task_configs import AvoidConfig, WaypointConfig  # noqa: E402
from ocean_warp.kernels.ray_cast import HIT_NONE  # noqa: E402
from ocean_warp.envs.ros import mcap_log  # noqa: E402
from ocean_warp.envs.ros.mcap_log import McapRecorder, check_record_path  # noqa: E402
from ocean_warp.envs.sensors import CameraHook  # noqa: E402
from ocean_warp.perception import CameraConfig  # noqa: E402
from ocean_warp.ros import topics  # noqa: E402
from ocean_warp.ros.geodesy import GUANABARA_BAY, GeodeticDatum, enu_to_geodetic  # noqa: E402
from ocean_warp.sensors import SensorConfig  # noqa: E402

HUMBLE = get_typestore(Stores.ROS2_HUMBLE)
"""rosbags' own ROS 2 Humble definitions: the messages must decode with them, not only with the file's."""
BOATS, DECISIONS = 3, 5
CURRENT_SPEED = (0.2, 0.6)
"""Range of the current the recorded run draws per episode [m/s]."""
A, F = 6378137.0, 1.0 / 298.257223563  # WGS 84
E2 = F * (2.0 - F)


# --- a recorded run -----------------------------------------------------------------------------------
def _task():
    """Obstacle avoidance on the seed twin's four-point boat (fast on the CPU), noisy sensors with a noise factor
    drawn per boat, a current of 0.2-0.6 m/s drawn per episode, the buoys 10-40 m ahead (within the lidar's 50 m)
    and 3 s episodes (a restart at t = 3 s)."""
    avoid = AvoidConfig()
    simulator = dataclasses.replace(WaypointConfig().simulator, sensors=SensorConfig())
    start = dataclasses.replace(avoid.start, waypoint_distance=(100.0, 100.0), sensor_noise_scale=(0.5, 1.5),
                                current_speed=CURRENT_SPEED)
    return dataclasses.replace(avoid, simulator=simulator, start=start, episode_time=3.0,
                               obstacles=ObstacleLayoutConfig(along_track=(0.1, 0.4)))


@dataclasses.dataclass
class Run:
    path: Path
    env: SailingEnv
    hook: CameraHook
    times: list
    """Simulated time [s] of each record."""
    host: list
    """Per record: the env's numbers then (buffers, readings, lidar), copied."""
    actions: list
    """Per decision: the actions (BOATS, 3)."""
    images: dict
    """Time [ns] -> (rgb, depth) of the decisions in which the camera rendered."""


def _host_state(env) -> dict:
    b, state = env.buffers, env.simulator.state
    lidar = env.obstacles.lidar
    return {"position": b.position.cpu().numpy().astype(np.float64).copy(),
            "orientation": b.orientation.cpu().numpy().astype(np.float64).copy(),
            "target": b.target.cpu().numpy().astype(np.float64).copy(),
            "velocity": b.velocity.cpu().numpy().astype(np.float64).copy(),
            "wind": b.wind_velocity.cpu().numpy().astype(np.float64).copy(),
            "policy_obs": b.policy_obs.cpu().numpy().astype(np.float64).copy(),
            "propeller_level": b.propeller_level.cpu().numpy().copy(),
            "readings": state.readings.numpy().astype(np.float64).copy(),
            "noise_scale": state.noise_scale.numpy().astype(np.float64).copy(),
            "current_speed": state.current_speed.numpy().astype(np.float64).copy(),
            "current_direction": state.current_direction.numpy().astype(np.float64).copy(),
            "ranges": lidar.range_array.numpy().copy(), "kinds": lidar.kind_array.numpy().copy()}


@pytest.fixture(scope="module")
def run(tmp_path_factory) -> Run:
    path = tmp_path_factory.mktemp("mcap") / "run.mcap"
    env = SailingEnv(_task(), BOATS, device="cpu", seed=5)
    hook = CameraHook(env, CameraConfig(width=8, height=6, rate=0.5))  # renders every other decision
    env.attach(hook)
    rng = np.random.default_rng(3)
    times, host, actions, images = [], [], [], {}
    with McapRecorder(path) as log:
        log.record(env, camera=hook)
        times.append(env.simulator.time)
        host.append(_host_state(env))
        for _ in range(DECISIONS):
            action = rng.uniform(-1.0, 1.0, (BOATS, 3)).astype(np.float32)
            actions.append(action)
            env.step(torch.from_numpy(action))
            log.record(env, camera=hook)
            times.append(env.simulator.time)
            host.append(_host_state(env))
            if int(hook.camera.gate.numpy()[0]) == 1:
                images[round(times[-1] * 1e9)] = (hook.camera.rgb_array.numpy().copy(),
                                                  hook.camera.depth_array.numpy().copy())
    assert os.listdir(path.parent) == ["run.mcap"]  # renamed into place, no temporary left
    return Run(path, env, hook, times, host, actions, images)


def _read(path) -> tuple[dict, dict]:
    """{topic: [(log time [ns], message decoded with rosbags' Humble types)]}, {topic: connection}."""
    messages, connections = {}, {}
    with AnyReader([Path(path)]) as reader:
        for connection in reader.connections:
            connections[connection.topic] = connection
        for connection, log_time, raw in reader.messages():
            messages.setdefault(connection.topic, []).append(
                (log_time, HUMBLE.deserialize_cdr(raw, connection.msgtype)))
    return messages, connections


@pytest.fixture(scope="module")
def bag(run):
    return _read(run.path)


def _ns(boat: int) -> str:
    return f"/eboat_{boat}"


def _stamp_ns(header) -> int:
    return header.stamp.sec * 1_000_000_000 + header.stamp.nanosec


# --- the file ---------------------------------------------------------------------------------------------
def test_file_is_a_ros2_mcap_with_ros2msg_schemas_and_cdr(run, bag):
    data = run.path.read_bytes()
    assert data[:8] == b"\x89MCAP0\r\n" and data[8] == 0x01  # magic, then the header record
    (length,) = struct.unpack_from("<Q", data, 9)
    (profile_length,) = struct.unpack_from("<I", data, 17)
    assert data[21:21 + profile_length] == b"ros2" and length >= 4 + profile_length
    _, connections = bag
    for topic, connection in connections.items():
        assert connection.msgdef.format is MessageDefinitionFormat.MSG, topic
        assert connection.ext.serialization_format == "cdr", topic
        # The file's definition of each type has exactly the fields (and constants) of ROS 2 Humble's.
        for name, definition in get_types_from_msg(connection.msgdef.data, connection.msgtype).items():
            assert definition == HUMBLE.fielddefs[name], (topic, name)


def test_topics_types_and_counts(run, bag):
    messages, connections = bag
    records, ns = DECISIONS + 1, [_ns(b) for b in range(BOATS)]
    expected = {"/clock": ("rosgraph_msgs/msg/Clock", records), "/tf": ("tf2_msgs/msg/TFMessage", records),
                "/tf_static": ("tf2_msgs/msg/TFMessage", 1)}
    captures = len(run.images)
    assert captures == 3  # at 0.5 Hz the camera renders in decisions 1, 3 and 5
    for n in ns:
        expected |= {
            f"{n}/mission_control/observations": ("std_msgs/msg/Float32MultiArray", records),
            f"{n}/atmosferic_control/wind": ("geometry_msgs/msg/Point", records),
            f"{n}/control_interface/sail": ("std_msgs/msg/Float32", DECISIONS),
            f"{n}/control_interface/rudder": ("std_msgs/msg/Float32", DECISIONS),
            f"{n}/control_interface/propulsion": ("std_msgs/msg/Int16", DECISIONS),
            f"{n}/lidar/scan": ("sensor_msgs/msg/LaserScan", records),
            f"{n}/gps/fix": ("sensor_msgs/msg/NavSatFix", records),
            f"{n}/imu/data": ("sensor_msgs/msg/Imu", records),
            f"{n}/wind/true": ("geometry_msgs/msg/Vector3Stamped", records),
            f"{n}/wind/apparent": ("geometry_msgs/msg/Vector3Stamped", records),
            f"{n}/current": ("geometry_msgs/msg/Vector3Stamped", records),
            f"{n}/camera/image_raw": ("sensor_msgs/msg/Image", captures),
            f"{n}/camera/camera_info": ("sensor_msgs/msg/CameraInfo", captures),
            f"{n}/camera/depth/image_raw": ("sensor_msgs/msg/Image", captures),
            f"{n}/camera/depth/camera_info": ("sensor_msgs/msg/CameraInfo", captures),
        }
    assert {topic: (c.msgtype, c.msgcount) for topic, c in connections.items()} == expected
    assert {topic: len(items) for topic, items in messages.items()} == {t: n for t, (_, n) in expected.items()}
    # Every type the log uses is one the topics module declares, and its table of boat topics is complete.
    assert {c.msgtype for c in connections.values()} == set(topics.TYPES)
    assert {t[len(ns[0]) + 1:] for t in expected if t.startswith(ns[0])} == set(topics.BOAT_TOPICS)


def test_timestamps_are_the_simulated_time(run, bag):
    messages, _ = bag
    times = [round(t * 1e9) for t in run.times]
    assert times == [k * 1_000_000_000 for k in range(DECISIONS + 1)]  # 1 s decisions from 0
    assert [log for log, _ in messages["/clock"]] == times
    assert [m.clock.sec * 1_000_000_000 + m.clock.nanosec for _, m in messages["/clock"]] == times
    for topic, items in messages.items():
        for log_time, message in items:
            header = getattr(message, "header", None)
            if header is not None:
                assert _stamp_ns(header) == log_time, topic
        if topic.endswith(("/observations", "/gps/fix", "/imu/data", "/lidar/scan")) or topic == "/tf":
            assert [log for log, _ in items] == times, topic
        if "/control_interface/" in topic:  # sent at the start of the decision they steered
            assert [log for log, _ in items] == times[:-1], topic
        if "/camera/" in topic:
            assert [log for log, _ in items] == sorted(run.images), topic
    for _, message in messages["/tf"]:
        assert all(_stamp_ns(t.header) == _stamp_ns(message.transforms[0].header) for t in message.transforms)


def _yaw(q: np.ndarray) -> np.ndarray:
    x, y, z, w = (q / np.linalg.norm(q, axis=1, keepdims=True)).T
    return np.arctan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def _roll(q: np.ndarray) -> np.ndarray:
    x, y, z, w = (q / np.linalg.norm(q, axis=1, keepdims=True)).T
    return np.arctan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))


def test_seed_observations_match_numpy_and_the_task(run, bag):
    """Distance and bearing to the waypoint from the buffers' pose and target, in numpy; speed, the apparent
    wind and the rest against the seed task's own (normalised) observation of the same moment."""
    messages, _ = bag
    lost_margin = run.env.task.lost_margin
    for k, state in enumerate(run.host):
        to_target = state["target"][:, :2] - state["position"][:, :2]
        distance = np.hypot(to_target[:, 0], to_target[:, 1])
        bearing = np.degrees(np.arctan2(to_target[:, 1], to_target[:, 0]) - _yaw(state["orientation"]))
        bearing = (bearing + 180.0) % 360.0 - 180.0
        obs = state["policy_obs"]
        for boat in range(BOATS):
            layout_message = messages[f"{_ns(boat)}/mission_control/observations"][k][1]
            values = layout_message.data
            assert layout_message.layout.dim[0].size == 9 and len(values) == 9
            np.testing.assert_allclose(values[0], distance[boat], rtol=1e-5)
            np.testing.assert_allclose(values[1], bearing[boat], atol=1e-3)
            np.testing.assert_allclose(values[2], state["velocity"][boat, 0], atol=1e-5)
            # the task's seed observation: 2 d / lost - 1, bearing / 180, v / 5 - 1, aws / 15 - 1, awa / 180
            leg = distance[boat] if k in (0, 3) else None  # at a fresh start the leg is the distance
            if leg is not None:
                np.testing.assert_allclose(obs[boat, 0], np.clip(2.0 * distance[boat] / (leg + lost_margin) - 1.0,
                                                                  -1, 1), atol=1e-4)
            np.testing.assert_allclose(obs[boat, 1], values[1] / 180.0, atol=1e-5)
            np.testing.assert_allclose(obs[boat, 2], np.clip(values[2] / 5.0 - 1.0, -1, 1), atol=1e-5)
            np.testing.assert_allclose(obs[boat, 3], np.clip(values[3] / 15.0 - 1.0, -1, 1), atol=1e-5)
            np.testing.assert_allclose(obs[boat, 4], values[4] / 180.0, atol=1e-5)
            assert values[7] == state["propeller_level"][boat]
            np.testing.assert_allclose(values[8], np.degrees(_roll(state["orientation"]))[boat], atol=1e-3)
            assert -180.0 <= values[1] < 180.0 and -180.0 <= values[4] <= 180.0


def test_commands_are_the_actions_in_degrees(run, bag):
    messages, _ = bag
    for k, action in enumerate(run.actions):
        levels = run.host[k + 1]["propeller_level"]  # the level the decision applied
        for boat in range(BOATS):
            sail = messages[f"{_ns(boat)}/control_interface/sail"][k][1].data
            rudder = messages[f"{_ns(boat)}/control_interface/rudder"][k][1].data
            level = messages[f"{_ns(boat)}/control_interface/propulsion"][k][1].data
            np.testing.assert_allclose(sail, (action[boat, 1] + 1.0) * 45.0, atol=1e-3)
            np.testing.assert_allclose(rudder, 60.0 * action[boat, 2], atol=1e-3)
            assert level == levels[boat] and abs(level - 5.0 * action[boat, 0]) < 1.0


def _geodetic_to_ecef(lat, lon, h):
    n = A / np.sqrt(1.0 - E2 * np.sin(lat) ** 2)
    return np.array([(n + h) * np.cos(lat) * np.cos(lon), (n + h) * np.cos(lat) * np.sin(lon),
                     (n * (1.0 - E2) + h) * np.sin(lat)])


def _ecef_to_enu(ecef, datum: GeodeticDatum):
    lat0, lon0 = math.radians(datum.latitude_deg), math.radians(datum.longitude_deg)
    d = ecef - _geodetic_to_ecef(lat0, lon0, datum.altitude_m)
    sl, cl, so, co = math.sin(lat0), math.cos(lat0), math.sin(lon0), math.cos(lon0)
    return np.array([-so * d[0] + co * d[1], -sl * co * d[0] - sl * so * d[1] + cl * d[2],
                     cl * co * d[0] + cl * so * d[1] + sl * d[2]])


def _heikkinen(x, y, z):
    """ECEF -> geodetic in closed form (Heikkinen 1982, as in Zhu 1994): latitude, longitude [rad], height [m]."""
    b = A * math.sqrt(1.0 - E2)
    ep2 = (A * A - b * b) / (b * b)
    p = math.hypot(x, y)
    f = 54.0 * b * b * z * z
    g = p * p + (1.0 - E2) * z * z - E2 * (A * A - b * b)
    c = E2 * E2 * f * p * p / g ** 3
    s = (1.0 + c + math.sqrt(c * c + 2.0 * c)) ** (1.0 / 3.0)
    k = s + 1.0 + 1.0 / s
    pp = f / (3.0 * k * k * g * g)
    q = math.sqrt(1.0 + 2.0 * E2 * E2 * pp)
    r0 = -pp * E2 * p / (1.0 + q) + math.sqrt(0.5 * A * A * (1.0 + 1.0 / q) - pp * (1.0 - E2) * z * z / (q * (1.0 + q))
                                              - 0.5 * pp * p * p)
    u = math.sqrt((p - E2 * r0) ** 2 + z * z)
    v = math.sqrt((p - E2 * r0) ** 2 + (1.0 - E2) * z * z)
    z0 = b * b * z / (A * v)
    return math.atan((z + ep2 * z0) / p), math.atan2(y, x), u * (1.0 - b * b / (A * v))


def test_geodesy_against_closed_form_and_round_trip():
    datum = GeodeticDatum(48.85, 2.35, 35.0)
    points = np.array([[0.0, 0.0, 0.0], [120.0, -80.0, 1.5], [-3.0e4, 5.0e4, -20.0], [2.0e5, 1.5e5, 1.0e4]])
    for d in (datum, GUANABARA_BAY):
        result = enu_to_geodetic(points, d)
        for point, (lat, lon, h) in zip(points, result):
            ecef = _geodetic_to_ecef(math.radians(lat), math.radians(lon), h)
            np.testing.assert_allclose(_ecef_to_enu(ecef, d), point, atol=1e-6)  # back where it came from
            expected = _heikkinen(*ecef)
            np.testing.assert_allclose([lat, lon], np.degrees(expected[:2]), atol=1e-10)
            np.testing.assert_allclose(h, expected[2], atol=1e-5)
    # The datum is the origin; 1 km north moves the latitude by 1 km over the meridian's radius of curvature.
    lat, lon, h = enu_to_geodetic([[0.0, 1000.0, 0.0]], datum)[0]
    phi = math.radians(48.85)
    meridian = A * (1.0 - E2) / (1.0 - E2 * math.sin(phi) ** 2) ** 1.5
    assert lon == pytest.approx(2.35, abs=1e-12)
    assert math.radians(lat - 48.85) == pytest.approx(1000.0 / (meridian + 35.0), rel=1e-4)
    assert enu_to_geodetic([[0.0, 0.0, 0.0]], datum)[0] == pytest.approx([48.85, 2.35, 35.0], abs=1e-9)
    with pytest.raises(ValueError, match="latitude_deg"):
        GeodeticDatum(91.0, 0.0)


def test_nav_sat_fix_is_the_gnss_reading_on_the_datum(run, bag):
    messages, _ = bag
    std = SensorConfig().gnss_position_std
    for k, state in enumerate(run.host):
        for boat in range(BOATS):
            fix = messages[f"{_ns(boat)}/gps/fix"][k][1]
            assert fix.header.frame_id == f"eboat_{boat}/base_link"
            assert fix.status.status == 0 and fix.status.service == 1 and fix.position_covariance_type == 2
            ecef = _geodetic_to_ecef(math.radians(fix.latitude), math.radians(fix.longitude), fix.altitude)
            np.testing.assert_allclose(_ecef_to_enu(ecef, GUANABARA_BAY), state["readings"][boat, 0:3], atol=1e-5)
            variance = (std * state["noise_scale"][boat]) ** 2
            np.testing.assert_allclose(fix.position_covariance.reshape(3, 3), np.eye(3) * variance, rtol=1e-6)
            assert abs(fix.latitude - GUANABARA_BAY.latitude_deg) < 0.01  # within a kilometre of the datum


def test_imu_wind_and_tf(run, bag):
    messages, _ = bag
    config = SensorConfig()
    upward = []
    for k, state in enumerate(run.host):
        q = state["orientation"] / np.linalg.norm(state["orientation"], axis=1, keepdims=True)
        transforms = {t.child_frame_id: t for t in messages["/tf"][k][1].transforms}
        assert set(transforms) == {f"eboat_{b}/base_link" for b in range(BOATS)}
        for boat in range(BOATS):
            reading, scale = state["readings"][boat], state["noise_scale"][boat]
            imu = messages[f"{_ns(boat)}/imu/data"][k][1]
            assert imu.header.frame_id == f"eboat_{boat}/base_link"
            np.testing.assert_allclose([imu.orientation.x, imu.orientation.y, imu.orientation.z, imu.orientation.w],
                                       q[boat], atol=1e-6)
            gyro, accel = imu.angular_velocity, imu.linear_acceleration
            np.testing.assert_allclose([gyro.x, gyro.y, gyro.z], reading[9:12], atol=1e-6)
            np.testing.assert_allclose([accel.x, accel.y, accel.z], reading[6:9], atol=1e-6)
            upward.append(accel.z)
            np.testing.assert_allclose(np.diag(imu.angular_velocity_covariance.reshape(3, 3)),
                                       [(config.gyroscope_std * scale) ** 2] * 3, rtol=1e-6)
            np.testing.assert_allclose(np.diag(imu.linear_acceleration_covariance.reshape(3, 3)),
                                       [(config.accelerometer_std * scale) ** 2] * 3, rtol=1e-6)
            for topic in ("wind/true", "atmosferic_control/wind"):
                message = messages[f"{_ns(boat)}/{topic}"][k][1]
                vector = getattr(message, "vector", message)
                np.testing.assert_allclose([vector.x, vector.y, vector.z], state["wind"][boat], atol=1e-6)
            apparent = messages[f"{_ns(boat)}/wind/apparent"][k][1]
            assert apparent.header.frame_id == f"eboat_{boat}/base_link"
            v = apparent.vector
            np.testing.assert_allclose(math.hypot(v.x, v.y), reading[14], atol=1e-6)
            np.testing.assert_allclose(math.atan2(-v.y, -v.x), reading[13], atol=1e-6)  # where it comes from
            # The current in map: the episode's draw, speed toward direction (steady: the run has no tide).
            current = messages[f"{_ns(boat)}/current"][k][1]
            assert current.header.frame_id == "map"
            speed, direction = state["current_speed"][boat], state["current_direction"][boat]
            assert CURRENT_SPEED[0] <= speed <= CURRENT_SPEED[1]
            np.testing.assert_allclose([current.vector.x, current.vector.y, current.vector.z],
                                       [speed * math.cos(direction), speed * math.sin(direction), 0.0], atol=1e-6)
            pose = transforms[f"eboat_{boat}/base_link"]
            assert pose.header.frame_id == f"eboat_{boat}/odom"
            t, r = pose.transform.translation, pose.transform.rotation
            np.testing.assert_allclose([t.x, t.y, t.z], state["position"][boat], atol=1e-6)
            np.testing.assert_allclose([r.x, r.y, r.z, r.w], q[boat], atol=1e-6)
    assert 8.8 < np.mean(upward) < 10.8  # specific force: on average +g up on a floating boat (REP 145)


def test_static_transforms(run, bag):
    messages, _ = bag
    (log_time, static), = messages["/tf_static"]
    assert log_time == 0
    pairs = {(t.header.frame_id, t.child_frame_id): t.transform for t in static.transforms}
    lidar, camera = run.env.task.lidar, run.hook.camera.config
    for boat in range(BOATS):
        p = f"eboat_{boat}/"
        odom = pairs[("map", p + "odom")]
        assert (odom.translation.x, odom.translation.y, odom.translation.z, odom.rotation.w) == (0, 0, 0, 1)
        mount = pairs[(p + "base_link", p + "lidar_link")]
        np.testing.assert_allclose([mount.translation.x, mount.translation.y, mount.translation.z], lidar.mount)
        link = pairs[(p + "base_link", p + "camera_link")]
        np.testing.assert_allclose([link.translation.x, link.translation.y, link.translation.z], camera.mount)
        # camera pitched down by mount_rpy[1]: a rotation about y by that angle
        pitch = camera.mount_rpy[1]
        np.testing.assert_allclose([link.rotation.x, link.rotation.y, link.rotation.z, link.rotation.w],
                                   [0.0, math.sin(pitch / 2), 0.0, math.cos(pitch / 2)], atol=1e-9)
        optical = pairs[(p + "camera_link", p + "camera_optical_frame")].rotation
        # the optical frame's z (forward) is the link's x, its x (right) the link's -y
        w, x, y, z = optical.w, optical.x, optical.y, optical.z
        rotation = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                             [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                             [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
        np.testing.assert_allclose(rotation @ [0, 0, 1], [1, 0, 0], atol=1e-12)
        np.testing.assert_allclose(rotation @ [1, 0, 0], [0, -1, 0], atol=1e-12)
    assert len(pairs) == 4 * BOATS


def test_laser_scan_is_the_lidar(run, bag):
    messages, _ = bag
    lidar = run.env.task.lidar
    hits = 0
    for k, state in enumerate(run.host):
        for boat in range(BOATS):
            scan = messages[f"{_ns(boat)}/lidar/scan"][k][1]
            assert scan.header.frame_id == f"eboat_{boat}/lidar_link"
            assert scan.angle_min == pytest.approx(-math.pi, abs=1e-6)
            assert scan.angle_increment == pytest.approx(2.0 * math.pi / lidar.beams, rel=1e-6)
            assert scan.angle_max == pytest.approx(-math.pi + (lidar.beams - 1) * 2.0 * math.pi / lidar.beams,
                                                   abs=1e-5)
            assert (scan.range_min, scan.range_max) == (pytest.approx(lidar.min_range), lidar.max_range)
            assert scan.scan_time == pytest.approx(run.env.decision_period)
            returned = state["kinds"][boat] != int(HIT_NONE)
            np.testing.assert_array_equal(scan.ranges[returned], state["ranges"][boat][returned])
            assert np.all(np.isposinf(scan.ranges[~returned]))
            hits += int(returned.sum())
    assert hits > 0  # the buoys ahead show


def test_camera_images_are_the_renders(run, bag):
    messages, _ = bag
    config = run.hook.camera.config
    info = config.camera_info()
    for j, (time_ns, (rgb, depth)) in enumerate(sorted(run.images.items())):
        for boat in range(BOATS):
            image = messages[f"{_ns(boat)}/camera/image_raw"][j][1]
            assert (image.height, image.width, image.encoding, image.step) == (6, 8, "rgb8", 24)
            np.testing.assert_array_equal(image.data.reshape(6, 8, 3), rgb[boat])
            depth_image = messages[f"{_ns(boat)}/camera/depth/image_raw"][j][1]
            assert (depth_image.encoding, depth_image.is_bigendian, depth_image.step) == ("32FC1", 0, 32)
            np.testing.assert_array_equal(np.frombuffer(depth_image.data.tobytes(), "<f4").reshape(6, 8), depth[boat])
            for topic in ("camera/camera_info", "camera/depth/camera_info"):
                camera_info = messages[f"{_ns(boat)}/{topic}"][j][1]
                assert camera_info.header.frame_id == f"eboat_{boat}/camera_optical_frame"
                np.testing.assert_allclose(camera_info.k, info["K"])
                np.testing.assert_allclose(camera_info.p, info["P"])
                assert camera_info.distortion_model == "plumb_bob" and (camera_info.width, camera_info.height) == (8, 6)
        assert np.isfinite(depth).any()  # looking 10 deg down, the camera sees the sea a few metres ahead


# --- errors and the file's atomicity -------------------------------------------------------------------
def test_bad_paths_missing_libraries_and_atomic_writes(tmp_path, monkeypatch):
    for bad in ("run.bag", "run.mcap.tmp", tmp_path / ".mcap", 3):
        with pytest.raises(ValueError, match=r"\.mcap"):
            McapRecorder(bad if not isinstance(bad, str) else tmp_path / bad)
    assert check_record_path(tmp_path / "RUN.MCAP").endswith("RUN.MCAP")
    assert os.listdir(tmp_path) == []
    # Aborted, or an exception inside the block: no file, no temporary, an existing file left as it was.
    (tmp_path / "kept.mcap").write_bytes(b"old")
    McapRecorder(tmp_path / "kept.mcap").abort()
    with pytest.raises(RuntimeError):
        with McapRecorder(tmp_path / "new" / "x.mcap"):
            raise RuntimeError("stop")
    assert sorted(os.listdir(tmp_path)) == ["kept.mcap", "new"] and os.listdir(tmp_path / "new") == []
    assert (tmp_path / "kept.mcap").read_bytes() == b"old"
    log = McapRecorder(tmp_path / "empty.mcap")
    with pytest.raises(ValueError, match="SailingEnv"):
        log.record(object())
    assert log.close() == str(tmp_path / "empty.mcap") and (tmp_path / "empty.mcap").stat().st_size > 0
    with pytest.raises(ValueError, match="closed"):
        log.record(object())
    with pytest.raises(ValueError, match="prefix"):
        topics.boat_namespace(0, 2, "autopilot")
    monkeypatch.setitem(sys.modules, "mcap_ros2.writer", None)
    with pytest.raises(ImportError, match=r"pip install 'ocean-warp\[mcap\]'") as error:
        McapRecorder(tmp_path / "no_library.mcap")
    assert "\n" not in str(error.value) and not (tmp_path / "no_library.mcap").exists()


def test_cli_errors_are_one_line(tmp_path, capsys, monkeypatch):
    from ocean_warp import cli

    for job in ("demo", "eval"):
        with pytest.raises(SystemExit) as exit_info:
            cli.main([job, "--record", str(tmp_path / "run.bag"), "--out", str(tmp_path / job), "--no-progress"])
        assert exit_info.value.code == 2
        error = capsys.readouterr().err.strip().splitlines()
        assert len(error) == 1 and "--record" in error[0] and ".mcap" in error[0], error
    monkeypatch.setitem(sys.modules, "mcap_ros2.writer", None)
    for job in ("demo", "eval"):
        with pytest.raises(SystemExit) as exit_info:
            cli.main([job, "--record", str(tmp_path / "run.mcap"), "--out", str(tmp_path / job), "--no-progress"])
        assert exit_info.value.code == 2
        error = capsys.readouterr().err.strip().splitlines()
        assert len(error) == 1 and "pip install 'ocean-warp[mcap]'" in error[0], error
    assert os.listdir(tmp_path) == []


# --- the commands end to end ----------------------------------------------------------------------------
def _rows(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def test_eval_records_every_controller_under_its_namespace(tmp_path, capsys):
    """Two runs, 2 s each, policy and autopilot: each controller's runs under /<controller>/eboat_<i>, 3 records
    (the start and 2 decisions); the results are those of the same evaluation without --record."""
    common = ["--task", "EBoatWaypoint-v0", "--runs", "2", "--time-limit", "2", "--no-progress"]
    assert evaluation.main([*common, "--out", str(tmp_path / "plain")]) == 0
    record = tmp_path / "logs" / "eval.mcap"
    assert evaluation.main([*common, "--out", str(tmp_path / "logged"), "--record", str(record)]) == 0
    assert f"wrote {record}" in capsys.readouterr().out
    assert _rows(tmp_path / "plain" / "runs.csv") == _rows(tmp_path / "logged" / "runs.csv")
    messages, connections = _read(record)
    controllers = [row["controller"] for row in _rows(tmp_path / "logged" / "results.csv")]
    assert controllers == ["policy", "autopilot"]
    for name in controllers:
        for run_index in range(2):
            ns = f"/{name}/eboat_{run_index}"
            assert connections[f"{ns}/gps/fix"].msgcount == 3
            assert connections[f"{ns}/control_interface/rudder"].msgcount == 2
            assert [t for t, _ in messages[f"{ns}/imu/data"]] == [0, 1_000_000_000, 2_000_000_000]
    assert connections["/clock"].msgcount == 3 and connections["/tf"].msgcount == 6
    assert connections["/tf_static"].msgcount == 2
    # The paths in trajectories.npz (from each run's origin) are the logged poses after the first decision.
    paths = np.load(tmp_path / "logged" / "trajectories.npz")
    task = evaluation.evaluation_task("EBoatWaypoint-v0")
    origins = environment_origins(2, task.simulator.ocean.tile_size, task.ocean_spacing)
    poses = {t.child_frame_id: t.transform.translation for _, m in messages["/tf"] for t in m.transforms
             if _stamp_ns(t.header) == 1_000_000_000}
    for name in controllers:
        for run_index in range(2):
            where = poses[f"{name}/eboat_{run_index}/base_link"]
            np.testing.assert_allclose([where.x - origins[run_index, 0], where.y - origins[run_index, 1]],
                                       [paths[f"{name}_x"][run_index, 1], paths[f"{name}_y"][run_index, 1]],
                                       atol=1e-5)


def test_demo_records_a_single_boat_under_the_seed_namespace(tmp_path, capsys):
    from ocean_warp import cli

    record = tmp_path / "demo.mcap"
    cli.main(["demo", "--task", "EBoatWaypoint-v0", "--boats", "1", "--time-limit", "2", "--no-usd", "--out",
              str(tmp_path / "out"), "--no-progress", "--record", str(record)])
    assert f"wrote {record}" in capsys.readouterr().out
    messages, connections = _read(record)
    assert {topic for topic in connections if topic.startswith("/eboat/")} == {
        f"/eboat/{name}" for name in topics.BOAT_TOPICS if not name.startswith(("camera", "lidar"))}
    assert connections["/eboat/mission_control/observations"].msgcount == 3
    assert connections["/eboat/control_interface/propulsion"].msgcount == 2
    (_, static), = messages["/tf_static"]
    assert [(t.header.frame_id, t.child_frame_id) for t in static.transforms] == [("map", "odom")]
    for _, message in messages["/tf"]:
        assert [(t.header.frame_id, t.child_frame_id) for t in message.transforms] == [("odom", "base_link")]
    assert messages["/eboat/gps/fix"][0][1].header.frame_id == "base_link"
    from mcap.reader import make_reader

    with open(record, "rb") as handle:
        metadata = {m.name: m.metadata for m in make_reader(handle).iter_metadata()}
    assert metadata["ocean_warp.demo"] == {"boat_0": "autopilot"}  # which controller sails each boat
    assert metadata["ocean_warp.env"]["boats"] == "1"
    assert sorted(os.listdir(tmp_path)) == ["demo.mcap", "out"]


def test_topic_builders_give_ros2_field_names():
    """Every dict a builder gives has exactly the fields of its ROS 2 type (a misspelt field would be written
    as its default by the encoder, silently)."""
    rng = np.random.default_rng(0)
    n = 2
    state = topics.BoatSnapshot(
        time_ns=1_500_000_000, position=rng.normal(size=(n, 3)), orientation=np.tile([0.0, 0.0, 0.0, 1.0], (n, 1)),
        velocity=rng.normal(size=(n, 6)), target=rng.normal(size=(n, 3)), wind_velocity=rng.normal(size=(n, 3)),
        current_velocity=rng.normal(size=(n, 3)), truth=rng.normal(size=(n, 16)), readings=rng.normal(size=(n, 16)),
        boom_angle=rng.normal(size=n),
        rudder_angle=rng.normal(size=n), propeller_level=np.array([3, -2]), noise_scale=np.ones(n),
        sensor_std=SensorConfig().channel_noise().astype(np.float64))
    built = topics.state_messages(state, prefix="/x") + topics.command_messages(0, [0.1, 0.2], [0.3, 0.4], [1, 2])
    built += [topics.static_messages(n, 0, lidar_config=AvoidConfig().lidar), topics.clock_message(7)]

    def check(fields, type_name):
        _, definitions = HUMBLE.fielddefs[type_name]
        assert set(fields) == {name for name, _ in definitions}, type_name
        for name, (kind, detail) in definitions:
            if kind.name == "NAME":
                check(fields[name], detail)
            elif kind.name == "ARRAY":
                assert len(fields[name]) == detail[1], (type_name, name)
            elif kind.name == "SEQUENCE" and detail[0][0].name == "NAME":
                for item in fields[name]:
                    check(item, detail[0][1])

    for message in built:
        check(message.fields, message.type)
    assert {m.topic for m in built if m.topic.startswith("/x/")} >= {"/x/eboat_0/gps/fix", "/x/eboat_1/imu/data"}
    assert topics.frame_id("/eboat", "base_link") == "base_link"
    assert topics.frame_id("/autopilot/eboat", "odom") == "autopilot/eboat/odom"
    assert mcap_log.MCAP_INSTALL_HINT == "pip install 'ocean-warp[mcap]'"
