"""The ray-cast scene's objects and the lidar's returns in a stage (layout: ``ocean_warp.usd.paths``)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from pxr import Gf, Kind, Usd, UsdGeom, Vt

from ..meshes import ellipsoid, tube
from ..perception.scene import SceneObject, Shape
from .geometry import define_mesh
from .materials import Look, bind_look, define_look
from .paths import LIDAR, OBJECTS

__all__ = ["ObjectsWriter", "LidarPointsWriter", "object_mesh"]

LIDAR_POINT_WIDTH = 0.08
"""Drawn diameter of a lidar return [m]."""


def _look_name(color) -> str:
    """The material of an object of ``color`` (r, g, b in 0-1): ``Object_RRGGBB``, one per colour."""
    return "Object_" + "".join(f"{round(255 * float(c)):02X}" for c in color)


def object_mesh(item: SceneObject):
    """The :class:`~ocean_warp.meshes.MeshData` that draws ``item`` in its own frame."""
    if item.shape is Shape.SPHERE:
        return ellipsoid((0.0, 0.0, 0.0), (item.radius,) * 3, rings=12, sides=18)
    if item.shape is Shape.CYLINDER:
        return tube((0.0, 0.0, -0.5 * item.height), (0.0, 0.0, 0.5 * item.height), item.radius, sides=24)
    return item.mesh


class ObjectsWriter:
    """``objects`` (world positions, one environment) as Xforms under :data:`~ocean_warp.usd.paths.OBJECTS`:
    fixed objects posed once, floating ones time-sampled by :meth:`write`; ``labels`` (one per object, or
    None) their display names."""

    def __init__(self, stage: Usd.Stage, objects: Sequence[SceneObject], labels: Sequence[str] | None = None):
        self.objects = list(objects)
        if labels is not None and len(labels) != len(self.objects):
            raise ValueError(f"ObjectsWriter.labels must name each of the {len(self.objects)} objects, "
                             f"got {len(labels)}")
        root = UsdGeom.Xform.Define(stage, OBJECTS)
        Usd.ModelAPI(root.GetPrim()).SetKind(Kind.Tokens.group)
        self._poses = []
        for k, item in enumerate(self.objects):
            path = f"{OBJECTS}/Object_{k:03d}"
            xform = UsdGeom.Xform.Define(stage, path)
            Usd.ModelAPI(xform.GetPrim()).SetKind(Kind.Tokens.component)
            if labels is not None:
                xform.GetPrim().SetDisplayName(str(labels[k]))
            translate = xform.AddTranslateOp(UsdGeom.XformOp.PrecisionDouble)
            orient = xform.AddOrientOp(UsdGeom.XformOp.PrecisionFloat)
            half_yaw = 0.5 * item.yaw
            translate.Set(Gf.Vec3d(*map(float, item.position)))
            orient.Set(Gf.Quatf(float(np.cos(half_yaw)), 0.0, 0.0, float(np.sin(half_yaw))))
            shape = define_mesh(stage, f"{path}/Shape", object_mesh(item), color=item.color)
            bind_look(shape.GetPrim(), define_look(stage, _look_name(item.color), Look(tuple(item.color))))
            self._poses.append((translate, orient) if item.floats else None)

    @property
    def floating(self) -> np.ndarray:
        """Indices of the objects whose pose :meth:`write` samples."""
        return np.array([k for k, pose in enumerate(self._poses) if pose is not None], dtype=np.int64)

    def write(self, time_code: float, positions: np.ndarray, orientations: np.ndarray) -> None:
        """Poses of every object (M, 3) [m] and (M, 4) quaternions x y z w at ``time_code``; only the
        floating ones are written."""
        for k, pose in enumerate(self._poses):
            if pose is None:
                continue
            x, y, z = map(float, positions[k])
            qx, qy, qz, qw = map(float, orientations[k])
            pose[0].Set(Gf.Vec3d(x, y, z), time_code)
            pose[1].Set(Gf.Quatf(qw, qx, qy, qz), time_code)


class LidarPointsWriter:
    """Lidar returns as time-sampled points at :data:`~ocean_warp.usd.paths.LIDAR` (one sample per frame:
    the frame's hit points; rows with NaN, beams that saw nothing, are left out)."""

    def __init__(self, stage: Usd.Stage, color=(0.1, 1.0, 0.2)):
        points = UsdGeom.Points.Define(stage, LIDAR)
        points.CreateDisplayColorPrimvar(UsdGeom.Tokens.constant).Set(Vt.Vec3fArray([Gf.Vec3f(*color)]))
        self._points = points.CreatePointsAttr()
        self._widths = points.CreateWidthsAttr()
        points.SetWidthsInterpolation(UsdGeom.Tokens.constant)
        self._widths.Set(Vt.FloatArray([LIDAR_POINT_WIDTH]))

    def write(self, time_code: float, points: np.ndarray) -> int:
        """The returns (P, 3) [m] at ``time_code``; returns how many were written."""
        rows = np.asarray(points, dtype=np.float32).reshape(-1, 3)
        rows = rows[np.all(np.isfinite(rows), axis=1)]
        self._points.Set(Vt.Vec3fArray.FromNumpy(rows), time_code)
        return len(rows)
