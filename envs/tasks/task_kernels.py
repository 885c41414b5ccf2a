"""The kernels of a sailing task, one thread per environment: rewards and episode ends, observations, and the
start of a new episode for the environments that ended.

The evaluation and observation kernels are built for each task from the reward terms (``reward_terms``) and the
observation blocks (``observation_blocks``) its config selects: what a task does not select is not in its kernel,
and each distinct selection is built (and compiled) once per process, whatever the number of environments or
configs that share it.

    wp.launch(evaluate_kernel_for(task), ...)    # the task's reward and episode ends, one launch a decision
    wp.launch(observe_kernel_for(task), ...)     # its policy and critic observations, one launch

Conventions: positions of waypoints are relative to the environment's origin on the periodic ocean;
the boat's position is world ENU. Bearings are measured from the bow, positive to port [rad].
"""

from __future__ import annotations

import functools

import warp as wp

from ocean_warp.kernels.eboat_actions import propeller_level
from ocean_warp.kernels.random_streams import EPISODE_START, RANDOMISATION, CURRENT_DRAW, REEF_DRAW, stream_state
from ocean_warp.kernels.rigid_body import STATUS_COLLIDED
from ocean_warp.kernels.spatial import PI, heading_of, vec6, wrap_angle

from .observation_blocks import SET_BLOCKS, SET_COLUMNS, privileged_columns, reef_column
from .reward_terms import (REWARD_TERMS, collision, flagged, lost, motor_energy, progress, propeller_shaping,
                           proximity, reach, reward_terms, smoothness, time_cost)
from .task_configs import ObservationSet
from .task_structs import BoatView, Course, EpisodeEnds, StartDistribution, StartRows, TaskParameters

__all__ = ["TaskParameters", "StartDistribution", "Course", "EpisodeEnds", "BoatView", "StartRows", "POLICY_OBS",
           "PRIVILEGED_OBS", "policy_observation_count", "evaluate_kernel", "evaluate_kernel_for", "observe_kernel",
           "observe_kernel_for", "draw_starts", "reef_level_for"]

PRIVILEGED_OBS = 12
"""Values the critic sees beyond the policy's observation."""
POLICY_OBS = {"seed": 5, "plus": 15}
"""Values of each observation set; a task appends its reef level and its lidar's sectors
(:func:`policy_observation_count`). ``observation_blocks`` names every column (its tests hold it to these)."""


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


@wp.func
def clamped_action(action: float) -> float:
    """``action`` clipped to [-1, 1]; 0 where it is not finite."""
    if wp.isfinite(action):
        return wp.clamp(action, -1.0, 1.0)
    return 0.0


@functools.cache
def evaluate_kernel(terms: tuple[str, ...]) -> wp.Kernel:
    """The kernel of a decision's reward, waypoint progress and episode end with the progress and the optional
    reward ``terms`` (names of ``reward_terms.REWARD_TERMS``; see ``RewardConfig``), built once per selection; its
    key names them (``evaluate_progress_reach_lost_flagged_collision`` for the seed's reward).

    Launched over the environments with (task: TaskParameters, actions (N, 3), status (N,) the simulator's flags,
    position (N,) vec3 [m], clearance (N,) each boat's gap to the nearest obstacle [m], course: Course,
    ends: EpisodeEnds)."""
    unknown = sorted(set(terms) - set(REWARD_TERMS))
    if unknown:
        raise ValueError(f"evaluate_kernel: unknown reward terms {unknown}; the terms: {', '.join(REWARD_TERMS)}")
    selected = set(terms)
    with_propeller, with_energy = "propeller" in selected, "energy" in selected
    with_reach, with_lost = "reach" in selected, "lost" in selected
    with_flagged, with_collision = "flagged" in selected, "collision" in selected
    with_proximity, with_smoothness, with_time = "proximity" in selected, "smoothness" in selected, "time" in selected
    with_level = with_propeller or with_energy
    name = "_".join(("evaluate_progress",) + tuple(term for term in REWARD_TERMS if term in selected))

    @wp.kernel(enable_backward=False, module="unique", name=name)
    def evaluate(
        task: TaskParameters,
        actions: wp.array2d(dtype=float),
        status: wp.array(dtype=int),
        position: wp.array(dtype=wp.vec3),
        clearance: wp.array(dtype=float),
        course: Course,
        ends: EpisodeEnds,
    ):
        env = wp.tid()
        flags = status[env]
        index = course.target_index[env]
        local = position[env] - course.origin[env]
        target = course.route[env, index]
        distance = wp.length(planar(target - local))
        leg = wp.length(planar(target - course.leg_start[env]))
        level = float(0.0)
        if wp.static(with_level):
            level = float(wp.abs(propeller_level(actions[env, 0])))

        r = float(0.0)
        ended = False
        success = False
        if flags != 0:
            if (flags & STATUS_COLLIDED) != 0:
                if wp.static(with_collision):
                    r = collision(task.collision_penalty)
            else:
                if wp.static(with_flagged):
                    r = flagged(task.flagged_penalty)
            ended = True
        else:
            r = progress(course.previous_distance[env], distance, task.progress_scale)
            if wp.static(with_propeller):
                r = propeller_shaping(r, level, task.propeller_gain, task.propeller_cost)
            if distance <= task.reach_radius:
                if wp.static(with_reach):
                    r = r + reach(task.reach_bonus)
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
                if wp.static(with_lost):
                    r = r + lost(task.lost_penalty)
                ended = True
            if wp.static(with_proximity):
                r = r + proximity(clearance[env], task.proximity_cost, task.proximity_range)
        before = wp.vec3(course.last_action[env, 0], course.last_action[env, 1], course.last_action[env, 2])
        now = wp.vec3(clamped_action(actions[env, 0]), clamped_action(actions[env, 1]),
                      clamped_action(actions[env, 2]))
        for k in range(3):
            course.last_action[env, k] = now[k]
        if wp.static(with_smoothness):
            r = r + smoothness(now, before, task.smoothness)
        if wp.static(with_time):
            r = r + time_cost(task.time_cost)
        if wp.static(with_energy):
            r = r + motor_energy(level, task.energy_cost, task.decision_period)

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

    return evaluate


def evaluate_kernel_for(task) -> wp.Kernel:
    """:func:`evaluate_kernel` of the reward terms ``task`` (a ``TaskConfig``) selects (``reward_terms``)."""
    return evaluate_kernel(reward_terms(task))


@functools.cache
def observe_kernel(observation_set: str, reef: bool) -> wp.Kernel:
    """The kernel of the policy's observation (the ``observation_set``'s block, then, with ``reef``, the reef
    level) and the critic's (the policy's values, then ``PRIVILEGED_BLOCK``), built once per selection; a lidar's
    sectors come after each (``ObstacleCourse.append_observation``). Its key names the selection
    (``observe_plus_reef``).

    Launched over the environments with (task: TaskParameters, boats: BoatView, course: Course), writing
    policy (N, >= the policy's values) and critic (N, >= those + ``PRIVILEGED_OBS``)."""
    if observation_set not in SET_COLUMNS:
        raise ValueError(f"observe_kernel: unknown observation set {observation_set!r}; the sets: "
                         f"{', '.join(SET_COLUMNS)}")
    set_columns = SET_COLUMNS[observation_set]
    with_reef = bool(reef)
    policy_values = len(SET_BLOCKS[observation_set]) + int(with_reef)
    name = f"observe_{observation_set}" + ("_reef" if with_reef else "")

    @wp.kernel(enable_backward=False, module="unique", name=name)
    def observe(
        task: TaskParameters,
        boats: BoatView,
        course: Course,
        policy: wp.array2d(dtype=float),
        critic: wp.array2d(dtype=float),
    ):
        env = wp.tid()
        rotation = boats.orientation[env]
        heading = heading_of(rotation)
        target = course.target_world[env]
        to_target = planar(target - boats.position[env])
        distance = wp.length(to_target)
        bearing = wrap_angle(wp.atan2(to_target[1], to_target[0]) - heading)
        leg = wp.length(planar(target - (course.origin[env] + course.leg_start[env])))
        lost_distance = leg + task.lost_margin
        p = wp.static(set_columns)(policy, env, 0, boats, course, distance, bearing, lost_distance)
        if wp.static(with_reef):
            p = reef_column(policy, env, p, boats, task.reef_levels)
        for k in range(wp.static(policy_values)):
            critic[env, k] = policy[env, k]
        privileged_columns(critic, env, wp.static(policy_values), boats, course, distance, bearing, lost_distance,
                           heading, task.route_length)

    return observe


def observe_kernel_for(task) -> wp.Kernel:
    """:func:`observe_kernel` of ``task``'s (a ``TaskConfig``) observation set and reef rule."""
    return observe_kernel(ObservationSet(task.observation).value, task.reef is not None)


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
