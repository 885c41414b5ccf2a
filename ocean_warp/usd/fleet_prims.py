"""The boats in a stage, in one of two layouts, both animated one frame at a time.

- **One prim per boat** (:class:`PrimFleetWriter`): ``Boat_0000``... Xforms (``component`` models) with a
  time-sampled translate and orient (the pose), each holding ``Body``, ``Boom`` and ``Rudder`` that
  reference the prototype, and ``Boom/Reef``, the sail, at its tack; the boom's and the rudder's rotateZ and
  the sail's scale (its reef) are time-sampled; each hull has its colour from
  :data:`~ocean_warp.usd.materials.HULL_PALETTE`. Good for a few dozen boats.
- **Point instancers** (:class:`InstancedFleetWriter`): animation inside a PointInstancer's prototype
  would be shared by every instance, so each moving part has its own instancer (``Bodies``, ``Booms``,
  ``Sails``, ``Rudders``) whose instances carry that part's world pose, composed here on the host from the
  boat's pose and the part's pivot and angle, and the sails their reef's scale. A few arrays per frame,
  however many boats; every hull has the prototype's colour.

A boat's sail is drawn at its reef: the full sail scaled by the level's linear factor s about its tack
(``BoatParts.sail_tack``, the foot of its luff at the mast), as the rig sails it; s can change at any frame
(a new episode).

The fleet's prim is an ``assembly`` model in both layouts.

Quaternions on the way in are Warp's (x, y, z, w), body (FLU) -> world (ENU).
"""

from __future__ import annotations

import numpy as np
from pxr import Gf, Sdf, UsdGeom, Vt

from ..eboat.parts import BODY, BOOM, REEF, RUDDER, BoatParts
from .materials import HULL_PALETTE, Look, LOOKS_BY_NAME, bind_look, define_look, hull_look_name
from .paths import FLEET, boat_path
from .vessel_prims import define_boat_prim, define_fleet_prim, set_boat_pose

__all__ = ["PrimFleetWriter", "InstancedFleetWriter", "quaternion_multiply", "quaternion_rotate", "about_z"]

INSTANCERS = {BODY: "Bodies", BOOM: "Booms", REEF: "Sails", RUDDER: "Rudders"}
"""Name of the instancer of each moving part."""


def quaternion_multiply(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(N, 4) Hamilton products a b of (N, 4) quaternions (x, y, z, w): rotate by b, then by a."""
    ax, ay, az, aw = np.moveaxis(a, -1, 0)
    bx, by, bz, bw = np.moveaxis(b, -1, 0)
    return np.stack([aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw,
                     aw * bw - ax * bx - ay * by - az * bz], axis=-1)


def quaternion_rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """(N, 3) vectors v (N, 3) or (3,) rotated by unit quaternions q (N, 4) (x, y, z, w)."""
    u, w = q[:, :3], q[:, 3:]
    t = 2.0 * np.cross(u, np.broadcast_to(v, u.shape))
    return v + w * t + np.cross(u, t)


def about_z(angle: np.ndarray) -> np.ndarray:
    """(N, 4) quaternions (x, y, z, w) of rotations by ``angle`` (N,) [rad] about z."""
    half = 0.5 * np.asarray(angle, dtype=np.float64)
    zeros = np.zeros_like(half)
    return np.stack([zeros, zeros, np.sin(half), np.cos(half)], axis=-1)


def _paint_hull(stage, boat: str, index: int) -> None:
    """Give the hull of the boat at path ``boat`` colour ``index`` of HULL_PALETTE: an override of the
    prototype's material binding and displayColor on this boat's own hull (entry 0 is the prototype's)."""
    if index % len(HULL_PALETTE) == 0:
        return
    color = HULL_PALETTE[index % len(HULL_PALETTE)]
    material = define_look(stage, hull_look_name(index), Look(color, roughness=LOOKS_BY_NAME["Hull"].roughness))
    hull = stage.OverridePrim(f"{boat}/{BODY}/Hull")
    UsdGeom.Gprim(hull).CreateDisplayColorPrimvar(UsdGeom.Tokens.constant).Set(Vt.Vec3fArray([Gf.Vec3f(*color)]))
    bind_look(hull, material)


class PrimFleetWriter:
    """One Xform per boat under :data:`~ocean_warp.usd.paths.FLEET`, referencing ``prototype`` (paths of the
    Body, Boom and Rudder groups by name)."""

    def __init__(self, stage, count: int, prototype: dict[str, str], parts: BoatParts):
        define_fleet_prim(stage, count)
        self._pose, self._boom, self._rudder, self._reef = [], [], [], []
        for i in range(count):
            self._pose.append(define_boat_prim(stage, i))
            body = UsdGeom.Xform.Define(stage, f"{boat_path(i)}/{BODY}")
            body.GetPrim().GetReferences().AddInternalReference(prototype[BODY])
            for name, pivot, ops in ((BOOM, parts.boom_pivot, self._boom), (RUDDER, parts.rudder_pivot, self._rudder)):
                part = UsdGeom.Xform.Define(stage, f"{boat_path(i)}/{name}")
                part.GetPrim().GetReferences().AddInternalReference(prototype[name])
                part.AddTranslateOp().Set(Gf.Vec3d(*map(float, pivot)))
                ops.append(part.AddRotateZOp())
            reef = UsdGeom.Xform.Define(stage, f"{boat_path(i)}/{BOOM}/{REEF}")
            reef.GetPrim().GetReferences().AddInternalReference(prototype[REEF])
            reef.AddTranslateOp().Set(Gf.Vec3d(*map(float, parts.sail_tack)))
            self._reef.append(reef.AddScaleOp())
            _paint_hull(stage, boat_path(i), i)

    def write(self, time_code: float, positions, orientations, boom_angles, rudder_angles, sail_scales=None) -> None:
        """One frame: positions (N, 3) [m], unit orientations (N, 4) (x, y, z, w), boom and rudder angles
        (N,) [rad] (positive to port; each a rotation of minus the angle about the pivot's z, in degrees), and
        each sail's linear scale about its tack (N,) (its reef; None: 1, the full sail)."""
        boom_degrees = 0.0 - np.degrees(boom_angles)
        rudder_degrees = 0.0 - np.degrees(rudder_angles)
        scales = np.ones(len(self._pose)) if sail_scales is None else np.asarray(sail_scales, dtype=np.float64)
        with Sdf.ChangeBlock():
            for i, ops in enumerate(self._pose):
                set_boat_pose(ops, positions[i], orientations[i], time_code)
                self._boom[i].Set(float(boom_degrees[i]), time_code)
                self._rudder[i].Set(float(rudder_degrees[i]), time_code)
                self._reef[i].Set(Gf.Vec3f(*(3 * (float(scales[i]),))), time_code)


class InstancedFleetWriter:
    """Four PointInstancers under :data:`~ocean_warp.usd.paths.FLEET` (``Bodies``, ``Booms``, ``Sails``,
    ``Rudders``), each with one prototype that references its group of ``prototype`` and one instance per
    boat."""

    def __init__(self, stage, count: int, prototype: dict[str, str], parts: BoatParts):
        define_fleet_prim(stage, count)
        self.parts = parts
        self.count = count
        self._attributes = {}
        # Each instance's prototype lies within this distance [m] of its position: the instancer's extent.
        self._radius = {name: float(np.linalg.norm(parts.group_points(name), axis=1).max()) for name in INSTANCERS}
        for name, instancer_name in INSTANCERS.items():
            path = f"{FLEET}/{instancer_name}"
            instancer = UsdGeom.PointInstancer.Define(stage, path)
            UsdGeom.Scope.Define(stage, f"{path}/Prototypes")
            proto = UsdGeom.Xform.Define(stage, f"{path}/Prototypes/{name}")
            proto.GetPrim().GetReferences().AddInternalReference(prototype[name])
            instancer.CreatePrototypesRel().SetTargets([proto.GetPath()])
            instancer.CreateProtoIndicesAttr(Vt.IntArray.FromNumpy(np.zeros(count, dtype=np.int32)))
            self._attributes[name] = (instancer.CreatePositionsAttr(), instancer.CreateOrientationsfAttr(),
                                      instancer.CreateExtentAttr())
        self._sail_scales = UsdGeom.PointInstancer.Get(stage, f"{FLEET}/{INSTANCERS[REEF]}").CreateScalesAttr()

    def part_poses(self, positions, orientations, boom_angles, rudder_angles) -> dict[str, tuple]:
        """World (positions (N, 3), orientations (N, 4) x y z w) of each part group: the body at the boat's
        pose, boom and rudder at their pivots, turned by minus their angle about the pivot's z axis, the sail
        at its tack on the boom."""
        poses = {BODY: (positions, orientations)}
        for name, pivot, angle in ((BOOM, self.parts.boom_pivot, boom_angles),
                                   (RUDDER, self.parts.rudder_pivot, rudder_angles)):
            poses[name] = (positions + quaternion_rotate(orientations, pivot),
                           quaternion_multiply(orientations, about_z(-np.asarray(angle, dtype=np.float64))))
        boom_at, boom_rotation = poses[BOOM]
        poses[REEF] = (boom_at + quaternion_rotate(boom_rotation, self.parts.sail_tack), boom_rotation)
        return poses

    def write(self, time_code: float, positions, orientations, boom_angles, rudder_angles, sail_scales=None) -> None:
        """One frame, the same arguments as :meth:`PrimFleetWriter.write`."""
        poses = self.part_poses(positions, orientations, boom_angles, rudder_angles)
        scales = np.ones(self.count) if sail_scales is None else np.asarray(sail_scales, dtype=np.float64)
        with Sdf.ChangeBlock():
            self._sail_scales.Set(Vt.Vec3fArray.FromNumpy(np.repeat(scales[:, None], 3, axis=1).astype(np.float32)),
                                  time_code)
            for name, (where, rotation) in poses.items():
                position_attr, orientation_attr, extent_attr = self._attributes[name]
                where32 = where.astype(np.float32)
                position_attr.Set(Vt.Vec3fArray.FromNumpy(where32), time_code)
                orientation_attr.Set(Vt.QuatfArray.FromNumpy(rotation.astype(np.float32)), time_code)
                if self.count:
                    low = where32.min(axis=0) - self._radius[name]
                    high = where32.max(axis=0) + self._radius[name]
                    extent_attr.Set(Vt.Vec3fArray([Gf.Vec3f(*map(float, low)), Gf.Vec3f(*map(float, high))]),
                                    time_code)
