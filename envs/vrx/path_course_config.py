"""The config of VRX's follow-the-path course's buoys (``envs/vrx/path_course.py``), kept light for the task
configs."""

from __future__ import annotations

import dataclasses

from ocean_warp.contact import ContactConfig
from ocean_warp.perception.lidar_config import LidarConfig
from ocean_warp.validation import require_int_in_range, require_non_negative, require_positive

__all__ = ["PathCourseConfig"]


@dataclasses.dataclass(frozen=True)
class PathCourseConfig:
    """The buoys of the path and its obstacles. Invalid values raise ``ValueError`` naming the field."""

    gate_buoy_radius: float = 0.25
    """Radius of a gate's buoys [m] (their centres are half ``VrxTaskConfig.gate_width`` either side of the gate's
    centre)."""
    obstacles: int = 3
    """Obstacle buoys tried per episode (fewer where they find no clear place in ``attempts`` draws)."""
    obstacle_radius: float = 0.4
    """[m]"""
    opening_clearance: float = 3.0
    """Least gap between an obstacle's surface and a gate's opening (the segment between its buoys) [m]."""
    start_clearance: float = 5.0
    """Least gap between any buoy's surface (a gate's or an obstacle) and the boat's start pose [m]: later gates
    are drawn again where a buoy would fall nearer (``vrx_kernels.vrx_draw_starts``)."""
    spacing: float = 2.0
    """Least gap between two obstacles [m]."""
    cross_track: float = 4.0
    """Obstacles lie up to this far off the line of their leg [m]."""
    attempts: int = 8
    """Draws per obstacle before its row is left empty."""
    contact: ContactConfig | None = dataclasses.field(default_factory=ContactConfig)
    """The contact's law (None: the buoys are there but nothing touches them)."""
    lidar: LidarConfig | None = None
    """A lidar on every boat, scanned when the observation is made; the policy sees ``lidar_sectors`` values after
    the task's and the last actions: the nearest return of each sector over the lidar's max range, in [0, 1] (None:
    no lidar, the buoys are not seen)."""
    lidar_sectors: int = 24
    """Equal sectors the lidar's beams are pooled into (a whole divisor of its beams per channel)."""

    def __post_init__(self):
        owner = "PathCourseConfig"
        for name in ("gate_buoy_radius", "obstacle_radius"):
            object.__setattr__(self, name, require_positive(owner, name, getattr(self, name), unit=" [m]"))
        for name in ("opening_clearance", "start_clearance", "spacing", "cross_track"):
            object.__setattr__(self, name, require_non_negative(owner, name, getattr(self, name), unit=" [m]"))
        object.__setattr__(self, "obstacles", require_int_in_range(owner, "obstacles", self.obstacles, 0, 64))
        object.__setattr__(self, "attempts", require_int_in_range(owner, "attempts", self.attempts, 1, 64))
        if self.contact is not None and not isinstance(self.contact, ContactConfig):
            raise ValueError(f"{owner}.contact must be a ContactConfig or None, got {self.contact!r}")
        if self.lidar is not None:
            if not isinstance(self.lidar, LidarConfig):
                raise ValueError(f"{owner}.lidar must be a LidarConfig or None, got {self.lidar!r}")
            sectors, beams = self.lidar_sectors, self.lidar.beams
            if isinstance(sectors, bool) or not isinstance(sectors, int) or not 1 <= sectors <= beams or beams % sectors:
                raise ValueError(f"{owner}.lidar_sectors must be a whole divisor of the lidar's {beams} beams, "
                                 f"got {sectors!r}")

    @property
    def lidar_observations(self) -> int:
        """Values of the policy's observation that come from the lidar (0 without one)."""
        return 0 if self.lidar is None else self.lidar_sectors
