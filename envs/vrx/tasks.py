"""The registered VRX tasks' default configs (``WamvStationKeeping-v0``, ``WamvWayfinding-v0``,
``WamvFollowPath-v0``): the WAM-V and each episode drawn in VRX 2023's ranges
(``ocean_warp.envs.tasks.vrx_conditions.VrxConditions``, each with its source).

Each episode draws its own count of goals or gates in VRX's range (``VrxConditions.waypoints``: 3-5 waypoints,
3-9 gates). Where they differ from VRX: the wind blows from any direction (VRX's worlds use three), the count of
gates is any of 3 to 9 (VRX's worlds have 3, 6 or 9), gates are 20 m wide (VRX: 15.8-24.2 m), training
episodes are shorter than VRX's 300 s (``ocean-warp eval --time-limit 300`` scores as VRX does), and the sea is
one per batch (its height is the vessel's ocean's; training draws it per iteration in VRX's 0-0.72 m:
``training.agents``). VRX has no current; neither do these.
"""

from __future__ import annotations

import dataclasses
import math

from ocean_warp.perception.lidar_config import LidarConfig
from ocean_warp.wind import WindConfig

from ..tasks.vrx_conditions import VrxConditions
from .path_course_config import PathCourseConfig
from .task_config import VrxStartConfig, VrxTask, VrxTaskConfig, wamv_vessel

__all__ = ["station_keeping_task", "wayfinding_task", "follow_path_task", "start_from", "path_lidar"]


def path_lidar(**changes) -> LidarConfig:
    """The follow-the-path task's lidar. VRX's WAM-V carries a 16-beam lidar at x 0.7, z 1.8 m pitched 8 deg down
    (``vrx_urdf/wamv_gazebo/config/wamv_config/example_component_config.yaml``, ``lidar_wamv``), whose points a
    team flattens onto the water to find the buoys; its channels 2 deg apart would pass over or under a 0.5 m
    buoy beyond a few metres. Here that flattened scan directly: a sensor at the waterline between the pontoons
    (x 0.7 m, z -0.1 m), 3 channels at -2, 0 and +2 deg (the boat's pitch and heave in waves) of 360 beams,
    30 m, exact, the sea's returns filtered out; then ``changes``."""
    return LidarConfig(**({"channels": 3, "beams": 360, "elevation_min": math.radians(-2.0),
                           "elevation_max": math.radians(2.0), "max_range": 30.0, "rate": 1.0,
                           "mount": (0.7, 0.0, -0.1), "water_returns": False} | changes))


def start_from(conditions: VrxConditions) -> VrxStartConfig:
    """The episode starts of ``conditions``: its wind (gusts up to its largest standard deviation, drawn per
    episode as a factor on it), the first goal's distance and its bearing off the start heading, no current."""
    deg = math.degrees
    gusts = conditions.wind_gust_std[1]
    return VrxStartConfig(goal_distance=conditions.goal_distance,
                          goal_bearing_deg=(deg(conditions.goal_bearing[0]), deg(conditions.goal_bearing[1])),
                          wind_speed=conditions.wind_speed,
                          gust_scale=(0.0, 1.0) if gusts > 0.0 else (1.0, 1.0),
                          current_speed=conditions.current_speed)


def _vessel(conditions: VrxConditions):
    """The WAM-V on a 0.3 m sea, with VRX's gusts (their largest standard deviation, VRX's 2 s time constant)."""
    vessel = wamv_vessel(0.3)
    wind = WindConfig(speed=0.0, gust_speed_std=conditions.wind_gust_std[1],
                      gust_speed_time=conditions.wind_gust_time_constant)
    return type(vessel)(dataclasses.replace(vessel.config, wind=wind))


def station_keeping_task() -> VrxTaskConfig:
    """Reach and hold a goal pose 5-12 m away, within 1 rad of the start heading (VRX 2023: 5.9-11.9 m), in 0-7 m/s
    of wind with gusts up to 2 m/s; 60 s training episodes (VRX scores 300 s)."""
    conditions = VrxConditions.station_keeping()
    start = dataclasses.replace(start_from(conditions), goal_spacing=(0.0, 0.0))
    return VrxTaskConfig(kind=VrxTask.STATION_KEEPING, vessel=_vessel(conditions), goals=1, episode_time=60.0,
                         start=start)


def wayfinding_task() -> VrxTaskConfig:
    """Visit 3 to 5 goal poses (VRX 2023's range, drawn per episode) on legs of 11-40 m (VRX: 11-60 m) turning any
    way, in 0-8 m/s of wind with gusts up to 2 m/s, within 240 s; a goal counts as reached within a pose error of
    1 m."""
    conditions = VrxConditions.wayfinding(goal_distance=(11.0, 40.0))
    start = dataclasses.replace(start_from(conditions), goal_spacing=conditions.goal_distance,
                                leg_turn_deg=(-180.0, 180.0))
    return VrxTaskConfig(kind=VrxTask.WAYFINDING, vessel=_vessel(conditions), goals=conditions.waypoints,
                         episode_time=240.0, start=start)


def follow_path_task() -> VrxTaskConfig:
    """Pass 3 to 9 gates (drawn per episode; VRX 2023: 3, 6 or 9) 20 m wide (VRX: 15.8-24.2 m) in order, the first
    19-31 m away within 0.7 rad of the start heading, then 25-40 m apart (VRX: 25-66 m) with turns of up to 97 deg,
    among 6 obstacle buoys (VRX: 1-17) and every buoy at least 5 m from the start, in 0-9 m/s of wind with gusts up
    to 5 m/s, within 240 s. The policy sees its gates, not the buoys (the shipped policy's observation);
    ``PathCourseConfig(lidar=path_lidar())`` adds the buoys as the lidar's 24 sectors after the last actions, for a
    policy trained with them."""
    conditions = VrxConditions.follow_path(gate_spacing=(25.0, 40.0))
    turn = math.degrees(conditions.gate_turn[1])
    start = dataclasses.replace(start_from(conditions), goal_spacing=conditions.gate_spacing,
                                leg_turn_deg=(-turn, turn))
    return VrxTaskConfig(kind=VrxTask.FOLLOW_PATH, vessel=_vessel(conditions), goals=conditions.waypoints,
                         episode_time=240.0, start=start, gate_width=20.0, lost_distance=80.0,
                         path_course=PathCourseConfig(obstacles=6))
