"""A boat's controller as a ROS 1 node: an exported policy (``ocean-warp export-policy``, ONNX) answers every
observation on the seed's topics with the seed's commands. It speaks only ROS, so the same node drives the
simulator (``ocean-warp ros``) and the real boat.

    python3 ocean_warp/ros/controller_node.py --policy eboat_waypoint.onnx              # boat /eboat
    python3 ocean_warp/ros/controller_node.py --policy p.onnx --namespace /eboat_2 --lost-distance 125

It subscribes to ``<namespace>/mission_control/observations`` (std_msgs/Float32MultiArray, the seed's 9 raw
values: distance to the waypoint [m], its bearing from the bow [deg, positive to port], speed [m/s], apparent
wind speed [m/s] and angle [deg], boom [deg], rudder [deg], propeller level, roll [deg]), builds the policy's
observation from the first five exactly as the seed task scales them (``envs/tasks/observation_blocks.seed_columns``):

    2 d / d_lost - 1,  bearing / 180,  u / 5 - 1,  apparent wind speed / 15 - 1,  apparent wind angle / 180

each clipped to [-1, 1], d_lost = the leg's length + the lost margin (--lost-distance, the seed's 100 + 25 m),
runs the policy (onnxruntime), clips its actions to [-1, 1] and publishes, in this order,
``<namespace>/control_interface/sail`` (Float32, (a1 + 1) 45 deg), ``control_interface/rudder`` (Float32,
60 a2 deg, positive turns to port) and ``control_interface/propulsion`` (Int16, int(5 a0), truncated toward
zero; 0 for a policy of a task without propeller). Only policies of the seed's observation set are accepted:
its 5 values, or 6 for a task with a reef rule (``EBoatMission-v0``), whose sixth is the rig's reef level as the
crew set it (``--reef-level``: 0 the full sail, 1, 2 the deepest reef), seen as level / 2. An observation that is not 9 finite numbers is ignored with a warning.

Imports: numpy, onnxruntime and rospy only (no torch, no Warp). Run this file by its path, as above: it loads
``onnx_policy.py`` and ``ros1.py`` from its own folder by path, not through the ``ocean_warp`` package (whose
``__init__`` imports Warp), so the three files copied onto the boat's computer are enough
(``python -m ocean_warp.ros.controller_node`` works too, but imports Warp with the package).
Without a ROS master it exits at once with one line (status 2); Ctrl-C or SIGTERM stop it cleanly.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import os
import signal
import sys
import threading
import time

import numpy as np

__all__ = ["SEED_POLICY_OBS", "DEFAULT_LOST_DISTANCE", "policy_observation", "commands_from_actions", "main"]

PROG = "controller_node.py"
"""The name in its usage and messages: the file is run by its path (no ``ocean-warp`` job runs it)."""
SEED_POLICY_OBS = 5
"""Values of the seed observation set."""
REEF_LEVELS = 3
"""The E-Boat's rigs: the full sail and two reefs (``EBoatConfig.reef_areas``)."""
SEED_RAW_VALUES = 9
"""Values on mission_control/observations (``ocean_warp.ros.topics.SEED_OBSERVATION``)."""
DEFAULT_LOST_DISTANCE = 125.0
"""The seed's d_lost [m]: its 100 m leg plus the 25 m lost margin."""
OBSERVATIONS = "mission_control/observations"
CONNECT_WAIT_S = 2.0
"""How long the first answer waits for subscribers on the command topics [s, wall clock]."""
SAIL, RUDDER, PROPULSION = "control_interface/sail", "control_interface/rudder", "control_interface/propulsion"


def _sibling(name: str):
    """``ocean_warp.ros.<name>`` where the package is loaded already, else the file ``<name>.py`` beside this
    one, loaded by its path under a private name (no ``ocean_warp`` package, so no Warp)."""
    loaded = sys.modules.get(f"ocean_warp.ros.{name}")
    if loaded is not None:
        return loaded
    private = f"_ocean_warp_ros_{name}"
    if private in sys.modules:
        return sys.modules[private]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), f"{name}.py")
    spec = importlib.util.spec_from_file_location(private, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[private] = module
    spec.loader.exec_module(module)
    return module


def policy_observation(raw, lost_distance: float = DEFAULT_LOST_DISTANCE, reef_level: int | None = None) -> np.ndarray:
    """The seed policy's 5 observation values (float32) from the 9 raw values of mission_control/observations
    (see the module's docstring), and a sixth, ``reef_level`` / 2, where a reef level is given (a policy of a
    task with a reef rule); ``ValueError`` unless ``raw`` is 9 finite numbers and the level one of the rigs."""
    if reef_level is not None and (isinstance(reef_level, bool) or reef_level not in range(REEF_LEVELS)):
        raise ValueError(f"reef_level must be None or one of 0..{REEF_LEVELS - 1}, got {reef_level!r}")
    values = np.asarray(raw, dtype=np.float64).reshape(-1)
    if values.size != SEED_RAW_VALUES or not np.all(np.isfinite(values)):
        raise ValueError(f"an observation must be {SEED_RAW_VALUES} finite numbers, got {values.size} "
                         f"({int(np.sum(~np.isfinite(values)))} not finite)")
    distance, bearing, speed, wind_speed, wind_angle = values[:5]
    scaled = [2.0 * distance / lost_distance - 1.0, bearing / 180.0, speed / 5.0 - 1.0, wind_speed / 15.0 - 1.0,
              wind_angle / 180.0]
    if reef_level is not None:
        scaled.append(reef_level / (REEF_LEVELS - 1))
    return np.clip(np.asarray(scaled), -1.0, 1.0).astype(np.float32)


def commands_from_actions(actions, *, propeller: bool = True) -> tuple[float, float, int]:
    """(sail [deg], rudder [deg], propeller level) of the policy's actions (clipped to [-1, 1] here), as the
    task maps them: (a1 + 1) 45 deg, 60 a2 deg, int(5 a0) truncated toward zero (0 without ``propeller``)."""
    a0, a1, a2 = (float(v) for v in np.clip(np.asarray(actions, dtype=np.float64).reshape(-1)[:3], -1.0, 1.0))
    level = int(math.trunc(5.0 * a0)) if propeller else 0
    return (a1 + 1.0) * 45.0, 60.0 * a2, level


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--policy", required=True, metavar="FILE.onnx",
                        help="an exported policy of the seed's observation set (ocean-warp export-policy)")
    parser.add_argument("--namespace", default="/eboat", help="the boat's namespace (default /eboat)")
    parser.add_argument("--lost-distance", type=float, default=DEFAULT_LOST_DISTANCE, metavar="METRES",
                        help="d_lost of the distance's scaling: the leg's length + the lost margin [m] (default 125)")
    parser.add_argument("--reef-level", type=int, default=None, choices=range(REEF_LEVELS), metavar="LEVEL",
                        help="the rig's reef level as set on the boat (0 full, 1, 2; needed by a policy that sees it)")
    parser.add_argument("--name", default="eboat_controller", help="the node's name (made unique with a suffix)")
    return parser


def _error(message: str) -> int:
    print(f"{PROG}: error: {message}", file=sys.stderr)
    return 2


class _Controller:
    """The subscriber's callback: observation -> policy -> commands (rospy's thread)."""

    def __init__(self, rospy, policy, namespace: str, lost_distance: float, reef_level: int | None = None):
        from std_msgs.msg import Float32, Int16

        self.rospy, self.policy, self.lost_distance = rospy, policy, lost_distance
        self.reef_level = reef_level
        self.Float32, self.Int16 = Float32, Int16
        meaning = policy.action_meaning
        self.propeller = not (meaning and "ignored" in meaning[0])
        ns = namespace.rstrip("/")
        self.sail = rospy.Publisher(f"{ns}/{SAIL}", Float32, queue_size=10)
        self.rudder = rospy.Publisher(f"{ns}/{RUDDER}", Float32, queue_size=10)
        self.level = rospy.Publisher(f"{ns}/{PROPULSION}", Int16, queue_size=10)
        self.answered = 0
        self._lock = threading.Lock()
        self._connected = False

    def _wait_for_listeners(self) -> None:
        """Before the first answer: wait up to CONNECT_WAIT_S for a subscriber on each command topic (rospy drops
        what a publisher sends before its subscribers connected; the first observation can come sooner, a
        latched one at once)."""
        if self._connected:
            return
        deadline = time.monotonic() + CONNECT_WAIT_S
        publishers = (self.sail, self.rudder, self.level)
        while any(p.get_num_connections() == 0 for p in publishers) and time.monotonic() < deadline:
            time.sleep(0.02)
        self._connected = all(p.get_num_connections() > 0 for p in publishers)
        if not self._connected:
            self.rospy.logwarn_throttle(10.0, f"{PROG}: nobody listens to every command topic yet; sending anyway")

    def __call__(self, message) -> None:
        try:
            observation = policy_observation(message.data, self.lost_distance, self.reef_level)
        except ValueError as error:
            self.rospy.logwarn_throttle(1.0, f"{PROG}: ignored an observation: {error}")
            return
        sail, rudder, level = commands_from_actions(self.policy.act(observation), propeller=self.propeller)
        self._wait_for_listeners()
        with self._lock:  # one observation's three commands together
            self.sail.publish(self.Float32(sail))
            self.rudder.publish(self.Float32(rudder))
            self.level.publish(self.Int16(level))
            self.answered += 1


def main(argv=None) -> int:
    """Run the controller until Ctrl-C or SIGTERM (0); 2 with one line for bad options, a policy that does
    not fit, no rospy or no master."""
    argv = sys.argv[1:] if argv is None else list(argv)
    ros1 = _sibling("ros1")
    remaps, rest = ros1.split_remaps(argv)
    args = _parser().parse_args(rest)
    if not (math.isfinite(args.lost_distance) and args.lost_distance > 0):
        return _error(f"--lost-distance must be a number > 0 [m], got {args.lost_distance}")
    if not args.namespace.startswith("/"):
        return _error(f"--namespace must be an absolute ROS name such as /eboat, got {args.namespace!r}")
    onnx_policy = _sibling("onnx_policy")
    try:
        policy = onnx_policy.OnnxPolicy(args.policy)
    except (ImportError, FileNotFoundError, ValueError) as error:
        return _error(str(error))
    if policy.observation != "seed" or policy.num_obs not in (SEED_POLICY_OBS, SEED_POLICY_OBS + 1):
        return _error(f"{args.policy}: the policy reads observation set {policy.observation!r} ({policy.num_obs} "
                      f"values); the seed's topics carry the seed set's {SEED_POLICY_OBS} only (and the reef level)")
    sees_reef = policy.num_obs == SEED_POLICY_OBS + 1
    if sees_reef and args.reef_level is None:
        return _error(f"{args.policy}: the policy sees the rig's reef level; pass --reef-level (0 full, 1, 2)")
    reef_level = args.reef_level if sees_reef else None
    try:
        rospy = ros1.import_rospy()
    except ros1.RosUnavailable as error:
        return _error(str(error))
    uri = ros1.master_uri(remaps)
    if not ros1.master_online(uri):
        return _error(ros1.no_master_text(uri))
    stop = threading.Event()
    controller = None
    for number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(number, lambda number, frame: stop.set())
    try:
        rospy.init_node(args.name, argv=[PROG] + remaps, anonymous=True, disable_signals=True)
        from std_msgs.msg import Float32MultiArray

        controller = _Controller(rospy, policy, args.namespace, args.lost_distance, reef_level)
        rospy.Subscriber(f"{args.namespace.rstrip('/')}/{OBSERVATIONS}", Float32MultiArray, controller, queue_size=1)
        rospy.loginfo(f"{PROG}: {policy.describe()}; answering {args.namespace.rstrip('/')}/{OBSERVATIONS}")
        while not stop.is_set() and not rospy.is_shutdown():
            stop.wait(0.1)
    finally:
        # The handlers stay: a second Ctrl-C during the shutdown must not raise KeyboardInterrupt.
        rospy.signal_shutdown("controller stopped")
    print(f"{PROG}: stopped; answered {0 if controller is None else controller.answered} observation(s)", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
