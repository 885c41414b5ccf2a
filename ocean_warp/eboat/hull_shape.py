"""A procedural sailboat hull for the E-Boat: the canoe body, lofted from superellipse sections.

The sheet gives the length overall (2.5 m) and the collision box of the hull (2.7 x 1.0 x 0.63 m). The
shape within them is ours: a pointed bow, a wide transom, maximum beam a little aft of midships, a keel
line with rocker, and full, firm-bilged sections (superellipse exponent 4) using the box's whole 1 m
beam. The sheet's mass figures put the centre of mass 0.16 m above the waterline (the mast's 12.5 kg
at 2 m), so the boat's stability comes from the waterplane: with 2.5-exponent sections of 0.92 m beam
the metacentric height was 6 cm and the boat capsized in 7 m/s of wind; these sections give about
0.25 m. The keel fin, its bulb and the rudder are not part of this mesh: they act through the foil
model (sheet, "Sail, keel and rudder"), which would otherwise count their drag twice.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..hull import Hull
from ..validation import require_finite, require_in_range, require_int_in_range, require_positive

_MIN_STATIONS, _MAX_STATIONS = 4, 400
_MIN_SECTION_POINTS, _MAX_SECTION_POINTS = 3, 100
_RATIO_BAND = 1.5
"""A budget's mesh keeps stations / section_points within this factor of the full hull's 44 / 12, where
any resolution within the budget does."""


def triangle_count(stations: int, section_points: int) -> int:
    """Triangles of :func:`eboat_hull`'s mesh with this resolution: 4 (stations - 1) (section_points - 1) on
    the two skins, 2 (section_points - 1) in the bow fans, 2 stations - 1 on the deck and 2 section_points - 1
    in the transom fan, which sums to ``stations * (4 * section_points - 2)`` (the full hull: 44 x 46 = 2 024)."""
    return int(stations) * (4 * int(section_points) - 2)


MIN_TRIANGLE_BUDGET = triangle_count(_MIN_STATIONS, _MIN_SECTION_POINTS)
"""The coarsest mesh the procedure makes (4 stations of 3 points): 40 triangles."""

__all__ = ["HullShape", "eboat_hull", "MIN_TRIANGLE_BUDGET", "resolution_for_budget", "triangle_count"]


@dataclasses.dataclass(frozen=True)
class HullShape:
    """Dimensions of the canoe body in the base frame [m] (x bow, z up, waterline at z = 0)."""

    stern_x: float = -1.2
    """Transom."""
    bow_x: float = 1.3
    """Stem head; with the transom, 2.5 m overall (sheet)."""
    half_beam: float = 0.5
    """Largest half-breadth, at the deck (beam 1.0 m, the sheet's box)."""
    deck_z: float = 0.38
    keel_z: float = -0.22
    """Lowest point of the keel line; deck to keel 0.60 m, within the sheet's 0.63 m box."""
    widest_at: float = 0.4
    """Fraction of the length from the stern where the beam is greatest."""
    transom_beam_fraction: float = 0.75
    section_exponent: float = 4.0
    stations: int = 44
    """Sections along the length."""
    section_points: int = 12
    """Points on each half-section, keel to deck."""

    def __post_init__(self):
        owner = "HullShape"
        for name in ("stern_x", "bow_x", "deck_z", "keel_z"):
            require_finite(owner, name, getattr(self, name))
        if self.bow_x <= self.stern_x:
            raise ValueError(f"{owner}.bow_x must lie forward of stern_x, got {self.bow_x!r} <= {self.stern_x!r}")
        if self.deck_z <= self.keel_z:
            raise ValueError(f"{owner}.deck_z must lie above keel_z, got {self.deck_z!r} <= {self.keel_z!r}")
        require_positive(owner, "half_beam", self.half_beam, unit=" [m]")
        require_positive(owner, "section_exponent", self.section_exponent)
        require_in_range(owner, "widest_at", self.widest_at, 0.05, 0.95)
        require_in_range(owner, "transom_beam_fraction", self.transom_beam_fraction, 0.0, 1.0)
        require_int_in_range(owner, "stations", self.stations, _MIN_STATIONS, _MAX_STATIONS)
        require_int_in_range(owner, "section_points", self.section_points, _MIN_SECTION_POINTS, _MAX_SECTION_POINTS)

    @property
    def triangle_count(self) -> int:
        """Triangles of this shape's mesh, ``stations * (4 * section_points - 2)`` (see :func:`triangle_count`)."""
        return triangle_count(self.stations, self.section_points)

    def with_triangle_budget(self, budget: int) -> HullShape:
        """This shape with ``stations`` and ``section_points`` chosen so that its mesh has at most ``budget``
        triangles and as many as it can, with stations / section_points within a factor 1.5 of the full
        hull's 44 / 12 where the budget allows (else as close to it as it allows); ties go to the closer
        ratio. The dimensions [m] stay as they are. A budget of 2 024 or a little more gives the full hull."""
        stations, section_points = resolution_for_budget(budget)
        return dataclasses.replace(self, stations=stations, section_points=section_points)

    @classmethod
    def for_triangle_budget(cls, budget: int) -> HullShape:
        """The default dimensions [m] meshed within ``budget`` triangles (see :meth:`with_triangle_budget`)."""
        return cls().with_triangle_budget(budget)


def resolution_for_budget(budget: int) -> tuple[int, int]:
    """(stations, section_points) of the finest mesh of at most ``budget`` triangles, keeping about the
    full hull's ratio of stations to section points (see :meth:`HullShape.with_triangle_budget`)."""
    if isinstance(budget, bool) or not isinstance(budget, (int, np.integer)) or budget < MIN_TRIANGLE_BUDGET:
        raise ValueError(f"HullShape.with_triangle_budget: budget must be an integer >= {MIN_TRIANGLE_BUDGET} "
                         f"(the coarsest mesh: {_MIN_STATIONS} stations of {_MIN_SECTION_POINTS} points), "
                         f"got {budget!r}")
    target = HullShape.stations / HullShape.section_points
    candidates = []
    for section_points in range(_MIN_SECTION_POINTS, _MAX_SECTION_POINTS + 1):
        stations = min(_MAX_STATIONS, int(budget) // (4 * section_points - 2))
        if stations >= _MIN_STATIONS:
            off_ratio = abs(math.log(stations / section_points / target))
            candidates.append((off_ratio, triangle_count(stations, section_points), stations, section_points))
    in_band = [c for c in candidates if c[0] <= math.log(_RATIO_BAND)]
    if in_band:
        best = max(in_band, key=lambda c: (c[1], -c[0]))
    else:  # too few triangles for the ratio: the closest ratio, then the most triangles
        best = min(candidates, key=lambda c: (c[0], -c[1]))
    return best[2], best[3]


def _half_beam(shape: HullShape, xi: np.ndarray) -> np.ndarray:
    """Half-breadth at the deck at fraction xi of the length from the stern: an ellipse-like curve to
    the widest point, then one that closes to a sharp bow."""
    aft = xi <= shape.widest_at
    t_aft = (shape.widest_at - xi) / shape.widest_at
    t_fore = (xi - shape.widest_at) / (1.0 - shape.widest_at)
    transom = shape.transom_beam_fraction
    aft_curve = np.sqrt(np.clip(1.0 - (1.0 - transom**2) * t_aft**2, 0.0, 1.0))
    fore_curve = np.clip(1.0 - np.clip(t_fore, 0.0, 1.0) ** 1.8, 0.0, 1.0) ** 0.75
    return shape.half_beam * np.where(aft, aft_curve, fore_curve)


def _keel_depth(shape: HullShape, xi: np.ndarray) -> np.ndarray:
    """Deck-to-keel depth: deepest a little aft of midships, rising towards the bow and the transom."""
    deepest = shape.deck_z - shape.keel_z
    aft = np.clip((0.45 - xi) / 0.45, 0.0, 1.0)
    fore = np.clip((xi - 0.45) / 0.55, 0.0, 1.0)
    rocker = 0.35 * aft**2 + 0.75 * fore**2.2
    return deepest * (1.0 - rocker)


def eboat_hull(shape: HullShape | None = None) -> Hull:
    """The canoe body as a closed mesh [m]: port and starboard skins, the deck and the transom, with
    ``shape.triangle_count`` triangles (:func:`triangle_count`)."""
    shape = shape or HullShape()
    n, m = shape.stations, shape.section_points
    xi = np.linspace(0.0, 1.0, n)
    x = shape.stern_x + xi * (shape.bow_x - shape.stern_x)
    half_beam = np.maximum(_half_beam(shape, xi), 1e-3)
    depth = _keel_depth(shape, xi)
    # Superellipse quarter section: u = 0 at the deck edge, u = pi/2 on the keel line.
    u = np.linspace(0.0, 0.5 * math.pi, m)
    power = 2.0 / shape.section_exponent
    ys = np.cos(u) ** power
    zs = np.sin(u) ** power

    vertices = []
    port = np.empty((n, m), dtype=np.int64)
    starboard = np.empty((n, m), dtype=np.int64)
    for i in range(n):
        for j in range(m):
            z = shape.deck_z - depth[i] * zs[j]
            if j == m - 1:  # the keel line point is shared by both skins
                port[i, j] = starboard[i, j] = len(vertices)
                vertices.append((x[i], 0.0, z))
                continue
            port[i, j] = len(vertices)
            vertices.append((x[i], half_beam[i] * ys[j], z))
            starboard[i, j] = len(vertices)
            vertices.append((x[i], -half_beam[i] * ys[j], z))
    stem = len(vertices)  # the bow closes on one point at deck height (the keel-line point is shared)
    vertices.append((shape.bow_x + 1e-3, 0.0, shape.deck_z))

    faces = []
    for i in range(n - 1):
        for j in range(m - 1):
            a, b, c, d = port[i, j], port[i + 1, j], port[i + 1, j + 1], port[i, j + 1]
            faces += [(a, b, c), (a, c, d)]
            a, b, c, d = starboard[i, j], starboard[i + 1, j], starboard[i + 1, j + 1], starboard[i, j + 1]
            faces += [(a, d, c), (a, c, b)]
    # Bow: fan from the stem point over the last station's section, both sides.
    last = n - 1
    for j in range(m - 1):
        faces.append((port[last, j], stem, port[last, j + 1]))
        faces.append((starboard[last, j], starboard[last, j + 1], stem))
    # Deck: quads between the deck edges of neighbouring stations, and the bow tip.
    for i in range(n - 1):
        faces += [(port[i, 0], starboard[i, 0], starboard[i + 1, 0]), (port[i, 0], starboard[i + 1, 0], port[i + 1, 0])]
    faces.append((port[last, 0], starboard[last, 0], stem))
    # Transom: the first station's section, closed with a fan from a point in its middle.
    transom_centre = len(vertices)
    vertices.append((shape.stern_x, 0.0, shape.deck_z - 0.5 * depth[0]))
    ring = [port[0, j] for j in range(m)] + [starboard[0, j] for j in range(m - 2, -1, -1)]
    for k in range(len(ring) - 1):
        faces.append((transom_centre, ring[k], ring[k + 1]))
    faces.append((transom_centre, ring[-1], ring[0]))
    return Hull(np.array(vertices), np.array(faces), name="eboat")
