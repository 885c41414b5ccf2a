"""Kerner's slamming force on one triangle against the formula in numpy, from two substeps of history."""

import numpy as np
import pytest
import warp as wp

import ocean_warp as ow
from ocean_warp.kernels.hull_forces import NO_SWEPT_RATE, WaterModel, slamming_wrench
from ocean_warp.kernels.spatial import vec6
from ocean_warp.simulator import _water_model
from tests.reference_hull import clip_submerged


@wp.kernel
def _two_substeps(corners: wp.array(dtype=wp.vec3), before: wp.array(dtype=wp.vec4), after: wp.array(dtype=wp.vec4),
                  velocity: wp.vec3, angular_velocity: wp.vec3, mass: float, hull_area: float, water: WaterModel,
                  swept_rate: wp.array(dtype=float), out: wp.array(dtype=vec6)):
    r0, r1, r2 = corners[0], corners[1], corners[2]
    out[0] = slamming_wrench(r0, r1, r2, before[0], before[1], before[2], velocity, angular_velocity, mass,
                             hull_area, swept_rate, 0, water)
    out[1] = slamming_wrench(r0, r1, r2, after[0], after[1], after[2], velocity, angular_velocity, mass,
                             hull_area, swept_rate, 0, water)


def polygon_area(points):
    """Area of a planar polygon: half the length of its vector area."""
    return 0.5 * np.linalg.norm(sum(np.cross(points[i], points[(i + 1) % len(points)]) for i in range(len(points))))


def submerged_area(corners, depths):
    points, _, _ = clip_submerged(corners, depths, np.zeros((3, 3)))
    return 0.0 if len(points) < 3 else polygon_area([np.asarray(p) for p in points])


@pytest.mark.parametrize("saturated", [False, True], ids=["ramping", "saturated"])
def test_slamming_force_follows_kerners_formula(device, rng, saturated):
    corners = rng.uniform(-1.0, 1.0, size=(3, 3))
    area_vector = 0.5 * np.cross(corners[1] - corners[0], corners[2] - corners[0])
    area = np.linalg.norm(area_vector)
    normal = area_vector / area
    flows = rng.uniform(-0.2, 0.2, size=(3, 3))
    angular = rng.uniform(-0.3, 0.3, size=3)
    centroid = corners.mean(axis=0)
    # Moving along its outward normal into the water (cos t > 0), with some sideways slip.
    relative = rng.uniform(2.0, 5.0) * normal + rng.uniform(-0.5, 0.5, size=3)
    relative += max(0.0, 1.0 - relative @ normal) * normal
    velocity = relative - np.cross(angular, centroid) + flows.mean(axis=0)
    # Two substeps: a corner or two wet, then deeper (the submerged area grows).
    wet, dry, third = rng.permutation(3)
    depths_before = np.empty(3)
    depths_before[[wet, dry, third]] = rng.uniform(0.05, 0.2), rng.uniform(-0.4, -0.05), rng.uniform(-0.4, 0.2)
    depths_after = depths_before + rng.uniform(0.1, 0.3)
    dt, mass, hull_area, power = rng.uniform(0.002, 0.01), rng.uniform(50, 500), rng.uniform(5.0, 20.0), rng.uniform(1, 3)

    speed = np.linalg.norm(relative)
    rate_before = submerged_area(corners, depths_before) * speed
    submerged = submerged_area(corners, depths_after)
    growth = (submerged * speed - rate_before) / (area * dt)
    assert growth > 0
    max_acceleration = growth * (0.5 if saturated else rng.uniform(1.5, 4.0))
    water = _water_model(ow.HydrodynamicsConfig(slamming=True, slamming_power=power,
                                                slamming_max_acceleration=max_acceleration), ow.WaterConfig(), dt)

    swept_rate = wp.array([float(NO_SWEPT_RATE)], dtype=float, device=device)
    out = wp.zeros(2, dtype=vec6, device=device)
    as_vec4 = lambda depths: wp.array(np.column_stack([depths, flows]), dtype=wp.vec4, device=device)  # noqa: E731
    wp.launch(_two_substeps, dim=1, device=device,
              inputs=[wp.array(corners, dtype=wp.vec3, device=device), as_vec4(depths_before), as_vec4(depths_after),
                      wp.vec3(*velocity), wp.vec3(*angular), mass, hull_area, water, swept_rate], outputs=[out])
    first, second = out.numpy().astype(np.float64)

    np.testing.assert_array_equal(first, np.zeros(6))  # no history yet: no slamming
    assert swept_rate.numpy()[0] == pytest.approx(submerged * speed, rel=1e-4)
    ramp = min(growth / max_acceleration, 1.0) ** power
    cos_t = relative @ normal / speed
    force = -ramp * cos_t * mass * 2.0 * submerged / (hull_area * dt) * relative
    scale = np.linalg.norm(force)
    np.testing.assert_allclose(second[:3], force, rtol=0, atol=1e-4 * scale)
    np.testing.assert_allclose(second[3:], np.cross(centroid, force), rtol=0, atol=1e-4 * scale * 2.0)
