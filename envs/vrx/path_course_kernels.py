"""The follow-the-path course's buoys on the device, one thread per environment: each gate's two buoys and the
obstacle buoys between the gates, written into the scene's free object rows at every episode start."""

from __future__ import annotations

import warp as wp

from ocean_warp.kernels.random_streams import PATH_OBSTACLES, stream_state
from ocean_warp.kernels.ray_cast import SHAPE_SPHERE

from ..tasks.obstacle_kernels import KIND_BUOY, ObjectRows, _park, _planar_distance
from .vrx_kernels import VrxCourse, gate_buoy

__all__ = ["PATH_OBSTACLES", "PathLayout", "draw_path_buoys", "distance_to_segment"]



@wp.struct
class PathLayout:
    """``PathCourseConfig`` and the gates' geometry on the device (lengths [m])."""

    gate_count: int
    gate_half_width: float
    gate_buoy_radius: float
    obstacle_slots: int
    obstacle_radius: float
    opening_clearance: float
    start_clearance: float
    spacing: float
    cross_track: float
    attempts: int
    parked_depth: float
    port_color: wp.vec3
    starboard_color: wp.vec3
    obstacle_color: wp.vec3


@wp.func
def distance_to_segment(p: wp.vec3, a: wp.vec3, b: wp.vec3) -> float:
    """Horizontal distance from ``p`` to the segment a-b [m]."""
    ab = wp.vec2(b[0] - a[0], b[1] - a[1])
    ap = wp.vec2(p[0] - a[0], p[1] - a[1])
    t = wp.clamp(wp.dot(ap, ab) / wp.max(wp.dot(ab, ab), 1.0e-12), 0.0, 1.0)
    return wp.length(ap - t * ab)


@wp.func
def _place_buoy(rows: ObjectRows, k: int, origin: wp.vec3, center: wp.vec3, radius: float, color: wp.vec3):
    rows.shape[k] = SHAPE_SPHERE
    rows.anchor[k] = origin + center
    rows.position[k] = rows.anchor[k]
    rows.orientation[k] = wp.quat_identity()
    rows.size[k] = wp.vec3(radius, 0.0, 0.0)
    rows.bound[k] = radius
    rows.color[k] = color
    rows.floats[k] = 1
    rows.draft[k] = 0.0


@wp.kernel(enable_backward=False)
def draw_path_buoys(layout: PathLayout, seed: wp.array(dtype=int), first_env: int, reset_mask: wp.array(dtype=wp.int32),
                    course: VrxCourse, first_row: wp.array(dtype=int), rows: ObjectRows,
                    table: wp.array2d(dtype=wp.vec4), buoy_count: wp.array(dtype=int)):
    """The buoys of every environment whose ``reset_mask`` is set, after ``vrx_draw_starts`` drew its gates
    (``course.route``, ``course.goal_count`` of them): table rows 2g and 2g + 1 are gate g's port and starboard
    buoys (``gate_buoy``), then up to ``obstacle_slots`` obstacle buoys from the environment's own stream (seed,
    environment ``first_env`` + index, episode number), each on a random leg (from the start or the gate before
    to the gate), at 20-80 % of it and up to ``cross_track`` off its line, kept only where its surface is
    ``opening_clearance`` from every gate's opening (the segment between its buoys' centres), ``start_clearance``
    from the start and ``spacing`` from the obstacles kept; the rows after them (the slots of gates beyond the
    episode's count and the obstacles not kept) are parked. Table rows: x, y from the origin [m], radius [m],
    ``KIND_BUOY``; zeros for a parked row. ``buoy_count`` gets the buoys placed."""
    env = wp.tid()
    if reset_mask[env] == 0:
        return
    origin = course.origin[env]
    base = first_row[env]
    gates = int(course.goal_count[env])
    for g in range(gates):
        gate = course.route[env, g]
        for side in range(2):
            sign = 1.0 - 2.0 * float(side)
            color = layout.port_color
            if side == 1:
                color = layout.starboard_color
            center = gate_buoy(gate, sign, layout.gate_half_width)
            _place_buoy(rows, base + 2 * g + side, origin, center, layout.gate_buoy_radius, color)
            table[env, 2 * g + side] = wp.vec4(center[0], center[1], layout.gate_buoy_radius, float(KIND_BUOY))
    state = stream_state(seed[0], PATH_OBSTACLES, course.episode_count[env], first_env + env)
    first = 2 * gates
    radius = layout.obstacle_radius
    kept = int(0)
    for slot in range(layout.obstacle_slots):
        for attempt in range(layout.attempts):
            leg = wp.min(int(wp.randf(state) * float(gates)), gates - 1)
            t = 0.2 + 0.6 * wp.randf(state)
            c = layout.cross_track * (2.0 * wp.randf(state) - 1.0)
            end = course.route[env, leg]
            start = wp.vec3(0.0, 0.0, 0.0)
            if leg > 0:
                start = course.route[env, leg - 1]
            a = wp.vec3(start[0], start[1], 0.0)
            b = wp.vec3(end[0], end[1], 0.0)
            length = wp.length(b - a)
            along = wp.vec3(1.0, 0.0, 0.0)
            if length > 1.0e-6:
                along = (b - a) / length
            center = a + (t * length) * along + c * wp.vec3(-along[1], along[0], 0.0)
            clear = wp.length(wp.vec2(center[0], center[1])) - radius >= layout.start_clearance
            for g in range(gates):
                gate = course.route[env, g]
                opening = distance_to_segment(center, gate_buoy(gate, 1.0, layout.gate_half_width),
                                              gate_buoy(gate, -1.0, layout.gate_half_width))
                clear = clear and opening - radius >= layout.opening_clearance
            for other in range(kept):
                placed = rows.anchor[base + first + other] - origin
                clear = clear and _planar_distance(center, placed) - 2.0 * radius >= layout.spacing
            if clear:
                _place_buoy(rows, base + first + kept, origin, center, radius, layout.obstacle_color)
                table[env, first + kept] = wp.vec4(center[0], center[1], radius, float(KIND_BUOY))
                kept = kept + 1
                break
    for row in range(first + kept, 2 * layout.gate_count + layout.obstacle_slots):
        _park(rows, base + row, origin, layout.parked_depth)
        table[env, row] = wp.vec4(0.0, 0.0, 0.0, 0.0)
    buoy_count[env] = first + kept
