"""Where the E-Boat's parts are, for each of its two hulls: the links (mass properties), the rig (mast, boom,
sail), the keel and rudder as lifting surfaces with their centres of effort, the propeller and the appendages'
displacement, all in the body frame [m].

- ``HullKind.REAL`` (default): the F-Boat as its CAD has it. The hull is lofted from the offsets table
  (``offsets_hull``); every link sits where the URDF's joint chain puts it (``urdf_links``); keel fin and
  bulb, rudder and sail from the sheet's real geometry (``real_geometry``). The body frame is the URDF's base
  frame lowered by 0.094 m, its origin on the real waterline at rest (``offsets_hull.BASE_TO_WATERLINE``).
- ``HullKind.PROCEDURAL``: the procedural canoe (``hull_shape``) with the sheet's link table at its assumed
  heights (``sheet.LINKS``) and the sheet's foil figures; body frame = base frame. The boat the shipped
  policies were trained on, kept for comparison.
"""

from __future__ import annotations

import dataclasses
import enum

import numpy as np

from ..lifting_surface import LiftingSurface
from .offsets_hull import BASE_TO_WATERLINE
from . import real_geometry as real
from .sheet import ACTUATORS, BOOM_HEIGHT, FOILS, HULL_LINK_HEIGHT, LINKS, MAST_STEP, FoilFigures, Link, Version
from .urdf_links import link_poses, urdf_links

__all__ = ["HullKind", "Ballast", "EBoatGeometry", "eboat_geometry", "eboat_lifting_surfaces", "PROCEDURAL_MAST_LENGTH"]

PROCEDURAL_MAST_LENGTH = 3.55
"""Sheet, mast row [m]: the procedural boat's mast, from its step to its head."""


class HullKind(str, enum.Enum):
    """Which E-Boat hull, and with it which link table and rig geometry."""

    REAL = "real"
    """The F-Boat as its CAD has it: the hull lofted from the offsets table, the URDF's links, the real keel
    fin and bulb, rudder and sail; origin on the real waterline at rest."""
    PROCEDURAL = "procedural"
    """The procedural canoe with the sheet's link table at assumed heights (the shipped policies' boat)."""


class Ballast(str, enum.Enum):
    """How the real boat's keel carries its mass."""

    CAD = "cad"
    """The URDF's keel link: 40.04 kg spread uniformly through fin and bulb (the CAD's density model)."""
    LEAD_BULB = "lead_bulb"
    """Assumed, not a fact: a 44 kg lead bulb (the bulb's 3.9 L of lead; sheet) on a solid GRP fin (its 3.6 L
    at 1900 kg/m^3, 6.9 kg), in place of the URDF's keel link: 10.8 kg heavier, with the centre of gravity
    0.03-0.05 m below the waterline as the sheet estimates for such a keel."""


@dataclasses.dataclass(frozen=True, eq=False)
class EBoatGeometry:
    """The parts of one E-Boat in its body frame (x to the bow, y to port, z up) [m]."""

    hull: HullKind
    base_z: float
    """Height of the URDF base frame's origin in the body frame [m]: 0 (procedural) or -0.094 (real). The
    sheet's figures given in the base frame (the seed's foil centres, its buoyancy points) move by this."""
    links: tuple[Link, ...]
    """The link table, centres of mass in the body frame."""
    mast_step: tuple[float, float, float]
    """Foot of the mast."""
    mast_length: float
    """From the step to the masthead [m]."""
    boom_pivot: tuple[float, float, float]
    """The gooseneck: the boom's pivot on its vertical axis (the real boat's 0.049 m aft of the mast's axis)."""
    sail_foot_height: float
    """Height of the sail's foot (the ORC main's boom height)."""
    sail_head_height: float
    """Height of the sail's head."""
    sail_center_height: float
    """The physics profile's sail centre of effort."""
    keel: LiftingSurface
    """The physics profile's keel fin."""
    keel_center: tuple[float, float, float]
    """Where the physics profile's keel lift acts."""
    rudder: LiftingSurface
    """The physics profile's rudder blade."""
    rudder_center: tuple[float, float, float]
    """Where the physics profile's rudder lift acts."""
    rudder_pivot: tuple[float, float, float]
    """The top of the rudder stock (its joint), on its axis of rotation."""
    propeller_position: tuple[float, float, float]
    """Where the thrust acts."""
    appendage_volume: float
    """Volume of keel, bulb and rudder outside the hull mesh [m^3] (0: none counted), always under water at
    sailing heels: its buoyancy acts at ``appendage_center`` (mesh hydrostatics)."""
    appendage_center: tuple[float, float, float]
    """Centroid of that volume."""

    @property
    def boom_height(self) -> float:
        """Height of the gooseneck [m]."""
        return self.boom_pivot[2]

    @property
    def masthead(self) -> np.ndarray:
        """(3,) the top of the mast [m]: vane and anemometer."""
        return np.array([self.mast_step[0], 0.0, self.mast_step[2] + self.mast_length])

    def from_base(self, point) -> tuple[float, float, float]:
        """A point given in the URDF base frame [m], in the body frame."""
        x, y, z = (float(v) for v in point)
        return (x, y, z + self.base_z)


def eboat_lifting_surfaces(figures: FoilFigures) -> tuple[LiftingSurface, LiftingSurface]:
    """The procedural boat's keel and rudder as lifting surfaces. Keel: the sheet's area on its wetted span
    (FoilFigures), NACA 0012-like (t/c 0.12, as the VPP inputs), its root on the hull (an end plate: effective
    aspect ratio twice the geometric). Rudder: the sheet's area on its box's chord, t/c 0.12, hung at the
    transom with its top at the free surface, which is no wall at speed (end-plate factor 1)."""
    root, tip = figures.keel_chords
    keel = LiftingSurface(span=figures.keel_span, root_chord=root, tip_chord=tip, end_plate_factor=2.0)
    chord = figures.rudder_chord
    rudder = LiftingSurface(span=figures.rudder_span, root_chord=chord, tip_chord=chord, end_plate_factor=1.0)
    return keel, rudder


def _procedural(version: Version) -> EBoatGeometry:
    figures = FOILS[version]
    keel, rudder = eboat_lifting_surfaces(figures)
    masthead_z = MAST_STEP[2] + PROCEDURAL_MAST_LENGTH
    return EBoatGeometry(
        hull=HullKind.PROCEDURAL, base_z=0.0, links=LINKS, mast_step=MAST_STEP, mast_length=PROCEDURAL_MAST_LENGTH,
        boom_pivot=(MAST_STEP[0], 0.0, BOOM_HEIGHT), sail_foot_height=BOOM_HEIGHT, sail_head_height=masthead_z,
        sail_center_height=figures.sail_center_height, keel=keel, keel_center=figures.keel_center_of_area,
        rudder=rudder, rudder_center=figures.rudder_center, rudder_pivot=(-1.086, 0.0, HULL_LINK_HEIGHT + 0.076),
        propeller_position=ACTUATORS["propeller_position"], appendage_volume=0.0, appendage_center=(0.0, 0.0, 0.0))


def _box_inertia(mass: float, size) -> tuple[tuple[float, ...], ...]:
    a, b, c = size
    return tuple(map(tuple, mass / 12.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])))


def _lead_bulb_keel() -> tuple[Link, Link]:
    """The assumed alternative keel (see :attr:`Ballast.LEAD_BULB`), base frame: the bulb a solid ellipsoid,
    the fin a solid slab of the fin's volume at mid-span and mid-chord."""
    bulb_mass = real.LEAD_BULB_MASS
    a, b, c = (0.5 * s for s in real.BULB_SIZE)
    bulb_inertia = tuple(map(tuple, bulb_mass / 5.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])))
    bulb = Link("lead bulb", bulb_mass, real.BULB_CENTER, bulb_inertia,
                "sheet, real geometry: a 44 kg lead bulb (assumed), at the bulb's centre; a solid ellipsoid")
    fin_mass = real.FIN_VOLUME * real.GRP_DENSITY
    fin_center = (real.KEEL_LEADING_EDGE_X - 0.5 * real.KEEL_CHORD, 0.0, real.KEEL_ROOT_Z - 0.5 * real.KEEL_SPAN)
    thickness = real.KEEL_THICKNESS_RATIO * real.KEEL_CHORD
    fin = Link("GRP fin", fin_mass, fin_center, _box_inertia(fin_mass, (real.KEEL_CHORD, thickness, real.KEEL_SPAN)),
               "the fin's volume (vpp_inputs_real.json) in solid GRP (assumed 1900 kg/m^3), at mid-span, mid-chord")
    return bulb, fin


def _real(ballast: Ballast) -> EBoatGeometry:
    base_z = -BASE_TO_WATERLINE
    links = list(urdf_links())
    if ballast is Ballast.LEAD_BULB:
        keel = next(i for i, link in enumerate(links) if link.name == "keel")
        links[keel:keel + 1] = _lead_bulb_keel()
    links = tuple(dataclasses.replace(link, center_of_mass=(link.center_of_mass[0], link.center_of_mass[1],
                                                            link.center_of_mass[2] + base_z)) for link in links)
    poses = link_poses()

    def body(link: str) -> tuple[float, float, float]:
        x, y, z = poses[link][1]
        return (float(x), float(y), float(z) + base_z)

    mast_step = body("mast_link")
    keel = LiftingSurface(span=real.KEEL_SPAN, root_chord=real.KEEL_CHORD, tip_chord=real.KEEL_CHORD,
                          thickness_ratio=real.KEEL_THICKNESS_RATIO, end_plate_factor=2.0)
    # Rudder: the measured outline is not quite a trapezoid (0.617 x (0.170 + 0.145) / 2 = 0.0972 m^2 against
    # 0.0991 m^2), so both chords grow 2 % to carry the sheet's area on its span. Its lift acts at the quarter
    # chord of the area centroid's section, span/3 (root + 2 tip) / (root + tip) below the root.
    stretch = real.RUDDER_AREA / (0.5 * real.RUDDER_SPAN * (real.RUDDER_ROOT_CHORD + real.RUDDER_TIP_CHORD))
    root, tip = stretch * real.RUDDER_ROOT_CHORD, stretch * real.RUDDER_TIP_CHORD
    rudder = LiftingSurface(span=real.RUDDER_SPAN, root_chord=root, tip_chord=tip,
                            thickness_ratio=real.RUDDER_THICKNESS_RATIO, end_plate_factor=1.0)
    centroid_depth = real.RUDDER_SPAN / 3.0 * (root + 2.0 * tip) / (root + tip)
    centroid_chord = root + (tip - root) * centroid_depth / real.RUDDER_SPAN
    volumes = np.array([real.KEEL_VOLUME, real.RUDDER_VOLUME])
    centers = np.array([real.KEEL_VOLUME_CENTER, real.RUDDER_VOLUME_CENTER])
    appendage_center = volumes @ centers / volumes.sum() + np.array([0.0, 0.0, base_z])
    return EBoatGeometry(
        hull=HullKind.REAL, base_z=base_z, links=links, mast_step=mast_step, mast_length=real.MAST_TOP_ABOVE_STEP,
        boom_pivot=body("boom_link"), sail_foot_height=real.SAIL_FOOT_Z + base_z,
        sail_head_height=real.SAIL_HEAD_Z + base_z, sail_center_height=real.SAIL_CENTROID_Z + base_z,
        keel=keel, keel_center=(real.KEEL_QUARTER_CHORD_X, 0.0, real.KEEL_ROOT_Z - 0.5 * real.KEEL_SPAN + base_z),
        rudder=rudder,
        rudder_center=(real.RUDDER_STOCK_X + 0.25 * centroid_chord, 0.0, real.RUDDER_CENTROID_Z + base_z),
        rudder_pivot=body("rudder_link"), propeller_position=body("propeller_link"),
        appendage_volume=float(volumes.sum()), appendage_center=tuple(float(v) for v in appendage_center))


def eboat_geometry(hull: HullKind, version: Version, ballast: Ballast = Ballast.CAD) -> EBoatGeometry:
    """The parts of the E-Boat with ``hull``: the procedural one follows ``version``'s foil figures; the real
    one carries ``ballast``."""
    if hull is HullKind.PROCEDURAL:
        return _procedural(version)
    return _real(ballast)
