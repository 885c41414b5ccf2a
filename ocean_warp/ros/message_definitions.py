"""The ROS 2 message definitions (``.msg`` text) of every type :mod:`ocean_warp.ros.topics` publishes, and their
concatenated form: the one rosbag2 stores as an MCAP schema (encoding "ros2msg") and that ``mcap_ros2``,
Foxglove, PlotJuggler and ``rosbags`` parse. Field names, types, defaults and constants are those of the ROS 2
interfaces (Humble and later); comments are left out.

Concatenated form of a type: its own definition, then, for every type it uses (depth first, each once), a line
of 80 "=", a line ``MSG: <package>/<Name>`` and that type's definition.
"""

from __future__ import annotations

import re

__all__ = ["DEFINITIONS", "schema_text", "dependencies"]

_SEPARATOR = "=" * 80

DEFINITIONS: dict[str, str] = {
    "builtin_interfaces/msg/Time": """\
int32 sec
uint32 nanosec
""",
    "std_msgs/msg/Header": """\
builtin_interfaces/Time stamp
string frame_id
""",
    "std_msgs/msg/Float32": """\
float32 data
""",
    "std_msgs/msg/Int16": """\
int16 data
""",
    "std_msgs/msg/MultiArrayDimension": """\
string label
uint32 size
uint32 stride
""",
    "std_msgs/msg/MultiArrayLayout": """\
std_msgs/MultiArrayDimension[] dim
uint32 data_offset
""",
    "std_msgs/msg/Float32MultiArray": """\
std_msgs/MultiArrayLayout layout
float32[] data
""",
    "geometry_msgs/msg/Point": """\
float64 x
float64 y
float64 z
""",
    "geometry_msgs/msg/Vector3": """\
float64 x
float64 y
float64 z
""",
    "geometry_msgs/msg/Quaternion": """\
float64 x 0
float64 y 0
float64 z 0
float64 w 1
""",
    "geometry_msgs/msg/Vector3Stamped": """\
std_msgs/Header header
geometry_msgs/Vector3 vector
""",
    "geometry_msgs/msg/Transform": """\
geometry_msgs/Vector3 translation
geometry_msgs/Quaternion rotation
""",
    "geometry_msgs/msg/TransformStamped": """\
std_msgs/Header header
string child_frame_id
geometry_msgs/Transform transform
""",
    "tf2_msgs/msg/TFMessage": """\
geometry_msgs/TransformStamped[] transforms
""",
    "rosgraph_msgs/msg/Clock": """\
builtin_interfaces/Time clock
""",
    "sensor_msgs/msg/NavSatStatus": """\
int8 STATUS_NO_FIX=-1
int8 STATUS_FIX=0
int8 STATUS_SBAS_FIX=1
int8 STATUS_GBAS_FIX=2
uint16 SERVICE_GPS=1
uint16 SERVICE_GLONASS=2
uint16 SERVICE_COMPASS=4
uint16 SERVICE_GALILEO=8
int8 status
uint16 service
""",
    "sensor_msgs/msg/NavSatFix": """\
uint8 COVARIANCE_TYPE_UNKNOWN=0
uint8 COVARIANCE_TYPE_APPROXIMATED=1
uint8 COVARIANCE_TYPE_DIAGONAL_KNOWN=2
uint8 COVARIANCE_TYPE_KNOWN=3
std_msgs/Header header
sensor_msgs/NavSatStatus status
float64 latitude
float64 longitude
float64 altitude
float64[9] position_covariance
uint8 position_covariance_type
""",
    "sensor_msgs/msg/Imu": """\
std_msgs/Header header
geometry_msgs/Quaternion orientation
float64[9] orientation_covariance
geometry_msgs/Vector3 angular_velocity
float64[9] angular_velocity_covariance
geometry_msgs/Vector3 linear_acceleration
float64[9] linear_acceleration_covariance
""",
    "sensor_msgs/msg/LaserScan": """\
std_msgs/Header header
float32 angle_min
float32 angle_max
float32 angle_increment
float32 time_increment
float32 scan_time
float32 range_min
float32 range_max
float32[] ranges
float32[] intensities
""",
    "sensor_msgs/msg/Image": """\
std_msgs/Header header
uint32 height
uint32 width
string encoding
uint8 is_bigendian
uint32 step
uint8[] data
""",
    "sensor_msgs/msg/RegionOfInterest": """\
uint32 x_offset
uint32 y_offset
uint32 height
uint32 width
bool do_rectify
""",
    "sensor_msgs/msg/CameraInfo": """\
std_msgs/Header header
uint32 height
uint32 width
string distortion_model
float64[] d
float64[9] k
float64[9] r
float64[12] p
uint32 binning_x
uint32 binning_y
sensor_msgs/RegionOfInterest roi
""",
}
"""Each type's own definition, by its full ROS 2 name (``package/msg/Name``)."""

_PRIMITIVES = {"bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32", "uint32",
               "int64", "uint64", "string", "wstring"}


def _full_name(short: str) -> str:
    package, name = short.split("/")
    return f"{package}/msg/{name}"


def _short_name(full: str) -> str:
    package, _, name = full.split("/")
    return f"{package}/{name}"


def _used_types(type_name: str) -> list[str]:
    """The full names of the non-primitive field types of ``type_name``'s own definition, in order."""
    used = []
    for line in DEFINITIONS[type_name].splitlines():
        field_type = re.sub(r"\[.*\]$", "", line.split()[0])
        if field_type not in _PRIMITIVES and "=" not in line:
            used.append(_full_name(field_type))
    return used


def dependencies(type_name: str) -> list[str]:
    """Every type ``type_name`` uses, directly or through others, depth first, each once (full names)."""
    found: list[str] = []

    def visit(name: str) -> None:
        for used in _used_types(name):
            if used not in found:
                found.append(used)
                visit(used)

    visit(type_name)
    return found


def schema_text(type_name: str) -> str:
    """The concatenated definition of ``type_name`` (a full name such as ``sensor_msgs/msg/Imu``), as an MCAP
    schema of encoding "ros2msg" holds it; ``ValueError`` for a type not in :data:`DEFINITIONS`."""
    if type_name not in DEFINITIONS:
        raise ValueError(f"schema_text: no definition of {type_name!r}; known: {', '.join(sorted(DEFINITIONS))}")
    parts = [DEFINITIONS[type_name].rstrip("\n")]
    for name in dependencies(type_name):
        parts.append(f"{_SEPARATOR}\nMSG: {_short_name(name)}\n{DEFINITIONS[name].rstrip(chr(10))}")
    return "\n".join(parts) + "\n"
