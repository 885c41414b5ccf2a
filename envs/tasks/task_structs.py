"""The Warp structs of a sailing task's kernels (``task_kernels``, ``observation_blocks``, ``reward_terms``): the
task's parameters, each environment's course and episode bookkeeping, what a decision's evaluation writes, the
simulator's arrays the observations read and the start rows a new episode writes."""

from __future__ import annotations

import warp as wp

from ocean_warp.kernels.spatial import vec6

__all__ = ["TaskParameters", "StartDistribution", "Course", "EpisodeEnds", "BoatView", "StartRows"]


@wp.struct
class TaskParameters:
    """A task's numbers (``TaskConfig`` and its ``RewardConfig``); which reward terms and observation blocks the
    kernels hold is chosen when they are built (``task_kernels.evaluate_kernel_for``, ``observe_kernel_for``)."""

    route_length: int
    """Waypoints per episode."""
    reach_radius: float
    """[m]"""
    lost_margin: float
    """[m] beyond the leg's length."""
    progress_scale: float
    """[m] (``reward_terms.progress``)."""
    propeller_gain: float
    propeller_cost: float
    """(``reward_terms.propeller_shaping``)"""
    reach_bonus: float
    lost_penalty: float
    flagged_penalty: float
    smoothness: float
    time_cost: float
    collision_penalty: float
    proximity_cost: float
    proximity_range: float
    """[m]"""
    energy_cost: float
    """Per second at full thrust; (|level| / 5)^1.5 of it at a lower level (``reward_terms.motor_energy``)."""
    decision_period: float
    """[s]"""
    max_episode_length: int
    """Decisions before a time-out."""
    reef_levels: int
    """The boat's reef levels, the full sail included (the observed value is level / (levels - 1))."""


@wp.struct
class Course:
    """Each environment's course and episode bookkeeping, N rows (the task's own arrays)."""

    origin: wp.array(dtype=wp.vec3)
    """World position of the environment's origin [m]."""
    route: wp.array2d(dtype=wp.vec3)
    """(N, R) the episode's waypoints from the origin [m]."""
    target_index: wp.array(dtype=int)
    """Index of the waypoint sailed to."""
    leg_start: wp.array(dtype=wp.vec3)
    """Where the current leg began, from the origin [m]."""
    previous_distance: wp.array(dtype=float)
    """Distance to the waypoint at the last decision [m]."""
    last_action: wp.array2d(dtype=float)
    """(N, 3) the actions of the last decision (0 at an episode's start)."""
    episode_length: wp.array(dtype=wp.int32)
    """Decisions in the episode."""
    episode_return: wp.array(dtype=float)
    """Reward summed over the episode."""
    episode_count: wp.array(dtype=int)
    """Episodes started (numbers each episode's random stream)."""
    target_world: wp.array(dtype=wp.vec3)
    """World position of the waypoint sailed to [m]."""


@wp.struct
class EpisodeEnds:
    """What a decision's evaluation writes: its reward and how episodes ended, N rows."""

    reward: wp.array(dtype=float)
    terminated: wp.array(dtype=wp.bool)
    time_out: wp.array(dtype=wp.bool)
    done: wp.array(dtype=wp.bool)
    reset_mask: wp.array(dtype=wp.int32)
    """1 where the episode ended (the environments to restart), else 0."""
    final_return: wp.array(dtype=float)
    final_length: wp.array(dtype=wp.int32)
    final_success: wp.array(dtype=float)
    final_status: wp.array(dtype=int)
    final_waypoints: wp.array(dtype=int)


@wp.struct
class BoatView:
    """The simulator's arrays the observations read (``EBoatState``), N rows."""

    position: wp.array(dtype=wp.vec3)
    orientation: wp.array(dtype=wp.quat)
    velocity: wp.array(dtype=vec6)
    wind_velocity: wp.array(dtype=wp.vec3)
    truth: wp.array2d(dtype=float)
    readings: wp.array2d(dtype=float)
    rudder_angle: wp.array(dtype=float)
    boom_angle: wp.array(dtype=float)
    sheet_limit: wp.array(dtype=float)
    reef_level: wp.array(dtype=int)


@wp.struct
class StartRows:
    """The simulator's start rows a new episode writes (``EBoatStart``), N rows."""

    position: wp.array(dtype=wp.vec3)
    orientation: wp.array(dtype=wp.quat)
    velocity: wp.array(dtype=vec6)
    sheet: wp.array(dtype=float)
    wind_speed: wp.array(dtype=float)
    wind_direction: wp.array(dtype=float)
    gust_scale: wp.array(dtype=float)
    foil_scale: wp.array(dtype=wp.vec3)
    noise_scale: wp.array(dtype=float)
    current_speed: wp.array(dtype=float)
    current_direction: wp.array(dtype=float)
    reef_level: wp.array(dtype=int)


@wp.struct
class StartDistribution:
    """The start of an episode (radians and metres; see ``envs.tasks.StartConfig``)."""

    heading_low: float
    heading_high: float
    heading_step: float
    heading_toward_waypoint: int
    wind_speed_low: float
    wind_speed_high: float
    wind_direction_low: float
    wind_direction_high: float
    wind_direction_step: float
    gust_scale_low: float
    gust_scale_high: float
    waypoint_distance_low: float
    waypoint_distance_high: float
    waypoint_bearing_low: float
    waypoint_bearing_high: float
    random_waypoint: int
    """1: draw the first (only) waypoint per episode; 0: the route is fixed."""
    start_point: wp.vec3
    position_jitter: float
    start_height: float
    surge_low: float
    surge_high: float
    sheet_low: float
    sheet_high: float
    foil_variation: float
    """Half-width v of the foil factors' range [1 - v, 1 + v]."""
    noise_scale_low: float
    noise_scale_high: float
    current_speed_low: float
    """[m/s]; low = high (the simulator config's speed) when the task does not randomise the current."""
    current_speed_high: float
    current_direction_low: float
    """[rad]"""
    current_direction_high: float
    reef_rule: int
    """1: the task draws a reef level per episode (``TaskConfig.reef``); 0: the full sail always."""
    reef_thresholds: wp.array(dtype=float)
    """The rule's true wind speeds [m/s] (``ReefRule.thresholds``; one unused row when there are none)."""
    reef_threshold_count: int
    reef_fixed_level: int
    """``ReefRule.level``, or -1 for the rule."""
    reef_random: float
    """``ReefRule.random_level``: probability of a uniform draw over the levels instead."""
    reef_levels: int
    """The boat's reef levels, the full sail included."""
