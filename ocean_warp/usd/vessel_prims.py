"""Any vessel's boats in a stage (``ocean_warp.vessel``): one prim per boat, one child per part of
``Vessel.parts()``, animated one frame at a time.

The vessel's parts are authored once under a ``class`` prim (``/Library/<vessel>/<part>/Mesh``, each with the
look of its material) and every boat's part references its own: ``Boat_0000/<part>``. A boat's Xform carries
its time-sampled translate and orient (the pose); a jointed part carries its pivot as a translate and minus its
joint's angle as a time-sampled rotateZ [deg] (``VesselPart``: it turns by -angle about its pivot's z). Parts a
vessel scales per boat (``PartScaling``) are drawn at their full size here.

Quaternions on the way in are Warp's (x, y, z, w), body (FLU) -> world (ENU).
"""

from __future__ import annotations

import re

import numpy as np
from pxr import Gf, Kind, Sdf, Usd, UsdGeom

from .geometry import define_mesh
from .materials import LOOKS_BY_NAME, bind_look, define_look
from .paths import BOAT_COUNT_ATTRIBUTE, FLEET, LIBRARY, boat_path

__all__ = ["MATERIAL_LOOKS", "prim_name", "vessel_prototype_path", "define_vessel_prototype", "VesselFleetWriter",
           "define_fleet_prim", "define_boat_prim", "set_boat_pose"]

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


class VesselFleetWriter:
    """One Xform per boat under :data:`~ocean_warp.usd.paths.FLEET` (``component`` models in an ``assembly``),
    each with one child per part referencing ``prototype`` (part name -> path)."""

    def __init__(self, stage, count: int, prototype: dict[str, str], parts):
        define_fleet_prim(stage, count)
        self.parts = tuple(parts)
        self.joints = tuple((part.joint, part.joint_column) for part in self.parts if part.joint is not None)
        """(state array name, column) of each jointed part, in the order of the parts."""
        self._pose, self._turns = [], []
        for i in range(count):
            self._pose.append(define_boat_prim(stage, i))
            turns = []
            for part in self.parts:
                prim = UsdGeom.Xform.Define(stage, f"{boat_path(i)}/{prim_name(part.name)}")
                prim.GetPrim().GetReferences().AddInternalReference(prototype[part.name])
                if part.joint is not None:
                    prim.AddTranslateOp().Set(Gf.Vec3d(*map(float, part.pivot)))
                    turns.append(prim.AddRotateZOp())
            self._turns.append(turns)

    def write(self, time_code: float, positions, orientations, joints: dict) -> None:
        """One frame: positions (N, 3) [m], unit orientations (N, 4) (x, y, z, w) and ``joints``, each jointed
        part's state array by name ((N,) or (N, C) [rad], positive to port)."""
        angles = []
        for name, column in self.joints:
            values = np.asarray(joints[name], dtype=np.float64)
            angles.append(values if values.ndim == 1 else values[:, column])
        degrees = -np.degrees(np.column_stack(angles)) if angles else np.zeros((len(self._pose), 0))
        with Sdf.ChangeBlock():
            for i, ops in enumerate(self._pose):
                set_boat_pose(ops, positions[i], orientations[i], time_code)
                for op, value in zip(self._turns[i], degrees[i]):
                    op.Set(float(value), time_code)
