"""The Warp hull-force kernels against the independent numpy implementation in reference_hull.py, on
random hulls, poses, velocities, coefficients and choppy seas."""

import dataclasses
import math

import numpy as np
import pytest

import ocean_warp as ow
from tests import reference_hull
from tests.hull_setups import random_rotations, rotation_matrix


def periodic_bilinear(field: np.ndarray, cell: float, points: np.ndarray) -> np.ndarray:
    """numpy's bilinear interpolation of a periodic grid field [iy, ix] at world points (M, 2) [m]."""
    n = field.shape[0]
    g = points / cell
    i0 = np.floor(g).astype(np.int64)
    t = g - i0
    ix0, iy0 = i0[:, 0] % n, i0[:, 1] % n
    ix1, iy1 = (ix0 + 1) % n, (iy0 + 1) % n
    lower = (1 - t[:, 0]) * field[iy0, ix0] + t[:, 0] * field[iy0, ix1]
    upper = (1 - t[:, 0]) * field[iy1, ix0] + t[:, 0] * field[iy1, ix1]
    return (1 - t[:, 1]) * lower + t[:, 1] * upper


def pressure_heads(ocean: ow.Ocean, sample, z: np.ndarray) -> np.ndarray:
    """p / (rho g) [m] at heights z under the sampled surface points: hydrostatic up to the surface above still
    water; below it -z plus the waves' dynamic head, linear in z between the surface and the ocean's three
    depths (each field read at the sample's grid position) and held below the deepest."""
    height = sample.height.astype(np.float64)
    levels = [0.0] + [-d for d in ocean.config.pressure_depths]
    heads = [height] + [periodic_bilinear(ocean.field_numpy(f"pressure_head_{k}").astype(np.float64),
                                          ocean.config.cell_size, sample.grid_position.astype(np.float64))
                        for k in (1, 2, 3)]
    dynamic = heads[3].copy()
    for upper in range(3):
        z0, z1 = levels[upper], levels[upper + 1]
        inside = (z <= z0) & (z >= z1)
        fraction = (z - z0) / (z1 - z0)
        dynamic = np.where(inside, heads[upper] + fraction * (heads[upper + 1] - heads[upper]), dynamic)
    return np.where(z >= 0.0, height - z, dynamic - z)


@pytest.mark.parametrize("falloffs", ["random", "special"])
def test_hull_wrenches_match_numpy_reference(device, rng, falloffs):
    """``falloffs``: random exponents of the drag's cos t, or 0.5 and 1, which the kernel takes without pow."""
    hulls = [ow.Hull.box(float(rng.uniform(1, 4)), float(rng.uniform(0.5, 2)), float(rng.uniform(0.4, 1.2)),
                         subdivisions=1),
             ow.Hull.ellipsoid(*rng.uniform(0.3, 1.5, size=3), subdivisions=2)]
    types = [ow.BoatType.floating_solid(h, draft_fraction=float(rng.uniform(0.2, 0.8))) for h in hulls]
    count = 10
    fleet = ow.Fleet(types, types=rng.integers(0, 2, size=count), device=device)
    ocean = ow.Ocean(ow.OceanConfig(tile_size=float(rng.uniform(60, 150)), resolution=64,
                                    significant_wave_height=float(rng.uniform(0.5, 2.0)),
                                    peak_period=float(rng.uniform(4, 8)), choppiness=float(rng.uniform(0, 0.8)),
                                    direction=float(rng.uniform(-np.pi, np.pi)), seed=int(rng.integers(2**31)),
                                    water=ow.WaterConfig(density=float(rng.uniform(990, 1030)),
                                                         gravity=float(rng.uniform(9.78, 9.83)),
                                                         kinematic_viscosity=float(rng.uniform(1.0e-6, 1.4e-6)))),
                     device=device)
    ocean.update(float(rng.uniform(0, 500)))
    hydro = dataclasses.replace(
        ow.HydrodynamicsConfig(), pressure_drag_linear=float(rng.uniform(0, 300)),
        pressure_drag_quadratic=float(rng.uniform(0, 900)), suction_linear=float(rng.uniform(0, 300)),
        suction_quadratic=float(rng.uniform(0, 900)), pressure_drag_falloff=float(rng.uniform(0.2, 2)) if falloffs == "random" else 0.5,
        suction_falloff=float(rng.uniform(0.2, 2)) if falloffs == "random" else 1.0)
    positions = np.column_stack([rng.uniform(-200, 200, size=(count, 2)), rng.uniform(-0.8, 0.4, size=count)])
    orientations = random_rotations(rng, count, max_angle=math.pi)
    velocities = np.concatenate([rng.uniform(-3, 3, size=(count, 3)), rng.uniform(-1, 1, size=(count, 3))], axis=1)
    fleet.reset(position=positions, orientation=orientations, velocity=velocities)
    simulator = ow.Simulator(ocean, fleet, ow.SimulatorConfig(hydrodynamics=hydro))
    simulator.compute_hull_wrenches()
    wrenches = fleet.forces.hydro_wrench.numpy()

    type_of_boat = fleet.model.hull_type.numpy()
    submerged_boats = 0
    for boat in range(count):
        hull = hulls[type_of_boat[boat]]
        rotation = rotation_matrix(orientations[boat])
        world = positions[boat] + hull.vertices @ rotation.T
        sample = ocean.sample(world[:, :2])
        depth = pressure_heads(ocean, sample, world[:, 2])
        flow = sample.velocity.astype(np.float64) @ rotation  # world -> body
        boat_flow = ocean.sample(positions[boat, :2]).velocity[0].astype(np.float64) @ rotation
        expected = reference_hull.hull_wrench(hull.vertices, hull.triangles, depth, flow, velocities[boat], hydro,
                                              boat_flow, ocean.config.water)
        submerged_boats += bool((depth > 0).any() and (depth <= 0).any())
        force_scale = ocean.config.water.density * ocean.config.water.gravity * hull.volume
        moment_scale = force_scale * np.ptp(hull.vertices, axis=0).max()
        np.testing.assert_allclose(wrenches[boat, :3], expected[:3], rtol=0, atol=2e-4 * force_scale)
        np.testing.assert_allclose(wrenches[boat, 3:], expected[3:], rtol=0, atol=2e-4 * moment_scale)
    assert submerged_boats >= 3, "too few boats cut the waterline to test the clipping"
