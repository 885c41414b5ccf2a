"""The E-Boat's figures, as the project's data sheet gives them (shared/eboat/README.md, "E-Boat digital
twin: data sheet"), which collects them from three snapshots of the original Gazebo model:

- V-A: APFN/eboat@a00572c (April 2023), model "eboat";
- V-B: Yara_OVE@801e77c (June 2023), model "eboat4", the one the six-waypoint mission spawns;
- V-C: Yara_OVE@62c4a83 (Sept 2023), model "eboat4" (the default here).

Frames as in the source: x to the bow, y to port, z up, base frame at the waterline. Where the sheet
is silent, the value here is an assumption, and says so ("assumed").
"""

from __future__ import annotations

import dataclasses
import enum

__all__ = ["Version", "Link", "LINKS", "HULL_LINK_HEIGHT", "FoilFigures", "VrxHydrodynamics", "VRX", "FOILS",
           "ACTUATORS", "ENVIRONMENT", "TOTAL_MASS"]


class Version(str, enum.Enum):
    """Which snapshot of the original model to follow where they differ."""

    A = "V-A"
    B = "V-B"
    C = "V-C"


HULL_LINK_HEIGHT = 0.2106
"""Sheet, "Frames in the source": the hull link frame sits 0.2106 m above the base frame (waterline)."""

TOTAL_MASS = {Version.A: 154.2, Version.B: 158.4, Version.C: 158.4}
"""Sheet, "total mass (sum of links)" [kg]: 158.4 for eboat4 (V-B, V-C), 154.2 for eboat (V-A)."""


@dataclasses.dataclass(frozen=True)
class Link:
    """One rigid part: mass [kg], centre of mass in the base frame [m] (or the body frame, where a table says
    so), inertia about its own centre of mass [kg m^2] as (ixx, iyy, izz, ixz), as a full (3, 3) tensor in
    the frame's axes, or None for a shape-derived one, and where the figures come from."""

    name: str
    mass: float
    center_of_mass: tuple[float, float, float]
    inertia: tuple | None
    source: str


def _hull_link(x: float, y: float, z: float) -> tuple[float, float, float]:
    """A point given in the hull link frame, in the base frame."""
    return (x, y, HULL_LINK_HEIGHT + z)


# The boom's height above the waterline is not on the sheet. A sail triangle from the boom to the
# masthead with its centre of effort at 1.5 m (sheet) puts the boom at about 0.45 m:
# masthead = 0.2106 - 0.153 + 3.55 = 3.61 m, and 0.45 + (3.61 - 0.45) / 3 = 1.50 m.
BOOM_HEIGHT = 0.45
"""[m] above the waterline (assumed, from the sail's centre of effort; see above)."""
MAST_STEP = _hull_link(0.595, 0.0, -0.153)
"""Sheet, mast row: mast joint at (0.595, 0, -0.153) in the hull link frame."""

LINKS = (
    Link("hull", 83.69, _hull_link(-0.198, 0.0, -0.060), (7.794, 42.817, 47.147, 1.267),
         "sheet, hull link row: CoM in the hull link frame"),
    Link("keel", 40.04, _hull_link(-0.140 + 0.005, 0.0, 0.004 - 0.725), (5.035, 5.272, 0.269, 0.0),
         "sheet, keel row: CoM (0.005, 0, -0.725) below the joint at (-0.140, 0, 0.004) of the hull link"),
    Link("mast", 12.5, (MAST_STEP[0], 0.0, MAST_STEP[2] + 1.958), None,
         "sheet, mast row: CoM 1.958 m above its joint; inertia of a 3.55 m cylinder of radius 0.05 m"),
    Link("boom", 2.41, (MAST_STEP[0] - 0.919, 0.0, BOOM_HEIGHT), None,
         "sheet, boom row: CoM 0.919 m aft of the mast; height assumed (BOOM_HEIGHT); inertia of a 1.8 m rod"),
    Link("sail", 2.22, (-0.012, 0.0, 1.5), None,
         "sheet, sail row: mass; CoM assumed at the centre of effort; inertia of a thin triangle"),
    Link("rudder", 1.60, _hull_link(-1.086, 0.0, 0.076 - 0.304), None,
         "sheet, rudder row: joint at (-1.086, 0, 0.076) of the hull link; CoM assumed half the 0.608 m "
         "span below it; inertia of its 0.189 x 0.015 x 0.608 m box"),
    Link("deck", 4.66, _hull_link(0.0, 0.0, 0.12), None, "sheet, other links: mass; position assumed (on deck)"),
    Link("electric leg", 3.63, _hull_link(-0.95, 0.0, -0.25), None,
         "sheet, other links: mass; position assumed (the propeller leg near the stern)"),
    Link("engine base", 0.89, _hull_link(-0.95, 0.0, 0.10), None,
         "sheet, other links: mass; position assumed (above the leg)"),
    Link("bow", 1.10, _hull_link(1.15, 0.0, 0.05), None, "sheet, other links: mass; position assumed (the bow)"),
    Link("rack port", 1.73, _hull_link(-0.3, 0.42, 0.12), None,
         "sheet, other links: mass; position assumed (port side)"),
    Link("rack starboard", 1.73, _hull_link(-0.3, -0.42, 0.12), None,
         "sheet, other links: mass; position assumed (starboard side, mirroring port)"),
    Link("camera", 2.07, _hull_link(0.9, 0.0, 0.25), None, "sheet, other links: mass; position assumed (forward)"),
)
"""The link table of the sheet ("Geometry and mass"), the procedural boat's: several heights assumed. The real
boat's links sit where the URDF's joint chain puts them (``urdf_links``). Links without an inertia on the
sheet get one from their shape (see ``mass_properties``) or, for the small parts, count as point masses."""

LINK_MASS_DIFFERENCE_V_A = -4.2
"""V-A's total is 4.2 kg lighter (154.2 vs 158.4 kg); the sheet does not say which link differs, so
V-A takes it off the hull shell, at the hull's centre of mass (assumed)."""


KEEL_LINE_Z = -0.22
"""Lowest point of the hull's keel line [m], where the keel fin leaves the hull (``HullShape.keel_z``)."""


@dataclasses.dataclass(frozen=True)
class FoilFigures:
    """Areas and centres of effort of the sail, keel and rudder."""

    sail_area: float
    """Sheet: 3.188 m^2."""
    keel_area: float
    """Sheet: 0.23779 m^2 (V-C), 0.2 (V-B; the sheet gives no V-A figure, taken as V-B's)."""
    rudder_area: float
    """Sheet: 0.10064 m^2 (V-C), 0.2 (V-A, V-B)."""
    keel_span: float = 0.854
    """Wetted span of the keel fin [m]: from the hull's keel line (z = -0.22 m) to the bottom of the sheet's
    keel box (joint at z 0.2146 m, CoM 0.725 m below it, box 1.127 m tall: z = -1.074 m)."""
    keel_taper: float = 0.8
    """Tip over root chord of the keel (assumed, as in the VPP inputs' 0.1927 / 0.24)."""
    rudder_chord: float = 0.189
    """Sheet: the rudder box is 0.189 m long; its span is the area over this chord."""
    sail_center_height: float = 1.5
    """Sheet: centre of effort (-0.012, 0, 1.5) m in the base frame."""
    sail_arm: float = 0.59
    """Sheet: the aerodynamic moment about the mast has an arm of 0.59 m; the centre of effort is placed
    this far aft of the mast along the boom (1.7 cm from the sheet's x = -0.012 at zero boom angle)."""
    keel_center: tuple[float, float, float] = (-0.135, 0.0, -0.40)
    """Centre of effort of the keel fin [m]: under the keel joint (sheet); its depth is the seed profile's
    assumption (mid-depth), the physics profile puts it at the fin's area centroid (``keel_center_of_area``)."""
    rudder_center: tuple[float, float, float] = (-1.086, 0.0, -0.16)
    """Centre of effort of the rudder [m]: under its joint (sheet), at mid-depth of its wetted part (assumed)."""
    boom_damping: float = 0.5
    """Sheet (V-C): boom joint damping [N m s/rad]."""

    @property
    def keel_chords(self) -> tuple[float, float]:
        """(root, tip) chords [m] of a trapezoid of ``keel_area`` on ``keel_span`` with ``keel_taper``."""
        root = 2.0 * self.keel_area / (self.keel_span * (1.0 + self.keel_taper))
        return root, root * self.keel_taper

    @property
    def keel_center_of_area(self) -> tuple[float, float, float]:
        """The keel's centre of effort at its area centroid [m]: span/3 (root + 2 tip)/(root + tip) below the
        hull's keel line (z = -0.22 m), under the keel joint."""
        root, tip = self.keel_chords
        depth = self.keel_span / 3.0 * (root + 2.0 * tip) / (root + tip)
        return (self.keel_center[0], 0.0, KEEL_LINE_Z - depth)

    @property
    def rudder_span(self) -> float:
        """[m]: area over chord."""
        return self.rudder_area / self.rudder_chord


FOILS = {
    Version.A: FoilFigures(sail_area=3.188, keel_area=0.2, rudder_area=0.2),
    Version.B: FoilFigures(sail_area=3.188, keel_area=0.2, rudder_area=0.2),
    Version.C: FoilFigures(sail_area=3.188, keel_area=0.23779, rudder_area=0.10064),
}

ACTUATORS = {
    "rudder_limit_deg": 60.0,  # sheet, actuators: rudder range +-60 deg
    "rudder_rate": 0.4,  # sheet: 0.4 rad/s servo
    "sheet_limit_deg": 90.0,  # sheet: sail sheet (boom limit) 0-90 deg
    "sheet_rate": 0.5,  # sheet: 0.5 rad/s
    "propeller_levels": 5,  # sheet: integer level -5 ... +5
    "thrust_per_level": 24.02,  # sheet: 24.02 N per level forward (120.1 N at 5)
    "reverse_factor": 0.4,  # sheet: reverse x 0.4
    "propeller_position": (-1.05, 0.0, -0.20),  # assumed: the electric leg's propeller, near the stern, submerged
}


@dataclasses.dataclass(frozen=True)
class VrxHydrodynamics:
    """Sheet, "Hydrodynamics of the original twin (VRX-style lumped model)"."""

    added_mass: tuple = (0.0, 124.0, 148.0, 0.0, 0.0, 0.0)
    """X_u., Y_v., Z_w. [kg] and rotational terms (0)."""
    linear_damping: tuple = (5.13, 24.0, 250.0, 25.0, 25.0, 120.0)
    """xU, yV, zW, kP, mQ, nR."""
    quadratic_damping: tuple = (7.24, 480.0, 0.0, 0.0, 0.0, 0.0)
    """xUU, yVV (no quadratic heave, roll, pitch, yaw terms in the source)."""
    astern_surge_factor: float = 1.3
    """Sheet: surge damping 1.3x larger going astern."""
    hull_radius: float = 0.4
    """R of the buoyancy circle segments [m]."""
    hull_length: float = 2.4
    """L [m]; each of the four points carries rho g (L / 2) S(R, h)."""
    points: tuple = ((0.6, 0.45, 0.0), (-0.6, 0.45, 0.0), (0.6, -0.45, 0.0), (-0.6, -0.45, 0.0))
    """The four buoyancy points [m]: y = +-0.45, x = +-0.6 (sheet); at the waterline height (assumed)."""
    water_density: float = 997.0
    """The source's rho [kg/m^3]."""


VRX = {
    Version.A: VrxHydrodynamics(linear_damping=(5.0, 8.0, 50.0, 5.0, 5.0, 40.0), quadratic_damping=(7.4, 160.0, 0, 0, 0, 0)),
    Version.B: VrxHydrodynamics(linear_damping=(5.13, 16.0, 250.0, 25.0, 25.0, 60.0),
                                quadratic_damping=(7.24, 320.0, 0, 0, 0, 0)),
    Version.C: VrxHydrodynamics(),
}

ENVIRONMENT = {
    "air_density": 1.201,  # sheet, "Sail, keel and rudder": air 1.201 kg/m^3
    "source_water_density": 997.0,  # sheet: water 997 kg/m^3 in the source (1025 for sea water)
    "physics_step": 0.01,  # sheet, "Environment of the original": physics step 0.01 s
}
