"""A ROS 1 client for the node's tests, run as its own process (rospy stays out of pytest's): it watches topics
or sends commands and prints one JSON object. Imports rospy through ``ocean_warp/ros/ros1.py`` loaded by its
path (no Warp, no torch). Waits end on what arrives (a count of observations, a span of the simulated clock),
with wall-clock limits only as hang guards, so a loaded machine makes them slower, never wrong.

    ros_driver.py watch --clock-span 12 --topic /clock --topic /eboat/gps/fix ...
    ros_driver.py commands --namespace /eboat
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import os
import sys
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def _ros1():
    spec = importlib.util.spec_from_file_location("_ros1", os.path.join(ROOT, "ocean_warp", "ros", "ros1.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


ros1 = _ros1()
rospy = ros1.import_rospy()


class Clock:
    """The latest /clock [s] and every tick seen."""

    def __init__(self):
        from rosgraph_msgs.msg import Clock as ClockMessage

        self.now = None
        self.ticks: list[float] = []
        self._lock = threading.Lock()
        rospy.Subscriber("/clock", ClockMessage, self._on, queue_size=100)

    def _on(self, message) -> None:
        with self._lock:
            self.now = message.clock.to_sec()
            self.ticks.append(self.now)


def _stamp(message):
    header = getattr(message, "header", None)
    if header is not None:
        return header.stamp.to_sec()
    transforms = getattr(message, "transforms", None)
    if transforms:
        return transforms[0].header.stamp.to_sec()
    return None


def _data(message):
    return list(message.data) if message._type == "std_msgs/Float32MultiArray" else None


def watch(args) -> dict:
    """Every message of the topics until the clock has advanced ``--clock-span`` s of simulated time since every
    topic delivered its first (or the first on ``--until``; at most ``--seconds`` of wall clock): per topic, its
    type, the /clock at arrival, the header stamp (None without one) and, for a Float32MultiArray, its data.
    Prints {"ready": [...]} once subscribed."""
    import rosgraph

    master = rosgraph.Master(rospy.get_caller_id())
    clock = Clock()
    seen: dict[str, list] = {topic: [] for topic in args.topic}
    types: dict[str, str] = {}
    deadline = time.monotonic() + args.wait
    subscribed, subscribers = set(), []
    while len(subscribed) < len(args.topic) and time.monotonic() < deadline:
        published = dict(master.getTopicTypes())
        for topic in args.topic:
            if topic in subscribed or topic == "/clock":
                subscribed.add(topic)
                continue
            if topic not in published:
                continue
            cls = ros1.message_class(published[topic])
            types[topic] = cls._type
            subscribers.append(rospy.Subscriber(topic, cls, lambda m, t=topic: seen[t].append(
                (clock.now, _stamp(m), _data(m))), queue_size=100))
            subscribed.add(topic)
        time.sleep(0.1)
    while any(s.get_num_connections() == 0 for s in subscribers) and time.monotonic() < deadline:
        time.sleep(0.05)  # connected to the node's publishers
    print(json.dumps({"ready": sorted(subscribed)}), flush=True)
    start, first = time.monotonic(), None
    while time.monotonic() - start < args.seconds:
        if args.until and len(seen.get(args.until, ())) >= 1:
            break
        if first is None:
            # The span starts once every topic has delivered: under load a connected subscriber can still wait
            # for its first message (in a loaded CI run one topic's came 10 s of clock after the others')
            if all(seen[topic] for topic in args.topic if topic != "/clock"):
                first = clock.now
        elif args.clock_span is not None and clock.now - first >= args.clock_span:
            break
        time.sleep(0.05)
    return {"types": types, "ticks": list(clock.ticks), "missing": sorted(set(args.topic) - subscribed),
            "messages": {topic: list(items) for topic, items in seen.items() if topic != "/clock"}}


def commands(args) -> dict:
    """Rudder commands and the rudder angle the observations report back: 30 deg, then NaN (to be ignored),
    then -20 deg; then the reset service."""
    from std_msgs.msg import Float32, Float32MultiArray
    from std_srvs.srv import Trigger

    ns = args.namespace
    clock = Clock()
    observed: list[tuple] = []
    rospy.Subscriber(f"{ns}/mission_control/observations", Float32MultiArray,
                     lambda m: observed.append((clock.now, list(m.data))), queue_size=100)
    rudder = rospy.Publisher(f"{ns}/control_interface/rudder", Float32, queue_size=10)
    deadline = time.monotonic() + args.wait
    while (rudder.get_num_connections() == 0 or not observed) and time.monotonic() < deadline:
        time.sleep(0.05)
    result = {"connected": rudder.get_num_connections() > 0}

    def settle(count: int) -> list:
        """The next ``count`` observations' (clock, rudder angle [deg]) (fewer only past the --wait guard)."""
        mark, limit = len(observed), time.monotonic() + args.wait
        while len(observed) < mark + count and time.monotonic() < limit:
            time.sleep(0.02)
        return [(t, data[6]) for t, data in observed[mark:mark + count]]

    result["before"] = settle(2)
    rudder.publish(Float32(30.0))
    result["after_30"] = settle(args.settle)
    rudder.publish(Float32(math.nan))
    result["after_nan"] = settle(args.settle)
    rudder.publish(Float32(-20.0))
    result["after_minus_20"] = settle(args.settle)
    rospy.wait_for_service(f"{args.reset}", timeout=args.wait)
    answer = rospy.ServiceProxy(args.reset, Trigger)()
    result["reset"] = {"success": answer.success, "message": answer.message}
    result["after_reset"] = settle(args.settle)
    result["ticks_after_reset"] = clock.ticks[-5:]
    return result


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("scenario", choices=("watch", "commands"))
    parser.add_argument("--topic", action="append", default=[])
    parser.add_argument("--seconds", type=float, default=120.0, help="watch: wall-clock seconds at most")
    parser.add_argument("--clock-span", type=float, default=None, help="watch: simulated seconds to watch")
    parser.add_argument("--wait", type=float, default=60.0, help="wall-clock seconds to wait for the node")
    parser.add_argument("--settle", type=int, default=4, help="commands: observations to take after each command")
    parser.add_argument("--until", default=None, help="watch: stop at the first message on this topic")
    parser.add_argument("--namespace", default="/eboat")
    parser.add_argument("--reset", default="/ocean_warp/reset")
    args = parser.parse_args()
    rospy.init_node("ocean_warp_test_driver", anonymous=True, disable_signals=True)
    try:
        result = watch(args) if args.scenario == "watch" else commands(args)
    finally:
        rospy.signal_shutdown("done")
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
