"""Metrics of sailed paths, in plain numpy: what ``ocean-warp eval`` reports about each run and controller.

Every function takes host arrays (positions [m] in the plane, headings and wind directions [rad] from +x
counter-clockwise) and knows nothing of the simulator, so each can be checked on paths built by hand.

- :func:`path_length`: distance sailed, the sum of the straight segments between recorded positions.
- :func:`wind_crossings`: tacks and gybes. A tack is the true wind's source crossing the bow (the wind
  changes side with the bow pointing less than 90 deg from where it comes from); a gybe is the same
  crossing at the stern. With ``margin`` = 0 this is the sign of sin(wind direction - heading) flipping,
  a tack when the heading is then within 90 deg of the direction the wind comes FROM. A crossing counts
  once the heading has settled ``margin`` past the wind axis on the new side (default 10 deg), so yawing
  in waves about head-to-wind or dead downwind counts nothing, and a tack that fails and falls back counts
  nothing either.
- :func:`motor_use`: the fraction of decisions with a non-zero propeller level.
- :func:`cross_track_spread`: how consistent the paths of many runs are, leg by leg (see there).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

__all__ = ["wrap_angle", "path_length", "wind_crossings", "motor_use", "leg_indices", "cross_track_profile",
           "cross_track_spread", "SPREAD_POINTS", "CROSSING_MARGIN"]

SPREAD_POINTS = 50
"""Points per leg at which the cross-track spread is taken."""
CROSSING_MARGIN = math.radians(10.0)
"""How far past the wind axis [rad] the heading must settle for a tack or gybe to count."""


def wrap_angle(angle):
    """``angle`` [rad] wrapped into [-pi, pi)."""
    return (np.asarray(angle, dtype=np.float64) + math.pi) % (2.0 * math.pi) - math.pi


def path_length(xy) -> float:
    """Length [m] of the polyline through the positions ``xy`` (T, 2) [m]: the sum of its segments (0 for
    fewer than two points; segments with a non-finite end are skipped)."""
    xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    if len(xy) < 2:
        return 0.0
    segments = np.hypot(*np.diff(xy, axis=0).T)
    return float(segments[np.isfinite(segments)].sum())


def wind_crossings(heading, wind_direction, *, margin: float = CROSSING_MARGIN) -> tuple[int, int]:
    """(tacks, gybes) in a sequence of headings.

    Args:
        heading: (T,) the boat's heading at each recorded instant [rad, from +x counter-clockwise].
        wind_direction: the direction the true wind blows TOWARD [rad], a scalar or (T,).
        margin: [rad], in [0, 90 deg): a change of side counts only once the heading is at least this far
            past the wind axis (0: every sign change of sin(wind direction - heading)).

    The angle of the wind's source from the bow, a = wind_from - heading, is unwrapped along the
    sequence; the wind changes side whenever a crosses a multiple of pi: an even multiple is the bow
    (a tack), an odd one the stern (a gybe). Samples closer than ``margin`` to a multiple of pi are not
    taken as settled on either side; between consecutive settled samples every multiple of pi crossed
    counts once. A heading change of more than 180 deg between two samples is taken the short way.
    """
    margin = float(margin)
    if not (0.0 <= margin < math.pi / 2):
        raise ValueError(f"wind_crossings: margin must be in [0, pi/2) [rad], got {margin!r}")
    heading = np.asarray(heading, dtype=np.float64).reshape(-1)
    wind_from = np.broadcast_to(np.asarray(wind_direction, dtype=np.float64), heading.shape) + math.pi
    keep = np.isfinite(heading) & np.isfinite(wind_from)
    if keep.sum() < 2:
        return 0, 0
    relative = np.unwrap(wrap_angle(wind_from[keep] - heading[keep]))
    region = np.floor(relative / math.pi)
    into = relative - region * math.pi  # in [0, pi): how far past the last multiple of pi
    settled = np.minimum(into, math.pi - into)
    settled = (settled >= margin) & (settled > 0.0)
    sides = region[settled].astype(np.int64)
    if len(sides) < 2:
        return 0, 0
    low = np.minimum(sides[:-1], sides[1:]) + 1  # multiples of pi crossed: low ... high (empty when equal)
    high = np.maximum(sides[:-1], sides[1:])
    crossed = np.maximum(high - low + 1, 0)
    evens = np.where(crossed > 0, np.floor_divide(high, 2) - np.floor_divide(low - 1, 2), 0)
    tacks = int(evens.sum())
    return tacks, int(crossed.sum()) - tacks


def motor_use(levels) -> float:
    """Fraction of decisions whose propeller level (integer, -5 ... 5) is not 0; NaN without decisions."""
    levels = np.asarray(levels).reshape(-1)
    return float(np.mean(levels != 0)) if levels.size else math.nan


def leg_indices(reached, leg: int) -> np.ndarray:
    """Indices of the samples of one leg: those taken while ``leg`` waypoints had been reached (the first
    is where the leg began), then the first sample after it (where its waypoint was reached, if it was).
    ``reached`` (T,): waypoints reached by each sample, non-decreasing."""
    reached = np.asarray(reached).reshape(-1)
    on_leg = np.flatnonzero(reached == leg)
    if on_leg.size == 0:
        return on_leg
    last = on_leg[-1]
    return np.append(on_leg, last + 1) if last + 1 < reached.size else on_leg


def cross_track_profile(xy, start, end, points: int = SPREAD_POINTS) -> np.ndarray:
    """Cross-track offsets [m] (positive to the left of start -> end) of the path ``xy`` (T, 2) at ``points``
    along-track distances equally spaced from 0 to the leg's length |end - start|.

    At along-track distance s the path's offset is taken where the path first reaches s (interpolated
    linearly on the segment that crosses it), so a path that doubles back, as a beat does, has one
    well-defined offset at each s; before the path's first point (s below it) the first point's offset is
    used, and beyond the farthest the path got, the last point's.
    """
    xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    start = np.asarray(start, dtype=np.float64)
    direction = np.asarray(end, dtype=np.float64) - start
    length = float(np.hypot(*direction))
    if length == 0.0:
        raise ValueError("cross_track_profile: the leg has no length (start == end)")
    if len(xy) == 0:
        return np.full(points, math.nan)
    along_unit = direction / length
    relative = xy - start
    along = relative @ along_unit
    across = relative @ np.array([-along_unit[1], along_unit[0]])
    grid = np.linspace(0.0, length, points)
    furthest = np.maximum.accumulate(along)
    first = np.searchsorted(furthest, grid, side="left")  # first sample with along >= s
    offsets = np.empty(points)
    before = first == 0
    offsets[before] = across[0]
    beyond = first >= len(xy)
    offsets[beyond] = across[-1]
    inside = ~before & ~beyond
    j = first[inside]
    a0, a1 = along[j - 1], along[j]  # a0 < s <= a1
    t = (grid[inside] - a0) / (a1 - a0)
    offsets[inside] = across[j - 1] + t * (across[j] - across[j - 1])
    return offsets


def cross_track_spread(paths: Sequence[np.ndarray], reached: Sequence[np.ndarray], route, start,
                       points: int = SPREAD_POINTS) -> tuple[np.ndarray, float]:
    """Spread of many runs' paths about each leg [m]: (per leg (R,), the mean over legs).

    Args:
        paths: per run, (T_i, 2) positions [m] from the run's origin.
        reached: per run, (T_i,) waypoints reached by each sample (which leg the sample is on).
        route: (R, 2) the waypoints [m] every run sails, in order, or (N, R, 2) each run's own (runs that
            drew their waypoints); leg k runs from waypoint k - 1 to waypoint k.
        start: (2,) where leg 0 starts [m].
        points: along-track points per leg.

    For each leg, every run that completed it (reached its waypoint) is resampled at ``points`` points
    equally spaced in along-track distance along its own leg (:func:`cross_track_profile`); at each point
    the population standard deviation (ddof 0) of the cross-track offsets across those runs is taken, and
    the leg's spread is the mean over its points. A run's leg of no length (a waypoint where the leg starts)
    has no track to stray from and is left out; a leg completed by fewer than two runs has no spread (NaN).
    The overall value is the mean over the legs that have one (NaN if none).
    """
    routes = np.asarray(route, dtype=np.float64)
    if routes.ndim < 3:  # one route for every run
        routes = np.broadcast_to(routes.reshape(1, routes.size // 2, 2), (len(paths), routes.size // 2, 2))
    legs = routes.shape[1]
    first = np.asarray(start, dtype=np.float64).reshape(1, 2)
    corners = [np.vstack([first, own]) for own in routes]
    per_leg = np.full(legs, math.nan)
    for leg in range(legs):
        profiles = []
        for xy, seen, corner in zip(paths, reached, corners):
            seen = np.asarray(seen).reshape(-1)
            if seen.size == 0 or seen.max() <= leg or np.array_equal(corner[leg], corner[leg + 1]):
                continue
            index = leg_indices(seen, leg)
            profiles.append(cross_track_profile(np.asarray(xy)[index], corner[leg], corner[leg + 1], points))
        if len(profiles) >= 2:
            per_leg[leg] = float(np.std(np.array(profiles), axis=0).mean())
    valid = per_leg[np.isfinite(per_leg)]
    return per_leg, float(valid.mean()) if valid.size else math.nan
