"""An independent numpy implementation of the per-triangle water-force model, for the tests.

It shares the model's definition with the Warp kernels (see ocean_warp.HydrodynamicsConfig) but not
their code or algorithms: triangles are clipped as polygons (Sutherland-Hodgman against depth > 0)
and fanned from the first corner after the dry ones, and the pressure integrals use quadrature
rules (centroid rule for the force, edge-midpoint rule, exact for quadratics, for its moment)
instead of closed forms. Everything in float64.
"""

from __future__ import annotations

import numpy as np


def clip_submerged(corners: np.ndarray, depths: np.ndarray, flows: np.ndarray):
    """The polygon of a triangle where depth > 0, as lists of points, depths and water velocities,
    starting at the first corner that follows a dry one (so the fan matches the model's split)."""
    points, point_depths, point_flows = [], [], []
    for i in range(3):
        j = (i + 1) % 3
        if depths[i] > 0.0:
            points.append(corners[i])
            point_depths.append(depths[i])
            point_flows.append(flows[i])
        if (depths[i] > 0.0) != (depths[j] > 0.0):
            wet, dry = (i, j) if depths[i] > 0.0 else (j, i)
            t = depths[wet] / (depths[wet] - depths[dry])
            points.append(corners[wet] + t * (corners[dry] - corners[wet]))
            point_depths.append(0.0)
            point_flows.append(flows[wet] + t * (flows[dry] - flows[wet]))
    dry = [i for i in range(3) if depths[i] <= 0.0]
    if len(dry) == 1 and len(points) == 4:
        # Start the fan at the cut point on the edge from the dry corner a to the next corner b.
        a = dry[0]
        b = (a + 1) % 3
        cut_ab = corners[b] + (depths[b] / (depths[b] - depths[a])) * (corners[a] - corners[b])
        start = int(np.argmin([np.linalg.norm(p - cut_ab) for p in points]))
        order = [(start + k) % 4 for k in range(4)]
        points = [points[k] for k in order]
        point_depths = [point_depths[k] for k in order]
        point_flows = [point_flows[k] for k in order]
    return points, point_depths, point_flows


def piece_wrench(r, d, u, linear, angular, friction, config, water) -> np.ndarray:
    """(force, moment about the origin) on one submerged triangle, body frame, in ``water`` (a WaterConfig)."""
    area_vector = 0.5 * np.cross(r[1] - r[0], r[2] - r[0])
    area = np.linalg.norm(area_vector)
    if area < 1e-12:
        return np.zeros(6)
    normal = area_vector / area
    rho_g = water.density * water.gravity
    pressure = rho_g * np.asarray(d)
    force = -pressure.mean() * area_vector
    midpoints = [0.5 * (r[i] + r[(i + 1) % 3]) for i in range(3)]
    mid_pressure = [0.5 * (pressure[i] + pressure[(i + 1) % 3]) for i in range(3)]
    first_moment = area / 3.0 * sum(p * m for p, m in zip(mid_pressure, midpoints))  # int p r dA
    moment = -np.cross(first_moment, normal)

    centroid = np.mean(r, axis=0)
    relative = linear + np.cross(angular, centroid) - np.mean(u, axis=0)
    speed = np.linalg.norm(relative)
    if speed > 1e-6:
        cos_t = normal @ relative / speed
        s = speed / config.reference_speed
        if cos_t > 0.0:
            drag = -(config.pressure_drag_linear * s + config.pressure_drag_quadratic * s**2) \
                * cos_t**config.pressure_drag_falloff * area * normal
        else:
            drag = (config.suction_linear * s + config.suction_quadratic * s**2) \
                * (-cos_t)**config.suction_falloff * area * normal
        if config.skin_friction:
            tangential = relative - (relative @ normal) * normal
            drag = drag - 0.5 * water.density * friction * area * np.linalg.norm(tangential) * tangential
        force = force + drag
        moment = moment + np.cross(centroid, drag)
    return np.concatenate([force, moment])


def ittc_friction(speed: float, length: float, viscosity: float) -> float:
    reynolds = max(speed * length / viscosity, 1e5)
    return 0.075 / (np.log10(reynolds) - 2.0) ** 2


def hull_wrench(vertices, triangles, depth, flow, nu, config, boat_flow, water) -> np.ndarray:
    """Wrench (Fx, Fy, Fz, Mx, My, Mz), body frame, about the origin, on one hull.

    vertices (V, 3) [m] and triangles (T, 3) of the hull; depth (V,) [m] below the local surface and
    flow (V, 3) water velocity [m/s] per vertex in the body frame; nu (6,) Fossen velocity; boat_flow
    (3,) water velocity at the origin (body frame), for the Reynolds number; ``config`` the hull model
    (HydrodynamicsConfig), ``water`` its water (WaterConfig)."""
    linear, angular = np.asarray(nu[:3], float), np.asarray(nu[3:], float)
    length = np.ptp(vertices[:, 0])
    friction = ittc_friction(np.linalg.norm(linear - boat_flow), length, water.kinematic_viscosity)
    total = np.zeros(6)
    for corners in triangles:
        points, point_depths, point_flows = clip_submerged(vertices[corners], depth[corners], flow[corners])
        for k in range(1, len(points) - 1):
            fan = [0, k, k + 1]
            total += piece_wrench([points[i] for i in fan], [point_depths[i] for i in fan],
                                  [point_flows[i] for i in fan], linear, angular, friction, config, water)
    return total
