"""What each value of a policy's observation is, and the device function that writes it: the blocks a task's
observation kernel (``task_kernels.observe_kernel``: the observation set, then the reef level; the critic's
privileged values after them) and ``obstacle_kernels.append_sectors`` (the lidar's sectors) write, each column with
its name and its scale and unit, each block's declaration next to its ``wp.func``. The one home of the layout: what
reads an observation from outside (the exported policies' metadata, ``ocean_warp.envs.ros.policy_export``) reads it
here.

    policy_layout(task)          # every column of a TaskConfig's policy observation, in order
    policy_blocks(task)          # the same as blocks: the set's, then "reef" and "lidar" where the task has them

A block's function writes its columns of row ``env`` from column ``first`` on and returns the column after them.
"""

from __future__ import annotations

import dataclasses
from typing import NamedTuple

import numpy as np
import warp as wp

from ocean_warp.kernels.eboat_actions import RUDDER_LIMIT, SHEET_HALF
from ocean_warp.kernels.sensor_readings import (ANGULAR_RATE, GNSS_POSITION, HEADING, SPECIFIC_FORCE, WATER_SPEED,
                                                WIND_ANGLE, WIND_SPEED)
from ocean_warp.kernels.spatial import DEGREES

from .task_configs import ObservationSet
from .task_structs import BoatView, Course

__all__ = ["ObservationColumn", "ObservationBlock", "SEED_BLOCK", "PLUS_BLOCK", "SET_BLOCKS", "PRIVILEGED_BLOCK",
           "reef_block", "lidar_block", "lidar_sectors_block", "policy_blocks", "policy_layout", "seed_columns", "plus_columns",
           "SET_COLUMNS", "reef_column", "privileged_columns", "finite_or_zero", "unit_clip"]


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
"""The seed paper's set (``ObservationSet.SEED``: exact state)."""


@wp.func
def finite_or_zero(value: float) -> float:
    if wp.isfinite(value):
        return value
    return 0.0


@wp.func
def unit_clip(value: float) -> float:
    return wp.clamp(finite_or_zero(value), -1.0, 1.0)


@wp.func
def seed_columns(policy: wp.array2d(dtype=float), env: int, first: int, boats: BoatView, course: Course,
                 distance: float, bearing: float, lost_distance: float) -> int:
    """:data:`SEED_BLOCK` from the true state: ``distance`` [m] and ``bearing`` [rad] of the waypoint from the boat,
    ``lost_distance`` [m] the leg's length plus the lost margin; the apparent wind from the true readings."""
    policy[env, first + 0] = unit_clip(2.0 * distance / lost_distance - 1.0)
    policy[env, first + 1] = unit_clip(bearing * DEGREES / 180.0)
    policy[env, first + 2] = unit_clip(boats.velocity[env][0] / 5.0 - 1.0)
    policy[env, first + 3] = unit_clip(boats.truth[env, WIND_SPEED] / 15.0 - 1.0)
    policy[env, first + 4] = unit_clip(boats.truth[env, WIND_ANGLE] * DEGREES / 180.0)
    return first + 5

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
"""Our set from the noisy sensors (``ObservationSet.PLUS``)."""


@wp.func
def plus_columns(policy: wp.array2d(dtype=float), env: int, first: int, boats: BoatView, course: Course,
                 distance: float, bearing: float, lost_distance: float) -> int:
    """:data:`PLUS_BLOCK` from the noisy readings, the actuators' feedback and the last actions; the waypoint
    from the GNSS fix and the compass (``distance`` and ``bearing``, the true ones, are not used)."""
    target = course.target_world[env]
    fix = wp.vec3(boats.readings[env, GNSS_POSITION + 0], boats.readings[env, GNSS_POSITION + 1], 0.0)
    offset = target - fix
    seen = wp.vec3(offset[0], offset[1], 0.0)
    seen_bearing = wp.atan2(seen[1], seen[0]) - boats.readings[env, HEADING]
    awa = boats.readings[env, WIND_ANGLE]
    policy[env, first + 0] = finite_or_zero(wp.length(seen) / lost_distance)
    policy[env, first + 1] = finite_or_zero(wp.sin(seen_bearing))
    policy[env, first + 2] = finite_or_zero(wp.cos(seen_bearing))
    policy[env, first + 3] = finite_or_zero(boats.readings[env, WATER_SPEED] / 2.0)
    policy[env, first + 4] = finite_or_zero(wp.sin(awa))
    policy[env, first + 5] = finite_or_zero(wp.cos(awa))
    policy[env, first + 6] = finite_or_zero(boats.readings[env, WIND_SPEED] / 10.0)
    policy[env, first + 7] = finite_or_zero(wp.atan2(boats.readings[env, SPECIFIC_FORCE + 1],
                                                     boats.readings[env, SPECIFIC_FORCE + 2]))
    policy[env, first + 8] = finite_or_zero(boats.readings[env, ANGULAR_RATE + 2] / 0.5)
    policy[env, first + 9] = finite_or_zero(boats.rudder_angle[env] / RUDDER_LIMIT)
    policy[env, first + 10] = finite_or_zero(boats.boom_angle[env] / (2.0 * SHEET_HALF))
    policy[env, first + 11] = finite_or_zero(boats.sheet_limit[env] / (2.0 * SHEET_HALF))
    for k in range(3):
        policy[env, first + 12 + k] = course.last_action[env, k]
    return first + 15


SET_BLOCKS = {block.name: block for block in (SEED_BLOCK, PLUS_BLOCK)}
"""Each observation set's block, by ``ObservationSet`` value."""
SET_COLUMNS = {SEED_BLOCK.name: seed_columns, PLUS_BLOCK.name: plus_columns}
"""Each observation set's block function, by ``ObservationSet`` value."""


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


@wp.func
def reef_column(policy: wp.array2d(dtype=float), env: int, first: int, boats: BoatView, reef_levels: int) -> int:
    """:func:`reef_block`'s column: the boat's reef level / (``reef_levels`` - 1)."""
    policy[env, first] = float(boats.reef_level[env]) / float(wp.max(reef_levels - 1, 1))
    return first + 1


def lidar_block(task) -> ObservationBlock:
    """The lidar's sectors of ``task`` (a ``TaskConfig``), after the reef level, where the task has a lidar:
    the nearest return of each sector over the lidar's range; empty otherwise."""
    return lidar_sectors_block(task.lidar, task.lidar_sectors)


def lidar_sectors_block(lidar, sectors: int) -> ObservationBlock:
    """The ``sectors`` values ``obstacle_kernels.append_sectors`` writes for ``lidar`` (a ``LidarConfig``; None:
    an empty block): the nearest return of each sector over the lidar's range."""
    if lidar is None:
        return ObservationBlock("lidar", ())
    azimuths = np.degrees(lidar.azimuths())
    width = lidar.beams // sectors
    return ObservationBlock("lidar", tuple(
        (f"lidar_sector_{k}", f"nearest return over the beams at azimuth {azimuths[k * width]:+.0f} to "
                              f"{azimuths[(k + 1) * width - 1]:+.0f} deg from the bow (positive to port) / "
                              f"{lidar.max_range:g} m, in [0, 1]") for k in range(sectors)))


PRIVILEGED_BLOCK = ObservationBlock("privileged", (
    ("true_distance_to_waypoint", "distance to the waypoint [m] / d_lost (the leg's length + the lost margin [m])"),
    ("true_bearing_to_waypoint_sin", "sin of the waypoint's bearing from the bow, positive to port"),
    ("true_bearing_to_waypoint_cos", "cos of the waypoint's bearing from the bow"),
    ("true_surge", "surge velocity u [m/s] / 2"),
    ("true_sway", "sway velocity v [m/s]"),
    ("true_yaw_rate", "yaw rate r [rad/s] / 0.5"),
    ("true_up_x", "world x of the body's up axis (heel and trim)"),
    ("true_up_y", "world y of the body's up axis (heel and trim)"),
    ("true_wind_speed", "true wind speed at the boat [m/s] / 10"),
    ("true_wind_angle_sin", "sin of the direction the true wind blows toward, from the bow"),
    ("true_wind_angle_cos", "cos of the direction the true wind blows toward, from the bow"),
    ("route_progress", "waypoints reached / the route's waypoints, in [0, 1)"),
))
"""What the critic sees after the policy's values (before any lidar sectors): the true state."""


@wp.func
def privileged_columns(critic: wp.array2d(dtype=float), env: int, first: int, boats: BoatView, course: Course,
                       distance: float, bearing: float, lost_distance: float, heading: float,
                       route_length: int) -> int:
    """:data:`PRIVILEGED_BLOCK` from the true state (``distance`` [m], ``bearing`` and ``heading`` [rad],
    ``lost_distance`` [m] as :func:`seed_columns`')."""
    rotation = boats.orientation[env]
    nu = boats.velocity[env]
    up = wp.quat_rotate(rotation, wp.vec3(0.0, 0.0, 1.0))
    wind = boats.wind_velocity[env]
    true_wind_angle = wp.atan2(wind[1], wind[0]) - heading
    critic[env, first + 0] = finite_or_zero(distance / lost_distance)
    critic[env, first + 1] = finite_or_zero(wp.sin(bearing))
    critic[env, first + 2] = finite_or_zero(wp.cos(bearing))
    critic[env, first + 3] = finite_or_zero(nu[0] / 2.0)
    critic[env, first + 4] = finite_or_zero(nu[1])
    critic[env, first + 5] = finite_or_zero(nu[5] / 0.5)
    critic[env, first + 6] = finite_or_zero(up[0])
    critic[env, first + 7] = finite_or_zero(up[1])
    critic[env, first + 8] = finite_or_zero(wp.length(wind) / 10.0)
    critic[env, first + 9] = finite_or_zero(wp.sin(true_wind_angle))
    critic[env, first + 10] = finite_or_zero(wp.cos(true_wind_angle))
    critic[env, first + 11] = float(course.target_index[env]) / float(route_length)
    return first + 12


def policy_blocks(task) -> tuple[ObservationBlock, ...]:
    """The blocks of ``task``'s policy observation in order: its observation set's, then the reef level and the
    lidar's sectors where it has them (``task_kernels.policy_observation_count`` values in all)."""
    appended = tuple(block for block in (reef_block(task), lidar_block(task)) if len(block))
    return (SET_BLOCKS[ObservationSet(task.observation).value],) + appended


def policy_layout(task) -> tuple[ObservationColumn, ...]:
    """Every column of ``task``'s policy observation, in the order the kernels write them."""
    return tuple(column for block in policy_blocks(task) for column in block.columns)
