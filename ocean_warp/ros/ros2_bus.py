"""The ROS 2 side of ``ocean-warp ros`` (:mod:`ocean_warp.envs.ros.node`, ``--ros 2``): :class:`Ros2Bus`, the
interface of :class:`~ocean_warp.ros.ros1_bus.Ros1Bus` on ``rclpy``: ``rclpy.init`` with ROS 2's remapping
arguments (``--ros-args -r from:=to``), one ``Node`` with ``use_sim_time`` true as a parameter, publishers by
topic (latched ones: QoS transient-local durability, depth 1, as ``/tf_static`` is in ROS 2), subscribers, the
reset service (``std_srvs/srv/Trigger``), log lines through the node's logger, and a
``SingleThreadedExecutor`` spinning the node in a daemon thread (the callbacks run there, as rospy's run in its
threads). There is no master: DDS discovery finds the peers, so nothing is checked before starting.

Messages: :func:`to_ros2` turns :mod:`ocean_warp.ros.topics`' dicts (already ROS 2 fields) into the message
classes of the ROS 2 Python packages (``sensor_msgs/msg/NavSatFix`` -> ``sensor_msgs.msg.NavSatFix``),
recursively by each class's ``get_fields_and_field_types()`` (rosidl's generated classes): nested messages,
lists of them, float and integer arrays as the numpy arrays (fixed size) and ``array.array`` s (sequences)
rclpy's setters expect, scalars coerced to the exact Python type rclpy asserts. It needs no rclpy, only the
message modules (any objects of that shape), so it is tested with fakes.

The node's own wind reports: ROS 1's node skips them by the caller id of their connection header; rclpy's
messages carry none, so this bus drops a message arriving on a topic it also publishes that equals one of the
last few it published there (a command equal to the node's own report changes nothing anyway).

NOT RUN AGAINST ROS 2. rclpy is not installable on the machine this was written on (no pip wheel, no Debian
package), so this module was written against rclpy's documented API (``rclpy.init``, ``Node.create_publisher /
create_subscription / create_service``, ``rclpy.qos.QoSProfile``, ``rclpy.executors.SingleThreadedExecutor``,
``rclpy.parameter.Parameter``, ``rclpy.try_shutdown``) and checked only with fake ``rclpy`` and message modules
(``tests/ocean_warp/ros/test_ros2_bus.py``), never with a real rclpy or a real ROS 2 graph. The test that would
run the node for real is skipped where rclpy is missing.
"""

from __future__ import annotations

import array
import collections
import importlib
import re
import threading

import numpy as np

from .topics import TF_STATIC, bus_name

__all__ = ["MESSAGE_MODULES", "Ros2Unavailable", "import_rclpy", "message_class", "to_ros2",
           "ros2_arguments", "Ros2Bus"]

MESSAGE_MODULES = ("rclpy", "rclpy.node", "rclpy.executors", "rclpy.qos", "rclpy.parameter", "builtin_interfaces.msg",
                   "std_msgs.msg", "sensor_msgs.msg", "geometry_msgs.msg", "tf2_msgs.msg", "rosgraph_msgs.msg",
                   "std_srvs.srv")
"""What :func:`import_rclpy` checks imports (rclpy first)."""
ROS1_ONLY_REMAPS = ("__master", "__ip", "__hostname", "__log")
"""rospy's special keys that mean nothing to ROS 2 (no master; DDS picks the network): left out."""
SOURCE_HINT = "source a ROS 2 installation first (e.g. . /opt/ros/jazzy/setup.bash)"


class Ros2Unavailable(ImportError):
    """rclpy or a message package cannot be imported (one line)."""


def import_rclpy():
    """The ``rclpy`` module, with the message packages the node uses importable; else :class:`Ros2Unavailable`."""
    try:
        for name in MESSAGE_MODULES:
            importlib.import_module(name)
    except ImportError as error:
        raise Ros2Unavailable(f"ROS 2's rclpy cannot be imported ({type(error).__name__}: {error}); "
                              f"{SOURCE_HINT}") from None
    return importlib.import_module("rclpy")


# --- messages -----------------------------------------------------------------------------------------
_FLOATS = {"float": "f", "double": "d", "float32": "f", "float64": "d"}
_INTS = {"int8": "b", "uint8": "B", "octet": "B", "byte": "B", "char": "B", "int16": "h", "uint16": "H",
         "int32": "i", "uint32": "I", "int64": "q", "uint64": "Q"}
_NUMPY = {"f": np.float32, "d": np.float64, "b": np.int8, "B": np.uint8, "h": np.int16, "H": np.uint16,
          "i": np.int32, "I": np.uint32, "q": np.int64, "Q": np.uint64}
_SEQUENCE = re.compile(r"sequence<\s*([^,>]+?)\s*(?:,\s*\d+\s*)?>")
_ARRAY = re.compile(r"(.+)\[(\d+)\]")
_CLASSES: dict[str, type] = {}


def message_class(type_name: str) -> type:
    """The ROS 2 message class of ``type_name``: ``pkg/msg/Name`` or ``pkg/Name`` (rosidl's own form in
    ``get_fields_and_field_types``), imported from the module ``pkg.msg``."""
    parts = str(type_name).split("/")
    if len(parts) == 3 and parts[1] == "msg":
        parts = [parts[0], parts[2]]
    if len(parts) != 2 or not all(parts):
        raise ValueError(f"not a ROS 2 message type name: {type_name!r} (expected package/msg/Name)")
    key = "/".join(parts)
    found = _CLASSES.get(key)
    if found is None:
        try:
            found = getattr(importlib.import_module(f"{parts[0]}.msg"), parts[1])
        except (ImportError, AttributeError):
            raise ValueError(f"no ROS 2 message class {parts[0]}/msg/{parts[1]} (is its package installed and "
                             "sourced?)") from None
        _CLASSES[key] = found
    return found


def to_ros2(type_name: str, fields: dict):
    """A ROS 2 message of ``type_name`` (e.g. ``sensor_msgs/msg/NavSatFix``) holding ``fields``, a dict as
    :mod:`ocean_warp.ros.topics` builds them. Fields the dict leaves out keep their defaults; ``ValueError`` for
    a field the type lacks."""
    return _filled(message_class(type_name), fields, type_name)


def _filled(cls: type, fields, where: str):
    if not isinstance(fields, dict):
        raise ValueError(f"{where}: expected a dict of fields, got {type(fields).__name__}")
    types = cls.get_fields_and_field_types()
    unknown = sorted(set(fields) - set(types))
    if unknown:
        raise ValueError(f"{where}: the ROS 2 type {cls.__name__} has no field {', '.join(unknown)}")
    message = cls()
    for name, value in fields.items():
        setattr(message, name, _value(types[name], value, f"{where}.{name}"))
    return message


def _value(field_type: str, value, where: str):
    field_type = field_type.strip()
    sequence = _SEQUENCE.fullmatch(field_type)
    fixed = None if sequence else _ARRAY.fullmatch(field_type)
    if sequence or fixed:
        base = (sequence or fixed).group(1).strip()
        code = _FLOATS.get(base) or _INTS.get(base)
        if code is not None:
            data = np.ascontiguousarray(np.frombuffer(value, dtype=np.uint8) if isinstance(value, (bytes, bytearray))
                                        else np.asarray(value), dtype=_NUMPY[code]).reshape(-1)
            if fixed:
                size = int(fixed.group(2))
                if data.size != size:
                    raise ValueError(f"{where}: {field_type} needs {size} values, got {data.size}")
                return data  # rclpy keeps fixed-size numeric arrays as numpy arrays of their dtype
            return array.array(code, data.tobytes())  # and numeric sequences as array.array
        return [_value(base, item, f"{where}[{k}]") for k, item in enumerate(value)]
    if field_type in _FLOATS:
        return float(value)
    if field_type in _INTS:
        return int(value)
    if field_type == "boolean":
        return bool(value)
    if field_type.startswith(("string", "wstring")):
        return str(value)
    return _filled(message_class(field_type), value, where)


# --- arguments ------------------------------------------------------------------------------------------
def ros2_arguments(program: str, remaps) -> tuple[list[str], list[str]]:
    """(the argv for ``rclpy.init``, the remaps left out) of rospy-style ``remaps``: ``from:=to`` becomes
    ``-r from:=to`` after ``--ros-args`` (``~x`` -> ``~/x``, ``__name`` -> ``__node``; ``__ns`` stays), a private
    parameter ``_x:=v`` becomes ``-p x:=v``; ROS 1's ``__master``, ``__ip``, ``__hostname``, ``__log`` are left
    out."""
    argv, dropped = [program, "--ros-args"], []
    for arg in remaps:
        source, _, target = arg.partition(":=")
        source = source.strip()
        if source in ROS1_ONLY_REMAPS:
            dropped.append(arg)
        elif source.startswith("_") and not source.startswith("__"):
            argv += ["-p", f"{source[1:]}:={target}"]
        else:
            if source == "__name":
                source = "__node"
            elif source.startswith("~") and not source.startswith("~/"):
                source = "~/" + source[1:]
            argv += ["-r", f"{source}:={target}"]
    return argv, dropped


def _service_name(name: str) -> str:
    """A rospy-style private name (``~reset``) in ROS 2's form (``~/reset``)."""
    return "~/" + name[1:].lstrip("/") if name.startswith("~") else name


# --- the bus --------------------------------------------------------------------------------------------
class Ros2Bus:
    """The node's rclpy side: init and shutdown, ``use_sim_time``, publishers by topic (boat topics relative, so
    ``__ns`` moves them), subscribers, the service, log lines, and the executor thread."""

    RECENT = 4
    """How many of its last messages per topic the bus remembers to drop its own echoes."""

    def __init__(self, rclpy, remaps, *, node_name: str, program: str):
        self.rclpy, self.remaps = rclpy, list(remaps)
        self.node_name, self.program = node_name, program
        self.node = self._executor = self._thread = None
        self._publishers: dict = {}
        self._subscribed: set = set()
        self._recent: dict = {}
        self._lock = threading.Lock()
        self._initialised = False
        self.spin_error = None
        """What ended the executor thread early (None: nothing)."""

    def start(self) -> None:
        """``rclpy.init`` with the remaps, the node (``use_sim_time`` true) and the executor's thread."""
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.node import Node
        from rclpy.parameter import Parameter

        argv, dropped = ros2_arguments(self.program, self.remaps)
        self.rclpy.init(args=argv)
        self._initialised = True
        self.node = Node(self.node_name,
                         parameter_overrides=[Parameter("use_sim_time", Parameter.Type.BOOL, True)])
        if dropped:
            self.warn(f"{self.program}: ROS 2 has no master: ignored {', '.join(dropped)}")
        self._executor = SingleThreadedExecutor()
        self._executor.add_node(self.node)
        self._thread = threading.Thread(target=self._spin, name="ocean-warp ros2 executor", daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        try:
            self._executor.spin()
        except BaseException as error:  # noqa: BLE001 - rclpy's shutdown exceptions end the thread; kept to say
            self.spin_error = error

    @property
    def caller_id(self) -> str:
        return self.node.get_fully_qualified_name()

    def stop(self, reason: str) -> None:
        """Stop the executor, destroy the node and shut rclpy down (idempotent)."""
        if self._executor is not None:
            executor, self._executor = self._executor, None
            try:
                executor.shutdown(timeout_sec=2.0)
            except Exception:  # noqa: BLE001 - already shut down with the context
                pass
        if self._thread is not None:
            self._thread.join(timeout=5.0)
            self._thread = None
        if self.node is not None:
            node, self.node = self.node, None
            try:
                node.destroy_node()
            except Exception:  # noqa: BLE001
                pass
        if self._initialised:
            self._initialised = False
            shutdown = getattr(self.rclpy, "try_shutdown", None)
            if shutdown is not None:
                shutdown()
            elif self.rclpy.ok():
                self.rclpy.shutdown()

    name = staticmethod(bus_name)
    """The name a publisher or subscriber gets (``topics.bus_name``)."""

    def publisher(self, topic: str, type_name: str, *, latch: bool = False):
        found = self._publishers.get(topic)
        if found is None:
            from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

            if latch:
                qos = QoSProfile(depth=1, history=HistoryPolicy.KEEP_LAST, reliability=ReliabilityPolicy.RELIABLE,
                                 durability=DurabilityPolicy.TRANSIENT_LOCAL)
            else:
                qos = QoSProfile(depth=2 if "camera" in topic else 10, history=HistoryPolicy.KEEP_LAST,
                                 reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE)
            found = self._publishers[topic] = self.node.create_publisher(message_class(type_name), self.name(topic),
                                                                         qos)
        return found

    def publish(self, messages, *, latched=()) -> None:
        """Publish :class:`~ocean_warp.ros.topics.Message` s (converted only where someone listens or the topic
        is latched: ``latched`` topics and /tf_static)."""
        for message in messages:
            latch = message.topic == TF_STATIC or message.topic in latched
            publisher = self.publisher(message.topic, message.type, latch=latch)
            if latch or publisher.get_subscription_count() > 0:
                ros_message = to_ros2(message.type, message.fields)
                if message.topic in self._subscribed:
                    with self._lock:
                        self._recent.setdefault(message.topic, collections.deque(maxlen=self.RECENT)).append(
                            ros_message)
                publisher.publish(ros_message)

    def subscribe(self, topic: str, type_name: str, callback) -> None:
        self._subscribed.add(topic)
        self.node.create_subscription(message_class(type_name), self.name(topic),
                                      lambda message: self._deliver(topic, message, callback), 10)

    def _deliver(self, topic: str, message, callback) -> None:
        with self._lock:
            recent = self._recent.get(topic)
            if recent:
                for k, sent in enumerate(recent):
                    if sent == message:
                        del recent[k]
                        return  # the node's own message, back through DDS
        callback(message)

    def service(self, name: str, handler) -> None:
        """The std_srvs/srv/Trigger service ``name`` (``~reset``: private); ``handler(request)`` returns
        (success, message)."""
        from std_srvs.srv import Trigger

        def answer(request, response):
            success, text = handler(request)
            response.success, response.message = bool(success), str(text)
            return response

        self.node.create_service(Trigger, _service_name(name), answer)

    def resolve_name(self, name: str) -> str:
        """``name`` as the node resolves it (``~reset`` -> ``/ocean_warp/reset``)."""
        if name.startswith("/"):
            return name
        if name.startswith("~"):
            return self.node.get_fully_qualified_name().rstrip("/") + "/" + name[1:].lstrip("/")
        return self.node.get_namespace().rstrip("/") + "/" + name

    def shut_down(self) -> bool:
        return not self.rclpy.ok() or (self._thread is not None and not self._thread.is_alive())

    def info(self, text: str) -> None:
        self.node.get_logger().info(text)

    def warn(self, text: str) -> None:
        logger = self.node.get_logger()
        (logger.warning if hasattr(logger, "warning") else logger.warn)(text)
