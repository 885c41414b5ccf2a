"""The real E-Boat's links where the seed team's URDF puts them: joint origins and link inertials, composed
through the joint chain into the base frame.

The figures are facts read from ``yara_description/urdf/eboat4.urdf.xacro`` of ``medialab-fboat/Yara_OVE``
(Apache-2.0; commit e708703), the model the sheet calls eboat4: each joint's origin (xyz [m], rpy [rad]) in
its parent link's frame and each link's inertial (mass [kg], centre of mass [m] in the link frame, inertia
[kg m^2] about it in the link frame). A link's pose in the base frame is its parents' poses composed, URDF
fashion: R = R_parent R_z(yaw) R_y(pitch) R_x(roll), t = t_parent + R_parent xyz. Links of zero mass (rope
and lens visuals, cable, sensor frames, rack supports) carry no inertial but may sit in the chain.
Movable joints (boom, keel, rudder, propeller, vane) are taken at zero.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np

from .sheet import Link

__all__ = ["UrdfJoint", "UrdfInertial", "URDF_JOINTS", "URDF_INERTIALS", "link_poses", "urdf_links", "URDF_SOURCE"]

URDF_SOURCE = "Yara_OVE@e708703 yara_description/urdf/eboat4.urdf.xacro"


@dataclasses.dataclass(frozen=True)
class UrdfJoint:
    """A joint of the URDF: its child link's frame in its parent's."""

    child: str
    parent: str
    xyz: tuple[float, float, float]
    """Origin of the child's frame in the parent's [m]."""
    rpy: tuple[float, float, float]
    """Roll, pitch, yaw of the child's frame in the parent's [rad]."""
    joint: str
    """The joint's name in the URDF."""


@dataclasses.dataclass(frozen=True)
class UrdfInertial:
    """A link's inertial block of the URDF, in the link's frame."""

    link: str
    name: str
    """What we call the part."""
    mass: float
    """[kg]"""
    center: tuple[float, float, float]
    """Centre of mass in the link frame [m]."""
    inertia: tuple[float, float, float, float, float, float]
    """(ixx, ixy, ixz, iyy, iyz, izz) about the centre of mass, link axes [kg m^2]."""


URDF_JOINTS = (
    UrdfJoint("hull_link", "base_link", (0.0, 0.0, 0.210586), (0.0, 0.0, 0.0), "dummy_joint"),
    UrdfJoint("bow_link", "hull_link", (1.24471, 0.0, 0.000666379), (0.0, 0.0, 0.0), "bow_joint"),
    UrdfJoint("mast_link", "hull_link", (0.59529, 0.0, -0.153011), (0.0, 0.0, 0.0), "mast_joint"),
    UrdfJoint("boom_link", "mast_link", (-0.049, 0.0, 0.933), (0.0, 0.0, 0.0), "boom_joint"),
    UrdfJoint("rope_c_link", "boom_link", (-1.7978, 0.0, 0.0223), (1.5708, 0.0, 0.0), "sail_joint_2"),
    UrdfJoint("sail_link", "rope_c_link", (0.0140742, 0.0441151, 0.0), (0.0, 0.0, 0.0), "rope_c_joint"),
    UrdfJoint("keel_link", "hull_link", (-0.13971, 0.0, 0.00405924), (0.0, 0.0, 0.0), "keel_joint"),
    UrdfJoint("rudder_link", "hull_link", (-1.08641, 0.0, 0.0764342), (0.0, 0.0, 0.0), "rudder_joint"),
    UrdfJoint("eletric_engine_base_link", "hull_link", (-1.24471, 0.0, 0.199376), (0.0, 0.0, 0.0),
              "eletric_egine_base"),
    UrdfJoint("eletric_engine_link", "hull_link", (-1.3297, 0.0, 0.389059), (0.0, 0.0, 0.0), "electric_engine_joint"),
    UrdfJoint("propeller_link", "eletric_engine_link", (-0.089683, 0.0, -0.949), (0.0, 0.0, 0.0), "propeller_joint"),
    UrdfJoint("biruta_link", "mast_link", (0.161823, 0.0, 3.765), (0.0, 0.0, 0.0), "biruta_joint"),
    UrdfJoint("deck_link", "hull_link", (-1.24471, 0.0, 0.199376), (0.0, 0.0, 0.0), "deck_joint"),
    UrdfJoint("support_hack_port_4_link", "deck_link", (2.44761, 0.0712925, 0.05), (0.0, 0.0, 0.0),
              "support_hack_port_4_joint"),
    UrdfJoint("support_hack_starboard_4_link", "deck_link", (2.44761, -0.071293, 0.05), (0.0, 0.0, 0.0),
              "support_hack_starboard_4_joint"),
    UrdfJoint("hack_port_link", "support_hack_port_4_link", (0.0126828, 0.0159808, 0.0899999),
              (-1.5708, -1.50078e-14, -0.372391), "hack_port_joint"),
    UrdfJoint("hack_starboard_link", "support_hack_starboard_4_link", (0.0126838, -0.0159804, 0.09),
              (1.5708, 0.0, 0.372391), "hack_starboard_joint"),
    UrdfJoint("camera_bow_link", "hull_link", (0.791272, 0.0, 0.339059), (0.0, 0.0, 0.0), "camera_bow_joint"),
    UrdfJoint("zed_windshield_link", "camera_bow_link", (0.184448, 0.0, 0.645), (1.5708, 0.0, 1.5708),
              "zed_windshield_joint"),
)
"""The joints of the URDF that lead to a link with mass (the URDF's figures; near-zero y offsets and rpy
terms below 1e-15 written as 0)."""

URDF_INERTIALS = (
    UrdfInertial("hull_link", "hull", 83.6871, (-0.198002, 3.41823e-05, -0.0601847),
                 (7.79423, -0.000716745, 1.26709, 42.8173, -0.00040264, 47.1467)),
    UrdfInertial("keel_link", "keel", 40.0429, (0.00547163, 2.63588e-07, -0.725086),
                 (5.03511, 7.80906e-07, -0.0285151, 5.27158, -2.96682e-06, 0.268882)),
    UrdfInertial("mast_link", "mast", 12.5051, (0.000187579, 2.65619e-06, 1.95789),
                 (15.8929, -1.88499e-06, -0.0063914, 15.8933, -5.77577e-05, 0.0187623)),
    UrdfInertial("boom_link", "boom", 2.41221, (-0.919334, 1.93244e-09, -2.13818e-05),
                 (0.000428164, -8.9867e-10, 7.73411e-05, 0.664587, -1.08464e-11, 0.664584)),
    UrdfInertial("sail_link", "sail", 2.216, (1.10322, 1.09346, -1.24505e-20),
                 (1.15797, 0.243689, 0.0, 0.386027, 0.0, 1.544)),
    UrdfInertial("rudder_link", "rudder", 1.60411, (-0.00643978, -6.54895e-06, -0.519314),
                 (0.0520097, -3.11339e-06, -0.00205504, 0.0547543, -6.35686e-07, 0.00276576)),
    UrdfInertial("deck_link", "deck", 4.65558, (1.10267, 0.00505112, 0.0298862),
                 (0.384796, 0.0209115, 0.00217436, 1.95434, 0.000402869, 2.33348)),
    UrdfInertial("eletric_engine_link", "electric leg", 3.62539, (-0.00825704, -3.56246e-09, -0.761657),
                 (0.396803, -7.66434e-09, -0.00560877, 0.401013, -5.77582e-09, 0.00711339)),
    UrdfInertial("eletric_engine_base_link", "engine base", 0.887162, (-0.0177716, 0.0, 0.122132),
                 (0.0037743, 0.0, 0.000214551, 0.00311449, 0.0, 0.00287765)),
    UrdfInertial("propeller_link", "propeller", 0.0667546, (-0.0280716, 2.41471e-06, 2.58598e-06),
                 (0.000104539, 2.96574e-10, -1.53341e-09, 6.3824e-05, -2.26066e-09, 6.38236e-05)),
    UrdfInertial("bow_link", "bow", 1.09744, (0.0248668, 3.43326e-08, 0.0804057),
                 (0.00961813, 9.91294e-09, -0.000631055, 0.00934886, -3.13957e-09, 0.000977479)),
    UrdfInertial("hack_port_link", "rack port", 1.73299, (-1.21877, -0.00999996, -0.172045),
                 (0.145894, 0.307705, -0.11957, 0.813431, 0.0467072, 0.908646)),
    UrdfInertial("hack_starboard_link", "rack starboard", 1.73225, (-1.21825, 0.00999997, -0.171867),
                 (0.145737, -0.307311, -0.119523, 0.812433, -0.0466871, 0.907495)),
    UrdfInertial("camera_bow_link", "camera", 2.06829, (0.0526688, -2.92253e-05, 0.2517),
                 (0.199288, -1.12989e-05, -0.0471625, 0.19841, -1.44209e-05, 0.0538996)),
    UrdfInertial("zed_windshield_link", "camera windshield", 0.109671, (0.0, 0.0, -0.002),
                 (0.000384223, 0.0, 0.0, 0.000504943, 0.0, 0.000121013)),
    UrdfInertial("biruta_link", "wind vane", 0.0021539, (-0.0148129, 1.0796e-10, 0.0419007),
                 (1.19286e-06, -1.19699e-14, 6.09373e-07, 2.92342e-06, -4.59008e-15, 1.8198e-06)),
)
"""Every link of the URDF with mass (the sheet's link table and the three it leaves out: propeller, camera
windshield, wind vane)."""


def _rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """URDF's fixed-axis rpy: R_z(yaw) R_y(pitch) R_x(roll)."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw),
                              math.sin(yaw))
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cr, -sr], [0.0, sr, cr]])
    ry = np.array([[cp, 0.0, sp], [0.0, 1.0, 0.0], [-sp, 0.0, cp]])
    rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
    return rz @ ry @ rx


def link_poses(joints=URDF_JOINTS, root: str = "base_link") -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each link's (rotation (3, 3), origin (3,)) in the frame of ``root`` [m], through the joint chain."""
    by_child = {joint.child: joint for joint in joints}
    poses = {root: (np.eye(3), np.zeros(3))}

    def pose(link: str, chain: tuple[str, ...] = ()) -> tuple[np.ndarray, np.ndarray]:
        if link in poses:
            return poses[link]
        if link not in by_child or link in chain:
            raise ValueError(f"link_poses: no joint chain from {link!r} to {root!r}")
        joint = by_child[link]
        rotation, origin = pose(joint.parent, chain + (link,))
        poses[link] = (rotation @ _rotation(*joint.rpy), origin + rotation @ np.asarray(joint.xyz))
        return poses[link]

    for joint in joints:
        pose(joint.child)
    return poses


@functools.cache
def urdf_links() -> tuple[Link, ...]:
    """The URDF's links with mass as :class:`~ocean_warp.eboat.sheet.Link` rows in the base frame: centre of
    mass [m] through the joint chain, inertia about it turned into base-frame axes (R I R^T), as a (3, 3)."""
    poses = link_poses()
    links = []
    for inertial in URDF_INERTIALS:
        rotation, origin = poses[inertial.link]
        ixx, ixy, ixz, iyy, iyz, izz = inertial.inertia
        own = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        turned = rotation @ own @ rotation.T
        center = origin + rotation @ np.asarray(inertial.center)
        links.append(Link(inertial.name, inertial.mass, tuple(float(v) for v in center),
                          tuple(tuple(float(v) for v in row) for row in turned),
                          f"{URDF_SOURCE}: inertial of {inertial.link} through the joint chain"))
    return tuple(links)
