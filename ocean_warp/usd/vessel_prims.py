"""Any vessel's boats in a stage (``ocean_warp.vessel``), one prim per boat, one child per part of
``Vessel.parts()``, animated one frame at a time (the other layout, point instancers for large fleets:
``ocean_warp.usd.vessel_instancers``).

The vessel's parts are authored once under a ``class`` prim (``/Library/<vessel>/<part>/Mesh``, each with the
look of its material) and every boat's part references its own: ``Boat_0000/<part>``. A boat's Xform carries
its time-sampled translate and orient (the pose); a jointed part carries its pivot as a translate and minus its
joint's angle as a time-sampled rotateZ [deg] (``VesselPart``: it turns by -angle about its pivot's z). A part
the vessel draws at a size of each boat's own (``PartScaling``: the E-Boat's sail at its reef) carries a
time-sampled scale about its origin (translate to the origin, scale, translate back). Each boat's hull parts
(material ``hull``) have its colour of :data:`~ocean_warp.usd.materials.HULL_PALETTE`.

Quaternions on the way in are Warp's (x, y, z, w), body (FLU) -> world (ENU).
"""

from __future__ import annotations

import re

import numpy as np
from pxr import Gf, Kind, Sdf, Usd, UsdGeom, Vt

from .geometry import define_mesh
from .materials import HULL_PALETTE, LOOKS_BY_NAME, Look, bind_look, define_look, hull_look_name
from .paths import BOAT_COUNT_ATTRIBUTE, FLEET, LIBRARY, boat_path

__all__ = ["MATERIAL_LOOKS", "prim_name", "vessel_prototype_path", "define_vessel_prototype", "VesselFleetWriter",
           "define_fleet_prim", "define_boat_prim", "set_boat_pose", "part_angles"]

MATERIAL_LOOKS = {"hull": "Hull", "sail": "Sail", "foil": "Foil", "metal": "Spar", "dark": "Foil"}
"""The look (:data:`~ocean_warp.usd.materials.LOOKS_BY_NAME`) of each ``VesselPart.material`` (others: Hull)."""


def prim_name(name: str) -> str:
    """``name`` as a USD prim name: every character but a letter, a digit or _ becomes _ (``WAM-V`` ->
    ``WAM_V``), and a leading digit gets a _ before it."""
    cleaned = re.sub(r"[^A-Za-z0-9_]", "_", str(name)) or "_"
    return f"_{cleaned}" if cleaned[0].isdigit() else cleaned


def vessel_prototype_path(vessel) -> str:
    """Where a stage keeps ``vessel``'s parts: ``/Library/<its name as a prim name>``."""
    return f"{LIBRARY}/{prim_name(vessel.name)}"


def define_vessel_prototype(stage, path: str, parts) -> dict[str, str]:
    """Author each of ``parts`` (``VesselPart`` s) under ``path`` (below a ``class`` prim, so not drawn) as an Xform
    holding its mesh (``Mesh``, in the part's own frame) with its look bound and its colour as displayColor.
    Returns each part's Xform path by part name."""
    paths = {}
    for part in parts:
        group = f"{path}/{prim_name(part.name)}"
        if group in paths.values():
            raise ValueError(f"USD: two parts of the vessel have the prim name {prim_name(part.name)!r}")
        UsdGeom.Xform.Define(stage, group)
        look = MATERIAL_LOOKS.get(part.material, "Hull")
        mesh = define_mesh(stage, f"{group}/Mesh", part.mesh, color=LOOKS_BY_NAME[look].color,
                           double_sided=part.material == "sail")
        bind_look(mesh.GetPrim(), define_look(stage, look))
        paths[part.name] = group
    return paths


def define_fleet_prim(stage, count: int):
    """The fleet's Xform, an ``assembly`` model that says how many boats it holds."""
    fleet = UsdGeom.Xform.Define(stage, FLEET)
    fleet.GetPrim().CreateAttribute(BOAT_COUNT_ATTRIBUTE, Sdf.ValueTypeNames.Int, custom=True).Set(int(count))
    Usd.ModelAPI(fleet.GetPrim()).SetKind(Kind.Tokens.assembly)
    return fleet


def define_boat_prim(stage, index: int) -> tuple:
    """Boat ``index``'s Xform, a ``component`` model; returns its (translate, orient) ops for :func:`set_boat_pose`."""
    boat = UsdGeom.Xform.Define(stage, boat_path(index))
    Usd.ModelAPI(boat.GetPrim()).SetKind(Kind.Tokens.component)
    return boat.AddTranslateOp(UsdGeom.XformOp.PrecisionDouble), boat.AddOrientOp(UsdGeom.XformOp.PrecisionFloat)


def set_boat_pose(ops: tuple, position, orientation, time_code: float) -> None:
    """A boat's pose at ``time_code``: ``position`` (3,) [m] and ``orientation`` (4,) x, y, z, w."""
    translate, orient = ops
    x, y, z = map(float, position)
    qx, qy, qz, qw = map(float, orientation)
    translate.Set(Gf.Vec3d(x, y, z), time_code)
    orient.Set(Gf.Quatf(qw, qx, qy, qz), time_code)


def part_angles(parts, joints: dict, count: int) -> dict[str, np.ndarray]:
    """Each jointed part's (``count``,) angle [rad] by part name, read from ``joints``, its state array by name
    ((N,) or (N, C): column ``joint_column``)."""
    angles = {}
    for part in parts:
        if part.joint is not None:
            values = np.asarray(joints[part.joint], dtype=np.float64)
            angles[part.name] = (values if values.ndim == 1 else values[:, part.joint_column]).reshape(count)
    return angles


def _paint_hull(stage, mesh_path: str, index: int) -> None:
    """Give the mesh at ``mesh_path`` (a boat's hull part) colour ``index`` of HULL_PALETTE: an override of the
    prototype's material binding and displayColor (entry 0 is the prototype's)."""
    if index % len(HULL_PALETTE) == 0:
        return
    color = HULL_PALETTE[index % len(HULL_PALETTE)]
    material = define_look(stage, hull_look_name(index), Look(color, roughness=LOOKS_BY_NAME["Hull"].roughness))
    hull = stage.OverridePrim(mesh_path)
    UsdGeom.Gprim(hull).CreateDisplayColorPrimvar(UsdGeom.Tokens.constant).Set(Vt.Vec3fArray([Gf.Vec3f(*color)]))
    bind_look(hull, material)


class VesselFleetWriter:
    """One Xform per boat under :data:`~ocean_warp.usd.paths.FLEET` (``component`` models in an ``assembly``),
    each with one child per part referencing ``prototype`` (part name -> path); the parts of ``scaling`` (a
    ``PartScaling`` or None) are scaled per boat."""

    def __init__(self, stage, count: int, prototype: dict[str, str], parts, scaling=None):
        define_fleet_prim(stage, count)
        self.parts = tuple(parts)
        self.count = count
        scaled = set(scaling.parts) if scaling is not None else set()
        self._pose, self._turns, self._scales = [], [], []
        for i in range(count):
            self._pose.append(define_boat_prim(stage, i))
            turns, scales = {}, []
            for part in self.parts:
                path = f"{boat_path(i)}/{prim_name(part.name)}"
                prim = UsdGeom.Xform.Define(stage, path)
                prim.GetPrim().GetReferences().AddInternalReference(prototype[part.name])
                if part.joint is not None:
                    prim.AddTranslateOp().Set(Gf.Vec3d(*map(float, part.pivot)))
                    turns[part.name] = prim.AddRotateZOp()
                if part.name in scaled:
                    origin = prim.AddTranslateOp(opSuffix="scaleOrigin")
                    origin.Set(Gf.Vec3d(*map(float, scaling.origin)))
                    scales.append(prim.AddScaleOp())
                    prim.AddTranslateOp(opSuffix="scaleOrigin", isInverseOp=True)
                if part.material == "hull":
                    _paint_hull(stage, f"{path}/Mesh", i)
            self._turns.append(turns)
            self._scales.append(scales)

    def write(self, time_code: float, positions, orientations, joints: dict, scales=None) -> None:
        """One frame: positions (N, 3) [m], unit orientations (N, 4) (x, y, z, w), ``joints``, each jointed
        part's state array by name ((N,) or (N, C) [rad], positive to port), and ``scales`` (N,), each boat's
        linear factor on its scaled parts (None: 1)."""
        degrees = {name: -np.degrees(angle) for name, angle in part_angles(self.parts, joints, self.count).items()}
        scales = np.ones(self.count) if scales is None else np.asarray(scales, dtype=np.float64)
        with Sdf.ChangeBlock():
            for i, ops in enumerate(self._pose):
                set_boat_pose(ops, positions[i], orientations[i], time_code)
                for name, op in self._turns[i].items():
                    op.Set(float(degrees[name][i]), time_code)
                for op in self._scales[i]:
                    op.Set(Gf.Vec3f(*(3 * (float(scales[i]),))), time_code)
