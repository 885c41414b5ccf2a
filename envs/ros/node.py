"""ocean-warp ros: the simulator as a ROS 1 node (rospy, from Debian's packages), or with --ros 2 a ROS 2 node
(rclpy; written against rclpy's documented API and checked only with fakes, never with a real rclpy).

    roscore &
    ocean-warp ros                                       # one boat of EBoatMission-v0, in real time
    ocean-warp ros --boats 4 --rate-factor 10 --record out/ros/run.mcap
    ocean-warp ros --lockstep --as-fast-as-possible      # each decision waits for a controller's commands
    ocean-warp ros /eboat/gps/fix:=/fix                  # rospy's remapping arguments

One boat sails under /eboat (the seed twin's namespace), several under /eboat_0, /eboat_1, ... The simulated
time is published on /clock (the node sets /use_sim_time true while it runs) at every decision and, between
decisions, every 1/--clock-hz s of simulated time (default 20 Hz; spread over the wall time of each decision at
a rate factor, all at once before each decision when sailing as fast as possible or in lockstep), so sim-time
timers tick evenly. Once per decision (every 1 s of simulated time in every task; at --rate-factor times real
time) each boat publishes:

  mission_control/observations  std_msgs/Float32MultiArray  the seed's 9 values (distance [m], bearing [deg],
                                                            speed [m/s], apparent wind [m/s, deg], boom,
                                                            rudder [deg], propeller level, roll [deg])
  atmosferic_control/wind       geometry_msgs/Point         true wind velocity, ENU [m/s]
  gps/fix                       sensor_msgs/NavSatFix       WGS 84 (the world origin in Guanabara Bay)
  imu/data                      sensor_msgs/Imu             attitude, gyro, accelerometer (base_link, FLU)
  wind/true, wind/apparent      geometry_msgs/Vector3Stamped true wind in map, apparent in base_link [m/s]
  current                       geometry_msgs/Vector3Stamped the water's current at the surface, in map [m/s]
  lidar/scan                    sensor_msgs/LaserScan       with a lidar (the avoidance tasks, or --lidar)
  camera/image_raw, camera/camera_info, camera/depth/...    with --camera
  mission_control/episode       std_msgs/Float32MultiArray  when an episode ends: success, waypoints,
                                                            decisions, return, status flags, end reason
                                                            (0 reached, 1 capsized, 2 collided, 3 flagged,
                                                            4 time-out, 5 lost), boat, time [s]

and /tf (odom -> base_link of every boat), /tf_static (latched: map -> odom, sensor mounts). It subscribes to
each boat's control_interface/sail (Float32, sheet: largest boom angle 0 to 90 deg), control_interface/rudder
(Float32, -60 to 60 deg, positive to port), control_interface/propulsion (Int16, level -5 to 5) and
atmosferic_control/wind (Point, sets the boat's mean true wind [m/s], ENU; the node's own messages on it are
ignored). A command holds until the next; one that is NaN, infinite or out of range is ignored with a warning.
The service ~reset (/ocean_warp/reset, std_srvs/Trigger) restarts every boat from --seed; the clock goes on
(one decision after the last time published: it never runs back, in the --record log neither).
Without a ROS master (ROS 1) the node exits at once with one line (status 2); ROS 2 has no master to
check (rospy-style remaps become --ros-args -r from:=to there, and the service is ~/reset). Ctrl-C (or
SIGTERM) stops it cleanly and finishes the --record file. ocean_warp.ros.topics says what every topic
holds (frames: REP 103, 105).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys

from ocean_warp.cli_support import (check_options, checked_device, checked_output_file, fail, finite_above,
                                    finite_at_least, plural, report_error)
from ocean_warp.ocean_config import SIGNIFICANT_WAVE_HEIGHT_RULE, is_valid_significant_wave_height

from ocean_warp.ros import ros1
from ocean_warp.ros.node_loop import PROG, RESET_SERVICE, NodeLoop
from ocean_warp.ros.ros1_bus import Ros1Bus
from ocean_warp.ros.topics import (BOAT_TOPICS, GLOBAL_TOPICS, NODE_TOPICS, boat_namespace, camera_messages,
                                   clock_message, env_lidar, episode_messages, lidar_messages, snapshot, state_messages,
                                   static_messages)

from .node_options import DEFAULT_CLOCK_HZ, MAX_CLOCK_HZ, parser as _parser

__all__ = ["DEFAULT_CLOCK_HZ", "NODE_NAME", "RESET_SERVICE", "main"]
NODE_NAME = "ocean_warp"
_CLOCK_MARGIN_NS = 1_000
"""Ticks closer than this [ns] to the next decision are left to it (the simulator's clock sums float64 steps)."""


def _check(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    check_options(parser, (
        ("--boats", args.boats, args.boats >= 1, "a whole number >= 1"),
        ("--rate-factor", args.rate_factor, finite_at_least(args.rate_factor, 0.0), "a finite number >= 0"),
        ("--clock-hz", args.clock_hz, finite_at_least(args.clock_hz, 0.0) and args.clock_hz <= MAX_CLOCK_HZ,
         f"a number from 0 to {MAX_CLOCK_HZ:g} [Hz]"),
        ("--duration", args.duration, args.duration is None or finite_above(args.duration, 0.0), "a number > 0 [s]"),
        ("--lockstep-timeout", args.lockstep_timeout, finite_at_least(args.lockstep_timeout, 0.0),
         "a finite number >= 0 [s]"),
        ("--sea-state", args.sea_state, args.sea_state is None or is_valid_significant_wave_height(args.sea_state),
         SIGNIFICANT_WAVE_HEIGHT_RULE),
        ("--wind", args.wind, args.wind is None or finite_at_least(args.wind, 0.0), "a finite number >= 0 [m/s]"),
    ))
    if args.lockstep_timeout and not args.lockstep:
        fail(parser, "--lockstep-timeout needs --lockstep")
    if args.record is not None:
        from .mcap_log import check_record_path

        try:
            check_record_path(args.record)
        except (ValueError, ImportError) as error:
            fail(parser, f"--record: {error}")


def _known_names(boats: int, namespace: str, node: str) -> set[str]:
    """Every topic and service of the node, resolved (what a remapping may name)."""
    relative = [f"{boat_namespace(b, boats)[1:]}/{topic}" for b in range(boats)
                for topic in list(BOAT_TOPICS) + list(NODE_TOPICS)]
    return ({ros1.resolve(name, namespace, node) for name in relative} | set(GLOBAL_TOPICS)
            | {ros1.resolve(RESET_SERVICE, namespace, node)})


def _node_name(remaps) -> str:
    return next((arg.split(":=", 1)[1] for arg in remaps if arg.startswith("__name:=")), NODE_NAME)


def main(argv=None) -> int:
    """``ocean-warp ros [options] [name:=new ...]``: returns 0 when it stopped (duration reached, Ctrl-C,
    SIGTERM, rospy shut down); 2 with one line for bad options, no rospy, no master or an unknown remapping."""
    argv = sys.argv[1:] if argv is None else list(argv)
    remaps, rest = ros1.split_remaps(argv)
    parser = _parser()
    args = parser.parse_args(rest)
    _check(parser, args)
    from ocean_warp.envs.apps.fleet_scenario import checked_task_name

    try:
        task_id = checked_task_name(args.task)
    except ValueError as error:
        fail(parser, str(error))
    device = checked_device(parser, args.device)
    if args.record is not None:
        checked_output_file(parser, args.record, "--record", (".mcap",))
    namespace = ros1.namespace_of(remaps)
    node = ros1.resolve(_node_name(remaps), namespace, "/")
    problem = ros1.unknown_remap(remaps, _known_names(args.boats, namespace, node), namespace, node)
    if problem is not None:
        return report_error(PROG, problem)
    try:
        version, client = _ros_client(args.ros)
    except ImportError as error:
        return report_error(PROG, str(error))
    uri = None
    if version == 1:  # ROS 2 has no master (DDS discovery): nothing to check
        uri = ros1.master_uri(remaps)
        if not ros1.master_online(uri):
            return report_error(PROG, ros1.no_master_text(uri))
    try:
        sim = _Simulation.build(args, task_id, device)
    except ValueError as error:
        fail(parser, str(error))
    recorder = None
    if args.record is not None:
        from .mcap_log import McapRecorder

        recorder = McapRecorder(args.record)
    if version == 1:
        bus = Ros1Bus(client, uri, remaps, node_name=NODE_NAME, program=PROG)
    else:
        from ocean_warp.ros.ros2_bus import Ros2Bus

        bus = Ros2Bus(client, remaps, node_name=NODE_NAME, program=PROG)
    try:
        bus.start()
    except Exception as error:  # noqa: BLE001 - rospy's/rclpy's init and the master's XML-RPC raise many kinds
        if recorder is not None:
            recorder.abort()
        bus.stop("ocean-warp ros could not start")
        print(f"{PROG}: could not start the ROS node: {type(error).__name__}: {error}", file=sys.stderr)
        return 1
    try:
        runner = NodeLoop(sim, bus, args, recorder)
        summary = runner.run()
    except BaseException:
        if recorder is not None:
            recorder.abort()
        raise
    finally:
        bus.stop("ocean-warp ros stopped")
    if recorder is not None:
        recorder.close()
        summary += f"; wrote {args.record} ({plural(recorder.messages_written, 'message')})"
    print(f"{PROG}: {summary}", flush=True)
    return 0


def _ros_client(choice: str):
    """(1 or 2, the rospy or rclpy module) for ``--ros`` ``choice``: "1", "2", or "auto" (ROS 1 where rospy is
    found, else ROS 2 where rclpy imports); an ImportError of one line naming what is missing otherwise."""
    from ocean_warp.ros.ros2_bus import Ros2Unavailable, import_rclpy

    if choice in ("1", "auto"):
        try:
            return 1, ros1.import_rospy()
        except ros1.RosUnavailable as error:
            if choice == "1":
                raise
            missing = str(error)
    try:
        return 2, import_rclpy()
    except Ros2Unavailable as error:
        if choice == "2":
            raise
        raise ImportError(f"{missing}; {error}") from None


# --- the simulation ---------------------------------------------------------------------------------------
@dataclasses.dataclass
class _Simulation:
    """The env and the sensors the node publishes beside its own: a lidar hook (--lidar, a task without a
    lidar), a camera hook (--camera)."""

    env: object
    task_id: str
    seed: int
    lidar_hook: object = None
    camera_hook: object = None
    time_offset_ns: int = 0
    """Added to the simulator's clock in everything published and logged: the time before the last reset plus
    one decision, so the node's time never runs back."""

    @classmethod
    def build(cls, args, task_id: str, device) -> _Simulation:
        from ocean_warp.envs import SailingEnv
        from ocean_warp.envs.apps.fleet_scenario import fleet_course_task

        config = fleet_course_task(sea_state=args.sea_state, wind=args.wind, seed=args.seed, time_limit=None,
                                   hull=args.hull, loop_period=None, device=device, task=task_id)
        env = SailingEnv(config, args.boats, device=device, seed=args.seed)
        sim = cls(env, task_id, args.seed)
        rate = 1.0 / env.decision_period
        if args.lidar and env_lidar(env) is None:
            from ocean_warp.envs.sensors import LidarHook
            from ocean_warp.envs.tasks.task_configs import avoid_lidar

            sim.lidar_hook = LidarHook(env, avoid_lidar(rate=rate))
            env.attach(sim.lidar_hook)
        if args.camera:
            from ocean_warp.envs.sensors import CameraHook
            from ocean_warp.perception import CameraConfig

            sim.camera_hook = CameraHook(env, CameraConfig(rate=rate))
            env.attach(sim.camera_hook)
        return sim

    @property
    def boats(self) -> int:
        return self.env.num_envs

    def clock_ns(self) -> int:
        """The node's simulated time [ns]: the simulator's clock plus the offset of the resets."""
        return int(round(float(self.env.simulator.time) * 1e9)) + self.time_offset_ns

    def time_s(self) -> float:
        """The node's simulated time [s] (:meth:`clock_ns`)."""
        return self.clock_ns() / 1e9

    def clock_ticks(self, clock_hz: float) -> list:
        """/clock messages every 1/``clock_hz`` s of simulated time after now and before the next decision
        (none for ``clock_hz`` 0)."""
        if clock_hz <= 0.0:
            return []
        now, step = self.clock_ns(), round(1e9 / clock_hz)
        end = now + round(float(self.env.decision_period) * 1e9) - _CLOCK_MARGIN_NS
        return [clock_message(t) for t in range(now + step, end, step)]

    def messages(self, *, with_static: bool) -> list:
        """Every message of the state now: /clock, /tf_static (``with_static``), the state topics and /tf,
        the lidar's scan and the camera's images."""
        env = self.env
        state = snapshot(env, self.time_offset_ns)
        t = state.time_ns
        lidar, scan_time = self._lidar()
        messages = [clock_message(t)]
        if with_static:
            messages.append(static_messages(self.boats, t, lidar_config=None if lidar is None else lidar.config,
                                            camera=None if self.camera_hook is None else self.camera_hook.camera))
        messages += state_messages(state)
        if lidar is not None:
            messages += lidar_messages(lidar, t, scan_time=scan_time)
        if self.camera_hook is not None:
            messages += camera_messages(self.camera_hook.camera, self.boats, t)
        return messages

    def _lidar(self):
        if self.lidar_hook is not None:
            return self.lidar_hook.lidar, float(self.lidar_hook.period * self.env.task.simulator.dt)
        own = env_lidar(self.env)
        return (own, float(self.env.decision_period)) if own is not None else (None, 0.0)

    def step(self, actions, winds: dict) -> list:
        """One decision with ``actions`` (N, 3) after setting the ``winds`` (boat -> (speed [m/s], direction
        [rad])); returns the episode-end messages of the boats whose episode ended (their held wind is set
        again on the new episode by the caller)."""
        import torch

        for boat, (speed, direction) in winds.items():
            self.set_wind(boat, speed, direction)
        env = self.env
        env.step(torch.from_numpy(actions).to(env.torch_device))
        b = env.buffers
        done = b.done.cpu().numpy()
        if not done.any():
            return []
        host = lambda tensor: tensor.cpu().numpy()  # noqa: E731
        return episode_messages(self.clock_ns(), done, host(b.final_success), host(b.final_waypoints),
                                host(b.final_length), host(b.final_return), host(b.final_status), host(b.time_out))

    def set_wind(self, boat: int, speed: float, direction: float) -> None:
        """Boat ``boat``'s mean true wind: ``speed`` [m/s] blowing towards ``direction`` [rad], its gusts kept."""
        wind = self.env.simulator.wind
        gust = float(wind.state.gust_scale.numpy()[boat])
        wind.set([boat], speed=speed, direction=direction, gust_scale=gust)

    def reset(self) -> None:
        """Every boat from the seed again; the node's clock goes on one decision after now."""
        next_ns = self.clock_ns() + round(float(self.env.decision_period) * 1e9)
        self.env.reset(seed=self.seed)
        self.time_offset_ns = next_ns - int(round(float(self.env.simulator.time) * 1e9))
