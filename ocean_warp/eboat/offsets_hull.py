"""The real E-Boat's hull, lofted from the offsets table measured on the seed team's CAD.

The table (``hull_offsets.csv`` beside this module; sheet, "The real geometry, measured from the CAD")
gives, at 27 stations from the transom to the bow, the height of the flat bottom and the outer
half-breadth 3 mm above it and at 23 waterlines up to the sheer, in the CAD hull frame: x from the
transom (0) forward, z = 0 at the sheer, z up. The hull is a flat bottom, slab sides flaring out, a plumb
bow and a transom, and a flat deck at the sheer.

The loft: each measured half-section is read as the bottom's half (from the centre line out to the chine,
the half-breadth of its lowest measured point) and the side (from the chine up to the sheer, the
half-breadth at the sheer extrapolated from the two highest waterlines); both are resampled at fixed
fractions (the bottom by half-breadth, the side by height), and the resampled points are interpolated
linearly in x between the measured stations onto evenly spaced ones, from the transom (x = 0) to the bow
(``LENGTH``, 2.489 m), extrapolating the two end intervals. The mesh closes with the first station's section
(the transom), the last one's (the plumb bow), each a fan from a point at its middle, and the deck between the
sheer lines. Port and starboard share the centre line of the bottom. Triangles: ``stations * (4 *
section_points - 2)``, as :func:`~ocean_warp.eboat.hull_shape.triangle_count` counts the procedural hull's,
so one budget picks both hulls' resolution.

Frames: the CAD hull frame maps to the URDF's base frame by x_b = x - 1.24471, z_b = z + 0.40996 (sheet).
The body frame is the base frame lowered by ``BASE_TO_WATERLINE`` (0.094 m), so that its origin lies on the
real boat's still waterline at rest (sheet: at 158.4 kg in sea water the waterline is at base z +0.094):
a boat reset at z = 0 floats about where it rests, as the body frame's "origin at the waterline" promises.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib.resources
import io

import numpy as np

from ..hull import Hull
from ..validation import require_int_in_range
from .hull_shape import MIN_TRIANGLE_BUDGET, resolution_for_budget

__all__ = ["HullOffsets", "load_hull_offsets", "parse_hull_offsets", "offsets_hull", "offsets_hull_for_budget",
           "cad_to_body", "CAD_X_TO_BASE", "CAD_Z_TO_BASE", "BASE_TO_WATERLINE", "LENGTH", "DEFAULT_STATIONS",
           "DEFAULT_SECTION_POINTS", "MIN_TRIANGLE_BUDGET"]

CAD_X_TO_BASE = -1.24471
"""Sheet, real geometry: x_b = x - 1.24471 [m] (the CAD hull frame's x from the transom to the base frame's)."""
CAD_Z_TO_BASE = 0.40996
"""Sheet, real geometry: z_b = z + 0.40996 [m] (the CAD's z = 0 at the sheer to the base frame's)."""
BASE_TO_WATERLINE = 0.094
"""Sheet, real geometry: at 158.4 kg in sea water the real boat floats with its waterline at base z +0.094 m.
The body frame is the base frame lowered by this much: z_body = z_b - 0.094."""
LENGTH = 2.489
"""Sheet, real geometry: the hull is 2.489 m long, transom (CAD x = 0) to bow."""
DEFAULT_STATIONS, DEFAULT_SECTION_POINTS = 44, 12
"""The default loft (as the procedural hull's): 44 x (4 x 12 - 2) = 2 024 triangles."""
_MIN_STATIONS, _MAX_STATIONS = 4, 400
_MIN_SECTION_POINTS, _MAX_SECTION_POINTS = 3, 100
_BOTTOM_SHARE = 3
"""One in this many of a half-section's intervals lies on the flat bottom (at least one); the rest on the side,
where the waterline moves."""
_CHINE_OFFSET = 0.003
"""The table's first half-breadth is measured 3 mm above the bottom [m]."""


def cad_to_body(points) -> np.ndarray:
    """(..., 3) points of the CAD hull frame [m] in the body frame (x_b = x - 1.24471, z = z_b - 0.094)."""
    points = np.asarray(points, dtype=np.float64)
    return points + np.array([CAD_X_TO_BASE, 0.0, CAD_Z_TO_BASE - BASE_TO_WATERLINE])


@dataclasses.dataclass(frozen=True, eq=False)
class HullOffsets:
    """A hull's offsets in the CAD hull frame [m]: stations, the bottom's height, and each half-section as
    measured points (height, half-breadth), lowest first."""

    stations: np.ndarray
    """(S,) x of the stations, increasing [m]."""
    bottom: np.ndarray
    """(S,) z of the flat bottom at each station [m] (below 0, the sheer)."""
    sections: tuple
    """S arrays (K_s, 2) of (z, half-breadth) [m], z increasing, all above the bottom and below the sheer."""
    length: float | None = None
    """From the transom (x = 0) to the bow [m], at or beyond the last station; None: the last station."""

    def __post_init__(self):
        stations, bottom = np.asarray(self.stations, dtype=np.float64), np.asarray(self.bottom, dtype=np.float64)
        if stations.ndim != 1 or len(stations) < 2 or bottom.shape != stations.shape:
            raise ValueError(f"HullOffsets: stations and bottom must be two (S >= 2,) arrays, got {stations.shape} "
                             f"and {bottom.shape}")
        if not np.all(np.isfinite(stations)) or np.any(np.diff(stations) <= 0.0):
            raise ValueError("HullOffsets.stations must be finite and strictly increasing [m]")
        if not np.all(np.isfinite(bottom)) or np.any(bottom >= 0.0):
            raise ValueError("HullOffsets.bottom must be finite and below the sheer (z < 0) [m]")
        if len(self.sections) != len(stations):
            raise ValueError(f"HullOffsets.sections must hold one section per station ({len(stations)}), "
                             f"got {len(self.sections)}")
        for x, floor, section in zip(stations, bottom, self.sections):
            section = np.asarray(section, dtype=np.float64)
            if section.ndim != 2 or section.shape[1] != 2 or len(section) < 2:
                raise ValueError(f"HullOffsets: the section at x = {x} m must hold at least 2 (z, y) points")
            z, y = section[:, 0], section[:, 1]
            if not (np.all(np.isfinite(section)) and np.all(np.diff(z) > 0.0) and z[0] > floor and z[-1] < 0.0
                    and np.all(y > 0.0)):
                raise ValueError(f"HullOffsets: the section at x = {x} m must have increasing heights between the "
                                 f"bottom ({floor} m) and the sheer (0) and positive half-breadths")
        length = float(stations[-1]) if self.length is None else self.length
        if not (isinstance(length, (int, float)) and np.isfinite(length) and length >= stations[-1]
                and stations[0] >= 0.0):
            raise ValueError(f"HullOffsets: the stations must lie in [0, length] from the transom, got "
                             f"{stations[0]}..{stations[-1]} m and length {self.length!r}")
        object.__setattr__(self, "length", float(length))
        object.__setattr__(self, "stations", stations)
        object.__setattr__(self, "bottom", bottom)
        object.__setattr__(self, "sections", tuple(np.asarray(s, dtype=np.float64) for s in self.sections))


def parse_hull_offsets(text: str, length: float | None = None) -> HullOffsets:
    """The offsets in the layout of ``hull_offsets.csv``: '#' comment lines, a header ``x_m, bottom_z_m,
    y_at_bottom_plus_3mm, y_at_z<height>...``, then one row per station (an empty cell: no hull there); the
    hull ``length`` [m] from the transom (None: to the last station)."""
    lines = [line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")]
    header = [cell.strip() for cell in lines[0].split(",")]
    if header[:3] != ["x_m", "bottom_z_m", "y_at_bottom_plus_3mm"] or len(header) < 5:
        raise ValueError(f"hull offsets: the header must start x_m, bottom_z_m, y_at_bottom_plus_3mm and name "
                         f"waterlines, got {header[:4]}")
    try:
        heights = np.array([float(name.removeprefix("y_at_z")) for name in header[3:]])
    except ValueError as error:
        raise ValueError(f"hull offsets: waterline columns must be named y_at_z<height>: {error}") from None
    table = np.genfromtxt(io.StringIO("\n".join(lines[1:])), delimiter=",", filling_values=np.nan, ndmin=2)
    if table.shape[1] != len(header):
        raise ValueError(f"hull offsets: rows must hold {len(header)} cells, got {table.shape[1]}")
    sections = []
    for row in table:
        z = np.concatenate([[row[1] + _CHINE_OFFSET], heights])
        y = row[2:]
        keep = np.isfinite(y)
        order = np.argsort(z[keep])
        sections.append(np.column_stack([z[keep][order], y[keep][order]]))
    return HullOffsets(stations=table[:, 0], bottom=table[:, 1], sections=tuple(sections), length=length)


@functools.cache
def load_hull_offsets() -> HullOffsets:
    """The E-Boat's offsets, ``hull_offsets.csv`` shipped with the package (sheet, real geometry)."""
    text = importlib.resources.files("ocean_warp.eboat").joinpath("hull_offsets.csv").read_text()
    return parse_hull_offsets(text, LENGTH)


def _split(section_points: int) -> tuple[int, int]:
    """(bottom, side) intervals of a half-section of ``section_points`` points (centre line to sheer)."""
    intervals = section_points - 1
    bottom = max(1, intervals // _BOTTOM_SHARE)
    return bottom, intervals - bottom


def _resampled_sections(offsets: HullOffsets, section_points: int) -> tuple[np.ndarray, np.ndarray]:
    """(S, P) half-breadths and heights [m] of each measured station's half-section at P = ``section_points``
    points: the centre line of the bottom, the bottom out to the chine, the side up to the sheer."""
    bottom_intervals, side_intervals = _split(section_points)
    across = np.linspace(0.0, 1.0, bottom_intervals + 1)
    up = np.linspace(0.0, 1.0, side_intervals + 1)[1:]
    ys, zs = [], []
    for floor, section in zip(offsets.bottom, offsets.sections):
        z, y = section[:, 0], section[:, 1]
        sheer = y[-1] + (y[-1] - y[-2]) * (0.0 - z[-1]) / (z[-1] - z[-2])
        side_z = np.concatenate([[floor], z, [0.0]])
        side_y = np.concatenate([[y[0]], y, [sheer]])
        heights = floor * (1.0 - up)
        ys.append(np.concatenate([y[0] * across, np.interp(heights, side_z, side_y)]))
        zs.append(np.concatenate([np.full(len(across), floor), heights]))
    return np.array(ys), np.array(zs)


def _along(stations: np.ndarray, values: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``values`` (S, ...) at ``stations`` (S,), linear in x at ``x`` (N,), extrapolating the end intervals."""
    index = np.clip(np.searchsorted(stations, x) - 1, 0, len(stations) - 2)
    t = (x - stations[index]) / (stations[index + 1] - stations[index])
    t = t.reshape((-1,) + (1,) * (values.ndim - 1))
    return values[index] + t * (values[index + 1] - values[index])


def offsets_hull(stations: int = DEFAULT_STATIONS, section_points: int = DEFAULT_SECTION_POINTS, *,
                 offsets: HullOffsets | None = None, name: str = "eboat") -> Hull:
    """The hull of ``offsets`` (default: the E-Boat's, :func:`load_hull_offsets`) as a closed mesh in the body
    frame [m], lofted at ``stations`` evenly spaced stations (4 to 400) from the transom to its length, of
    ``section_points`` points each (3 to 100, centre line to sheer): ``stations * (4 * section_points - 2)``
    triangles."""
    n = require_int_in_range("offsets_hull", "stations", stations, _MIN_STATIONS, _MAX_STATIONS)
    m = require_int_in_range("offsets_hull", "section_points", section_points, _MIN_SECTION_POINTS,
                             _MAX_SECTION_POINTS)
    offsets = offsets if offsets is not None else load_hull_offsets()
    measured_y, measured_z = _resampled_sections(offsets, m)
    x = np.linspace(0.0, offsets.length, n)
    half_breadth = np.maximum(_along(offsets.stations, measured_y, x), 0.0)
    height = _along(offsets.stations, measured_z, x)
    half_breadth[:, 0] = 0.0

    # Vertices: the centre line of the bottom, then port (y > 0) and starboard points of every station.
    vertices = []
    port = np.empty((n, m), dtype=np.int64)
    starboard = np.empty((n, m), dtype=np.int64)
    for i in range(n):
        port[i, 0] = starboard[i, 0] = len(vertices)
        vertices.append((x[i], 0.0, height[i, 0]))
        for j in range(1, m):
            port[i, j] = len(vertices)
            vertices.append((x[i], half_breadth[i, j], height[i, j]))
            starboard[i, j] = len(vertices)
            vertices.append((x[i], -half_breadth[i, j], height[i, j]))

    faces = []
    for i in range(n - 1):
        for j in range(m - 1):  # outward: -z on the bottom, +y on the port side, mirrored to starboard
            a, b, c, d = port[i, j], port[i + 1, j], port[i + 1, j + 1], port[i, j + 1]
            faces += [(a, d, c), (a, c, b)]
            a, b, c, d = starboard[i, j], starboard[i + 1, j], starboard[i + 1, j + 1], starboard[i, j + 1]
            faces += [(a, b, c), (a, c, d)]
        a, b, c, d = port[i, m - 1], port[i + 1, m - 1], starboard[i + 1, m - 1], starboard[i, m - 1]
        faces += [(a, d, c), (a, c, b)]  # the deck, +z
    for i, outward in ((0, -1.0), (n - 1, 1.0)):  # transom (-x) and bow (+x): fans from the section's middle
        middle = len(vertices)
        vertices.append((x[i], 0.0, 0.5 * height[i, 0]))
        ring = [starboard[i, j] for j in range(m - 1, 0, -1)] + [port[i, j] for j in range(m)]
        for k in range(len(ring)):  # the ring runs up starboard, across the bottom, up port: closed by the deck
            first, second = ring[k], ring[(k + 1) % len(ring)]
            faces.append((middle, first, second) if outward > 0 else (middle, second, first))
    body = cad_to_body(np.array(vertices))
    return Hull(body, np.array(faces, dtype=np.int64), name=name)


def offsets_hull_for_budget(budget: int, *, offsets: HullOffsets | None = None) -> Hull:
    """The E-Boat's real hull lofted within ``budget`` triangles (at least ``MIN_TRIANGLE_BUDGET``, 40: 4
    stations of 3 points) and as many as it allows, with about the default's ratio of stations to section
    points (:func:`~ocean_warp.eboat.hull_shape.resolution_for_budget`)."""
    stations, section_points = resolution_for_budget(budget)
    return offsets_hull(stations, section_points, offsets=offsets)

