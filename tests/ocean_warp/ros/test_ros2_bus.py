"""The ROS 2 side of ``ocean-warp ros`` (:mod:`ocean_warp.ros.ros2_bus`) without ROS 2: a fake ``rclpy`` and fake
message packages (classes shaped like rosidl's: ``__slots__``, ``get_fields_and_field_types()``, setters that
insist on rclpy's types) are put into ``sys.modules``. They check the dict -> message conversion of every
message a small real SailingEnv publishes, and what Ros2Bus asks of rclpy (names, QoS, remaps, the Trigger
service, the executor, shutdown). Nothing here shows that a real rclpy accepts it: the one test that would run the
node against rclpy is skipped where rclpy is missing (as on the machine these were written on)."""

from __future__ import annotations

import argparse
import array
import importlib.util
import subprocess
import sys
import threading
import types

import numpy as np
import pytest

from ocean_warp.ros import ros2_bus, topics
from ocean_warp.ros.topics import Message

# --- fake message packages, shaped like rosidl's generated classes ----------------------------------------
_FLOAT_TYPES = {"float": ("f", np.float32), "double": ("d", np.float64)}
_INT_TYPES = {"int8": "b", "uint8": "B", "int16": "h", "uint16": "H", "int32": "i", "uint32": "I"}
DEFINITIONS = {
    "builtin_interfaces/Time": {"sec": "int32", "nanosec": "uint32"},
    "std_msgs/Header": {"stamp": "builtin_interfaces/Time", "frame_id": "string"},
    "std_msgs/Float32": {"data": "float"},
    "std_msgs/Int16": {"data": "int16"},
    "std_msgs/MultiArrayDimension": {"label": "string", "size": "uint32", "stride": "uint32"},
    "std_msgs/MultiArrayLayout": {"dim": "sequence<std_msgs/MultiArrayDimension>", "data_offset": "uint32"},
    "std_msgs/Float32MultiArray": {"layout": "std_msgs/MultiArrayLayout", "data": "sequence<float>"},
    "geometry_msgs/Point": {"x": "double", "y": "double", "z": "double"},
    "geometry_msgs/Vector3": {"x": "double", "y": "double", "z": "double"},
    "geometry_msgs/Quaternion": {"x": "double", "y": "double", "z": "double", "w": "double"},
    "geometry_msgs/Vector3Stamped": {"header": "std_msgs/Header", "vector": "geometry_msgs/Vector3"},
    "geometry_msgs/Transform": {"translation": "geometry_msgs/Vector3", "rotation": "geometry_msgs/Quaternion"},
    "geometry_msgs/TransformStamped": {"header": "std_msgs/Header", "child_frame_id": "string",
                                       "transform": "geometry_msgs/Transform"},
    "sensor_msgs/NavSatStatus": {"status": "int8", "service": "uint16"},
    "sensor_msgs/NavSatFix": {"header": "std_msgs/Header", "status": "sensor_msgs/NavSatStatus",
                              "latitude": "double", "longitude": "double", "altitude": "double",
                              "position_covariance": "double[9]", "position_covariance_type": "uint8"},
    "sensor_msgs/Imu": {"header": "std_msgs/Header", "orientation": "geometry_msgs/Quaternion",
                        "orientation_covariance": "double[9]", "angular_velocity": "geometry_msgs/Vector3",
                        "angular_velocity_covariance": "double[9]", "linear_acceleration": "geometry_msgs/Vector3",
                        "linear_acceleration_covariance": "double[9]"},
    "sensor_msgs/LaserScan": {"header": "std_msgs/Header", "angle_min": "float", "angle_max": "float",
                              "angle_increment": "float", "time_increment": "float", "scan_time": "float",
                              "range_min": "float", "range_max": "float", "ranges": "sequence<float>",
                              "intensities": "sequence<float>"},
    "sensor_msgs/Image": {"header": "std_msgs/Header", "height": "uint32", "width": "uint32", "encoding": "string",
                          "is_bigendian": "uint8", "step": "uint32", "data": "sequence<uint8>"},
    "tf2_msgs/TFMessage": {"transforms": "sequence<geometry_msgs/TransformStamped>"},
    "rosgraph_msgs/Clock": {"clock": "builtin_interfaces/Time"},
}
REQUIRED = {topics.NAV_SAT_FIX, topics.IMU, topics.LASER_SCAN, topics.TF_MESSAGE, topics.CLOCK_TYPE,
            topics.FLOAT32_MULTI_ARRAY}


def _check(field_type: str, value, where: str) -> None:
    """What rclpy's generated setters assert (simplified): exact Python types, numpy arrays of the dtype and
    size for fixed arrays, array.array of the typecode for numeric sequences."""
    if field_type.startswith("sequence<"):
        base = field_type[len("sequence<"):-1]
        code = (_FLOAT_TYPES.get(base) or (_INT_TYPES.get(base), None))[0]
        if code is not None:
            assert isinstance(value, array.array) and value.typecode == code, where
        else:
            assert isinstance(value, list), where
            for item in value:
                _check(base, item, where)
    elif field_type.endswith("]"):
        base, size = field_type[:-1].split("[")
        assert isinstance(value, np.ndarray) and value.dtype == _FLOAT_TYPES[base][1] and value.size == int(size), \
            where
    elif field_type in _FLOAT_TYPES:
        assert type(value) is float, where
    elif field_type in _INT_TYPES:
        assert type(value) is int, where
    elif field_type == "string":
        assert type(value) is str, where
    else:
        assert type(value).__name__ == field_type.split("/")[-1], where


def _fake_message(type_name: str, definition: dict) -> type:
    def __init__(self):
        for name in definition:
            object.__setattr__(self, name, None)

    def __setattr__(self, name, value):
        if name not in definition:
            raise AttributeError(name)
        _check(definition[name], value, f"{type_name}.{name}")
        object.__setattr__(self, name, value)

    def __eq__(self, other):
        return type(self) is type(other) and all(
            np.array_equal(getattr(self, n), getattr(other, n)) if isinstance(getattr(self, n), (np.ndarray,
                                                                                                  array.array))
            else getattr(self, n) == getattr(other, n) for n in definition)

    return type(type_name.split("/")[1], (), {
        "__slots__": tuple(definition), "__init__": __init__, "__setattr__": __setattr__, "__eq__": __eq__,
        "get_fields_and_field_types": classmethod(lambda cls: dict(definition)), "_type": type_name})


class FakeLogger:
    def __init__(self, log):
        self.log = log

    def info(self, text):
        self.log.append(("info", text))

    def warning(self, text):
        self.log.append(("warn", text))


class FakePublisher:
    def __init__(self, cls, name, qos, listeners=1):
        self.cls, self.name, self.qos, self.listeners, self.sent = cls, name, qos, listeners, []

    def get_subscription_count(self):
        return self.listeners

    def publish(self, message):
        assert isinstance(message, self.cls)
        self.sent.append(message)


class FakeRclpy:
    """What the bus uses of rclpy, recording every call."""

    def __init__(self):
        self.init_args = None
        self.is_ok = False
        self.nodes, self.executors, self.log = [], [], []

    def make_modules(self) -> dict:
        rclpy = types.ModuleType("rclpy")
        rclpy.init = self.init
        rclpy.ok = lambda: self.is_ok
        rclpy.try_shutdown = self.try_shutdown
        node_module, executors, qos, parameter = (types.ModuleType(f"rclpy.{n}") for n in
                                                  ("node", "executors", "qos", "parameter"))
        fake = self

        class Node:
            def __init__(self, name, parameter_overrides=()):
                assert fake.is_ok, "rclpy.init first"
                self.name, self.parameters = name, {p.name: p.value for p in parameter_overrides}
                self.publishers, self.subscriptions, self.services, self.destroyed = [], [], [], False
                fake.nodes.append(self)

            def create_publisher(self, cls, name, qos):
                self.publishers.append(FakePublisher(cls, name, qos))
                return self.publishers[-1]

            def create_subscription(self, cls, name, callback, qos):
                self.subscriptions.append((cls, name, callback, qos))

            def create_service(self, cls, name, callback):
                self.services.append((cls, name, callback))

            def get_fully_qualified_name(self):
                return "/" + self.name

            def get_namespace(self):
                return "/"

            def get_logger(self):
                return FakeLogger(fake.log)

            def destroy_node(self):
                self.destroyed = True

        class SingleThreadedExecutor:
            def __init__(self):
                self.nodes, self.stopped, self.spinning = [], threading.Event(), threading.Event()
                fake.executors.append(self)

            def add_node(self, node):
                self.nodes.append(node)

            def spin(self):
                self.spinning.set()
                self.stopped.wait(10)

            def shutdown(self, timeout_sec=None):
                self.stopped.set()

        class Parameter:
            class Type:
                BOOL = "bool"

            def __init__(self, name, kind, value):
                self.name, self.kind, self.value = name, kind, value

        class QoSProfile:
            def __init__(self, *, depth, history, reliability, durability):
                self.depth, self.history, self.reliability, self.durability = depth, history, reliability, durability

        node_module.Node = Node
        executors.SingleThreadedExecutor = SingleThreadedExecutor
        parameter.Parameter = Parameter
        qos.QoSProfile = QoSProfile
        qos.DurabilityPolicy = types.SimpleNamespace(TRANSIENT_LOCAL="transient_local", VOLATILE="volatile")
        qos.HistoryPolicy = types.SimpleNamespace(KEEP_LAST="keep_last")
        qos.ReliabilityPolicy = types.SimpleNamespace(RELIABLE="reliable")
        for name in ("node", "executors", "qos", "parameter"):
            setattr(rclpy, name, locals()[{"node": "node_module"}.get(name, name)])
        return {"rclpy": rclpy, "rclpy.node": node_module, "rclpy.executors": executors, "rclpy.qos": qos,
                "rclpy.parameter": parameter}

    def init(self, args=None):
        self.init_args, self.is_ok = list(args), True

    def try_shutdown(self):
        self.is_ok = False


class _Trigger:
    class Request:
        pass

    class Response:
        def __init__(self):
            self.success, self.message = False, ""


@pytest.fixture
def fake_ros2(monkeypatch):
    """Fake rclpy and message packages in ``sys.modules`` (and ros2_bus's class cache emptied); the FakeRclpy."""
    fake = FakeRclpy()
    modules = fake.make_modules()
    for type_name, definition in DEFINITIONS.items():
        package, name = type_name.split("/")
        module = modules.setdefault(f"{package}.msg", types.ModuleType(f"{package}.msg"))
        setattr(module, name, _fake_message(type_name, definition))
    srv = types.ModuleType("std_srvs.srv")
    srv.Trigger = _Trigger
    modules["std_srvs.srv"] = srv
    for package in {name.split(".")[0] for name in modules}:
        modules.setdefault(package, types.ModuleType(package))
    for name, module in modules.items():
        monkeypatch.setitem(sys.modules, name, module)
    monkeypatch.setattr(ros2_bus, "_CLASSES", {})
    return fake


@pytest.fixture(scope="module")
def published():
    """Every message of a decision of two boats of EBoatWaypoint-v0 (WaypointConfig) with a lidar, from the
    node's own simulation: /clock, /tf_static, the state topics, /tf, lidar/scan, and an episode end."""
    from ocean_warp.envs.ros.node import _Simulation

    args = argparse.Namespace(sea_state=None, wind=None, seed=3, hull="auto", lidar=True, camera=False, boats=2)
    sim = _Simulation.build(args, "EBoatWaypoint-v0", "cpu")
    sim.step(np.zeros((2, 3), dtype=np.float32), {})
    messages = sim.messages(with_static=True)
    messages += topics.episode_messages(7_000_000_000, [True, False], [1, 0], [2, 0], [7, 0], [1.5, 0], [0, 0])
    return messages


def _same(message, fields: dict, where: str) -> None:
    """Every field of ``message`` set, and equal to ``fields``' (recursively)."""
    assert set(message.get_fields_and_field_types()) == set(fields), where
    for name, expected in fields.items():
        value = getattr(message, name)
        if isinstance(expected, dict):
            _same(value, expected, f"{where}.{name}")
        elif isinstance(expected, list) and expected and isinstance(expected[0], dict):
            assert len(value) == len(expected), where
            for k, (item, sub) in enumerate(zip(value, expected)):
                _same(item, sub, f"{where}.{name}[{k}]")
        elif isinstance(expected, (list, tuple, np.ndarray, bytes)):
            kind = np.float32 if isinstance(value, array.array) and value.typecode == "f" else None
            np.testing.assert_array_equal(np.asarray(value), np.asarray(expected, dtype=kind), err_msg=where)
        elif isinstance(expected, float):
            assert value == pytest.approx(expected, rel=1e-6, nan_ok=True), f"{where}.{name}"
        else:
            assert value == expected and type(value) is type(expected), f"{where}.{name}"


def test_every_published_message_converts_field_by_field(fake_ros2, published):
    seen = set()
    for message in published:
        converted = ros2_bus.to_ros2(message.type, message.fields)
        assert type(converted).__name__ == message.type.split("/")[-1]
        _same(converted, message.fields, message.topic)
        seen.add(message.type)
    assert REQUIRED <= seen, REQUIRED - seen
    scan = next(m for m in published if m.type == topics.LASER_SCAN)
    assert len(scan.fields["ranges"]) > 1


def test_conversion_details(fake_ros2):
    clock = ros2_bus.to_ros2("rosgraph_msgs/msg/Clock", {"clock": topics.stamp(3_500_000_001)})
    assert (clock.clock.sec, clock.clock.nanosec) == (3, 500_000_001)
    point = ros2_bus.to_ros2(topics.POINT, {"x": 1, "y": np.float32(2.5), "z": np.int64(0)})  # coerced to float
    assert (point.x, point.y, point.z) == (1.0, 2.5, 0.0) and type(point.x) is float
    image = ros2_bus.to_ros2(topics.IMAGE, {"header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": "c"},
                                            "height": 1, "width": 2, "encoding": "rgb8", "is_bigendian": 0,
                                            "step": 6, "data": bytes(range(6))})
    assert image.data == array.array("B", range(6))
    with pytest.raises(ValueError, match="no field bogus"):
        ros2_bus.to_ros2(topics.POINT, {"x": 1.0, "bogus": 2.0})
    with pytest.raises(ValueError, match=r"double\[9\] needs 9 values"):
        ros2_bus.to_ros2(topics.NAV_SAT_FIX, {"position_covariance": [0.0] * 4})
    with pytest.raises(ValueError, match="no ROS 2 message class"):
        ros2_bus.to_ros2("nope_msgs/msg/Nothing", {})
    with pytest.raises(ValueError, match="not a ROS 2 message type"):
        ros2_bus.message_class("Header")


def test_remaps_become_ros_args():
    argv, dropped = ros2_bus.ros2_arguments("ocean-warp ros", [
        "/eboat/gps/fix:=/fix", "__ns:=/sim", "__name:=sim", "~reset:=/reset_all", "_rate:=2",
        "__master:=http://x:11311"])
    assert argv == ["ocean-warp ros", "--ros-args", "-r", "/eboat/gps/fix:=/fix", "-r", "__ns:=/sim",
                    "-r", "__node:=sim", "-r", "~/reset:=/reset_all", "-p", "rate:=2"]
    assert dropped == ["__master:=http://x:11311"]
    assert ros2_bus.ros2_arguments("p", []) == (["p", "--ros-args"], [])


def test_bus_on_fake_rclpy(fake_ros2, published):
    rclpy = sys.modules["rclpy"]
    bus = ros2_bus.Ros2Bus(rclpy, ["/eboat_0/gps/fix:=/fix", "__master:=http://x:1"], node_name="ocean_warp",
                           program="ocean-warp ros")
    bus.start()
    assert fake_ros2.init_args == ["ocean-warp ros", "--ros-args", "-r", "/eboat_0/gps/fix:=/fix"]
    (node,) = fake_ros2.nodes
    assert node.name == "ocean_warp" and node.parameters == {"use_sim_time": True}
    (executor,) = fake_ros2.executors
    assert executor.nodes == [node] and executor.spinning.wait(5)
    assert bus._thread.daemon and not bus.shut_down()
    assert bus.caller_id == "/ocean_warp" and bus.resolve_name("~reset") == "/ocean_warp/reset"
    assert ("warn", "ocean-warp ros: ROS 2 has no master: ignored __master:=http://x:1") in fake_ros2.log

    # subscribers, the service
    got = []
    bus.subscribe("/eboat_0/control_interface/rudder", topics.FLOAT32, got.append)
    bus.subscribe("/eboat_0/atmosferic_control/wind", topics.POINT, got.append)
    names = [(cls.__name__, name, qos) for cls, name, _, qos in node.subscriptions]
    assert names == [("Float32", "eboat_0/control_interface/rudder", 10),
                     ("Point", "eboat_0/atmosferic_control/wind", 10)]
    bus.service("~reset", lambda request: (True, "reset done"))
    ((cls, name, callback),) = node.services
    assert cls is _Trigger and name == "~/reset"
    response = callback(_Trigger.Request(), _Trigger.Response())
    assert (response.success, response.message) == (True, "reset done")

    # publishers: names, QoS (latched: transient local, depth 1), every message converted and sent
    bus.publish(published, latched={"/eboat_0/mission_control/observations"})
    by_name = {p.name: p for p in node.publishers}
    assert "/tf" in by_name and "/clock" in by_name and "eboat_1/gps/fix" in by_name and "eboat_0/lidar/scan" in by_name
    for publisher in node.publishers:
        latched = publisher.name in ("/tf_static", "eboat_0/mission_control/observations")
        assert publisher.qos.durability == ("transient_local" if latched else "volatile"), publisher.name
        assert publisher.qos.depth == (1 if latched else 10), publisher.name
        assert publisher.qos.reliability == "reliable" and publisher.qos.history == "keep_last"
        assert len(publisher.sent) == sum(1 for m in published if bus.name(m.topic) == publisher.name)
    assert len(by_name["/tf_static"].sent) == 1 and by_name["/tf_static"].sent[0].transforms
    for boat in range(2):  # the current, in map: the task's still water (no current by default)
        (current,) = by_name[f"eboat_{boat}/current"].sent
        assert type(current).__name__ == "Vector3Stamped" and current.header.frame_id == "map"
        assert (current.vector.x, current.vector.y, current.vector.z) == (0.0, 0.0, 0.0)

    # unlatched topics without subscribers are not converted; latched ones are
    for publisher in node.publishers:
        publisher.listeners, publisher.sent = 0, []
    bus.publish(published, latched={"/eboat_0/mission_control/observations"})
    assert [p.name for p in node.publishers if p.sent] == ["/tf_static", "eboat_0/mission_control/observations"]

    # the node's own wind report coming back is dropped; a command is delivered
    for publisher in node.publishers:
        publisher.listeners = 1
    bus.publish([Message("/eboat_0/atmosferic_control/wind", topics.POINT, 0, {"x": 1.0, "y": 2.0, "z": 0.0})])
    on_wind = node.subscriptions[1][2]
    on_wind(ros2_bus.to_ros2(topics.POINT, {"x": 1.0, "y": 2.0, "z": 0.0}))
    assert got == []
    wind = ros2_bus.to_ros2(topics.POINT, {"x": 3.0, "y": 0.0, "z": 0.0})
    on_wind(wind)
    rudder = ros2_bus.to_ros2(topics.FLOAT32, {"data": 5.0})
    node.subscriptions[0][2](rudder)
    assert got == [wind, rudder]

    bus.info("hello")
    bus.warn("careful")
    assert ("info", "hello") in fake_ros2.log and ("warn", "careful") in fake_ros2.log

    bus.stop("done")
    assert executor.stopped.is_set() and node.destroyed and not fake_ros2.is_ok and bus._thread is None
    assert bus.shut_down()
    bus.stop("again")  # idempotent


def test_ros_option_chooses_the_client(fake_ros2, monkeypatch):
    from ocean_warp.envs.ros import node
    from ocean_warp.ros import ros1

    monkeypatch.setattr(ros1, "import_rospy", lambda: (_ for _ in ()).throw(ros1.RosUnavailable("no rospy here")))
    version, client = node._ros_client("auto")
    assert version == 2 and client is sys.modules["rclpy"]
    with pytest.raises(ros1.RosUnavailable, match="no rospy here"):
        node._ros_client("1")
    monkeypatch.setitem(sys.modules, "rclpy", None)  # import fails
    with pytest.raises(ImportError, match=r"no rospy here; ROS 2's rclpy cannot be imported"):
        node._ros_client("auto")
    with pytest.raises(ros2_bus.Ros2Unavailable, match="source a ROS 2 installation"):
        node._ros_client("2")


@pytest.mark.skipif(importlib.util.find_spec("rclpy") is None, reason="rclpy is not installed (no ROS 2 here)")
def test_node_runs_on_real_rclpy():
    """With a real ROS 2: the node starts on rclpy, publishes for 3 s of simulated time and stops cleanly."""
    argv = [sys.executable, "-c", "import sys; from ocean_warp.envs.ros.node import main; sys.exit(main())",
            "--ros", "2", "--as-fast-as-possible", "--duration", "3", "--device", "cpu"]
    result = subprocess.run(argv, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert "stopped at t = 3.0 s" in result.stdout
