"""Obstacle layouts as a person writes them: how many buoys and piles each environment gets at every reset,
how big, and where (between the start and the first waypoint, clear of both). The layouts are drawn on the
device (``ocean_warp.envs.tasks.obstacle_kernels.draw_layouts``) from each environment's own random
stream, so one seed gives one sequence of layouts, replayable, on any device and in any shard.

Geometry: the leg runs from the boat's start S to the first waypoint W, length L. An obstacle's centre is
S + t (W - S) + c n, with t uniform in ``along_track``, c uniform in [-``cross_track``, ``cross_track``] and
n the leg's left normal. A candidate is kept only when its surface (centre distance minus radius) is at
least ``start_clearance`` from S, ``waypoint_clearance`` from W and ``spacing`` from every obstacle kept
before it; after ``attempts`` rejected candidates its slot stays empty (the environment gets fewer).
"""

from __future__ import annotations

import dataclasses

from ocean_warp.validation import (
    require_in_range,
    require_int_in_range,
    require_non_negative,
    require_positive,
    require_range_pair,
)

__all__ = ["ObstacleLayoutConfig", "BUOY_COLOR", "PILE_COLOR"]

BUOY_COLOR = (0.95, 0.45, 0.1)
"""Linear RGB of a buoy, for the camera and the stages (``SceneObject.buoy``'s)."""
PILE_COLOR = (0.45, 0.42, 0.4)
"""Linear RGB of a pile (``SceneObject.pillar``'s)."""


@dataclasses.dataclass(frozen=True)
class ObstacleLayoutConfig:
    """Buoys (floating spheres) and piles (fixed upright cylinders) drawn per environment at every reset
    (the module docstring gives the geometry). Lengths [m]; invalid values raise ``ValueError`` naming the
    field."""

    count: tuple[int, int] = (6, 12)
    """Range of obstacles per environment, both ends included (uniform); the high end is the number of
    slots each environment keeps (at most 64)."""
    pile_fraction: float = 0.4
    """Chance that an obstacle is a pile; the rest are buoys."""
    buoy_radius: tuple[float, float] = (0.4, 1.0)
    """Range of a buoy's radius [m]."""
    pile_radius: tuple[float, float] = (0.3, 1.2)
    """Range of a pile's radius [m]."""
    pile_height: float = 6.0
    """A pile's height [m]; it stands from a quarter of it below still water."""
    along_track: tuple[float, float] = (0.1, 0.9)
    """Range of t, the centre's place along the leg as a fraction of its length (0: start, 1: waypoint)."""
    cross_track: float = 15.0
    """Half-width of the band about the leg the centres are drawn in [m]."""
    start_clearance: float = 10.0
    """No obstacle's surface nearer the start than this [m]."""
    waypoint_clearance: float = 10.0
    """No obstacle's surface nearer the first waypoint than this [m] (above the task's reach radius, so that
    the waypoint can be reached without touching one)."""
    spacing: float = 4.0
    """Least gap between two obstacles' surfaces [m] (wider than the boat, so every gap can be sailed)."""
    attempts: int = 20
    """Candidates drawn for a slot before it is left empty."""

    def __post_init__(self):
        owner = "ObstacleLayoutConfig"
        count = self.count
        if not (isinstance(count, (tuple, list)) and len(count) == 2):
            raise ValueError(f"{owner}.count must be a (low, high) pair of whole numbers, got {count!r}")
        low = require_int_in_range(owner, "count", count[0], 0, 64)
        high = require_int_in_range(owner, "count", count[1], 1, 64)
        if low > high:
            raise ValueError(f"{owner}.count must have low <= high, got {count!r}")
        object.__setattr__(self, "count", (low, high))
        object.__setattr__(self, "pile_fraction", require_in_range(owner, "pile_fraction", self.pile_fraction,
                                                                   0.0, 1.0))
        for name in ("buoy_radius", "pile_radius"):
            pair = require_range_pair(owner, name, getattr(self, name), 0.0, 50.0)
            if pair[0] <= 0.0:
                raise ValueError(f"{owner}.{name} must be above 0 m, got {getattr(self, name)!r}")
            object.__setattr__(self, name, pair)
        object.__setattr__(self, "pile_height", require_positive(owner, "pile_height", self.pile_height,
                                                                 unit=" [m]"))
        object.__setattr__(self, "along_track", require_range_pair(owner, "along_track", self.along_track, 0.0, 1.0))
        for name in ("cross_track", "start_clearance", "waypoint_clearance", "spacing"):
            object.__setattr__(self, name, require_non_negative(owner, name, getattr(self, name), unit=" [m]"))
        object.__setattr__(self, "attempts", require_int_in_range(owner, "attempts", self.attempts, 1, 1000))

    @property
    def slots(self) -> int:
        """Object rows each environment keeps for its layout: the most obstacles it can get."""
        return self.count[1]
