"""The E-Boat's parts (``ocean_warp.eboat.parts``) as a USD prototype that every boat of a stage references."""

from __future__ import annotations

from pxr import UsdGeom

from ..eboat.parts import BODY, BOOM, REEF, RUDDER, BoatParts
from .geometry import define_mesh
from .materials import LOOKS_BY_NAME, bind_look, define_look

__all__ = ["define_boat_prototype"]

PART_LOOKS = {"Hull": "Hull", "Keel": "Foil", "Mast": "Spar", "Spar": "Spar", "Sail": "Sail", "Blade": "Foil"}
"""The material (:data:`~ocean_warp.usd.materials.LOOKS_BY_NAME`) of each part of the prototype."""


def define_boat_prototype(stage, path: str, parts: BoatParts) -> dict[str, str]:
    """Author ``parts`` under ``path`` (which should lie below a ``class`` prim, so it is not drawn) as four
    Xforms: ``Body`` (Hull, Keel, Mast), ``Boom`` (Spar, in the boom's pivot frame), ``Reef`` (Sail, the full
    sail with its tack at the origin, so that a boat's reef scales it about its origin) and ``Rudder`` (Blade,
    in the rudder's pivot frame), each part with its material (:data:`PART_LOOKS`) bound and its colour as
    displayColor. Returns the groups' paths by name."""
    paths = {name: f"{path}/{name}" for name in (BODY, BOOM, REEF, RUDDER)}
    for group in paths.values():
        UsdGeom.Xform.Define(stage, group)
    meshes = ((BODY, "Hull", parts.hull), (BODY, "Keel", parts.keel), (BODY, "Mast", parts.mast),
              (BOOM, "Spar", parts.spar), (REEF, "Sail", parts.sail_in_tack_frame()),
              (RUDDER, "Blade", parts.blade))
    for group, name, mesh in meshes:
        look = PART_LOOKS[name]
        prim = define_mesh(stage, f"{paths[group]}/{name}", mesh, color=LOOKS_BY_NAME[look].color,
                           double_sided=name == "Sail")
        bind_look(prim.GetPrim(), define_look(stage, look))
    return paths
