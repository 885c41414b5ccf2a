"""Wave-making resistance of slender hulls and catamarans by Michell's thin-ship integral (numpy, offline).

Michell (1898, "The wave resistance of a ship", Phil. Mag. 45) linearised the flow past a hull whose beam is
small beside its length: each side of the centreplane is a source sheet of strength proportional to the hull's
slope, and the energy its far-field waves carry away is the resistance. With the half-breadth y = f(x, z) of a
hull moving at U along -x (x forward, z up, still water at z = 0), k0 = g / U^2 and lambda = sec(theta) for the
wave travelling at theta to the course (Tuck, "Wave resistance of thin ships and catamarans", Applied
Mathematics Report T8701, University of Adelaide, 1987; Tuck 1989, "The wave resistance formula of J. H.
Michell (1898) and its significance to recent research in ship hydrodynamics", J. Austral. Math. Soc. B 30):

    R = (4 rho g^2 / (pi U^2)) int_1^inf |A(lambda)|^2 lambda^2 / sqrt(lambda^2 - 1) dlambda,
    A(lambda) = int int f_x(x, z) exp(k0 lambda^2 z) exp(i k0 lambda x) dx dz
              = -i k0 lambda int int f(x, z) exp(k0 lambda^2 z) exp(i k0 lambda x) dx dz,

the second form by parts, so that a hull with a blunt end (f jumping to 0 at a flat bow or transom) needs no
derivative. Two such demihulls side by side, their centreplanes ``separation`` apart, radiate the same waves
shifted by +-separation / 2 across the course; their amplitudes add with the factor
2 cos(k0 lambda sqrt(lambda^2 - 1) separation / 2), so the pair's integrand is the demihull's times
4 cos^2(...) (Tuck 1987, the catamaran case): 4x at separation 0 (one hull of twice the breadth), 2x on average
far apart, with humps and hollows between (the interference the pair's resistance curve shows).

The offsets are sampled on a grid (stations x, depths z) and the double integral is exact for the piecewise-
linear interpolant of f (Filon-type weights: the exponentials are integrated analytically on each interval), so
the fast oscillation at short waves costs no extra samples. lambda is integrated with lambda = cosh(u) near 1,
which removes the square-root singularity there, then on a grid uniform in the phase of the bow-stern and
hull-hull oscillations, for eight bow-stern periods; beyond, those oscillations average out and the tail is the
blunt ends' alone (a smooth hull's tail falls as 1 / lambda^5 and is left out). About 0.2 s for a pair's table.

Thin-ship theory has no viscosity and no free-surface nonlinearity; it overpredicts the humps and hollows of
measured curves (Tuck 1989), and it is fitted to nothing here: it is a residuary estimate from geometry alone.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .resistance import FROUDE_SAMPLES, FROUDE_STEP, ResiduaryResistance
from .validation import require_finite, require_in_range, require_int_in_range, require_positive

__all__ = ["HullOffsets", "mesh_offsets", "michell_resistance", "michell_residuary"]

_RESOLVED_PERIODS = 8.0
"""Bow-stern periods of the integrand sampled before its tail is taken in the mean."""
_FAR_SECANT = 1e4
"""lambda up to which the tail is integrated numerically (its 1 / lambda^3 limit after)."""
_POINTS_PER_PERIOD = 12
"""Samples per period of the integrand's fastest oscillation."""
_MAX_POINTS = 200_000
"""Cap on the lambda samples of one speed (very low Froude numbers, where the resistance is negligible)."""


@dataclasses.dataclass(frozen=True, eq=False)
class HullOffsets:
    """A demihull's half-breadths y = f(x, z) [m] on a grid: ``stations`` x [m] (non-decreasing; a repeated
    station is a step, as at a flat end), ``depths`` z [m] (increasing, <= 0, the still water at 0) and
    ``half_breadth`` (stations, depths) [m], >= 0 and 0 at the first and last station (a closed hull)."""

    stations: np.ndarray
    depths: np.ndarray
    half_breadth: np.ndarray

    def __post_init__(self):
        owner = "HullOffsets"
        x = np.asarray(self.stations, dtype=np.float64)
        z = np.asarray(self.depths, dtype=np.float64)
        f = np.asarray(self.half_breadth, dtype=np.float64)
        if x.ndim != 1 or len(x) < 3 or not np.all(np.isfinite(x)) or np.any(np.diff(x) < 0) or x[-1] <= x[0]:
            raise ValueError(f"{owner}.stations must be >= 3 finite non-decreasing x [m] spanning a length, "
                             f"got {self.stations!r}")
        if z.ndim != 1 or len(z) < 2 or not np.all(np.isfinite(z)) or np.any(np.diff(z) <= 0) or z[-1] > 0:
            raise ValueError(f"{owner}.depths must be >= 2 finite increasing z <= 0 [m], got {self.depths!r}")
        if f.shape != (len(x), len(z)) or not np.all(np.isfinite(f)) or np.any(f < 0):
            raise ValueError(f"{owner}.half_breadth must be ({len(x)}, {len(z)}) finite values >= 0 [m], "
                             f"got shape {f.shape}")
        if np.any(f[0] != 0) or np.any(f[-1] != 0):
            raise ValueError(f"{owner}.half_breadth must be 0 at the first and last station (close the hull: "
                             "repeat a station for a blunt end)")
        for name, value in (("stations", x), ("depths", z), ("half_breadth", f)):
            value.setflags(write=False)
            object.__setattr__(self, name, value)

    @property
    def length(self) -> float:
        """Overall length [m]."""
        return float(self.stations[-1] - self.stations[0])

    @property
    def volume(self) -> float:
        """Displaced volume [m^3] of the interpolated hull, both sides of its centreplane."""
        sections = 2.0 * np.trapezoid(self.half_breadth, self.depths, axis=1)
        return float(np.trapezoid(sections, self.stations))


def mesh_offsets(vertices, triangles, waterline_z: float, *, stations: int = 40, depths: int = 32,
                 end_gap: float = 1e-6) -> HullOffsets:
    """The half-breadths of one closed demihull mesh (``vertices`` (V, 3) [m], ``triangles`` (T, 3), body frame,
    upright) below the plane z = ``waterline_z`` [m]: at each grid point, half the width across y of the mesh's
    cut, from ray hits on its triangles. ``stations`` evenly spaced x from end to end, the end ones sampled
    ``end_gap`` [m] inside and each closed by a zero station at the same x (a step: a blunt end keeps its full
    section, a pointed one has none); ``depths`` evenly spaced z from the keel to the waterline (or the mesh's
    top, if lower), given from the waterline."""
    owner = "mesh_offsets"
    waterline_z = require_finite(owner, "waterline_z", waterline_z)
    stations = require_int_in_range(owner, "stations", stations, 3, 10_000)
    depths = require_int_in_range(owner, "depths", depths, 2, 10_000)
    end_gap = require_positive(owner, "end_gap", end_gap, unit=" [m]")
    vertices = np.asarray(vertices, dtype=np.float64)
    corners = vertices[np.asarray(triangles, dtype=np.int64)]
    x_min, x_max = corners[:, :, 0].min(), corners[:, :, 0].max()
    keel = corners[:, :, 2].min()
    if not keel < waterline_z:
        raise ValueError(f"{owner}: waterline_z must lie above the keel {keel:.4g} m, got {waterline_z!r}")
    top = min(waterline_z, corners[:, :, 2].max())
    xs = np.linspace(x_min + end_gap, x_max - end_gap, stations)
    zs = np.linspace(keel + end_gap, top, depths)
    grid_x, grid_z = np.meshgrid(xs, zs, indexing="ij")
    points = np.column_stack([grid_x.ravel(), grid_z.ravel()])
    low = np.full(len(points), np.inf)
    high = np.full(len(points), -np.inf)
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    e1, e2 = (b - a)[:, [0, 2]], (c - a)[:, [0, 2]]
    determinant = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    facing = np.abs(determinant) > 1e-14  # triangles seen edge-on along y (flat ends) cut no ray across y
    for index in np.flatnonzero(facing):
        d = points - a[index, [0, 2]]
        s = (d[:, 0] * e2[index, 1] - d[:, 1] * e2[index, 0]) / determinant[index]
        t = (e1[index, 0] * d[:, 1] - e1[index, 1] * d[:, 0]) / determinant[index]
        inside = (s >= -1e-12) & (t >= -1e-12) & (s + t <= 1.0 + 1e-12)
        y = a[index, 1] + s * (b[index, 1] - a[index, 1]) + t * (c[index, 1] - a[index, 1])
        low = np.where(inside, np.minimum(low, y), low)
        high = np.where(inside, np.maximum(high, y), high)
    half = np.where(high > low, 0.5 * (high - low), 0.0).reshape(grid_x.shape)
    closed = np.concatenate([np.zeros((1, len(zs))), half, np.zeros((1, len(zs)))])
    # The end sections, sampled just inside, stand at the ends themselves: a blunt end is a step there.
    return HullOffsets(np.concatenate([[x_min, x_min], xs[1:-1], [x_max, x_max]]), zs - waterline_z, closed)


def _interval_weights(nodes: np.ndarray, s: np.ndarray) -> np.ndarray:
    """(S, N) weights w with int f(t) exp(s t) dt = sum_j w_j f_j exactly for the piecewise-linear f through
    ``nodes`` (N,), for each rate s (S,) with Re(s) >= 0 or purely imaginary (the exponential is taken from each
    interval's upper end, so it never overflows for the depths, which are <= 0)."""
    h = np.diff(nodes)[None, :]
    s = np.asarray(s)[:, None]
    v = s * h
    small = np.abs(v) < 1e-3
    v_safe = np.where(small, 1.0, v)
    decay = np.exp(-v_safe)
    rising = np.where(small, 0.5 - v / 6.0 + v * v / 24.0, (v_safe - 1.0 + decay) / v_safe**2)
    falling = np.where(small, 0.5 - v / 3.0 + v * v / 8.0, (1.0 - decay * (1.0 + v_safe)) / v_safe**2)
    upper = np.exp(s * nodes[None, 1:]) * h
    weights = np.zeros((s.shape[0], len(nodes)), dtype=np.result_type(s, np.float64))
    weights[:, 1:] += upper * rising
    weights[:, :-1] += upper * falling
    return weights


def _amplitude(stations: np.ndarray, depths: np.ndarray, half_breadth: np.ndarray, k0: float,
               secant: np.ndarray) -> np.ndarray:
    """Michell's amplitude A(lambda) [m^2] of the offsets at wave number k0 [1/m], for each secant (S,)."""
    along = _interval_weights(stations, 1j * k0 * secant)
    down = _interval_weights(depths, k0 * secant**2)
    return -1j * k0 * secant * np.sum((along @ half_breadth) * down, axis=1)


def _essential_stations(offsets: HullOffsets) -> tuple[np.ndarray, np.ndarray]:
    """The stations and half-breadths without those the linear interpolation of their neighbours reproduces
    (a parallel middle body needs none inside): the same interpolant, fewer terms."""
    x, f = offsets.stations, offsets.half_breadth
    keep = [0]
    for i in range(1, len(x) - 1):
        a, b = keep[-1], i + 1
        span = x[b] - x[a]
        between = f[a] + (f[b] - f[a]) * ((x[i] - x[a]) / span if span > 0 else 0.0)
        if span == 0 or not np.allclose(f[i], between, rtol=0.0, atol=1e-12 * max(f.max(), 1e-300)):
            keep.append(i)
    keep.append(len(x) - 1)
    return x[keep], f[keep]


def _resolved_secant(k0: float, length: float) -> float:
    """lambda up to which the integrand is sampled: _RESOLVED_PERIODS bow-stern periods (2 pi / (k0 L) each in
    lambda) and at least 6, so that beyond it the oscillation averages out over the tail's slow decay."""
    return max(6.0, _RESOLVED_PERIODS * 2.0 * math.pi / (k0 * length))


def _secant_nodes(k0: float, length: float, separation: float, top: float) -> tuple[np.ndarray, np.ndarray]:
    """(u, lambda = cosh u) on [1, top]: uniform in u up to lambda 2 (where the 1 / sqrt(lambda^2 - 1) of the
    integrand is taken out by dlambda = sinh u du), then uniform in the phase k0 (lambda L / 2 + lambda^2
    separation / 2) of the bow-stern and hull-hull oscillations, _POINTS_PER_PERIOD per period."""
    def phase(secant):
        return k0 * (0.5 * length * secant + 0.5 * separation * secant**2)

    knee = min(2.0, top)
    rate = k0 * (0.5 * length + separation * knee)
    knee_u = math.acosh(knee)
    count = max(int(math.ceil(knee_u * math.sinh(knee_u) * rate * _POINTS_PER_PERIOD / math.pi)), 200)
    near = np.linspace(0.0, knee_u, count + 1)
    periods = (phase(top) - phase(knee)) / math.pi
    count = min(max(int(math.ceil(periods * _POINTS_PER_PERIOD)), 200), _MAX_POINTS)
    target = np.linspace(phase(knee), phase(top), count + 1)[1:]
    if separation > 0:
        a, b = 0.5 * k0 * separation, 0.5 * k0 * length
        far = 2.0 * target / (b + np.sqrt(b * b + 4.0 * a * target))
    else:
        far = target / (0.5 * k0 * length)
    return near, far


def _steps(stations: np.ndarray, half_breadth: np.ndarray) -> np.ndarray:
    """(steps, depths) the jumps of the half-breadth along x at repeated stations (blunt ends) [m]."""
    jumps = {}
    for i in np.flatnonzero(np.diff(stations) == 0):
        jumps[stations[i]] = jumps.get(stations[i], 0.0) + half_breadth[i + 1] - half_breadth[i]
    return np.array(list(jumps.values())).reshape(-1, half_breadth.shape[1])


def michell_resistance(offsets: HullOffsets, speeds, *, separation: float | None = None, density: float = 1025.0,
                       gravity: float = 9.81, max_secant: float | None = None) -> np.ndarray:
    """Michell's wave resistance [N] of the demihull ``offsets`` at each of ``speeds`` [m/s] (> 0), or, with
    ``separation`` [m], of two of them side by side that far apart (centreplane to centreplane), in water of
    ``density`` [kg/m^3] under ``gravity`` [m/s^2].

    The integrand is sampled up to ``max_secant`` (default: eight bow-stern periods, at least 4); beyond, the
    oscillations along the course average out and what is left is the steps' (blunt ends'): |A|^2 -> sum over the
    steps of |int step(z) exp(k0 lambda^2 z) dz|^2 (times 2 for a pair, its mean), integrated to lambda 10^4 and
    in its 1 / lambda^3 limit after."""
    owner = "michell_resistance"
    speeds = np.atleast_1d(np.asarray(speeds, dtype=np.float64))
    if speeds.ndim != 1 or not np.all(np.isfinite(speeds)) or np.any(speeds <= 0):
        raise ValueError(f"{owner}: speeds must be finite values > 0 [m/s], got {speeds!r}")
    if separation is not None:
        separation = require_in_range(owner, "separation", separation, 0.0, math.inf, unit=" [m]")
    pair = separation is not None
    separation = separation or 0.0
    density = require_positive(owner, "density", density, unit=" [kg/m^3]")
    gravity = require_positive(owner, "gravity", gravity, unit=" [m/s^2]")
    if max_secant is not None:
        max_secant = require_in_range(owner, "max_secant", max_secant, 1.5, _FAR_SECANT)
    stations, half_breadth = _essential_stations(offsets)
    depths = offsets.depths
    steps = _steps(stations, half_breadth)

    def integrand(k0, secant, u=None):
        values = np.abs(_amplitude(stations, depths, half_breadth, k0, secant)) ** 2
        if pair:
            values = values * 4.0 * np.cos(0.5 * k0 * secant * np.sqrt(secant**2 - 1.0) * separation) ** 2
        # dlambda lambda^2 / sqrt(lambda^2 - 1) is du cosh^2 u near lambda = 1.
        return values * (secant**2 if u is not None else secant**2 / np.sqrt(secant**2 - 1.0))

    resistance = np.empty_like(speeds)
    for index, speed in enumerate(speeds):
        k0 = gravity / speed**2
        top = max_secant if max_secant is not None else _resolved_secant(k0, offsets.length)
        near, far = _secant_nodes(k0, offsets.length, separation, top)
        integral = float(np.trapezoid(integrand(k0, np.cosh(near), u=near), near))
        knee = np.cosh(near[-1:])
        integral += float(np.trapezoid(np.concatenate([integrand(k0, knee), integrand(k0, far)]),
                                       np.concatenate([knee, far])))
        if len(steps):
            tail = np.geomspace(top, _FAR_SECANT, 400)
            transforms = steps @ _interval_weights(depths, k0 * tail**2).T
            mean = np.sum(np.abs(transforms) ** 2, axis=0) * (2.0 if pair else 1.0)
            integral += float(np.trapezoid(mean * tail**2 / np.sqrt(tail**2 - 1.0), tail))
            integral += mean[-1] * _FAR_SECANT**3 / (2.0 * _FAR_SECANT**2)
        resistance[index] = 4.0 * density * gravity**2 / (math.pi * speed**2) * integral
    return resistance


def michell_residuary(offsets: HullOffsets, *, separation: float | None = None, hulls: int = 1,
                      center=(0.0, 0.0, 0.0), volume: float | None = None,
                      max_secant: float | None = None) -> ResiduaryResistance:
    """Michell's wave resistance tabulated as a :class:`ResiduaryResistance` (r = R / (rho g volume) at Fn =
    U / sqrt(g L) = 0, 0.05, ..., L the demihull's length; no heel term): of one demihull (``hulls`` 1), or of
    ``hulls`` 2 demihulls ``separation`` [m] apart. ``volume`` [m^3] (default the offsets' times ``hulls``) and
    ``center`` [m], body frame, where the force acts, as the hull kernel takes them. r depends on the Froude
    number alone, so the water's density and gravity drop out."""
    owner = "michell_residuary"
    if hulls not in (1, 2) or (hulls == 2) != (separation is not None):
        raise ValueError(f"{owner}: hulls must be 1 (no separation) or 2 (with a separation), got hulls={hulls!r}, "
                         f"separation={separation!r}")
    volume = hulls * offsets.volume if volume is None else require_positive(owner, "volume", volume, unit=" [m^3]")
    gravity = 9.81
    froude = FROUDE_STEP * np.arange(1, FROUDE_SAMPLES)
    speeds = froude * math.sqrt(gravity * offsets.length)
    resistance = michell_resistance(offsets, speeds, separation=separation, density=1.0, gravity=gravity,
                                    max_secant=max_secant)
    upright = np.concatenate([[0.0], resistance / (gravity * volume)])
    return ResiduaryResistance(waterline_length=offsets.length, displaced_volume=volume, upright=tuple(upright),
                               heel_increase=(0.0,) * FROUDE_SAMPLES, center=tuple(center))
