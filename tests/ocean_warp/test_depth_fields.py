"""An ocean that leaves out the pressure at depth and the motion below (for hulls that read only the surface)."""

import numpy as np
import pytest

import ocean_warp as ow
from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig


def random_sea(rng) -> ow.OceanConfig:
    return ow.OceanConfig(tile_size=float(rng.uniform(100, 300)), resolution=32,
                          significant_wave_height=float(rng.uniform(0.3, 2.0)), peak_period=float(rng.uniform(3, 8)),
                          choppiness=float(rng.uniform(0.0, 1.0)), seed=int(rng.integers(2**31)))


def test_surface_fields_are_the_same_and_the_depth_fields_zero(device, rng):
    """Without its depth fields an ocean's surface fields (height, displacement, slope, velocity) are bit for bit
    those of the full ocean at a random time, and fields 4-6 stay zero where the full ocean's are not."""
    config = random_sea(rng)
    full, surface_only = ow.Ocean(config, device=device), ow.Ocean(config, device=device, depth_fields=False)
    t = float(rng.uniform(0.0, 100.0))
    full.update(t)
    surface_only.update(t)
    every, some = full.fields.numpy(), surface_only.fields.numpy()
    np.testing.assert_array_equal(some[:4], every[:4])
    assert np.all(some[4:] == 0.0) and np.abs(every[4:]).max() > 0.01


def test_the_four_point_boat_gets_an_ocean_without_them_and_the_mesh_boat_one_with_them(device):
    points = EBoatSimulator(EBoatSimulatorConfig(boat=EBoatConfig(profile="seed")), 2, device=device)
    mesh = EBoatSimulator(EBoatSimulatorConfig(), 2, device=device)
    assert not points.ocean.depth_fields and mesh.ocean.depth_fields


def test_a_mesh_hull_on_an_ocean_without_them_and_a_bad_switch_are_refused(device):
    ocean = ow.Ocean(ow.OceanConfig(resolution=16, tile_size=50.0), device=device, depth_fields=False)
    with pytest.raises(ValueError, match="pressure at depth"):
        EBoatSimulator(EBoatSimulatorConfig(), 1, device=device, ocean=ocean)
    with pytest.raises(ValueError, match="depth_fields must be True or False"):
        ow.Ocean(ow.OceanConfig(resolution=16, tile_size=50.0), device=device, depth_fields="no")
