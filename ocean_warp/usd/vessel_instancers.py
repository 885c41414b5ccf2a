"""Any vessel's boats in a stage as point instancers, for large fleets: animation inside a PointInstancer's
prototype would be shared by every instance, so each part of ``Vessel.parts()`` has its own instancer under
:data:`~ocean_warp.usd.paths.FLEET` (named as the part's prim), whose instances carry that part's world pose,
composed here on the host from the boat's pose and the part's pivot and joint angle, and, for a part the vessel
scales per boat (``PartScaling``), the boat's scale about the part's scaling origin. A few arrays per frame,
however many boats; every hull has the prototype's colour. The instancer of a fixed part (the first) marks
itself with :data:`~ocean_warp.usd.paths.BOAT_ORIGINS_ATTRIBUTE`: its instances stand at the boats' origins.

Quaternions on the way in are Warp's (x, y, z, w), body (FLU) -> world (ENU).
"""

from __future__ import annotations

import numpy as np
from pxr import Gf, Sdf, UsdGeom, Vt

from ..frames import about_z, quaternion_multiply, quaternion_rotate
from .paths import BOAT_ORIGINS_ATTRIBUTE, FLEET
from .vessel_prims import define_fleet_prim, part_angles, prim_name

__all__ = ["InstancedVesselWriter"]


class InstancedVesselWriter:
    """One PointInstancer per part of ``parts`` under :data:`~ocean_warp.usd.paths.FLEET`, each with one prototype
    that references the part's group of ``prototype`` (part name -> path) and one instance per boat; the parts
    of ``scaling`` (a ``PartScaling`` or None) are scaled per boat about its origin."""

    def __init__(self, stage, count: int, prototype: dict[str, str], parts, scaling=None):
        define_fleet_prim(stage, count)
        self.parts = tuple(parts)
        self.count = count
        scaled = set(scaling.parts) if scaling is not None else set()
        largest = max(scaling.scales) if scaling is not None else 1.0
        # A scaled part's prototype is its mesh moved so that its scaling origin sits at the prototype's origin.
        self._origin = {part.name: np.asarray(scaling.origin if part.name in scaled else (0.0, 0.0, 0.0), np.float64)
                        for part in self.parts}
        self._attributes, self._scales, self._radius = {}, {}, {}
        origins_marked = False
        for part in self.parts:
            name = prim_name(part.name)
            path = f"{FLEET}/{name}"
            instancer = UsdGeom.PointInstancer.Define(stage, path)
            UsdGeom.Scope.Define(stage, f"{path}/Prototypes")
            proto = UsdGeom.Xform.Define(stage, f"{path}/Prototypes/{name}")
            proto.GetPrim().GetReferences().AddInternalReference(prototype[part.name])
            origin = self._origin[part.name]
            if part.name in scaled:
                proto.AddTranslateOp().Set(Gf.Vec3d(*map(float, -origin)))
                self._scales[part.name] = instancer.CreateScalesAttr()
            instancer.CreatePrototypesRel().SetTargets([proto.GetPath()])
            instancer.CreateProtoIndicesAttr(Vt.IntArray.FromNumpy(np.zeros(count, dtype=np.int32)))
            self._attributes[part.name] = (instancer.CreatePositionsAttr(), instancer.CreateOrientationsfAttr(),
                                           instancer.CreateExtentAttr())
            # Each instance's prototype lies within this distance [m] of its position: the instancer's extent.
            factor = largest if part.name in scaled else 1.0
            self._radius[part.name] = factor * float(np.linalg.norm(part.mesh.points - origin, axis=1).max())
            if part.joint is None and part.name not in scaled and not origins_marked:
                instancer.GetPrim().CreateAttribute(BOAT_ORIGINS_ATTRIBUTE, Sdf.ValueTypeNames.Bool,
                                                    custom=True).Set(True)
                origins_marked = True

    def part_poses(self, positions, orientations, joints: dict) -> dict[str, tuple]:
        """World (positions (N, 3), orientations (N, 4) x y z w) of each part's instances: a fixed part at the
        boat's pose, a jointed one at its pivot turned by minus its angle about the pivot's z axis, a scaled one
        at its scaling origin."""
        angles = part_angles(self.parts, joints, self.count)
        poses = {}
        for part in self.parts:
            where, rotation = positions, orientations
            if part.joint is not None:
                where = positions + quaternion_rotate(orientations, np.asarray(part.pivot, np.float64))
                rotation = quaternion_multiply(orientations, about_z(-angles[part.name]))
            poses[part.name] = (where + quaternion_rotate(rotation, self._origin[part.name]), rotation)
        return poses

    def write(self, time_code: float, positions, orientations, joints: dict, scales=None) -> None:
        """One frame, the same arguments as :meth:`~ocean_warp.usd.vessel_prims.VesselFleetWriter.write`."""
        poses = self.part_poses(positions, orientations, joints)
        scales = np.ones(self.count) if scales is None else np.asarray(scales, dtype=np.float64)
        with Sdf.ChangeBlock():
            for attribute in self._scales.values():
                attribute.Set(Vt.Vec3fArray.FromNumpy(np.repeat(scales[:, None], 3, axis=1).astype(np.float32)),
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
