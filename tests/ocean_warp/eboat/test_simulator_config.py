"""Simulator and hydrodynamics configs: clear errors, and the optional slamming term."""

import math

import numpy as np
import pytest

import ocean_warp as ow
from tests.hull_setups import calm_ocean


@pytest.mark.parametrize("field,value,message", [
    ("dt", 0.0, "dt must be > 0"),
    ("dt", math.nan, "dt must be a number > 0"),
    ("substeps", 0, r"substeps must be an integer in \[1, 1000\]"),
    ("max_tilt", 4.0, r"max_tilt must be in \[0.0, 3.14"),
    ("block_dim", 4096, r"block_dim must be an integer in \[1, 1024\]"),
    ("hydrodynamics", "water", "hydrodynamics must be a HydrodynamicsConfig"),
])
def test_bad_simulator_config(field, value, message):
    with pytest.raises(ValueError, match=r"SimulatorConfig\." + message):
        ow.SimulatorConfig(**{field: value})


@pytest.mark.parametrize("field,value,message", [
    ("pressure_drag_quadratic", -5.0, "pressure_drag_quadratic must be >= 0"),
    ("suction_falloff", math.inf, "suction_falloff must be finite"),
    ("skin_friction", 1, "skin_friction must be True or False"),
])
def test_bad_hydrodynamics_config(field, value, message):
    with pytest.raises(ValueError, match=r"HydrodynamicsConfig\." + message):
        ow.HydrodynamicsConfig(**{field: value})


def test_simulator_refuses_mismatched_devices(device):
    fleet = ow.Fleet(ow.BoatType.floating_solid(ow.Hull.box(1.0, 1.0, 1.0)), 2, device=device)
    if fleet.device.is_cuda:
        with pytest.raises(ValueError, match="the ocean is on cpu"):
            ow.Simulator(calm_ocean("cpu"), fleet)


def test_slamming_brakes_a_hull_that_hits_the_water(device):
    """A box dropped flat onto still water meets a larger peak force with slamming on than off."""
    peaks = {}
    for slamming in (False, True):
        boat = ow.BoatType.floating_solid(ow.Hull.box(2.0, 1.0, 0.5, subdivisions=2), draft_fraction=0.4)
        fleet = ow.Fleet(boat, 1, device=device)
        fleet.reset(position=[0.0, 0.0, 0.3], velocity=[0, 0, -4.0, 0, 0, 0])
        hydro = ow.HydrodynamicsConfig(slamming=slamming, slamming_max_acceleration=50.0)
        simulator = ow.Simulator(calm_ocean(device), fleet, ow.SimulatorConfig(dt=0.005, substeps=2,
                                                                                hydrodynamics=hydro))
        forces = []
        for _ in range(60):
            simulator.step()
            forces.append(fleet.numpy()["hydro_wrench"][0, 2])
        assert np.all(np.isfinite(forces))
        peaks[slamming] = max(forces)
    assert peaks[True] > 1.2 * peaks[False]
