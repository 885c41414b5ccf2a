"""The kernels of an obstacle course, one thread per environment: a layout drawn into the scene's free object
rows at every reset (``ObstacleLayoutConfig`` gives the geometry), and the lidar's sectors appended to the
observations."""

from __future__ import annotations

import warp as wp

from ocean_warp.kernels.random_streams import LAYOUT, stream_state
from ocean_warp.kernels.ray_cast import SHAPE_CYLINDER, SHAPE_SPHERE

from .task_kernels import Course

__all__ = ["LAYOUT", "KIND_BUOY", "KIND_PILE", "LayoutParameters", "ObjectRows", "draw_layouts", "append_sectors"]

KIND_BUOY = wp.constant(1)
KIND_PILE = wp.constant(2)
"""Kinds in a layout's table (0: an empty row)."""


@wp.struct
class LayoutParameters:
    """``ObstacleLayoutConfig`` on the device (lengths [m])."""

    count_low: int
    count_high: int
    pile_fraction: float
    buoy_radius_low: float
    buoy_radius_high: float
    pile_radius_low: float
    pile_radius_high: float
    pile_half_height: float
    along_low: float
    along_high: float
    cross_track: float
    start_clearance: float
    waypoint_clearance: float
    spacing: float
    attempts: int
    parked_depth: float
    """How far below the environment's origin an empty row is parked [m] (``Scene.free_slots``)."""
    buoy_color: wp.vec3
    pile_color: wp.vec3


@wp.struct
class ObjectRows:
    """The scene's object rows a layout writes (``Scene``: its ``view``, ``anchor``, ``floats``, ``draft``)."""

    shape: wp.array(dtype=int)
    anchor: wp.array(dtype=wp.vec3)
    position: wp.array(dtype=wp.vec3)
    orientation: wp.array(dtype=wp.quat)
    size: wp.array(dtype=wp.vec3)
    bound: wp.array(dtype=float)
    color: wp.array(dtype=wp.vec3)
    floats: wp.array(dtype=int)
    draft: wp.array(dtype=float)


@wp.func
def _planar_distance(a: wp.vec3, b: wp.vec3) -> float:
    return wp.length(wp.vec2(a[0] - b[0], a[1] - b[1]))


@wp.func
def _park(rows: ObjectRows, k: int, origin: wp.vec3, depth: float):
    rows.shape[k] = SHAPE_SPHERE
    rows.anchor[k] = origin - wp.vec3(0.0, 0.0, depth)
    rows.position[k] = rows.anchor[k]
    rows.orientation[k] = wp.quat_identity()
    rows.size[k] = wp.vec3(0.0, 0.0, 0.0)
    rows.bound[k] = 0.0
    rows.floats[k] = 0
    rows.draft[k] = 0.0


@wp.kernel(enable_backward=False)
def draw_layouts(layout: LayoutParameters, seed: wp.array(dtype=int), first_env: int,
                 reset_mask: wp.array(dtype=wp.int32), course: Course, first_row: wp.array(dtype=int),
                 rows: ObjectRows, table: wp.array2d(dtype=wp.vec4), obstacle_count: wp.array(dtype=int)):
    """A new layout for every environment whose ``reset_mask`` is set, after its start was drawn
    (``draw_starts``: the leg from ``course.leg_start`` to ``course.route[env, 0]``), from its own random
    stream (seed, environment ``first_env`` + index, episode number): the obstacles kept are written to rows
    ``first_row[env]`` on, the rest of its ``count_high`` rows are parked; ``table[env]`` lists them (x, y from
    the origin [m], radius [m], ``KIND_*``; zeros for an empty row) and ``obstacle_count`` gets how many were
    kept."""
    env = wp.tid()
    if reset_mask[env] == 0:
        return
    state = stream_state(seed[0], LAYOUT, course.episode_count[env], first_env + env)
    origin = course.origin[env]
    start = course.leg_start[env]
    waypoint = course.route[env, 0]
    leg = wp.vec3(waypoint[0] - start[0], waypoint[1] - start[1], 0.0)
    length = wp.length(leg)
    along = wp.vec3(1.0, 0.0, 0.0)
    if length > 1.0e-6:
        along = leg / length
    left = wp.vec3(-along[1], along[0], 0.0)
    wanted = layout.count_low + int(wp.randf(state) * float(layout.count_high - layout.count_low + 1))
    wanted = wp.min(wanted, layout.count_high)
    base = first_row[env]
    kept = int(0)
    for slot in range(layout.count_high):
        if slot >= wanted:
            continue
        for attempt in range(layout.attempts):
            t = layout.along_low + (layout.along_high - layout.along_low) * wp.randf(state)
            c = layout.cross_track * (2.0 * wp.randf(state) - 1.0)
            is_pile = wp.randf(state) < layout.pile_fraction
            u = wp.randf(state)
            radius = layout.buoy_radius_low + (layout.buoy_radius_high - layout.buoy_radius_low) * u
            if is_pile:
                radius = layout.pile_radius_low + (layout.pile_radius_high - layout.pile_radius_low) * u
            center = start + (t * length) * along + c * left
            clear = _planar_distance(center, start) - radius >= layout.start_clearance
            clear = clear and _planar_distance(center, waypoint) - radius >= layout.waypoint_clearance
            for other in range(kept):
                placed = rows.anchor[base + other] - origin
                gap = _planar_distance(center, placed) - radius - rows.size[base + other][0]
                clear = clear and gap >= layout.spacing
            if clear:
                k = base + kept
                rows.orientation[k] = wp.quat_identity()
                rows.draft[k] = 0.0
                if is_pile:
                    rows.shape[k] = SHAPE_CYLINDER
                    rows.anchor[k] = origin + wp.vec3(center[0], center[1], 0.5 * layout.pile_half_height)
                    rows.size[k] = wp.vec3(radius, layout.pile_half_height, 0.0)
                    rows.bound[k] = wp.length(wp.vec2(radius, layout.pile_half_height))
                    rows.color[k] = layout.pile_color
                    rows.floats[k] = 0
                    table[env, kept] = wp.vec4(center[0], center[1], radius, float(KIND_PILE))
                else:
                    rows.shape[k] = SHAPE_SPHERE
                    rows.anchor[k] = origin + wp.vec3(center[0], center[1], 0.0)
                    rows.size[k] = wp.vec3(radius, 0.0, 0.0)
                    rows.bound[k] = radius
                    rows.color[k] = layout.buoy_color
                    rows.floats[k] = 1
                    table[env, kept] = wp.vec4(center[0], center[1], radius, float(KIND_BUOY))
                rows.position[k] = rows.anchor[k]
                kept = kept + 1
                break
    for slot in range(kept, layout.count_high):
        _park(rows, base + slot, origin, layout.parked_depth)
        table[env, slot] = wp.vec4(0.0, 0.0, 0.0, 0.0)
    obstacle_count[env] = kept


@wp.kernel(enable_backward=False)
def append_sectors(sectors: wp.array2d(dtype=float), policy_column: int, critic_column: int,
                   policy: wp.array2d(dtype=float), critic: wp.array2d(dtype=float)):
    """The lidar's nearest return per sector (over its max range, in [0, 1]) into the observations, from
    column ``policy_column`` of the policy's and ``critic_column`` of the critic's."""
    env, sector = wp.tid()
    value = sectors[env, sector]
    policy[env, policy_column + sector] = value
    critic[env, critic_column + sector] = value
