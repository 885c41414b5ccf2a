"""The kernels of a sailing task, one thread per environment: actions to commands, rewards and episode
ends, observations, and the start of a new episode for the environments that ended.

Conventions: positions of waypoints are relative to the environment's origin on the periodic ocean;
the boat's position is world ENU. Bearings are measured from the bow, positive to port [rad].
"""

from __future__ import annotations

import warp as wp

from ocean_warp.kernels.eboat_actions import MAX_LEVEL, RUDDER_LIMIT, SHEET_HALF, commanded_level
from ocean_warp.kernels.random_streams import stream_state
from ocean_warp.kernels.rigid_body import STATUS_COLLIDED
from ocean_warp.kernels.spatial import DEGREES, PI, heading_of, vec6, wrap_angle

__all__ = ["TaskParameters", "StartDistribution", "Course", "EpisodeEnds", "BoatView", "StartRows", "POLICY_OBS",
           "PRIVILEGED_OBS", "policy_observation_count", "evaluate", "observe",
           "draw_starts", "reef_level_for"]

EPISODE_START = wp.constant(0x3C6E_F372)
"""Tag of the random stream that draws each episode's start."""
RANDOMISATION = wp.constant(0x510E_527F)
"""Tag of the random stream that draws each episode's domain randomisation (foil and sensor-noise factors)."""
CURRENT_DRAW = wp.constant(0x5BE0_CD19)
"""Tag of the random stream that draws each episode's current (speed and direction)."""
REEF_DRAW = wp.constant(0x1F83_D9AB)
"""Tag of the random stream that draws each episode's random reef level (``ReefRule.random_level``)."""
SEED_OBS = wp.constant(5)
PLUS_OBS = wp.constant(15)
PRIVILEGED_OBS = 12
"""Values the critic sees beyond the policy's observation."""
POLICY_OBS = {"seed": 5, "plus": 15}
"""Values of each observation set; a task appends its reef level and its lidar's sectors
(:func:`policy_observation_count`). ``observation_blocks`` names every column (its tests hold it to these)."""


@wp.struct
class TaskParameters:
    route_length: int
    """Waypoints per episode."""
    reach_radius: float
    """[m]"""
    lost_margin: float
    """[m] beyond the leg's length."""
    progress_scale: float
    """[m]"""
    propeller_gain: float
    propeller_cost: float
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
    """Per second at full thrust; (|level| / 5)^1.5 of it at a lower level."""
    decision_period: float
    """[s]"""
    max_episode_length: int
    """Decisions before a time-out."""
    observation_set: int
    """0: the seed's 5 values, 1: Waypoint+'s 15."""
    sail_only: int
    """1: the task has no propeller (``TaskConfig.propeller`` False): the level commanded, and the one the
    reward sees, is 0 whatever a0 is. 0 (also a zeroed struct's value): a0 sets the level."""
    reef_observation: int
    """1: the policy sees its reef level after the observation set's values (a task with a ``reef`` rule)."""
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


def policy_observation_count(task) -> int:
    """Values of ``task``'s policy observation (a ``TaskConfig``): its observation set's, then the reef level (a
    task with a ``reef`` rule), then the lidar's sectors (a task with a ``lidar``)."""
    return POLICY_OBS[task.observation.value] + task.reef_observations + task.lidar_observations


@wp.func
def reef_level_for(start: StartDistribution, wind_speed: float) -> int:
    """The reef level the rule gives at mean true wind ``wind_speed`` [m/s]: the fixed level where there is one,
    else the number of thresholds at or below the speed; 0 without a rule."""
    if start.reef_rule == 0:
        return 0
    if start.reef_fixed_level >= 0:
        return start.reef_fixed_level
    level = int(0)
    for k in range(start.reef_threshold_count):
        if start.reef_thresholds[k] <= wind_speed:
            level = level + 1
    return level


@wp.func
def from_uniform(u: float, low: float, high: float, step: float) -> float:
    """A uniform number ``u`` in [0, 1) mapped onto [low, high], or onto the grid low + k step below high
    (inclusive of high when the grid does not close a circle) when ``step`` > 0.

    The caller draws ``u = wp.randf(state)`` in the kernel itself: a ``wp.func`` receives a copy of a
    random state, so drawing in here would not advance the caller's stream and every draw would
    repeat the same number."""
    if step <= 0.0:
        return low + (high - low) * u
    cells = int(wp.floor((high - low) / step + 1.0e-4))
    if wp.abs(high - low - 2.0 * PI) > 1.0e-4:
        cells = cells + 1
    cells = wp.max(cells, 1)
    return low + step * float(wp.min(int(u * float(cells)), cells - 1))


@wp.func
def planar(v: wp.vec3) -> wp.vec3:
    return wp.vec3(v[0], v[1], 0.0)


@wp.kernel(enable_backward=False)
def evaluate(
    task: TaskParameters,
    actions: wp.array2d(dtype=float),
    status: wp.array(dtype=int),
    position: wp.array(dtype=wp.vec3),
    clearance: wp.array(dtype=float),
    course: Course,
    ends: EpisodeEnds,
):
    """Reward, waypoint progress and the end of the episode after a decision (see ``RewardConfig``);
    ``clearance``: each boat's gap to the nearest obstacle [m] (the proximity term)."""
    env = wp.tid()
    flags = status[env]
    index = course.target_index[env]
    local = position[env] - course.origin[env]
    target = course.route[env, index]
    distance = wp.length(planar(target - local))
    leg = wp.length(planar(target - course.leg_start[env]))
    level = float(wp.abs(commanded_level(task.sail_only == 0, actions[env, 0])))

    r = float(0.0)
    ended = False
    success = False
    if flags != 0:
        r = -task.flagged_penalty
        if (flags & STATUS_COLLIDED) != 0:
            r = -task.collision_penalty
        ended = True
    else:
        r = (course.previous_distance[env] - distance) / task.progress_scale
        if r > 0.0:
            r = r * (1.0 - task.propeller_gain * level / float(MAX_LEVEL))
        else:
            r = r - task.propeller_cost * level
        if distance <= task.reach_radius:
            r = r + task.reach_bonus
            if index + 1 >= task.route_length:
                ended = True
                success = True
                index = index + 1
            else:
                course.leg_start[env] = target
                index = index + 1
                target = course.route[env, index]
                distance = wp.length(planar(target - local))
        elif distance > leg + task.lost_margin:
            r = r - task.lost_penalty
            ended = True
        r = r - task.proximity_cost * wp.max(1.0 - clearance[env] / task.proximity_range, 0.0)
    smooth = float(0.0)
    for k in range(3):
        a = actions[env, k]
        if wp.isfinite(a):
            a = wp.clamp(a, -1.0, 1.0)
        else:
            a = 0.0
        change = a - course.last_action[env, k]
        smooth += change * change
        course.last_action[env, k] = a
    energy = task.energy_cost * task.decision_period * wp.pow(level / float(MAX_LEVEL), 1.5)
    r = r - task.smoothness * smooth - task.time_cost - energy

    length = course.episode_length[env] + 1
    total = course.episode_return[env] + r
    late = (not ended) and length >= task.max_episode_length
    ends.reward[env] = r
    ends.terminated[env] = ended
    ends.time_out[env] = late
    ends.done[env] = ended or late
    course.previous_distance[env] = distance
    course.target_index[env] = wp.min(index, task.route_length - 1)
    course.target_world[env] = course.origin[env] + course.route[env, wp.min(index, task.route_length - 1)]
    course.episode_length[env] = length
    course.episode_return[env] = total
    if ended or late:
        ends.reset_mask[env] = 1
        ends.final_return[env] = total
        ends.final_length[env] = length
        ends.final_status[env] = flags
        ends.final_waypoints[env] = index
        if success:
            ends.final_success[env] = 1.0
        else:
            ends.final_success[env] = 0.0
    else:
        ends.reset_mask[env] = 0


@wp.func
def finite_or_zero(value: float) -> float:
    if wp.isfinite(value):
        return value
    return 0.0


@wp.func
def unit_clip(value: float) -> float:
    return wp.clamp(finite_or_zero(value), -1.0, 1.0)


@wp.kernel(enable_backward=False)
def observe(
    task: TaskParameters,
    boats: BoatView,
    course: Course,
    policy: wp.array2d(dtype=float),
    critic: wp.array2d(dtype=float),
):
    """The policy's observation (the task's set, then its reef level, level / (levels - 1) in [0, 1], on a task
    with a reef rule; ``observation_blocks`` names each column) and the critic's: the policy's followed by privileged truth (distance, bearing,
    velocities, attitude, true wind, progress along the route). A lidar's sectors come after each
    (``ObstacleCourse.append_observation``)."""
    env = wp.tid()
    rotation = boats.orientation[env]
    heading = heading_of(rotation)
    target = course.target_world[env]
    to_target = planar(target - boats.position[env])
    distance = wp.length(to_target)
    bearing = wrap_angle(wp.atan2(to_target[1], to_target[0]) - heading)
    leg = wp.length(planar(target - (course.origin[env] + course.leg_start[env])))
    lost_distance = leg + task.lost_margin
    p = 0
    if task.observation_set == 0:
        policy[env, 0] = unit_clip(2.0 * distance / lost_distance - 1.0)
        policy[env, 1] = unit_clip(bearing * DEGREES / 180.0)
        policy[env, 2] = unit_clip(boats.velocity[env][0] / 5.0 - 1.0)
        policy[env, 3] = unit_clip(boats.truth[env, 14] / 15.0 - 1.0)
        policy[env, 4] = unit_clip(boats.truth[env, 13] * DEGREES / 180.0)
        p = SEED_OBS
    else:
        seen = planar(target - wp.vec3(boats.readings[env, 0], boats.readings[env, 1], 0.0))
        seen_bearing = wp.atan2(seen[1], seen[0]) - boats.readings[env, 12]
        awa = boats.readings[env, 13]
        policy[env, 0] = finite_or_zero(wp.length(seen) / lost_distance)
        policy[env, 1] = finite_or_zero(wp.sin(seen_bearing))
        policy[env, 2] = finite_or_zero(wp.cos(seen_bearing))
        policy[env, 3] = finite_or_zero(boats.readings[env, 15] / 2.0)
        policy[env, 4] = finite_or_zero(wp.sin(awa))
        policy[env, 5] = finite_or_zero(wp.cos(awa))
        policy[env, 6] = finite_or_zero(boats.readings[env, 14] / 10.0)
        policy[env, 7] = finite_or_zero(wp.atan2(boats.readings[env, 7], boats.readings[env, 8]))
        policy[env, 8] = finite_or_zero(boats.readings[env, 11] / 0.5)
        policy[env, 9] = finite_or_zero(boats.rudder_angle[env] / RUDDER_LIMIT)
        policy[env, 10] = finite_or_zero(boats.boom_angle[env] / (2.0 * SHEET_HALF))
        policy[env, 11] = finite_or_zero(boats.sheet_limit[env] / (2.0 * SHEET_HALF))
        for k in range(3):
            policy[env, 12 + k] = course.last_action[env, k]
        p = PLUS_OBS
    if task.reef_observation != 0:
        policy[env, p] = float(boats.reef_level[env]) / float(wp.max(task.reef_levels - 1, 1))
        p = p + 1
    for k in range(p):
        critic[env, k] = policy[env, k]
    nu = boats.velocity[env]
    up = wp.quat_rotate(rotation, wp.vec3(0.0, 0.0, 1.0))
    wind = boats.wind_velocity[env]
    true_wind_angle = wp.atan2(wind[1], wind[0]) - heading
    critic[env, p + 0] = finite_or_zero(distance / lost_distance)
    critic[env, p + 1] = finite_or_zero(wp.sin(bearing))
    critic[env, p + 2] = finite_or_zero(wp.cos(bearing))
    critic[env, p + 3] = finite_or_zero(nu[0] / 2.0)
    critic[env, p + 4] = finite_or_zero(nu[1])
    critic[env, p + 5] = finite_or_zero(nu[5] / 0.5)
    critic[env, p + 6] = finite_or_zero(up[0])
    critic[env, p + 7] = finite_or_zero(up[1])
    critic[env, p + 8] = finite_or_zero(wp.length(wind) / 10.0)
    critic[env, p + 9] = finite_or_zero(wp.sin(true_wind_angle))
    critic[env, p + 10] = finite_or_zero(wp.cos(true_wind_angle))
    critic[env, p + 11] = float(course.target_index[env]) / float(task.route_length)


@wp.kernel(enable_backward=False)
def draw_starts(
    task: TaskParameters,
    start: StartDistribution,
    seed: wp.array(dtype=int),
    first_env: int,
    reset_mask: wp.array(dtype=wp.int32),
    course: Course,
    rows: StartRows,
):
    """A new episode for every environment whose ``reset_mask`` is set, from its own random stream
    (seed, environment ``first_env`` + index, episode number): the simulator's start rows and the task's
    bookkeeping (``first_env``: the number of this batch's first environment in a larger one). The
    domain randomisation (foil and sensor-noise factors), the current and the random reef level draw last,
    each from a stream of its own, so the rest of an episode's start does not depend on them. The reef level
    follows the rule at the drawn mean wind speed (before gusts)."""
    env = wp.tid()
    if reset_mask[env] == 0:
        return
    episode = course.episode_count[env] + 1
    course.episode_count[env] = episode
    state = stream_state(seed[0], EPISODE_START, episode, first_env + env)

    jitter = start.position_jitter * wp.vec3(2.0 * wp.randf(state) - 1.0, 2.0 * wp.randf(state) - 1.0, 0.0)
    local = start.start_point + jitter
    if start.random_waypoint != 0:
        distance = from_uniform(wp.randf(state), start.waypoint_distance_low, start.waypoint_distance_high, 0.0)
        bearing = from_uniform(wp.randf(state), start.waypoint_bearing_low, start.waypoint_bearing_high, 0.0)
        course.route[env, 0] = start.start_point + distance * wp.vec3(wp.cos(bearing), wp.sin(bearing), 0.0)
    first = course.route[env, 0]
    heading = from_uniform(wp.randf(state), start.heading_low, start.heading_high, start.heading_step)
    if start.heading_toward_waypoint != 0:
        heading = heading + wp.atan2(first[1] - local[1], first[0] - local[0])
    rows.position[env] = course.origin[env] + local + wp.vec3(0.0, 0.0, start.start_height)
    rows.orientation[env] = wp.quat_from_axis_angle(wp.vec3(0.0, 0.0, 1.0), heading)
    surge = from_uniform(wp.randf(state), start.surge_low, start.surge_high, 0.0)
    rows.velocity[env] = vec6(surge, 0.0, 0.0, 0.0, 0.0, 0.0)
    rows.sheet[env] = from_uniform(wp.randf(state), start.sheet_low, start.sheet_high, 0.0)
    rows.wind_speed[env] = from_uniform(wp.randf(state), start.wind_speed_low, start.wind_speed_high, 0.0)
    rows.wind_direction[env] = from_uniform(wp.randf(state), start.wind_direction_low, start.wind_direction_high,
                                     start.wind_direction_step)
    rows.gust_scale[env] = from_uniform(wp.randf(state), start.gust_scale_low, start.gust_scale_high, 0.0)
    # Domain randomisation, from a stream of its own: the draws above stay what they were without it.
    # wp.randf advances ``dr`` here (a wp.func would get a copy of the state; see ``from_uniform``).
    dr = stream_state(seed[0], RANDOMISATION, episode, first_env + env)
    v = start.foil_variation
    sail = (1.0 - v) + (2.0 * v) * wp.randf(dr)
    keel = (1.0 - v) + (2.0 * v) * wp.randf(dr)
    rudder = (1.0 - v) + (2.0 * v) * wp.randf(dr)
    rows.foil_scale[env] = wp.vec3(sail, keel, rudder)
    rows.noise_scale[env] = start.noise_scale_low + (start.noise_scale_high - start.noise_scale_low) * wp.randf(dr)
    # The current, from a stream of its own too (a range of one value draws exactly that value).
    flow = stream_state(seed[0], CURRENT_DRAW, episode, first_env + env)
    rows.current_speed[env] = from_uniform(wp.randf(flow), start.current_speed_low, start.current_speed_high, 0.0)
    rows.current_direction[env] = from_uniform(wp.randf(flow), start.current_direction_low,
                                               start.current_direction_high, 0.0)
    # The reef level: the rule's at the drawn mean wind, or with probability reef_random a uniform draw over the
    # levels, from a stream of its own (both numbers always drawn, so each episode's pair is fixed).
    level = reef_level_for(start, rows.wind_speed[env])
    reef = stream_state(seed[0], REEF_DRAW, episode, first_env + env)
    chance = wp.randf(reef)
    pick = wp.randf(reef)
    if start.reef_rule != 0 and chance < start.reef_random:
        level = wp.min(int(pick * float(start.reef_levels)), start.reef_levels - 1)
    rows.reef_level[env] = level

    course.target_index[env] = 0
    course.leg_start[env] = local
    course.previous_distance[env] = wp.length(planar(first - local))
    for k in range(3):
        course.last_action[env, k] = 0.0
    course.episode_length[env] = 0
    course.episode_return[env] = 0.0
    course.target_world[env] = course.origin[env] + first
