"""What each value of a policy's observation is: the blocks ``task_kernels.observe`` (the observation set, then
the reef level) and ``obstacle_kernels.append_sectors`` (the lidar's sectors) write, each column with its name
and its scale and unit. The one home of the layout: the kernels take their counts from here, and what reads an
observation from outside (the exported policies' metadata, ``ocean_warp.envs.ros.policy_export``) reads it
here.

    policy_layout(task)          # every column of a TaskConfig's policy observation, in order
    policy_blocks(task)          # the same as blocks: the set's, then "reef" and "lidar" where the task has them
"""

from __future__ import annotations

import dataclasses
from typing import NamedTuple

import numpy as np

from .task_configs import ObservationSet

__all__ = ["ObservationColumn", "ObservationBlock", "SEED_BLOCK", "PLUS_BLOCK", "SET_BLOCKS", "reef_block",
           "lidar_block", "policy_blocks", "policy_layout"]


class ObservationColumn(NamedTuple):
    """One value of an observation: its ``name`` (an identifier, unique within a task's layout) and ``unit``:
    how the value is scaled from a physical quantity and that quantity's unit."""

    name: str
    unit: str

    def text(self) -> str:
        """``"name: unit"``, the line an exported policy's metadata carries for this value."""
        return f"{self.name}: {self.unit}"


@dataclasses.dataclass(frozen=True)
class ObservationBlock:
    """A run of consecutive observation values that one kernel writes (``name``: the block's), column by
    column."""

    name: str
    columns: tuple[ObservationColumn, ...]

    def __post_init__(self):
        columns = tuple(ObservationColumn(*column) for column in self.columns)
        names = [column.name for column in columns]
        if len(set(names)) != len(names):
            raise ValueError(f"ObservationBlock {self.name!r}: column names must be unique, got {names}")
        object.__setattr__(self, "columns", columns)

    def __len__(self) -> int:
        return len(self.columns)

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(column.name for column in self.columns)


_CLIPPED = "clipped to [-1, 1]"
SEED_BLOCK = ObservationBlock("seed", (
    ("distance_to_waypoint", f"2 d / d_lost - 1, {_CLIPPED}; d [m] from the boat to the waypoint, d_lost [m] the "
                             "leg's length + the lost margin"),
    ("bearing_to_waypoint", f"bearing of the waypoint from the bow [deg] / 180, positive to port; {_CLIPPED}"),
    ("speed_ahead", f"surge speed u [m/s] / 5 - 1; {_CLIPPED}"),
    ("apparent_wind_speed", f"apparent wind speed [m/s] / 15 - 1; {_CLIPPED}"),
    ("apparent_wind_angle", f"apparent wind angle from the bow [deg] / 180, positive to port; {_CLIPPED}"),
))
"""The seed paper's set (``ObservationSet.SEED``, observation_set 0: exact state)."""

PLUS_BLOCK = ObservationBlock("plus", (
    ("distance_to_waypoint", "distance to the waypoint from the GNSS fix [m] / d_lost (the leg's length + the lost "
                             "margin [m])"),
    ("bearing_to_waypoint_sin", "sin of the waypoint's bearing from the bow (GNSS and compass), positive to port"),
    ("bearing_to_waypoint_cos", "cos of the waypoint's bearing from the bow (GNSS and compass)"),
    ("water_speed", "speed through the water [m/s] / 2"),
    ("apparent_wind_angle_sin", "sin of the apparent wind angle from the bow (vane), positive to port"),
    ("apparent_wind_angle_cos", "cos of the apparent wind angle from the bow (vane)"),
    ("apparent_wind_speed", "apparent wind speed (anemometer) [m/s] / 10"),
    ("heel", "heel from the accelerometer [rad]"),
    ("yaw_rate", "yaw rate (gyro) [rad/s] / 0.5"),
    ("rudder_angle", "rudder angle (actuator feedback) / 60 deg"),
    ("boom_angle", "boom angle (actuator feedback) / 90 deg"),
    ("sheet_limit", "sheet limit (actuator feedback) / 90 deg"),
    ("last_action_propeller", "last decision's action a0 (propeller), in [-1, 1]"),
    ("last_action_sheet", "last decision's action a1 (sheet), in [-1, 1]"),
    ("last_action_rudder", "last decision's action a2 (rudder), in [-1, 1]"),
))
"""Our set from the noisy sensors (``ObservationSet.PLUS``, observation_set 1)."""

SET_BLOCKS = {block.name: block for block in (SEED_BLOCK, PLUS_BLOCK)}
"""Each observation set's block, by ``ObservationSet`` value."""


def reef_block(task) -> ObservationBlock:
    """The reef level of ``task`` (a ``TaskConfig``), one column after the set's where the task has a reef rule;
    empty otherwise."""
    if task.reef is None:
        return ObservationBlock("reef", ())
    boat = task.simulator.boat
    areas = " / ".join(f"{area:g}" for area in boat.sail_areas)
    return ObservationBlock("reef", ((
        "reef_level", f"reef level of the sail / {max(boat.reef_levels - 1, 1)}, in [0, 1]: 0 the full sail, 1 the "
                      f"deepest reef (sail areas {areas} m2 by level, set at the episode's start by the task's rule "
                      "from the true wind)"),))


def lidar_block(task) -> ObservationBlock:
    """The lidar's sectors of ``task`` (a ``TaskConfig``), after the reef level, where the task has a lidar:
    the nearest return of each sector over the lidar's range; empty otherwise."""
    lidar = task.lidar
    if lidar is None:
        return ObservationBlock("lidar", ())
    sectors = task.lidar_sectors
    azimuths = np.degrees(lidar.azimuths())
    width = lidar.beams // sectors
    return ObservationBlock("lidar", tuple(
        (f"lidar_sector_{k}", f"nearest return over the beams at azimuth {azimuths[k * width]:+.0f} to "
                              f"{azimuths[(k + 1) * width - 1]:+.0f} deg from the bow (positive to port) / "
                              f"{lidar.max_range:g} m, in [0, 1]") for k in range(sectors)))


def policy_blocks(task) -> tuple[ObservationBlock, ...]:
    """The blocks of ``task``'s policy observation in order: its observation set's, then the reef level and the
    lidar's sectors where it has them (``task_kernels.policy_observation_count`` values in all)."""
    appended = tuple(block for block in (reef_block(task), lidar_block(task)) if len(block))
    return (SET_BLOCKS[ObservationSet(task.observation).value],) + appended


def policy_layout(task) -> tuple[ObservationColumn, ...]:
    """Every column of ``task``'s policy observation, in the order the kernels write them."""
    return tuple(column for block in policy_blocks(task) for column in block.columns)
