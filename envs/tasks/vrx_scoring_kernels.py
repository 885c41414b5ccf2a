"""VRX's scoring rules on the device, one thread per environment: each decision updates the running state of
the environment's episode, and an ended episode's score is written out (``envs.tasks.vrx_scoring`` owns the
arrays and explains the rules with their sources in osrf/vrx).

Angles [rad], lengths [m], times [s]. A goal is a pose (x, y, yaw) held in a ``wp.vec3``; a gate a
``wp.vec4`` (red buoy x, y, green buoy x, y)."""

from __future__ import annotations

import warp as wp

from ocean_warp.kernels.spatial import heading_of, wrap_angle

__all__ = [
    "HEADING_WEIGHT_BASE",
    "GATE_OUTSIDE",
    "GATE_BEFORE",
    "GATE_AFTER",
    "GATE_CROSSED",
    "GATE_INVALID",
    "NO_GATE",
    "FollowPathRulesParameters",
    "pose_error",
    "gate_side",
    "station_keeping_update",
    "station_keeping_finish",
    "wayfinding_update",
    "wayfinding_finish",
    "follow_path_update",
    "follow_path_finish",
]

HEADING_WEIGHT_BASE = wp.constant(0.75)
"""k in VRX's pose error d + k^d |heading error|: the heading counts fully on the goal and fades with distance."""

GATE_OUTSIDE = wp.constant(0)
"""The boat is not between the gate's buoys (beyond half its width from its centre line)."""
GATE_BEFORE = wp.constant(1)
"""Between the buoys' lines, on the near side of the gate."""
GATE_AFTER = wp.constant(2)
"""Between the buoys' lines, on the far side."""
GATE_CROSSED = wp.constant(3)
"""Crossed forward, in order: scored."""
GATE_INVALID = wp.constant(4)
"""Crossed backwards: lost for good."""
NO_GATE = wp.constant(-1000000)
"""``last_scored`` when no gate has been scored since the last invalidated one (VRX's INT_MIN)."""


@wp.struct
class FollowPathRulesParameters:
    """``FollowPathRules`` on the device."""

    points_per_gate: float
    bonus: float
    obstacle_penalty: float
    collision_buffer: float


@wp.func
def pose_error(x: float, y: float, yaw: float, goal: wp.vec3) -> float:
    """VRX's 2D pose error of a boat at (x, y) heading ``yaw`` to the goal pose ``goal`` (x, y, yaw):
    d + 0.75^d |heading error|, d the distance [m], the heading error wrapped into [0, pi] [rad]."""
    d = wp.length(wp.vec2(goal[0] - x, goal[1] - y))
    heading_error = wp.abs(wrap_angle(goal[2] - yaw))
    return d + wp.pow(HEADING_WEIGHT_BASE, d) * heading_error


@wp.func
def gate_side(x: float, y: float, gate: wp.vec4) -> int:
    """Where the boat at (x, y) is with respect to ``gate`` (red x, y, green x, y): GATE_OUTSIDE, _BEFORE or
    _AFTER. The gate's forward direction is z x (red - green): crossing forward, red lies to starboard."""
    across = wp.vec2(gate[0] - gate[2], gate[1] - gate[3])
    width = wp.length(across)
    u = across / width
    forward = wp.vec2(-u[1], u[0])
    rel = wp.vec2(x - 0.5 * (gate[0] + gate[2]), y - 0.5 * (gate[1] + gate[3]))
    if wp.abs(wp.dot(rel, u)) > 0.5 * width:
        return GATE_OUTSIDE
    if wp.dot(rel, forward) >= 0.0:
        return GATE_AFTER
    return GATE_BEFORE


@wp.kernel(enable_backward=False)
def station_keeping_update(
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    target: wp.array(dtype=wp.vec3),
    error_sum: wp.array(dtype=float),
    samples: wp.array(dtype=wp.int32),
):
    """One sample of the pose error to the goal ``target`` (world x, y, yaw) into the episode's sum."""
    i = wp.tid()
    p = position[i]
    error_sum[i] = error_sum[i] + pose_error(p[0], p[1], heading_of(orientation[i]), target[i])
    samples[i] = samples[i] + 1


@wp.kernel(enable_backward=False)
def station_keeping_finish(
    mask: wp.array(dtype=wp.bool),
    write_score: int,
    error_sum: wp.array(dtype=float),
    samples: wp.array(dtype=wp.int32),
    final_score: wp.array(dtype=float),
):
    """Where ``mask``: the mean pose error into ``final_score`` (if ``write_score``; NaN for an episode of no
    sample: it has no score), then the running state cleared for a new episode."""
    i = wp.tid()
    if not mask[i]:
        return
    if write_score != 0:
        score = wp.nan
        if samples[i] > 0:
            score = error_sum[i] / float(samples[i])
        final_score[i] = score
    error_sum[i] = 0.0
    samples[i] = 0


@wp.kernel(enable_backward=False)
def wayfinding_update(
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    origin: wp.array(dtype=wp.vec3),
    route: wp.array2d(dtype=wp.vec3),
    count: wp.array(dtype=wp.int32),
    min_error: wp.array2d(dtype=float),
    samples: wp.array(dtype=wp.int32),
):
    """Each of the first ``count`` waypoints of ``route`` (x, y from ``origin``, yaw): its least pose error."""
    i = wp.tid()
    p = position[i] - origin[i]
    yaw = heading_of(orientation[i])
    for j in range(count[i]):
        e = pose_error(p[0], p[1], yaw, route[i, j])
        if samples[i] == 0 or e < min_error[i, j]:
            min_error[i, j] = e
    samples[i] = samples[i] + 1


@wp.kernel(enable_backward=False)
def wayfinding_finish(
    mask: wp.array(dtype=wp.bool),
    write_score: int,
    count: wp.array(dtype=wp.int32),
    min_error: wp.array2d(dtype=float),
    samples: wp.array(dtype=wp.int32),
    final_score: wp.array(dtype=float),
):
    """Where ``mask``: the mean over the waypoints of their least pose errors into ``final_score`` (NaN with no
    sample or no waypoint), then the running state cleared."""
    i = wp.tid()
    if not mask[i]:
        return
    if write_score != 0:
        score = wp.nan
        if samples[i] > 0 and count[i] > 0:
            total = float(0.0)
            for j in range(count[i]):
                total += min_error[i, j]
            score = total / float(count[i])
        final_score[i] = score
    for j in range(min_error.shape[1]):
        min_error[i, j] = 0.0
    samples[i] = 0


@wp.kernel(enable_backward=False)
def follow_path_update(
    rules: FollowPathRulesParameters,
    position: wp.array(dtype=wp.vec3),
    origin: wp.array(dtype=wp.vec3),
    gates: wp.array2d(dtype=wp.vec4),
    count: wp.array(dtype=wp.int32),
    contact: wp.array(dtype=wp.bool),
    dt: float,
    gate_state: wp.array2d(dtype=wp.int32),
    last_crossed: wp.array(dtype=wp.int32),
    last_scored: wp.array(dtype=wp.int32),
    since_collision: wp.array(dtype=float),
    collisions: wp.array(dtype=wp.int32),
    score: wp.array(dtype=float),
    finished: wp.array(dtype=wp.int32),
):
    """One decision of VRX's navigation scoring (``vrx_scoring.FollowPathScore`` says the rules): the
    collision penalty, then the first gate whose state changes."""
    i = wp.tid()
    if finished[i] != 0:
        return
    since_collision[i] = since_collision[i] + dt
    if contact[i] and since_collision[i] > rules.collision_buffer:
        collisions[i] = collisions[i] + 1
        since_collision[i] = 0.0
        score[i] = wp.max(0.0, score[i] - rules.obstacle_penalty)
    p = position[i] - origin[i]
    n = count[i]
    for g in range(last_crossed[i] + 1, n):
        if g != 0 and gate_state[i, 0] != GATE_CROSSED:
            break
        state = gate_state[i, g]
        if state == GATE_CROSSED or state == GATE_INVALID:
            continue
        side = gate_side(p[0], p[1], gates[i, g])
        if side == GATE_AFTER and state == GATE_BEFORE:
            gate_state[i, g] = GATE_CROSSED
            score[i] = score[i] + rules.points_per_gate
            if g != 0 and g == last_scored[i] + 1:
                score[i] = score[i] + rules.bonus
            last_crossed[i] = g
            last_scored[i] = g
            if g == n - 1:
                score[i] = score[i] + rules.bonus
                finished[i] = 1
            return
        if g != 0 and side == GATE_BEFORE and state == GATE_AFTER:
            gate_state[i, g] = GATE_INVALID
            last_scored[i] = NO_GATE
            last_crossed[i] = g
            if g == n - 1:
                finished[i] = 1
            return
        gate_state[i, g] = side


@wp.kernel(enable_backward=False)
def follow_path_finish(
    mask: wp.array(dtype=wp.bool),
    write_score: int,
    rules: FollowPathRulesParameters,
    gate_state: wp.array2d(dtype=wp.int32),
    last_crossed: wp.array(dtype=wp.int32),
    last_scored: wp.array(dtype=wp.int32),
    since_collision: wp.array(dtype=float),
    collisions: wp.array(dtype=wp.int32),
    score: wp.array(dtype=float),
    finished: wp.array(dtype=wp.int32),
    final_score: wp.array(dtype=float),
):
    """Where ``mask``: the points into ``final_score`` (if ``write_score``), then a new course: no gate
    crossed, the first collision counted at once."""
    i = wp.tid()
    if not mask[i]:
        return
    if write_score != 0:
        final_score[i] = score[i]
    for g in range(gate_state.shape[1]):
        gate_state[i, g] = GATE_OUTSIDE
    last_crossed[i] = -1
    last_scored[i] = NO_GATE
    since_collision[i] = rules.collision_buffer + 1.0
    collisions[i] = 0
    score[i] = 0.0
    finished[i] = 0
