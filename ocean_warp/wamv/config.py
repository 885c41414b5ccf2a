"""Which WAM-V to build: mass properties, pontoons, force profile, thrusters and mesh resolution."""

from __future__ import annotations

import dataclasses
import enum

import numpy as np

from ..validation import require_choice, require_finite, require_in_range, require_int_in_range, require_positive
from . import figures

__all__ = ["WamvProfile", "ThrusterLayout", "WamvConfig"]


class WamvProfile(str, enum.Enum):
    """Which models make the WAM-V's water forces."""

    PHYSICS = "physics"
    """Per-triangle pressure on the twin-pontoon mesh with the core's cross-flow drag and ITTC friction (as the
    E-Boat's physics profile), the pair's wave-making resistance by Michell's thin-ship integral
    (``WamvConfig.wave_resistance``), and, with ``WamvConfig.seakeeping``, the pontoons' own potential-flow database
    (added mass, radiation, diffraction)."""
    VRX = "vrx"
    """Per-triangle hydrostatics (no drag terms on the mesh) with VRX's lumped linear and quadratic damping and
    added mass (``figures.VRX_LINEAR_DAMPING``...), to compare with Gazebo."""


class ThrusterLayout(str, enum.Enum):
    """How the two stern thrusters move."""

    FIXED = "fixed"
    """Both point straight ahead: differential thrust steers."""
    AZIMUTH = "azimuth"
    """Each swings about its engine's vertical axis up to ``WamvConfig.max_thruster_angle``."""


def _vector(owner: str, name: str, value) -> tuple[float, float, float]:
    array = np.asarray(value, dtype=np.float64) if np.ndim(value) == 1 else np.full(1, np.nan)
    if array.shape != (3,) or not np.all(np.isfinite(array)):
        raise ValueError(f"{owner}.{name} must be 3 finite coordinates [m], got {value!r}")
    return tuple(float(v) for v in array)


@dataclasses.dataclass(frozen=True)
class WamvConfig:
    """The WAM-V: VRX's figures by default (``ocean_warp.wamv.figures`` names each one's source). Body frame FLU
    with its origin midway between the pontoons' axes, at their height (VRX's ``base_link``)."""

    mass: float = figures.MASS
    """Total mass [kg] (180: VRX's base link)."""
    inertia: tuple[float, float, float] = figures.INERTIA
    """(Ixx, Iyy, Izz) about the centre of mass, body axes [kg m^2] (120, 393, 446)."""
    center_of_mass: tuple[float, float, float] = (figures.PONTOON_CENTER_X, 0.0, 0.0)
    """Centre of mass in the body frame [m]. VRX puts the base link's at its origin and its 15.5 kg engines 2.4 m
    aft of it, which brings the whole model's near the pontoons' middle; the 180 kg alone here have it over the
    pontoons' centre of buoyancy (x = -0.4 m), at their axes' height, so that it floats level."""
    pontoon_length: float = figures.PONTOON_LENGTH
    """Length of each pontoon [m] (4.9)."""
    pontoon_radius: float = figures.PONTOON_RADIUS
    """Radius of each pontoon [m] (0.213)."""
    pontoon_spacing: float = figures.PONTOON_SPACING
    """Between the pontoons' axes [m] (2.06)."""
    pontoon_center_x: float = figures.PONTOON_CENTER_X
    """Middle of the pontoons along x [m] (-0.4)."""
    profile: WamvProfile | str = WamvProfile.PHYSICS
    """"physics" (default) or "vrx" (see :class:`WamvProfile`)."""
    seakeeping: bool = True
    """Physics profile: sail with the pontoons' shipped hydrodynamic database (``wamv_hydrodynamics.json``: added
    mass, radiation memory, diffraction); False: a constant zero added mass and drag-only damping. Needs the
    default pontoons and mesh resolution (the database is checked against the mesh); ignored by "vrx"."""
    wave_resistance: bool = True
    """Physics profile: resist motion ahead with the pontoons' wave-making resistance too (Michell's thin-ship
    integral for the pair, ``ocean_warp.wamv.wave_resistance``); False: friction alone, as the profile had it.
    Ignored by "vrx"."""
    thrusters: ThrusterLayout | str = ThrusterLayout.FIXED
    """"fixed" (default) or "azimuth" (see :class:`ThrusterLayout`)."""
    engine_pivots: tuple = figures.ENGINE_PIVOTS
    """((x, y, z) left, (x, y, z) right) [m]: each engine's vertical pivot, body frame (VRX's stern mounts)."""
    propeller_offset: tuple[float, float, float] = figures.PROPELLER_OFFSET
    """The propeller from its pivot in the engine's frame [m]; the thrust acts there."""
    max_forward_thrust: float = figures.MAX_FORCE_FORWARD
    """Largest thrust ahead of one thruster [N] (250)."""
    max_reverse_thrust: float = figures.MAX_FORCE_REVERSE
    """Largest thrust astern of one thruster, a magnitude [N] (100)."""
    max_thruster_angle: float = figures.MAX_THRUSTER_ANGLE
    """Azimuth thrusters: largest angle either side [rad] (pi / 2), in (0, pi]."""
    wind_coefficients: tuple[float, float, float] = figures.WIND_COEFFICIENTS
    """The wind's lumped coefficients (c_x, c_y [N s^2/m^2], c_z [N m s^2/m^2]) on the apparent wind in the body frame
    (``kernels.lumped_windage``); zeros: no windage."""
    pontoon_sides: int = 16
    """Mesh resolution: sides of each pontoon's polygonal section (6 to 64)."""
    pontoon_stations: int = 12
    """Mesh resolution: segments along each pontoon (1 to 200)."""

    def __post_init__(self):
        owner = "WamvConfig"
        for name, unit in (("mass", " [kg]"), ("pontoon_length", " [m]"), ("pontoon_radius", " [m]"),
                           ("pontoon_spacing", " [m]"), ("max_forward_thrust", " [N]"),
                           ("max_reverse_thrust", " [N]")):
            object.__setattr__(self, name, require_positive(owner, name, getattr(self, name), unit=unit))
        inertia = np.asarray(self.inertia, dtype=np.float64) if np.ndim(self.inertia) == 1 else np.full(1, np.nan)
        if inertia.shape != (3,) or not np.all(np.isfinite(inertia)) or np.any(inertia <= 0.0):
            raise ValueError(f"{owner}.inertia must be 3 finite moments > 0 [kg m^2], got {self.inertia!r}")
        object.__setattr__(self, "inertia", tuple(float(v) for v in inertia))
        object.__setattr__(self, "center_of_mass", _vector(owner, "center_of_mass", self.center_of_mass))
        object.__setattr__(self, "propeller_offset", _vector(owner, "propeller_offset", self.propeller_offset))
        try:
            pivots = tuple(_vector(owner, "engine_pivots", p) for p in self.engine_pivots)
        except TypeError:
            pivots = ()
        if len(pivots) != 2:
            raise ValueError(f"{owner}.engine_pivots must be two (x, y, z) points [m], got {self.engine_pivots!r}")
        object.__setattr__(self, "engine_pivots", pivots)
        object.__setattr__(self, "pontoon_center_x", require_finite(owner, "pontoon_center_x", self.pontoon_center_x))
        if self.pontoon_spacing <= 2.0 * self.pontoon_radius:
            raise ValueError(f"{owner}.pontoon_spacing must exceed the pontoons' diameter {2 * self.pontoon_radius} "
                             f"m, got {self.pontoon_spacing!r}")
        object.__setattr__(self, "profile", require_choice(owner, "profile", self.profile, WamvProfile))
        object.__setattr__(self, "thrusters", require_choice(owner, "thrusters", self.thrusters, ThrusterLayout))
        for name in ("seakeeping", "wave_resistance"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"{owner}.{name} must be True or False, got {getattr(self, name)!r}")
        object.__setattr__(self, "max_thruster_angle", require_in_range(
            owner, "max_thruster_angle", self.max_thruster_angle, 1e-6, np.pi, unit=" [rad]"))
        coefficients = np.asarray(self.wind_coefficients, dtype=np.float64).reshape(-1)
        if coefficients.shape != (3,) or not np.all(np.isfinite(coefficients)) or np.any(coefficients < 0.0):
            raise ValueError(f"{owner}.wind_coefficients must be 3 finite values >= 0, got {self.wind_coefficients!r}")
        object.__setattr__(self, "wind_coefficients", tuple(float(c) for c in coefficients))
        object.__setattr__(self, "pontoon_sides", require_int_in_range(owner, "pontoon_sides", self.pontoon_sides,
                                                                       6, 64))
        object.__setattr__(self, "pontoon_stations", require_int_in_range(owner, "pontoon_stations",
                                                                          self.pontoon_stations, 1, 200))

    @property
    def uses_hydro_database(self) -> bool:
        """Whether the hull sails with the shipped hydrodynamic database (physics profile with ``seakeeping``)."""
        return self.profile is WamvProfile.PHYSICS and self.seakeeping

    @property
    def propeller_positions(self) -> np.ndarray:
        """(2, 3) each propeller with its engine straight ahead, body frame [m]."""
        return np.asarray(self.engine_pivots) + np.asarray(self.propeller_offset)
