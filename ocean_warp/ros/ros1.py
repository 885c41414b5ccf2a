"""ROS 1 through ``rospy``: finding it, turning :mod:`ocean_warp.ros.topics`' messages (plain dicts of ROS 2
fields) into rospy message objects, checking for a ROS master without hanging, and the remapping arguments
(``name:=new``) a node accepts.

rospy comes from Debian's packages (bookworm: ``ros-core python3-rospy python3-std-msgs python3-sensor-msgs
python3-geometry-msgs python3-rosgraph-msgs python3-tf2-msgs python3-std-srvs``), pure Python installed for the
system interpreter under ``/usr/lib/python3/dist-packages``. A virtual environment of the same Python minor
version imports them when that folder is *appended* to ``sys.path`` (its own numpy and the rest still win):
:func:`import_rospy` does that only when a plain ``import rospy`` fails.

ROS 1 and the ROS 2 form of the dicts differ only in: ``builtin_interfaces/Time`` ``{sec, nanosec}`` becomes
rospy's ``Time(secs, nsecs)`` (fields of type ``time``); ``std_msgs/Header`` has a ``seq`` (rospy's publisher
numbers it); CameraInfo's ``d k r p`` are ``D K R P`` (field names match case-insensitively); type names lose
their ``/msg/`` (``sensor_msgs/msg/Imu`` -> ``sensor_msgs/Imu``). ``/clock`` is ``rosgraph_msgs/Clock`` and
``/tf`` ``tf2_msgs/TFMessage`` in both.

Imports: the standard library only (rospy when asked), no other module of ocean_warp, so that the controller
node (:mod:`ocean_warp.ros.controller_node`) can load this file by its path without Warp or torch.
"""

from __future__ import annotations

import importlib
import os
import socket
import sys

__all__ = ["DIST_PACKAGES", "DEBIAN_PACKAGES", "INSTALL_HINT", "RosUnavailable", "import_rospy", "ros1_type",
           "message_class", "to_ros1", "master_uri", "master_online", "no_master_text", "split_remaps",
           "SPECIAL_REMAPS", "namespace_of", "resolve", "unknown_remap"]

DIST_PACKAGES = "/usr/lib/python3/dist-packages"
"""Where Debian installs rospy and the message packages (for the system's Python 3)."""
DEBIAN_PACKAGES = ("ros-core", "python3-rospy", "python3-std-msgs", "python3-sensor-msgs", "python3-geometry-msgs",
                   "python3-rosgraph-msgs", "python3-tf2-msgs", "python3-std-srvs")
"""The Debian (bookworm) packages the ROS 1 node needs."""
INSTALL_HINT = "apt-get install " + " ".join(DEBIAN_PACKAGES)
"""How to get them, in one line."""
MESSAGE_MODULES = ("rospy", "rosgraph", "std_msgs.msg", "sensor_msgs.msg", "geometry_msgs.msg", "rosgraph_msgs.msg",
                   "tf2_msgs.msg", "std_srvs.srv")
"""What :func:`import_rospy` checks imports."""
SPECIAL_REMAPS = ("__name", "__ns", "__master", "__ip", "__hostname", "__log")
"""rospy's special remapping keys (node name, namespace, master, network, log file): always accepted."""


class RosUnavailable(ImportError):
    """rospy or a message package cannot be imported (the message, one line, names the Debian packages)."""


def import_rospy():
    """The ``rospy`` module, with the message packages the nodes use importable: a plain import, else one
    with :data:`DIST_PACKAGES` appended to ``sys.path``; else :class:`RosUnavailable` naming the packages."""
    try:
        return _import_all()
    except ImportError as error:
        missing = error
    if os.path.isdir(DIST_PACKAGES) and DIST_PACKAGES not in sys.path:
        sys.path.append(DIST_PACKAGES)
        importlib.invalidate_caches()
        try:
            return _import_all()
        except ImportError as error:
            missing = error
    raise RosUnavailable(f"ROS 1's rospy cannot be imported ({type(missing).__name__}: {missing}); on Debian or "
                         f"Ubuntu install it with: {INSTALL_HINT}") from None


def _import_all():
    for name in MESSAGE_MODULES:
        importlib.import_module(name)
    return sys.modules["rospy"]


# --- messages -----------------------------------------------------------------------------------------
_PRIMITIVES = {"bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32", "uint32",
               "int64", "uint64", "string"}
_CLASSES: dict[str, type] = {}


def ros1_type(ros2_type: str) -> str:
    """The ROS 1 name of a ROS 2 message type: ``sensor_msgs/msg/Imu`` -> ``sensor_msgs/Imu`` (a ROS 1 name is
    returned as it is); ``ValueError`` for anything else."""
    parts = str(ros2_type).split("/")
    if len(parts) == 3 and parts[1] == "msg":
        return f"{parts[0]}/{parts[2]}"
    if len(parts) == 2 and all(parts):
        return str(ros2_type)
    raise ValueError(f"not a ROS message type name: {ros2_type!r} (expected package/msg/Name or package/Name)")


def message_class(type_name: str) -> type:
    """The rospy message class of ``type_name`` (ROS 2 or ROS 1 form; ``Header`` is ``std_msgs/Header``)."""
    name = "std_msgs/Header" if type_name == "Header" else ros1_type(type_name)
    found = _CLASSES.get(name)
    if found is None:
        package, short = name.split("/")
        try:
            found = getattr(importlib.import_module(f"{package}.msg"), short)
        except (ImportError, AttributeError):
            raise ValueError(f"no ROS 1 message class {name} (is its Debian package installed?)") from None
        _CLASSES[name] = found
    return found


def to_ros1(type_name: str, fields: dict):
    """A rospy message of ``type_name`` (e.g. ``sensor_msgs/msg/NavSatFix``) holding ``fields``, a dict of its
    ROS 2 fields as :mod:`ocean_warp.ros.topics` builds them. Fields the dict leaves out keep their defaults
    (``header.seq``: rospy's publisher numbers it). ``ValueError`` for a field the ROS 1 type lacks."""
    return _filled(message_class(type_name), fields, ros1_type(type_name))


def _filled(cls: type, fields: dict, where: str):
    if not isinstance(fields, dict):
        raise ValueError(f"{where}: expected a dict of fields, got {type(fields).__name__}")
    message = cls()
    by_lower = {key.lower(): key for key in fields}
    used = set()
    for slot, slot_type in zip(cls.__slots__, cls._slot_types):
        key = slot if slot in fields else by_lower.get(slot.lower())
        if key is None:
            continue
        used.add(key)
        setattr(message, slot, _value(slot_type, fields[key], f"{where}.{slot}"))
    unknown = sorted(set(fields) - used)
    if unknown:
        raise ValueError(f"{where}: the ROS 1 type {cls._type} has no field {', '.join(unknown)}")
    return message


def _value(slot_type: str, value, where: str):
    base, bracket, _ = slot_type.partition("[")
    if base in ("time", "duration"):
        return _time(base, value, where)
    if bracket:
        if base in ("uint8", "char"):
            return bytes(value)
        if base in _PRIMITIVES:
            return list(value)
        return [_value(base, item, f"{where}[{k}]") for k, item in enumerate(value)]
    if base in _PRIMITIVES:
        return value
    return _filled(message_class(base), value, where)


def _time(kind: str, value, where: str):
    import rospy

    if not isinstance(value, dict) or set(value) != {"sec", "nanosec"}:
        raise ValueError(f"{where}: a {kind} must be a dict of sec and nanosec, got {value!r}")
    cls = rospy.Time if kind == "time" else rospy.Duration
    return cls(int(value["sec"]), int(value["nanosec"]))


# --- the master -----------------------------------------------------------------------------------------
def master_uri(remaps=(), environ=None) -> str:
    """The master's URI: a ``__master:=`` remap, else ``ROS_MASTER_URI``, else ROS's default
    ``http://localhost:11311``."""
    for arg in remaps:
        if arg.startswith("__master:="):
            return arg.split(":=", 1)[1]
    environ = os.environ if environ is None else environ
    return environ.get("ROS_MASTER_URI") or "http://localhost:11311"


def master_online(uri: str, timeout: float = 3.0) -> bool:
    """Whether a ROS master answers at ``uri`` within ``timeout`` [s] (rospy's ``init_node`` would wait for one
    forever)."""
    import xmlrpc.client
    from urllib.parse import urlparse

    try:
        parsed = urlparse(uri)
        host, port = parsed.hostname, parsed.port or 11311
        if not host or parsed.scheme not in ("http", "https"):
            return False
        with socket.create_connection((host, port), timeout=timeout):
            pass
        previous = socket.getdefaulttimeout()
        socket.setdefaulttimeout(timeout)
        try:
            code, _, _ = xmlrpc.client.ServerProxy(uri).getPid("/ocean_warp_probe")
        finally:
            socket.setdefaulttimeout(previous)
        return code == 1
    except (OSError, ValueError, xmlrpc.client.Error):
        return False


def no_master_text(uri: str) -> str:
    """The one-line error of a node started without a master at ``uri``."""
    return f"no ROS master at {uri} (start roscore, or set ROS_MASTER_URI)"


# --- remapping arguments ----------------------------------------------------------------------------------
def split_remaps(argv) -> tuple[list[str], list[str]]:
    """(the ``name:=value`` arguments, the others) of a command line."""
    remaps = [arg for arg in argv if ":=" in arg]
    return remaps, [arg for arg in argv if ":=" not in arg]


def namespace_of(remaps=(), environ=None) -> str:
    """The node's namespace, ending in "/": ``__ns:=`` among ``remaps``, else ``ROS_NAMESPACE``, else "/"."""
    environ = os.environ if environ is None else environ
    value = next((arg.split(":=", 1)[1] for arg in remaps if arg.startswith("__ns:=")),
                 environ.get("ROS_NAMESPACE", "/"))
    value = "/" + value.strip("/")
    return value if value.endswith("/") else value + "/"


def resolve(name: str, namespace: str, node: str) -> str:
    """A ROS name resolved as rospy resolves it: ``/x`` as it is, ``~x`` under the node's full name ``node``,
    anything else under ``namespace`` (ending in "/")."""
    name = name.strip()
    if name.startswith("/"):
        full = name
    elif name.startswith("~"):
        full = node.rstrip("/") + "/" + name[1:].lstrip("/")
    else:
        full = namespace + name
    return "/" + "/".join(part for part in full.split("/") if part)


def unknown_remap(remaps, known, namespace: str, node: str) -> str | None:
    """The first remapping of ``remaps`` whose source is neither a special key (:data:`SPECIAL_REMAPS`), a
    private parameter (``_name:=value``) nor one of the resolved names ``known``, in one line; None when
    every one is known."""
    for arg in remaps:
        source, _, target = arg.partition(":=")
        source = source.strip()
        if source in SPECIAL_REMAPS or (source.startswith("_") and not source.startswith("__")):
            continue
        if not source or not target.strip():
            return f"remapping {arg!r} must be name:=new_name"
        full = resolve(source, namespace, node)
        if full not in known:
            shown = ", ".join(sorted(known)[:6])
            return (f"remapping {arg!r}: {full} is none of this node's topics or services (e.g. {shown}, ...; "
                    f"{len(known)} in all)")
    return None
