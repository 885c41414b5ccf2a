"""Authoring a :class:`~ocean_warp.meshes.MeshData` as a USD mesh."""

from __future__ import annotations

import numpy as np
from pxr import Gf, UsdGeom, Vt

from ..meshes import MeshData

__all__ = ["define_mesh"]


def define_mesh(stage, path: str, mesh: MeshData, *, color=None, double_sided: bool = False) -> UsdGeom.Mesh:
    """Author ``mesh`` as a static UsdGeom.Mesh at ``path`` with its extent, ``color`` (r, g, b in 0-1) as
    its displayColor, and no subdivision (these are polygonal models)."""
    prim = UsdGeom.Mesh.Define(stage, path)
    prim.CreatePointsAttr(Vt.Vec3fArray.FromNumpy(mesh.points.astype(np.float32)))
    prim.CreateFaceVertexCountsAttr(Vt.IntArray.FromNumpy(mesh.face_counts))
    prim.CreateFaceVertexIndicesAttr(Vt.IntArray.FromNumpy(mesh.face_indices))
    low, high = mesh.extent
    prim.CreateExtentAttr(Vt.Vec3fArray([Gf.Vec3f(*map(float, low)), Gf.Vec3f(*map(float, high))]))
    prim.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
    if double_sided:
        prim.CreateDoubleSidedAttr(True)
    if color is not None:
        prim.CreateDisplayColorPrimvar(UsdGeom.Tokens.constant).Set(Vt.Vec3fArray([Gf.Vec3f(*map(float, color))]))
    return prim
