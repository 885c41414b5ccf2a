"""The WAM-V's physics hull: two closed pontoons, procedural (our own mesh, not VRX's visual model)."""

from __future__ import annotations

import math

import numpy as np

from ..hull import Hull
from .config import WamvConfig

__all__ = ["wamv_hull_mesh", "section_radius"]


def section_radius(radius: float, sides: int) -> float:
    """Circumradius [m] of the regular ``sides``-gon whose area is that of a circle of ``radius`` [m]: the pontoon's
    polygonal section displaces what the round pontoon does when fully immersed."""
    return radius * math.sqrt(2.0 * math.pi / (sides * math.sin(2.0 * math.pi / sides)))


def _pontoon(config: WamvConfig, y: float) -> tuple[np.ndarray, np.ndarray]:
    """One pontoon along x at ``y`` [m]: ``pontoon_stations + 1`` rings of ``pontoon_sides`` vertices (one at the
    keel line) and a centre vertex on each flat end, wound outward."""
    sides, stations = config.pontoon_sides, config.pontoon_stations
    radius = section_radius(config.pontoon_radius, sides)
    angles = -0.5 * math.pi + 2.0 * math.pi * np.arange(sides) / sides  # counter-clockwise seen from the bow
    half = 0.5 * config.pontoon_length
    xs = np.linspace(config.pontoon_center_x - half, config.pontoon_center_x + half, stations + 1)
    rings = np.stack([np.column_stack([np.full(sides, x), y + radius * np.cos(angles), radius * np.sin(angles)])
                      for x in xs]).reshape(-1, 3)
    stern_center, bow_center = len(rings), len(rings) + 1
    vertices = np.concatenate([rings, [[xs[0], y, 0.0], [xs[-1], y, 0.0]]])
    triangles = []
    for k in range(stations):
        for j in range(sides):
            a, b = k * sides + j, k * sides + (j + 1) % sides
            triangles += [(a, b + sides, a + sides), (a, b, b + sides)]
    last = stations * sides
    for j in range(sides):
        triangles.append((stern_center, (j + 1) % sides, j))
        triangles.append((bow_center, last + j, last + (j + 1) % sides))
    return vertices, np.asarray(triangles, dtype=np.int64)


def wamv_hull_mesh(config: WamvConfig | None = None) -> Hull:
    """The two pontoons of ``config`` (default VRX's) as one closed mesh in the body frame (FLU, origin midway
    between their axes, at their height): cylinders of ``pontoon_length`` with flat ends, as VRX's buoyancy takes
    them, their polygonal section of ``pontoon_sides`` sides with the round section's area, ``pontoon_stations``
    segments along. The frame, beams and deck stay out of the water and out of the physics mesh."""
    config = config if config is not None else WamvConfig()
    half = 0.5 * config.pontoon_spacing
    left_vertices, left_triangles = _pontoon(config, half)
    right_vertices, right_triangles = _pontoon(config, -half)
    vertices = np.concatenate([left_vertices, right_vertices])
    triangles = np.concatenate([left_triangles, right_triangles + len(left_vertices)])
    return Hull(vertices, triangles, name="wamv pontoons")
