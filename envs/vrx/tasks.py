"""The registered VRX tasks' default configs (``WamvStationKeeping-v0``, ``WamvWayfinding-v0``,
``WamvFollowPath-v0``): the WAM-V, VRX's task, and each episode drawn in the ranges below."""

from __future__ import annotations

from .task_config import VrxStartConfig, VrxTask, VrxTaskConfig

__all__ = ["station_keeping_task", "wayfinding_task", "follow_path_task"]


def station_keeping_task() -> VrxTaskConfig:
    """Hold a goal pose 5-12 m from the start (VRX 2023's 5.9-11.9 m) for 60 s (VRX scores 300 s: evaluate with a
    longer time limit), in 0-7 m/s of wind (VRX's 0, 5 or 7 m/s) and up to 0.3 m/s of current, on a 0.3 m sea."""
    start = VrxStartConfig(goal_distance=(5.0, 12.0), wind_speed=(0.0, 7.0), current_speed=(0.0, 0.3))
    return VrxTaskConfig(kind=VrxTask.STATION_KEEPING, goals=1, episode_time=60.0, start=start)


def wayfinding_task() -> VrxTaskConfig:
    """Visit 4 goal poses (the first 10-20 m away, then 10-20 m apart) within 150 s; a goal counts as reached
    within a pose error of 1 m."""
    start = VrxStartConfig(goal_distance=(10.0, 20.0), goal_spacing=(10.0, 20.0), wind_speed=(0.0, 5.0),
                           current_speed=(0.0, 0.3))
    return VrxTaskConfig(kind=VrxTask.WAYFINDING, goals=4, episode_time=150.0, start=start)


def follow_path_task() -> VrxTaskConfig:
    """Pass 4 gates in order (10 m wide, the first 10-20 m away, then 15-25 m apart) within 150 s."""
    start = VrxStartConfig(goal_distance=(10.0, 20.0), goal_spacing=(15.0, 25.0), wind_speed=(0.0, 5.0),
                           current_speed=(0.0, 0.3))
    return VrxTaskConfig(kind=VrxTask.FOLLOW_PATH, goals=4, episode_time=150.0, start=start, lost_distance=60.0)
