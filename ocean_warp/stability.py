"""Large-angle statical stability of a hull mesh: the righting-arm (GZ) curve.

At each heel the closed mesh is turned about its body x axis (and, when trim is free, about y), the
still-water plane is lowered or raised until the volume below it carries the boat's mass, and the trim
is found at which the centre of buoyancy lies straight below or above the centre of gravity fore and aft.
The righting arm GZ is the horizontal, athwartships distance from the centre of buoyancy to the centre
of gravity, positive when the buoyancy turns the boat back upright; the righting moment is m g GZ.

Host side, numpy float64: the triangles are clipped exactly at the plane (``hull_form``'s clipping) and
the volume and its first moments closed with the divergence theorem; the waterplane adds nothing to them
(depth 0, vertical normal). :class:`Appendages` the mesh leaves out (a keel fin and bulb, a rudder) add their
volume's buoyancy at its turned centroid, fading out as the centroid nears the surface exactly as the
simulator's ``kernels.appendage_buoyancy`` has it; the mesh carries the rest of the mass. Heel is a rotation about +x (port side up, ``frames.roll_pitch_yaw``'s roll);
trim is a rotation about +y after it (bow down), so body -> world is R_y(trim) R_x(heel).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .hull import Hull
from .hull_form import areas_and_normals, clip_triangles
from .validation import require_finite, require_in_range, require_positive

__all__ = ["WATER_DENSITY", "Appendages", "RightingArmCurve", "Flotation", "float_heeled", "righting_arm_curve",
           "heel_under_moment", "equilibrium_heel"]

WATER_DENSITY = 1025.0
"""Sea water [kg/m^3]."""
MAX_TRIM = 0.6
"""Largest trim [rad] searched for the fore-and-aft balance (34 deg)."""
LEVEL_TOLERANCE = 1e-10
"""Water level tolerance [m]."""
TRIM_TOLERANCE = 1e-9
"""Trim tolerance [rad]."""


@dataclasses.dataclass(frozen=True)
class Appendages:
    """Volume outside a hull mesh that floats with it (keel fin, bulb, rudder): its buoyancy, rho g V share,
    acts straight up at its centroid, share = clamp(1/2 + depth / fade_height, 0, 1) with depth the centroid's
    below the still-water plane (1 while it is well under water)."""

    volume: float
    """V [m^3] (> 0)."""
    center: tuple
    """(3,) its centroid, body frame [m]."""
    fade_height: float
    """Band about the surface over which the buoyancy fades [m] (> 0)."""

    def __post_init__(self):
        owner = "Appendages"
        object.__setattr__(self, "volume", require_positive(owner, "volume", self.volume, unit=" [m^3]"))
        center = np.asarray(self.center, dtype=np.float64)
        if center.shape != (3,) or not np.all(np.isfinite(center)):
            raise ValueError(f"{owner}.center must be 3 finite numbers [m], got {self.center!r}")
        object.__setattr__(self, "center", tuple(float(v) for v in center))
        object.__setattr__(self, "fade_height", require_positive(owner, "fade_height", self.fade_height,
                                                                 unit=" [m]"))

    def share(self, depth: float) -> float:
        """Fraction of the volume's buoyancy at centroid ``depth`` [m] below the surface."""
        return min(max(0.5 + depth / self.fade_height, 0.0), 1.0)


@dataclasses.dataclass(frozen=True)
class Flotation:
    """The boat floating at one heel, in the world-aligned frame with its origin at the body origin."""

    heel: float
    """[rad], about body x, positive port side up."""
    trim: float
    """[rad], about y after the heel, positive bow down."""
    water_level: float
    """Height z of the still-water plane above the body origin [m]."""
    volume: float
    """Displaced volume [m^3], the appendages' share included."""
    center_of_buoyancy: np.ndarray
    """(3,) [m], of the hull's and the appendages' displacement together."""
    center_of_gravity: np.ndarray
    """(3,) [m]."""

    @property
    def righting_arm(self) -> float:
        """GZ [m]: the centre of gravity's y minus the centre of buoyancy's (positive: righting)."""
        return float(self.center_of_gravity[1] - self.center_of_buoyancy[1])


@dataclasses.dataclass(frozen=True)
class RightingArmCurve:
    """GZ of one hull and loading at a set of heels."""

    heel: np.ndarray
    """(H,) [rad]."""
    righting_arm: np.ndarray
    """(H,) GZ [m]."""
    trim: np.ndarray
    """(H,) equilibrium trim [rad], positive bow down (0 where trim is held)."""
    water_level: np.ndarray
    """(H,) still-water plane above the body origin [m]."""
    mass: float
    """[kg]"""
    center_of_mass: np.ndarray
    """(3,) centre of gravity, body frame [m]."""
    density: float
    """Water [kg/m^3]."""
    free_trim: bool
    """Whether the trim was free (else held at 0)."""
    appendages: Appendages | None = None
    """What floats with the mesh outside it (None: nothing)."""

    def righting_moment(self, gravity: float = 9.81) -> np.ndarray:
        """(H,) m g GZ [N m] under ``gravity`` [m/s^2]."""
        return self.mass * gravity * self.righting_arm


def _rotation(heel: float, trim: float) -> np.ndarray:
    """Body -> world rotation R_y(trim) R_x(heel) (3, 3)."""
    ch, sh, ct, st = math.cos(heel), math.sin(heel), math.cos(trim), math.sin(trim)
    roll = np.array([[1.0, 0.0, 0.0], [0.0, ch, -sh], [0.0, sh, ch]])
    pitch = np.array([[ct, 0.0, st], [0.0, 1.0, 0.0], [-st, 0.0, ct]])
    return pitch @ roll


def _quadratic_mean(u: np.ndarray) -> np.ndarray:
    """(P,) mean of u^2 over each linear triangle from corner values ``u`` (P, 3)."""
    return (np.sum(u * u, axis=1) + u[:, 0] * u[:, 1] + u[:, 1] * u[:, 2] + u[:, 2] * u[:, 0]) / 6.0


def _submerged(world: np.ndarray, level: float) -> tuple[float, np.ndarray, float]:
    """Volume [m^3], centre (3,) [m] and waterplane area [m^2] of the closed triangles ``world`` (T, 3, 3)
    below z = ``level``; centre NaN when nothing is submerged."""
    wet = clip_triangles(world, level - world[:, :, 2])
    if len(wet) == 0:
        return 0.0, np.full(3, np.nan), 0.0
    _, vector = areas_and_normals(wet)
    depth = wet[:, :, 2] - level
    volume = float(np.sum(vector[:, 2] * depth.mean(axis=1)))
    if volume <= 0.0:
        return 0.0, np.full(3, np.nan), float(-np.sum(vector[:, 2]))
    moments = np.array([np.sum(0.5 * vector[:, 0] * _quadratic_mean(wet[:, :, 0])),
                        np.sum(0.5 * vector[:, 1] * _quadratic_mean(wet[:, :, 1])),
                        np.sum(0.5 * vector[:, 2] * _quadratic_mean(depth))])
    center = moments / volume + np.array([0.0, 0.0, level])
    return volume, center, float(-np.sum(vector[:, 2]))


def _bracketed_root(function, low: float, high: float, tolerance: float, what: str) -> float:
    """Root of the increasing ``function`` on [low, high] (Illinois regula falsi, sign change required)."""
    f_low, f_high = function(low), function(high)
    if not f_low <= 0.0 <= f_high:
        raise ValueError(f"{what}: no equilibrium in [{low:.4g}, {high:.4g}] (residuals {f_low:.4g}, {f_high:.4g})")
    side = 0
    for _ in range(200):
        middle = (low * f_high - high * f_low) / (f_high - f_low) if f_high != f_low else 0.5 * (low + high)
        if high - low < tolerance:
            break
        f_middle = function(middle)
        if f_middle == 0.0:
            return middle
        if f_middle < 0.0:
            low, f_low = middle, f_middle
            f_high = 0.5 * f_high if side == -1 else f_high
            side = -1
        else:
            high, f_high = middle, f_middle
            f_low = 0.5 * f_low if side == 1 else f_low
            side = 1
    return 0.5 * (low + high) if high - low < tolerance else middle


def _level_for_volume(world: np.ndarray, volume: float, appendage_z: float | None = None,
                      appendages: Appendages | None = None) -> float:
    """Height z [m] of the plane below which ``world`` (T, 3, 3), with ``appendages``' share at the height
    ``appendage_z`` [m], displaces ``volume`` [m^3]."""
    low, high = float(world[:, :, 2].min()), float(world[:, :, 2].max())

    def surplus(level: float) -> float:
        extra = 0.0 if appendages is None else appendages.volume * appendages.share(level - appendage_z)
        return _submerged(world, level)[0] + extra - volume

    if appendages is not None:
        low = min(low, appendage_z - 0.5 * appendages.fade_height)
        high = max(high, appendage_z + 0.5 * appendages.fade_height)
    return _bracketed_root(surplus, low, high, LEVEL_TOLERANCE, "float_heeled (water level)")


def _balance(triangles: np.ndarray, center_of_mass: np.ndarray, volume: float, heel: float, trim: float,
             appendages: Appendages | None = None) -> Flotation:
    """Flotation at ``heel`` and ``trim`` [rad] with the plane carrying ``volume`` [m^3], ``appendages``'
    share included."""
    rotation = _rotation(heel, trim)
    world = triangles @ rotation.T
    if appendages is None:
        level = _level_for_volume(world, volume)
        displaced, center, _ = _submerged(world, level)
        return Flotation(heel, trim, level, displaced, center, rotation @ center_of_mass)
    turned = rotation @ np.asarray(appendages.center)
    level = _level_for_volume(world, volume, float(turned[2]), appendages)
    displaced, center, _ = _submerged(world, level)
    extra = appendages.volume * appendages.share(level - float(turned[2]))
    if displaced <= 0.0:
        center, displaced = turned, extra
    else:
        center = (displaced * center + extra * turned) / (displaced + extra)
        displaced += extra
    return Flotation(heel, trim, level, displaced, center, rotation @ center_of_mass)


def _checked(owner: str, mass, center_of_mass, density) -> tuple[float, np.ndarray, float]:
    mass = require_positive(owner, "mass", mass, unit=" [kg]")
    density = require_positive(owner, "density", density, unit=" [kg/m^3]")
    center = np.asarray(center_of_mass, dtype=np.float64)
    if center.shape != (3,) or not np.all(np.isfinite(center)):
        raise ValueError(f"{owner}.center_of_mass must be 3 finite numbers [m], got {center_of_mass!r}")
    return mass, center, density


def _checked_heels(owner: str, field: str, heels) -> np.ndarray:
    array = np.atleast_1d(np.asarray(heels, dtype=np.float64))
    if array.ndim != 1 or array.size == 0:
        raise ValueError(f"{owner}.{field} must be a non-empty 1-D sequence [rad], got shape {array.shape}")
    if not np.all(np.isfinite(array)) or np.any(array < 0.0) or np.any(array > math.pi):
        raise ValueError(f"{owner}.{field} must be finite and in [0, pi] [rad], got {heels!r}")
    return array


def _checked_appendages(owner: str, appendages) -> Appendages | None:
    if appendages is not None and not isinstance(appendages, Appendages):
        raise ValueError(f"{owner}.appendages must be an Appendages or None, got {appendages!r}")
    return appendages


def float_heeled(hull: Hull, mass: float, center_of_mass, heel: float, *, density: float = WATER_DENSITY,
                 free_trim: bool = True, appendages: Appendages | None = None) -> Flotation:
    """``hull`` holding ``mass`` [kg] with its centre of gravity at ``center_of_mass`` (3,) [m, body frame],
    floating at ``heel`` [rad] in water of ``density`` [kg/m^3]: free in heave, and in trim if
    ``free_trim`` (else upright fore and aft); ``appendages`` outside the mesh float with it."""
    mass, center, density = _checked("float_heeled", mass, center_of_mass, density)
    heel = require_in_range("float_heeled", "heel", heel, 0.0, math.pi, unit=" [rad]")
    appendages = _checked_appendages("float_heeled", appendages)
    triangles = hull.vertices[hull.triangles].astype(np.float64)
    volume = mass / density
    whole = _submerged(triangles, float(triangles[:, :, 2].max()) + 1e-9)[0]
    if volume >= whole + (0.0 if appendages is None else appendages.volume):
        raise ValueError(f"float_heeled: the hull's whole volume holds less than mass {mass} kg; it sinks")
    if not free_trim:
        return _balance(triangles, center, volume, heel, 0.0, appendages)

    def surplus_ahead(trim: float) -> float:
        state = _balance(triangles, center, volume, heel, trim, appendages)
        return float(state.center_of_buoyancy[0] - state.center_of_gravity[0])

    trim = _bracketed_root(surplus_ahead, -MAX_TRIM, MAX_TRIM, TRIM_TOLERANCE, "float_heeled (trim)")
    return _balance(triangles, center, volume, heel, trim, appendages)


def righting_arm_curve(hull: Hull, mass: float, center_of_mass, heels, *, density: float = WATER_DENSITY,
                       free_trim: bool = True, appendages: Appendages | None = None) -> RightingArmCurve:
    """GZ [m] of ``hull`` holding ``mass`` [kg] with its centre of gravity at ``center_of_mass`` (3,) [m, body
    frame] at each of ``heels`` (H,) [rad, 0 to pi], free in heave and (``free_trim``) in trim, with
    ``appendages`` outside the mesh floating with it."""
    mass, center, density = _checked("righting_arm_curve", mass, center_of_mass, density)
    heels = _checked_heels("righting_arm_curve", "heels", heels)
    appendages = _checked_appendages("righting_arm_curve", appendages)
    states = [float_heeled(hull, mass, center, heel, density=density, free_trim=free_trim, appendages=appendages)
              for heel in heels]
    return RightingArmCurve(heel=heels, righting_arm=np.array([s.righting_arm for s in states]),
                            trim=np.array([s.trim for s in states]),
                            water_level=np.array([s.water_level for s in states]), mass=mass,
                            center_of_mass=center, density=density, free_trim=bool(free_trim),
                            appendages=appendages)


def heel_under_moment(curve: RightingArmCurve, moment: float, gravity: float = 9.81) -> float:
    """The smallest heel [rad] at which the righting moment m g GZ of ``curve`` (linear between its heels,
    which must start at 0) equals the heeling ``moment`` [N m, >= 0]; NaN if it never does."""
    moment = require_finite("heel_under_moment", "moment", moment)
    if moment < 0.0:
        raise ValueError(f"heel_under_moment.moment must be >= 0 [N m], got {moment!r}")
    if curve.heel[0] != 0.0 or np.any(np.diff(curve.heel) <= 0.0):
        raise ValueError("heel_under_moment.curve must have increasing heels starting at 0")
    excess = curve.righting_moment(require_positive("heel_under_moment", "gravity", gravity)) - moment
    above = np.flatnonzero(excess >= 0.0)
    if len(above) == 0:
        return math.nan
    i = int(above[0])
    if i == 0:
        return 0.0
    fraction = -excess[i - 1] / (excess[i] - excess[i - 1])
    return float(curve.heel[i - 1] + fraction * (curve.heel[i] - curve.heel[i - 1]))


def equilibrium_heel(hull: Hull, curve: RightingArmCurve, moment: float, gravity: float = 9.81) -> float:
    """The smallest heel [rad] at which ``hull``, loaded as for ``curve`` (which must be its curve), rights
    with exactly ``moment`` [N m]: bracketed by ``curve``, then solved on the mesh; NaN if the curve never
    reaches ``moment``."""
    estimate = heel_under_moment(curve, moment, gravity)
    if math.isnan(estimate) or estimate == 0.0:
        return estimate
    upper = int(np.searchsorted(curve.heel, estimate))

    def excess(heel: float) -> float:
        state = float_heeled(hull, curve.mass, curve.center_of_mass, heel, density=curve.density,
                             free_trim=curve.free_trim, appendages=curve.appendages)
        return curve.mass * gravity * state.righting_arm - moment

    return _bracketed_root(excess, float(curve.heel[upper - 1]), float(curve.heel[upper]), 1e-9, "equilibrium_heel")
