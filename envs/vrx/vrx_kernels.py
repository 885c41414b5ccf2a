"""The kernels of VRX's tasks, one thread per environment: rewards and episode ends, observations, and the start
of a new episode for the environments that ended. Vessel-blind: they read the common state of
``ocean_warp.vessel.VesselSimulator`` (pose, velocity, status, wind) and write its start rows.

Goals are poses: ``route[env, g]`` holds x, y from the environment's origin [m] and, in its third component, the
goal heading [rad]; ``target_world`` the current goal's world x, y and heading. A gate of the path is a goal
pose too: its centre and the direction it is passed in.
"""

from __future__ import annotations

import functools

import warp as wp

from ocean_warp.kernels.random_streams import VRX_START, VRX_CONDITIONS, stream_state
from ocean_warp.kernels.rigid_body import STATUS_COLLIDED
from ocean_warp.kernels.spatial import PI, heading_of, vec6, wrap_angle

from .reward_terms import VRX_REWARD_TERMS, effort_cost, error_cost, flagged_penalty, pose_progress, reach_bonus

__all__ = ["VrxParameters", "VrxStartDistribution", "VrxCourse", "VesselStartRows", "STATION_KEEPING",
           "WAYFINDING", "FOLLOW_PATH", "POLICY_BASE", "PRIVILEGED", "pose_error", "gate_buoy", "vrx_evaluate_kernel",
           "vrx_observe", "vrx_draw_starts", "vrx_gate_buoys", "vrx_contact"]

STATION_KEEPING = wp.constant(0)
WAYFINDING = wp.constant(1)
FOLLOW_PATH = wp.constant(2)
POLICY_BASE = 10
"""Policy values before the last actions (see ``vrx_observe``)."""
PRIVILEGED = 3
"""Values the critic sees beyond the policy's: the wind in the body frame (2) and the pose error."""
HEADING_BASE = wp.constant(0.75)
"""VRX's k in the pose error d + k^d |heading error|."""
GATE_ATTEMPTS = wp.constant(8)
"""Draws of a later gate's leg before it turns straight away from the start (``vrx_draw_starts``)."""


@wp.struct
class VrxParameters:
    kind: int
    goal_count: int
    """The most goals (gates) of an episode: the route's width."""
    goal_count_low: int
    """The fewest; an episode draws its own count in [goal_count_low, goal_count]."""
    num_actions: int
    reach_error: float
    """[m]"""
    lost_distance: float
    """[m]"""
    position_scale: float
    """[m]"""
    decision_period: float
    """[s]"""
    max_episode_length: int
    progress_scale: float
    error_cost: float
    action_cost: float
    reach_bonus: float
    flagged_penalty: float


@wp.struct
class VrxStartDistribution:
    goal_distance_low: float
    goal_distance_high: float
    goal_spacing_low: float
    goal_spacing_high: float
    goal_bearing_low: float
    """[rad] from the start heading"""
    goal_bearing_high: float
    leg_turn_low: float
    """[rad] from the previous leg's direction"""
    leg_turn_high: float
    wind_speed_low: float
    wind_speed_high: float
    wind_direction_low: float
    wind_direction_high: float
    gust_scale_low: float
    gust_scale_high: float
    current_speed_low: float
    current_speed_high: float
    current_direction_low: float
    current_direction_high: float
    noise_scale_low: float
    noise_scale_high: float
    start_speed_low: float
    start_speed_high: float
    start_height: float
    gate_half_width: float
    """Half the width between a gate's buoys' centres [m]."""
    buoy_clearance: float
    """Least distance from the start to a gate buoy's centre [m] (0: gates without buoys, no constraint)."""


@wp.struct
class VrxCourse:
    """The task's per-environment arrays."""

    origin: wp.array(dtype=wp.vec3)
    route: wp.array2d(dtype=wp.vec3)
    goal_count: wp.array(dtype=wp.int32)
    """The episode's own count of goals (gates); the route's later columns repeat its last goal."""
    target_index: wp.array(dtype=int)
    previous_error: wp.array(dtype=float)
    """The pose error to the current goal after the last decision [m]."""
    previous_position: wp.array(dtype=wp.vec3)
    """World position after the last decision [m] (gate crossings)."""
    episode_length: wp.array(dtype=wp.int32)
    episode_return: wp.array(dtype=float)
    episode_count: wp.array(dtype=int)
    target_world: wp.array(dtype=wp.vec3)
    last_action: wp.array2d(dtype=float)
    """The actions of the last decision, clipped (zeros at an episode's start)."""


@wp.struct
class VesselStartRows:
    """The rows of a vessel's start that every vessel has (``ocean_warp.vessel.VesselSimulator``)."""

    position: wp.array(dtype=wp.vec3)
    orientation: wp.array(dtype=wp.quat)
    velocity: wp.array(dtype=vec6)
    wind_speed: wp.array(dtype=float)
    wind_direction: wp.array(dtype=float)
    gust_scale: wp.array(dtype=float)
    current_speed: wp.array(dtype=float)
    current_direction: wp.array(dtype=float)
    noise_scale: wp.array(dtype=float)


@wp.func
def pose_error(distance: float, heading_error: float) -> float:
    """VRX's pose error [m + rad]: d + 0.75^d |heading error| (the heading counts less far from the goal)."""
    return distance + wp.pow(HEADING_BASE, distance) * wp.abs(heading_error)


@wp.func
def goal_offset(goal: wp.vec3, local: wp.vec3, yaw: float) -> wp.vec3:
    """The goal's x, y offset in the boat's yawed frame [m] and the heading error [rad], as a vec3."""
    dx = goal[0] - local[0]
    dy = goal[1] - local[1]
    c = wp.cos(yaw)
    s = wp.sin(yaw)
    return wp.vec3(c * dx + s * dy, -s * dx + c * dy, wrap_angle(goal[2] - yaw))


@wp.func
def gate_buoy(gate: wp.vec3, sign: float, half_width: float) -> wp.vec3:
    """The centre of a gate's buoy (x, y from the origin [m]): ``half_width`` to port (sign 1, green) or starboard
    (-1, red) of the gate's centre, across the heading it is passed in."""
    return wp.vec3(gate[0] - sign * half_width * wp.sin(gate[2]), gate[1] + sign * half_width * wp.cos(gate[2]), 0.0)


@wp.func
def gate_clear_of_start(gate: wp.vec3, half_width: float, clearance: float) -> bool:
    """Whether both buoys of ``gate`` lie at least ``clearance`` [m] (centre to the start) from the start."""
    port = gate_buoy(gate, 1.0, half_width)
    starboard = gate_buoy(gate, -1.0, half_width)
    return wp.min(wp.length(wp.vec2(port[0], port[1])), wp.length(wp.vec2(starboard[0], starboard[1]))) >= clearance


@wp.func
def leg_end(previous: wp.vec3, distance: float, bearing: float) -> wp.vec3:
    """The goal ``distance`` [m] on from ``previous`` along ``bearing`` [rad], facing along it (x, y, heading)."""
    return wp.vec3(previous[0] + distance * wp.cos(bearing), previous[1] + distance * wp.sin(bearing), bearing)


@wp.func
def clip_unit(value: float, limit: float) -> float:
    """``value`` clamped to [-limit, limit]; 0 when it is not finite."""
    if not wp.isfinite(value):
        return 0.0
    return wp.clamp(value, -limit, limit)


@wp.func
def crossed_gate(gate: wp.vec3, half_width: float, before: wp.vec3, after: wp.vec3) -> bool:
    """Whether the move from ``before`` to ``after`` (from the origin [m]) passes the gate at ``gate`` (centre x,
    y and the heading it is passed in) forward, between its buoys ``half_width`` [m] either side."""
    c = wp.cos(gate[2])
    s = wp.sin(gate[2])
    along_before = c * (before[0] - gate[0]) + s * (before[1] - gate[1])
    along_after = c * (after[0] - gate[0]) + s * (after[1] - gate[1])
    if not (along_before < 0.0 and along_after >= 0.0):
        return False
    t = along_before / (along_before - along_after)
    x = before[0] + t * (after[0] - before[0]) - gate[0]
    y = before[1] + t * (after[1] - before[1]) - gate[1]
    return wp.abs(-s * x + c * y) <= half_width


@functools.lru_cache(maxsize=None)
def vrx_evaluate_kernel(terms: tuple[str, ...]) -> wp.Kernel:
    """The kernel of a decision's reward, goal progress and episode end with the progress and the optional reward
    ``terms`` (names of ``reward_terms.VRX_REWARD_TERMS``), built once per selection; its key names them.

    Launched over the environments with (p: VrxParameters, gate_half_width [m], actions (N, A), status (N,),
    position (N,) vec3 [m], orientation (N,) quat, course: VrxCourse) and the episode-end outputs."""
    unknown = sorted(set(terms) - set(VRX_REWARD_TERMS))
    if unknown:
        raise ValueError(f"vrx_evaluate_kernel: unknown reward terms {unknown}; the terms: "
                         f"{', '.join(VRX_REWARD_TERMS)}")
    with_error, with_effort = "error" in terms, "effort" in terms
    with_reach, with_flagged = "reach" in terms, "flagged" in terms
    name = "_".join(("vrx_evaluate_progress",) + tuple(term for term in VRX_REWARD_TERMS if term in terms))

    @wp.kernel(enable_backward=False, module="unique", name=name)
    def vrx_evaluate(
        p: VrxParameters,
        gate_half_width: float,
        actions: wp.array2d(dtype=float),
        status: wp.array(dtype=int),
        position: wp.array(dtype=wp.vec3),
        orientation: wp.array(dtype=wp.quat),
        course: VrxCourse,
        reward: wp.array(dtype=float),
        terminated: wp.array(dtype=wp.bool),
        time_out: wp.array(dtype=wp.bool),
        done: wp.array(dtype=wp.bool),
        reset_mask: wp.array(dtype=wp.int32),
        final_return: wp.array(dtype=float),
        final_length: wp.array(dtype=wp.int32),
        final_success: wp.array(dtype=float),
        final_status: wp.array(dtype=int),
        final_waypoints: wp.array(dtype=int),
    ):
        """Reward, goal progress and the end of the episode after a decision (see ``VrxRewardConfig``)."""
        env = wp.tid()
        flags = status[env]
        index = course.target_index[env]
        local = position[env] - course.origin[env]
        yaw = heading_of(orientation[env])
        goal = course.route[env, index]
        offset = goal_offset(goal, local, yaw)
        distance = wp.sqrt(offset[0] * offset[0] + offset[1] * offset[1])
        error = pose_error(distance, offset[2])
        r = pose_progress(course.previous_error[env], error, p.progress_scale)
        if wp.static(with_error):
            r = r + error_cost(error, p.error_cost, p.decision_period)
        effort = float(0.0)
        for k in range(p.num_actions):
            a = clip_unit(actions[env, k], 1.0)
            course.last_action[env, k] = a
            effort += a * a
        if wp.static(with_effort):
            r = r + effort_cost(effort, p.num_actions, p.action_cost)

        reached = False
        if p.kind == WAYFINDING:
            reached = error < p.reach_error
        elif p.kind == FOLLOW_PATH:
            reached = crossed_gate(goal, gate_half_width, course.previous_position[env] - course.origin[env], local)
        if reached:
            if wp.static(with_reach):
                r = r + reach_bonus(p.reach_bonus)
            index += 1
        count = int(course.goal_count[env])
        finished = index >= count
        if not finished:
            goal = course.route[env, index]
            offset = goal_offset(goal, local, yaw)
            distance = wp.sqrt(offset[0] * offset[0] + offset[1] * offset[1])
            error = pose_error(distance, offset[2])
        flagged = flags != 0
        lost = distance > p.lost_distance or not wp.isfinite(error)
        if flagged:
            if wp.static(with_flagged):
                r = r + flagged_penalty(p.flagged_penalty)
        if not wp.isfinite(r):
            r = -p.flagged_penalty
        length = int(course.episode_length[env]) + 1
        ended = flagged or lost or finished
        timed = (not ended) and length >= p.max_episode_length
        reward[env] = r
        terminated[env] = ended
        time_out[env] = timed
        done[env] = ended or timed
        total = course.episode_return[env] + r
        course.target_index[env] = wp.min(index, count - 1)
        course.previous_error[env] = error
        course.previous_position[env] = position[env]
        if ended or timed:
            reset_mask[env] = 1
            final_return[env] = total
            final_length[env] = wp.int32(length)
            success = float(0.0)
            if p.kind == STATION_KEEPING:
                if (not flagged) and error < 1.0:
                    success = 1.0
            elif finished:
                success = 1.0
            final_success[env] = success
            final_status[env] = flags
            final_waypoints[env] = index
            course.episode_return[env] = 0.0
            course.episode_length[env] = wp.int32(0)
        else:
            reset_mask[env] = 0
            course.episode_return[env] = total
            course.episode_length[env] = wp.int32(length)
        current = course.route[env, course.target_index[env]]
        origin = course.origin[env]
        course.target_world[env] = wp.vec3(origin[0] + current[0], origin[1] + current[1], current[2])

    return vrx_evaluate


@wp.kernel(enable_backward=False)
def vrx_observe(
    p: VrxParameters,
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    wind_velocity: wp.array(dtype=wp.vec3),
    course: VrxCourse,
    policy: wp.array2d(dtype=float),
    critic: wp.array2d(dtype=float),
):
    """The policy's values: the goal's offset in the boat's yawed frame / scale (2), sin and cos of the heading
    error (2), the distance / scale (1), surge, sway [m/s] and yaw rate [rad/s] (3), the next goal's offset /
    scale (2: the same goal when there is no next), then the last actions (A). The critic's: the policy's, the
    wind in the yawed frame / 10 m/s (2) and the pose error / scale (1). Non-finite values read as 0."""
    env = wp.tid()
    index = course.target_index[env]
    local = position[env] - course.origin[env]
    yaw = heading_of(orientation[env])
    offset = goal_offset(course.route[env, index], local, yaw)
    following = goal_offset(course.route[env, wp.min(index + 1, int(course.goal_count[env]) - 1)], local, yaw)
    scale = 1.0 / p.position_scale
    distance = wp.sqrt(offset[0] * offset[0] + offset[1] * offset[1])
    nu = velocity[env]
    values = wp.vector(length=POLICY_BASE, dtype=float)
    values[0] = clip_unit(offset[0] * scale, 5.0)
    values[1] = clip_unit(offset[1] * scale, 5.0)
    values[2] = clip_unit(wp.sin(offset[2]), 1.0)
    values[3] = clip_unit(wp.cos(offset[2]), 1.0)
    values[4] = clip_unit(distance * scale, 5.0)
    values[5] = clip_unit(nu[0], 10.0)
    values[6] = clip_unit(nu[1], 10.0)
    values[7] = clip_unit(nu[5], 10.0)
    values[8] = clip_unit(following[0] * scale, 5.0)
    values[9] = clip_unit(following[1] * scale, 5.0)
    for k in range(POLICY_BASE):
        policy[env, k] = values[k]
        critic[env, k] = values[k]
    for k in range(p.num_actions):
        a = course.last_action[env, k]
        policy[env, POLICY_BASE + k] = a
        critic[env, POLICY_BASE + k] = a
    wind = wind_velocity[env]
    c = wp.cos(yaw)
    s = wp.sin(yaw)
    base = POLICY_BASE + p.num_actions
    critic[env, base] = clip_unit((c * wind[0] + s * wind[1]) * 0.1, 5.0)
    critic[env, base + 1] = clip_unit((-s * wind[0] + c * wind[1]) * 0.1, 5.0)
    critic[env, base + 2] = clip_unit(pose_error(distance, offset[2]) * scale, 10.0)


@wp.func
def uniform(u: float, low: float, high: float) -> float:
    return low + (high - low) * u


@wp.kernel(enable_backward=False)
def vrx_draw_starts(
    p: VrxParameters,
    start: VrxStartDistribution,
    seed: wp.array(dtype=int),
    first_env: int,
    reset_mask: wp.array(dtype=wp.int32),
    course: VrxCourse,
    rows: VesselStartRows,
):
    """A new episode for every environment whose ``reset_mask`` is set, from its own random streams (seed,
    environment ``first_env`` + index, episode number): the boat at the origin with a random heading, the goals
    (the first at the start distance, its bearing off the start heading in the start's range; each next at the
    spacing from the one before, its leg turned from the leg before within the turn range; each with a random
    heading, or, a gate, facing along its leg), the episode's count of goals in the configured range (the route's
    later columns repeat its last goal), and the wind, current and sensor noise from a stream of their own. A
    later gate of a path with buoys whose buoy would lie nearer the start than ``buoy_clearance`` has its leg drawn
    again, up to ``GATE_ATTEMPTS`` draws, then turned straight away from the start. The last actions are
    zeroed."""
    env = wp.tid()
    if reset_mask[env] == 0:
        return
    episode = course.episode_count[env] + 1
    course.episode_count[env] = episode
    state = stream_state(seed[0], VRX_START, episode, first_env + env)
    heading = uniform(wp.randf(state), -PI, PI)
    previous = wp.vec3(0.0, 0.0, 0.0)
    bearing = heading
    for g in range(p.goal_count):
        low = start.goal_spacing_low
        high = start.goal_spacing_high
        turn_low = start.leg_turn_low
        turn_high = start.leg_turn_high
        if g == 0:
            low = start.goal_distance_low
            high = start.goal_distance_high
            turn_low = start.goal_bearing_low
            turn_high = start.goal_bearing_high
        distance = uniform(wp.randf(state), low, high)
        leg = wrap_angle(bearing + uniform(wp.randf(state), turn_low, turn_high))
        goal_heading = uniform(wp.randf(state), -PI, PI)
        if p.kind == FOLLOW_PATH and g > 0 and start.buoy_clearance > 0.0:
            clear = gate_clear_of_start(leg_end(previous, distance, leg), start.gate_half_width, start.buoy_clearance)
            for attempt in range(GATE_ATTEMPTS - 1):
                if not clear:
                    distance = uniform(wp.randf(state), low, high)
                    leg = wrap_angle(bearing + uniform(wp.randf(state), turn_low, turn_high))
                    clear = gate_clear_of_start(leg_end(previous, distance, leg), start.gate_half_width,
                                                start.buoy_clearance)
            if not clear:
                # Straight away from the start: the start then lies behind the gate, on its centre line, its
                # buoys at least half its width away (the task's config checks that this is clear).
                if wp.length(wp.vec2(previous[0], previous[1])) > 1.0e-6:
                    leg = wp.atan2(previous[1], previous[0])
                else:
                    leg = bearing
        bearing = leg
        previous = leg_end(previous, distance, bearing)  # a gate faces along its leg
        if p.kind != FOLLOW_PATH:
            previous = wp.vec3(previous[0], previous[1], goal_heading)
        course.route[env, g] = previous
    origin = course.origin[env]
    rows.position[env] = origin + wp.vec3(0.0, 0.0, start.start_height)
    rows.orientation[env] = wp.quat_from_axis_angle(wp.vec3(0.0, 0.0, 1.0), heading)
    rows.velocity[env] = vec6(uniform(wp.randf(state), start.start_speed_low, start.start_speed_high),
                              0.0, 0.0, 0.0, 0.0, 0.0)
    # The count is drawn last so that a range's episode sails the same first goals as the fixed count would.
    count = p.goal_count
    if p.goal_count_low < p.goal_count:
        span = p.goal_count - p.goal_count_low + 1
        count = p.goal_count_low + wp.min(int(wp.randf(state) * float(span)), span - 1)
    course.goal_count[env] = wp.int32(count)
    last = course.route[env, count - 1]
    for g in range(count, p.goal_count):
        course.route[env, g] = last
    conditions = stream_state(seed[0], VRX_CONDITIONS, episode, first_env + env)
    rows.wind_speed[env] = uniform(wp.randf(conditions), start.wind_speed_low, start.wind_speed_high)
    rows.wind_direction[env] = uniform(wp.randf(conditions), start.wind_direction_low, start.wind_direction_high)
    rows.gust_scale[env] = uniform(wp.randf(conditions), start.gust_scale_low, start.gust_scale_high)
    rows.current_speed[env] = uniform(wp.randf(conditions), start.current_speed_low, start.current_speed_high)
    rows.current_direction[env] = uniform(wp.randf(conditions), start.current_direction_low,
                                          start.current_direction_high)
    rows.noise_scale[env] = uniform(wp.randf(conditions), start.noise_scale_low, start.noise_scale_high)
    course.target_index[env] = 0
    first = course.route[env, 0]
    offset = goal_offset(first, wp.vec3(0.0, 0.0, 0.0), heading)
    course.previous_error[env] = pose_error(wp.sqrt(offset[0] * offset[0] + offset[1] * offset[1]), offset[2])
    course.previous_position[env] = rows.position[env]
    course.target_world[env] = wp.vec3(origin[0] + first[0], origin[1] + first[1], first[2])
    course.episode_length[env] = wp.int32(0)
    course.episode_return[env] = 0.0
    for k in range(p.num_actions):
        course.last_action[env, k] = 0.0


@wp.kernel(enable_backward=False)
def vrx_gate_buoys(route: wp.array2d(dtype=wp.vec3), half_width: float, gates: wp.array2d(dtype=wp.vec4)):
    """The follow-the-path score's gates: each gate's red (starboard) and green (port) buoy x, y from the origin
    [m] (the gate's centre -+ ``half_width`` across the heading it is passed in)."""
    env, g = wp.tid()
    gate = route[env, g]
    red = gate_buoy(gate, -1.0, half_width)
    green = gate_buoy(gate, 1.0, half_width)
    gates[env, g] = wp.vec4(red[0], red[1], green[0], green[1])


@wp.kernel(enable_backward=False)
def vrx_contact(status: wp.array(dtype=int), contact: wp.array(dtype=wp.bool)):
    """Whether each boat touches an obstacle now (its COLLIDED flag), for the follow-the-path score."""
    env = wp.tid()
    contact[env] = (status[env] & STATUS_COLLIDED) != 0
