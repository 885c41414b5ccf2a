"""Lumped buoyancy at a few points, as in the VRX-style Gazebo twins (the original E-Boat model).

Each point carries the buoyancy of a slice of a horizontal cylinder of radius R and length l:
rho g l S(R, h), S the area of the circle segment of depth h = clamp(surface height - point height, 0, R),

    S(R, h) = R^2 acos((R - h) / R) - (R - h) sqrt(2 R h - h^2),

pushing straight up (world z) at the point.
"""

from __future__ import annotations

import warp as wp

from .ocean_surface import OceanSurface, surface_height
from .spatial import vec6, wrench_at

__all__ = ["PointBuoyancy", "circle_segment_area", "point_buoyancy"]



@wp.struct
class PointBuoyancy:
    points: wp.array(dtype=wp.vec3)
    """Points in the body frame [m]."""
    radius: float
    """R [m]."""
    slice_length: float
    """l [m] of cylinder each point stands for."""
    density: float
    """Water [kg/m^3]."""
    gravity: float
    """[m/s^2]"""


@wp.func
def circle_segment_area(radius: float, depth: float) -> float:
    """Area [m^2] of the segment of a circle of ``radius`` cut at ``depth`` below its top (0..radius)."""
    h = wp.clamp(depth, 0.0, radius)
    rest = radius - h
    return radius * radius * wp.acos(rest / radius) - rest * wp.sqrt(wp.max(2.0 * radius * h - h * h, 0.0))


@wp.kernel(enable_backward=False)
def point_buoyancy(
    buoyancy: PointBuoyancy,
    surface: OceanSurface,
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    model_wrench: wp.array(dtype=vec6),
):
    """Add the points' buoyancy to each boat's model wrench (body frame, about the origin)."""
    boat = wp.tid()
    rotation = orientation[boat]
    origin = position[boat]
    up_body = wp.quat_rotate_inv(rotation, wp.vec3(0.0, 0.0, 1.0))
    total = model_wrench[boat]
    for k in range(buoyancy.points.shape[0]):
        point = buoyancy.points[k]
        world = origin + wp.quat_rotate(rotation, point)
        depth = surface_height(surface, wp.vec2(world[0], world[1])) - world[2]
        lift = buoyancy.density * buoyancy.gravity * buoyancy.slice_length * circle_segment_area(buoyancy.radius, depth)
        total += wrench_at(lift * up_body, point)
    model_wrench[boat] = total
