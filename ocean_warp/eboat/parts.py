"""The E-Boat as a viewer or a sensor sees it: hull, keel, mast, boom with sail and rudder, as meshes from the
data sheet's dimensions (``ocean_warp.eboat``), for the USD stages and the ray-cast scene.

Frames: the body frame (x to the bow, y to port, z up, origin at the waterline) for the fixed parts; the
boom and the rudder each in a pivot frame, origin on its vertical axis of rotation, so that a boat's
boom angle b [rad] (positive to port) is a rotation of -b about the pivot's z axis, and likewise the
rudder angle (positive with the trailing edge to port), as in ``ocean_warp.kernels.sailing_rig``.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..meshes import MeshData, concatenate, ellipsoid, extruded, foil_section, triangle, tube
from .eboat import MAST_LENGTH, EBoatConfig
from .hull_shape import eboat_hull
from .sheet import BOOM_HEIGHT, FOILS, HULL_LINK_HEIGHT, MAST_STEP

__all__ = ["BoatParts", "eboat_parts", "BODY", "BOOM", "RUDDER"]

BODY, BOOM, RUDDER = "Body", "Boom", "Rudder"
"""Names of the prototype's three rigid groups (children of the prototype prim)."""

BOOM_LENGTH = 1.8
"""From the mast to the clew [m] (the rod of ``EBoat.boom_inertia``)."""
MAST_RADIUS = 0.05
"""[m]: the sheet's 3.55 x 0.1 m mast."""
SPAR_RADIUS = 0.03
"""[m] (assumed)."""
RUDDER_STOCK = (-1.086, 0.0, HULL_LINK_HEIGHT + 0.076)
"""Sheet, rudder row: the joint at (-1.086, 0, 0.076) of the hull link, in the body frame [m]."""
RUDDER_SPAN, RUDDER_CHORD, RUDDER_THICKNESS = 0.608, 0.189, 0.015
"""Sheet, rudder row: its 0.189 x 0.015 x 0.608 m box [m]."""
KEEL_ROOT_Z = -0.2
"""Where the keel fin leaves the hull [m] (the canoe body's keel line is at -0.22 near the fin)."""
KEEL_THICKNESS = 0.12
"""Fin thickness as a fraction of its chord (assumed)."""


@dataclasses.dataclass(frozen=True)
class BoatParts:
    """Meshes of one boat [m]: ``hull``, ``keel`` and ``mast`` in the body frame; ``spar`` and ``sail`` in
    the boom's pivot frame at ``boom_pivot``; ``blade`` in the rudder's pivot frame at ``rudder_pivot``."""

    hull: MeshData
    keel: MeshData
    mast: MeshData
    spar: MeshData
    sail: MeshData
    blade: MeshData
    boom_pivot: np.ndarray
    """(3,) the boom's gooseneck on the mast, body frame [m]."""
    rudder_pivot: np.ndarray
    """(3,) the top of the rudder stock, body frame [m]."""

    def group_points(self, group: str) -> np.ndarray:
        """(P, 3) every vertex of ``group`` (BODY, BOOM or RUDDER) in that group's own frame [m]."""
        meshes = {BODY: (self.hull, self.keel, self.mast), BOOM: (self.spar, self.sail), RUDDER: (self.blade,)}
        return concatenate(*meshes[group]).points


def eboat_parts(config: EBoatConfig | None = None, *, hull_detail: int = 2) -> BoatParts:
    """The E-Boat of ``config`` (default V-C) as meshes. The hull is the physics hull's shape lofted with
    ``hull_detail`` times as many stations and section points (1: the physics mesh itself). The keel fin
    has the version's keel area and its centre of effort at mid-span, a quarter chord aft of its leading
    edge, with a bulb below; the sail is the triangle from the boom to the masthead (2.8 m^2; the sheet's
    3.188 m^2 sail has roach this leaves out)."""
    config = config if config is not None else EBoatConfig()
    if isinstance(hull_detail, bool) or not isinstance(hull_detail, int) or not 1 <= hull_detail <= 8:
        raise ValueError(f"eboat_parts: hull_detail must be an integer in [1, 8], got {hull_detail!r}")
    shape = config.meshed_hull_shape
    fine = dataclasses.replace(shape, stations=shape.stations * hull_detail,
                               section_points=shape.section_points * hull_detail)
    hull = eboat_hull(fine)
    hull_mesh = MeshData(np.asarray(hull.vertices, dtype=np.float64),
                         np.full(len(hull.triangles), 3, dtype=np.int32),
                         np.asarray(hull.triangles, dtype=np.int32).reshape(-1))

    figures = FOILS[config.version]
    keel_x, _, keel_z = figures.keel_center
    span = 2.0 * (KEEL_ROOT_Z - keel_z)
    chord = figures.keel_area / span
    fin = extruded(foil_section(chord, KEEL_THICKNESS, leading_edge_x=keel_x + 0.25 * chord),
                   KEEL_ROOT_Z - span, KEEL_ROOT_Z + 0.05)  # a little into the hull, so no gap shows
    bulb = ellipsoid((keel_x - 0.1 * chord, 0.0, KEEL_ROOT_Z - span), (0.35, 0.07, 0.07))

    mast_foot = np.array([MAST_STEP[0], 0.0, MAST_STEP[2]])
    masthead_z = MAST_STEP[2] + MAST_LENGTH
    mast = tube(mast_foot, mast_foot + (0.0, 0.0, MAST_LENGTH), MAST_RADIUS)
    boom_pivot = np.array([MAST_STEP[0], 0.0, BOOM_HEIGHT])
    spar = tube((0.0, 0.0, 0.0), (-BOOM_LENGTH, 0.0, 0.0), SPAR_RADIUS)
    sail = triangle((-MAST_RADIUS, 0.0, SPAR_RADIUS), (-BOOM_LENGTH, 0.0, SPAR_RADIUS),
                    (-MAST_RADIUS, 0.0, masthead_z - BOOM_HEIGHT - 0.05))
    blade = extruded(foil_section(RUDDER_CHORD, RUDDER_THICKNESS / RUDDER_CHORD, leading_edge_x=0.25 * RUDDER_CHORD),
                     -RUDDER_SPAN, 0.0)
    return BoatParts(hull=hull_mesh, keel=concatenate(fin, bulb), mast=mast, spar=spar, sail=sail, blade=blade,
                     boom_pivot=boom_pivot, rudder_pivot=np.array(RUDDER_STOCK))
