"""The E-Boat as a viewer or a sensor sees it: hull, keel, mast, boom with sail and rudder, as meshes of the
boat's own geometry (``ocean_warp.eboat.geometry``), for the USD stages and the ray-cast scene.

The real boat (default): the hull lofted from the offsets table, the keel's constant-chord fin with its bulb,
the tapered rudder on its stock, the mast to its head and the sail as the trapezoid the CAD measures (3.19
m^2, its centroid at the sheet's 2.15 m above the base frame). The procedural boat: its canoe body, a keel of
the sheet's area with a bulb below, the rudder box and a triangular sail.

Frames: the body frame (x to the bow, y to port, z up, origin at the waterline) for the fixed parts; the
boom and the rudder each in a pivot frame, origin on its vertical axis of rotation, so that a boat's
boom angle b [rad] (positive to port) is a rotation of -b about the pivot's z axis, and likewise the
rudder angle (positive with the trailing edge to port), as in ``ocean_warp.kernels.sailing_rig``. A reefed
sail is this sail scaled by its level's linear factor about its tack, ``BoatParts.sail_tack`` (the foot of its
luff at the mast), as the rig sails it (``EBoatConfig.reef_scales``).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..meshes import MeshData, concatenate, ellipsoid, extruded, foil_section, triangle, tube
from . import real_geometry as real
from .eboat import EBoatConfig, eboat_hull_mesh
from .geometry import EBoatGeometry, HullKind, eboat_geometry
from .sheet import FOILS

__all__ = ["BoatParts", "eboat_parts", "BODY", "BOOM", "REEF", "RUDDER"]

BODY, BOOM, REEF, RUDDER = "Body", "Boom", "Reef", "Rudder"
"""Names of the prototype's rigid groups (children of the prototype prim): the body, the boom's spar, the sail
(in its tack's frame, so that a reef scales it about its origin) and the rudder."""

BOOM_LENGTH = 1.8
"""From the mast to the clew [m] (the rod of ``EBoat.boom_inertia``)."""
MAST_RADIUS = 0.05
"""[m]: the sheet's 3.55 x 0.1 m mast."""
SPAR_RADIUS = 0.03
"""[m] (assumed)."""
RUDDER_SPAN, RUDDER_CHORD, RUDDER_THICKNESS = 0.608, 0.189, 0.015
"""Sheet, rudder row: its 0.189 x 0.015 x 0.608 m box [m] (the procedural boat's blade)."""
STOCK_RADIUS = 0.012
"""[m] The real rudder's stock from the blade's root up to its joint (assumed)."""
KEEL_ROOT_Z = -0.2
"""Where the procedural keel fin leaves the hull [m] (the canoe body's keel line is at -0.22 near the fin)."""
KEEL_THICKNESS = 0.12
"""The procedural fin's thickness as a fraction of its chord (assumed)."""


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
    sail_tack: np.ndarray
    """(3,) the sail's tack, the foot of its luff at the mast, in the boom's pivot frame [m]: a reef of linear
    factor s draws ``sail`` as tack + s (point - tack)."""

    def group_points(self, group: str) -> np.ndarray:
        """(P, 3) every vertex of ``group`` (BODY, BOOM, REEF or RUDDER) in that group's own frame [m]: the
        boom's spar and sail in the pivot's, the sail alone (REEF) in its tack's."""
        if group == REEF:
            return self.sail_in_tack_frame().points
        meshes = {BODY: (self.hull, self.keel, self.mast), BOOM: (self.spar, self.sail), RUDDER: (self.blade,)}
        return concatenate(*meshes[group]).points

    def sail_in_tack_frame(self) -> MeshData:
        """The full sail with its tack at the origin (the boom pivot's axes) [m]."""
        return MeshData(self.sail.points - self.sail_tack, self.sail.face_counts, self.sail.face_indices)


def eboat_parts(config: EBoatConfig | None = None, *, hull_detail: int = 2) -> BoatParts:
    """The E-Boat of ``config`` (default: the real V-C boat) as meshes. The hull is the physics hull's shape
    lofted with ``hull_detail`` times as many stations and section points (1: the physics mesh itself)."""
    config = config if config is not None else EBoatConfig()
    if isinstance(hull_detail, bool) or not isinstance(hull_detail, int) or not 1 <= hull_detail <= 8:
        raise ValueError(f"eboat_parts: hull_detail must be an integer in [1, 8], got {hull_detail!r}")
    hull = eboat_hull_mesh(config, hull_detail)
    hull_mesh = MeshData(np.asarray(hull.vertices, dtype=np.float64),
                         np.full(len(hull.triangles), 3, dtype=np.int32),
                         np.asarray(hull.triangles, dtype=np.int32).reshape(-1))
    geometry = eboat_geometry(config.hull, config.version, config.ballast)
    mast_foot = np.array(geometry.mast_step)
    mast = tube(mast_foot, geometry.masthead, MAST_RADIUS)
    boom_pivot = np.array(geometry.boom_pivot)
    spar = tube((0.0, 0.0, 0.0), (-BOOM_LENGTH, 0.0, 0.0), SPAR_RADIUS)
    if geometry.hull is HullKind.PROCEDURAL:
        keel, sail, blade = _procedural_appendages(config, geometry)
    else:
        keel, sail, blade = _real_appendages(geometry)
    return BoatParts(hull=hull_mesh, keel=keel, mast=mast, spar=spar, sail=sail, blade=blade,
                     boom_pivot=boom_pivot, rudder_pivot=np.array(geometry.rudder_pivot),
                     sail_tack=sail.points[0].copy())


def _procedural_appendages(config: EBoatConfig, geometry: EBoatGeometry) -> tuple[MeshData, MeshData, MeshData]:
    """Keel, sail and rudder blade of the procedural boat: the keel fin has the version's keel area and its
    centre of effort at mid-span, a quarter chord aft of its leading edge, with a bulb below; the sail is the
    triangle from the boom to the masthead (2.8 m^2; the sheet's 3.188 m^2 sail has roach this leaves out); the
    blade is the sheet's rudder box as a foil."""
    figures = FOILS[config.version]
    keel_x, _, keel_z = figures.keel_center
    span = 2.0 * (KEEL_ROOT_Z - keel_z)
    chord = figures.keel_area / span
    fin = extruded(foil_section(chord, KEEL_THICKNESS, leading_edge_x=keel_x + 0.25 * chord),
                   KEEL_ROOT_Z - span, KEEL_ROOT_Z + 0.05)  # a little into the hull, so no gap shows
    bulb = ellipsoid((keel_x - 0.1 * chord, 0.0, KEEL_ROOT_Z - span), (0.35, 0.07, 0.07))
    masthead_z = float(geometry.masthead[2])
    # The tack first (``BoatParts.sail_tack`` is the sail's first point).
    sail = triangle((-MAST_RADIUS, 0.0, SPAR_RADIUS), (-BOOM_LENGTH, 0.0, SPAR_RADIUS),
                    (-MAST_RADIUS, 0.0, masthead_z - geometry.boom_height - 0.05))
    blade = extruded(foil_section(RUDDER_CHORD, RUDDER_THICKNESS / RUDDER_CHORD, leading_edge_x=0.25 * RUDDER_CHORD),
                     -RUDDER_SPAN, 0.0)
    return concatenate(fin, bulb), sail, blade


def _real_appendages(geometry: EBoatGeometry) -> tuple[MeshData, MeshData, MeshData]:
    """Keel, sail and rudder blade of the real boat (``real_geometry``): the constant-chord fin from the bulb
    up into the hull, the bulb an ellipsoid of the sheet's length, width and height; the sail the trapezoid
    from its foot to its head along the mast's aft face; the tapered blade with its mid-chord on the stock
    (a small tube from the blade's root up to the joint)."""
    base_z = geometry.base_z
    bulb_center = np.array(geometry.from_base(real.BULB_CENTER))
    bulb_half = 0.5 * np.array(real.BULB_SIZE)
    fin_bottom = real.KEEL_ROOT_Z - real.KEEL_SPAN + base_z
    fin = extruded(foil_section(real.KEEL_CHORD, real.KEEL_THICKNESS_RATIO, leading_edge_x=real.KEEL_LEADING_EDGE_X),
                   fin_bottom, real.KEEL_ROOT_Z + base_z + 0.05)  # a little into the hull, so no gap shows
    bulb = ellipsoid(bulb_center, bulb_half)
    foot, head = geometry.sail_foot_height - geometry.boom_height, geometry.sail_head_height - geometry.boom_height
    luff = geometry.mast_step[0] - MAST_RADIUS - geometry.boom_pivot[0]  # the mast's aft face
    # The tack first (``BoatParts.sail_tack`` is the sail's first point).
    sail = MeshData(np.array([[luff, 0.0, foot], [luff - real.SAIL_FOOT_LENGTH, 0.0, foot],
                              [luff - real.SAIL_HEAD_LENGTH, 0.0, head], [luff, 0.0, head]]),
                    np.array([4], dtype=np.int32), np.array([0, 1, 2, 3], dtype=np.int32))
    root = geometry.rudder_pivot[2]
    blade_root = real.RUDDER_CENTROID_Z + base_z + real.RUDDER_SPAN / 3.0 * (
        real.RUDDER_ROOT_CHORD + 2.0 * real.RUDDER_TIP_CHORD) / (real.RUDDER_ROOT_CHORD + real.RUDDER_TIP_CHORD)
    tip = real.RUDDER_TIP_CHORD
    # The tip section with its mid-chord on the stock, widened to the root chord about its leading edge.
    blade = extruded(foil_section(tip, real.RUDDER_THICKNESS_RATIO, leading_edge_x=0.5 * tip),
                     blade_root - real.RUDDER_SPAN - root, blade_root - root,
                     top_scale=real.RUDDER_ROOT_CHORD / tip)
    stock = tube((0.0, 0.0, blade_root - root), (0.0, 0.0, 0.0), STOCK_RADIUS)
    return concatenate(fin, bulb), sail, concatenate(blade, stock)
