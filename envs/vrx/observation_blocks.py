"""The columns of a VRX task's observation, named with their scales and units next to the kernel that writes them
(``vrx_kernels.vrx_observe``): the exported policy's metadata and the ROS side read them."""

from __future__ import annotations

from ..tasks.observation_blocks import ObservationBlock, ObservationColumn, lidar_sectors_block
from .vrx_kernels import POLICY_BASE

__all__ = ["VRX_BLOCK", "VRX_PRIVILEGED_BLOCK", "vrx_policy_blocks", "vrx_policy_layout"]

VRX_BLOCK = ObservationBlock("vrx", (
    ("goal_ahead", "x / 10 m, clipped to +-5: the goal's offset ahead, in the boat's yawed frame"),
    ("goal_to_port", "y / 10 m, clipped to +-5: the goal's offset to port, in the boat's yawed frame"),
    ("heading_error_sin", "sin(goal heading - heading)"),
    ("heading_error_cos", "cos(goal heading - heading)"),
    ("goal_distance", "d / 10 m, clipped to 5"),
    ("surge_speed", "u [m/s], clipped to +-10"),
    ("sway_speed", "v [m/s] to port, clipped to +-10"),
    ("yaw_rate", "r [rad/s], clipped to +-10"),
    ("next_goal_ahead", "x / 10 m of the next goal (the current one when none is next)"),
    ("next_goal_to_port", "y / 10 m of the next goal (the current one when none is next)"),
))
"""The policy's values before its last actions (``vrx_observe``)."""

VRX_PRIVILEGED_BLOCK = ObservationBlock("vrx_privileged", (
    ("wind_ahead", "true wind along the yawed x / 10 m/s"),
    ("wind_to_port", "true wind along the yawed y / 10 m/s"),
    ("pose_error", "VRX's d + 0.75^d |heading error| / 10 m"),
))
"""What the critic sees beyond the policy's values."""

assert len(VRX_BLOCK) == POLICY_BASE, "the block must name every value vrx_observe writes before the actions"


def vrx_policy_blocks(task) -> tuple[ObservationBlock, ...]:
    """The blocks of the policy observation of ``task`` (a ``VrxTaskConfig``): the task's values, the last actions
    of its vessel, then the path's lidar sectors where the task has them (``append_sectors``)."""
    actions = ObservationBlock("last_actions", tuple(ObservationColumn(f"last_{spec.name}", f"-1 .. 1: {spec.meaning}")
                                                     for spec in task.vessel.actions))
    lidar = task.path_lidar
    return (VRX_BLOCK, actions, lidar_sectors_block(lidar, 0 if lidar is None else task.lidar_observations))


def vrx_policy_layout(task) -> tuple[ObservationColumn, ...]:
    """Every column of ``task``'s policy observation, in the order the kernels write them."""
    return tuple(column for block in vrx_policy_blocks(task) for column in block.columns)
