"""A kind of boat: its hull mesh, mass properties and Fossen maneuvering coefficients."""

from __future__ import annotations

import dataclasses

import numpy as np

from .hull import Hull
from .resistance import ResiduaryResistance

__all__ = ["BoatType", "skew", "parallel_axis_term"]


def skew(vector) -> np.ndarray:
    """S(a) with S(a) b = a x b."""
    x, y, z = np.asarray(vector, dtype=np.float64)
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def parallel_axis_term(mass: float, offset) -> np.ndarray:
    """m (|d|^2 I - d d^T) [kg m^2]: what moving a mass's inertia from its centre to a point at
    ``offset`` [m] from the centre adds (parallel-axis theorem)."""
    d = np.asarray(offset, dtype=np.float64)
    return mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))


def _six_by_six(owner: str, name: str, value) -> np.ndarray:
    """A 6-vector is read as a diagonal; a (6, 6) matrix must be symmetric."""
    array = np.asarray(value, dtype=np.float64)
    if array.shape == (6,):
        array = np.diag(array)
    if array.shape != (6, 6):
        raise ValueError(f"{owner}.{name} must be 6 diagonal values or a (6, 6) matrix, got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{owner}.{name} holds NaN or infinite values")
    if not np.allclose(array, array.T, rtol=1e-9, atol=1e-9 * max(1.0, np.abs(array).max())):
        raise ValueError(f"{owner}.{name} must be symmetric")
    return array


def _six_vector(owner: str, name: str, value) -> np.ndarray:
    array = np.asarray(value, dtype=np.float64)
    if array.shape != (6,) or not np.all(np.isfinite(array)) or np.any(array < 0):
        raise ValueError(f"{owner}.{name} must be 6 finite values >= 0 (surge, sway, heave, roll, pitch, yaw), "
                         f"got {value!r}")
    return array


@dataclasses.dataclass(frozen=True, eq=False)
class BoatType:
    """Everything about a kind of boat that does not change while it sails.

    Frames: body frame FLU (x bow, y port, z up) with its origin where the hull mesh has it. Fossen's
    velocity vector nu = (u, v, w, p, q, r) is the body-frame velocity of that origin and the angular
    velocity; 6-vectors and 6x6 matrices below follow that order and act about the origin.
    """

    hull: Hull
    """The mesh the water presses on."""
    mass: float
    """Total mass [kg]."""
    center_of_mass: tuple = (0.0, 0.0, 0.0)
    """Centre of mass in the body frame [m]."""
    inertia: object = None
    """(3, 3) inertia tensor about the centre of mass, body axes [kg m^2]; None: the hull as a uniform solid."""
    added_mass: object = None
    """Added mass M_A: 6 diagonal values or a symmetric (6, 6) matrix [kg, kg m, kg m^2], constant, entering
    the mass matrix directly. None (default): the infinite-frequency added mass of ``seakeeping`` if given,
    else zero (a hull with no database keeps a constant added mass, as Fossen's and VRX's models do)."""
    linear_damping: object = (0.0,) * 6
    """Diagonal linear damping on the velocity relative to the water [N s/m, N m s/rad]."""
    quadratic_damping: object = (0.0,) * 6
    """Diagonal quadratic damping, force -d |nu_r| nu_r [N s^2/m^2, N m s^2/rad^2]."""
    astern_surge_factor: float = 1.0
    """Surge damping (linear and quadratic) is this many times larger when moving astern (E-Boat: 1.3)."""
    seakeeping: object = None
    """The hull's hydrodynamic database (``ocean_warp.seakeeping.HydroDatabase``): its infinite-frequency added
    mass is M_A, and the simulator integrates its radiation memory and its diffraction load
    (``ocean_warp.kernels.radiation``). None: no radiation damping (a constant added mass, drag-only damping)."""
    residuary: ResiduaryResistance | None = None
    """The hull's residuary (wave-making) resistance, applied by the hull pass; None: none (a hull without
    one relies on the per-triangle drag, see ``HydrodynamicsConfig.cross_flow_only``)."""
    name: str = ""

    def __post_init__(self):
        owner = f"BoatType {self.name or self.hull.name!r}"
        if not isinstance(self.hull, Hull):
            raise ValueError(f"{owner}: hull must be an ocean_warp.Hull, got {type(self.hull).__name__}")
        mass = self.mass
        if isinstance(mass, bool) or not isinstance(mass, (int, float)) or not np.isfinite(mass) or mass <= 0:
            raise ValueError(f"{owner}.mass must be a finite number > 0 [kg], got {mass!r}")
        center = np.asarray(self.center_of_mass, dtype=np.float64)
        if center.shape != (3,) or not np.all(np.isfinite(center)):
            raise ValueError(f"{owner}.center_of_mass must be 3 finite coordinates [m], got {self.center_of_mass!r}")
        inertia = self.hull.solid_inertia(float(mass)) if self.inertia is None else np.asarray(self.inertia, float)
        if inertia.shape != (3, 3) or not np.all(np.isfinite(inertia)) or not np.allclose(inertia, inertia.T):
            raise ValueError(f"{owner}.inertia must be a finite symmetric (3, 3) matrix [kg m^2]")
        principal = np.linalg.eigvalsh(inertia)
        tolerance = 1e-9 * principal.max()
        if principal.min() <= 0 or principal[2] > principal[0] + principal[1] + tolerance:
            raise ValueError(f"{owner}.inertia is not the inertia of a real body: principal moments "
                             f"{np.round(principal, 6).tolist()} must be > 0 and obey the triangle inequality")
        object.__setattr__(self, "mass", float(mass))
        object.__setattr__(self, "center_of_mass", center)
        object.__setattr__(self, "inertia", inertia)
        object.__setattr__(self, "added_mass", self._added_mass(owner))
        object.__setattr__(self, "linear_damping", _six_vector(owner, "linear_damping", self.linear_damping))
        object.__setattr__(self, "quadratic_damping", _six_vector(owner, "quadratic_damping", self.quadratic_damping))
        factor = self.astern_surge_factor
        if isinstance(factor, bool) or not isinstance(factor, (int, float)) or not np.isfinite(factor) or factor <= 0:
            raise ValueError(f"{owner}.astern_surge_factor must be a finite number > 0, got {factor!r}")
        object.__setattr__(self, "astern_surge_factor", float(factor))
        if self.residuary is not None and not isinstance(self.residuary, ResiduaryResistance):
            raise ValueError(f"{owner}.residuary must be a ResiduaryResistance or None, got {self.residuary!r}")
        if np.linalg.eigvalsh(self.mass_matrix).min() <= 0:
            raise ValueError(f"{owner}: the mass matrix M_RB + M_A is not positive definite; check added_mass")
        if not self.name:
            object.__setattr__(self, "name", self.hull.name)

    def _added_mass(self, owner: str) -> np.ndarray:
        """The added mass the mass matrix takes: the one given, or the database's A_inf, or zero."""
        database = self.seakeeping
        if database is not None and not (hasattr(database, "added_mass_infinite") and hasattr(database, "radiation")):
            raise ValueError(f"{owner}.seakeeping must be an ocean_warp.seakeeping.HydroDatabase or None, "
                             f"got {type(database).__name__}")
        if self.added_mass is None:
            return _six_by_six(owner, "added_mass", np.zeros(6) if database is None else database.added_mass_infinite)
        given = _six_by_six(owner, "added_mass", self.added_mass)
        if database is not None and not np.allclose(given, database.added_mass_infinite, rtol=1e-6, atol=1e-6):
            raise ValueError(f"{owner}: give added_mass or seakeeping, not both (the database's infinite-frequency "
                             "added mass is the added mass)")
        return given

    @classmethod
    def floating_solid(cls, hull: Hull, *, draft_fraction: float = 0.5, density: float = 1025.0, **fields) -> "BoatType":
        """A uniform solid of ``hull`` whose mass is that of the water displaced by the fraction
        ``draft_fraction`` of its volume (density in kg/m^3), centred at the centre of volume."""
        if not 0.0 < draft_fraction < 1.0:
            raise ValueError(f"BoatType.floating_solid: draft_fraction must be in (0, 1), got {draft_fraction!r}")
        mass = draft_fraction * density * hull.volume
        return cls(hull=hull, mass=mass, center_of_mass=tuple(hull.center_of_volume), **fields)

    @property
    def inertia_about_origin(self) -> np.ndarray:
        """(3, 3) inertia about the body origin [kg m^2] (parallel-axis theorem)."""
        return self.inertia + parallel_axis_term(self.mass, self.center_of_mass)

    @property
    def rigid_body_mass_matrix(self) -> np.ndarray:
        """Fossen's M_RB about the body origin: [[m I, -m S(r_g)], [m S(r_g), I_o]]."""
        m, s = self.mass, skew(self.center_of_mass)
        return np.block([[m * np.eye(3), -m * s], [m * s, self.inertia_about_origin]])

    @property
    def mass_matrix(self) -> np.ndarray:
        """M = M_RB + M_A, the matrix that multiplies the acceleration."""
        return self.rigid_body_mass_matrix + self.added_mass
