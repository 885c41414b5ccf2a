"""The E-Boat simulator's config, named views and device resets."""

import dataclasses
import math

import numpy as np
import pytest
import warp as wp

import ocean_warp as ow
from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.frames import quaternion_from_roll_pitch_yaw
from ocean_warp.torch_streams import ordered_with_torch


def test_water_has_one_source():
    """The sea's water (OceanConfig.water) reaches the hull pass, the rig, the buoyancy points, the rigid
    bodies' weight and the accelerometers; an ocean of other water is refused by name."""
    water = ow.WaterConfig(density=997.0, gravity=9.815)
    config = EBoatSimulatorConfig(ocean=dataclasses.replace(EBoatSimulatorConfig().ocean, water=water))
    assert config.water is config.ocean.water
    sim = EBoatSimulator(config, 1, device="cpu")
    assert sim.sensors._model.gravity == pytest.approx(9.815)
    assert sim.rig.parameters.water_density == pytest.approx(997.0)
    assert sim.simulator.water.density == pytest.approx(997.0)
    assert sim.simulator.water.gravity == pytest.approx(9.815)
    points = EBoatSimulator(dataclasses.replace(config, boat=EBoatConfig(hydrostatics="points")), 1, device="cpu")
    buoyancy = points.simulator.models[1].parameters
    assert buoyancy.density == pytest.approx(997.0) and buoyancy.gravity == pytest.approx(9.815)
    with pytest.raises(ValueError, match="the boats sail in the water of the ocean they float on"):
        EBoatSimulator(config, 1, device="cpu", ocean=ow.Ocean(EBoatSimulatorConfig().ocean, device="cpu"))
    with pytest.raises(ValueError, match=r"WaterConfig\.density must be > 0"):
        ow.WaterConfig(density=-1.0)
    with pytest.raises(ValueError, match=r"WaterConfig\.gravity must be > 0"):
        ow.WaterConfig(gravity=0.0)
    with pytest.raises(ValueError, match=r"OceanConfig\.water must be a WaterConfig"):
        ow.OceanConfig(water=1025.0)


@pytest.mark.parametrize("field,value,message", [
    ("dt", math.nan, "dt must be a number > 0"),
    ("substeps", 0, r"substeps must be an integer in \[1, 1000\]"),
    ("wind", 5.0, "wind must be a WindConfig"),
    ("max_tilt", 4.0, r"max_tilt must be in \[0.0, 3.14"),
])
def test_bad_simulator_config_names_the_field(field, value, message):
    with pytest.raises(ValueError, match=r"EBoatSimulatorConfig\." + message):
        EBoatSimulatorConfig(**{field: value})


def test_views_share_memory_and_are_bound_at_construction(device):
    sim = EBoatSimulator(None, 5, device=device)
    tensors = sim.tensors
    for view, arrays in ((tensors.state, sim.state), (tensors.control, sim.control), (tensors.start, sim.start)):
        for name in arrays.names():
            assert getattr(view, name).data_ptr() == getattr(arrays, name).ptr, name
    assert tensors.state.position.shape == (5, 3) and tensors.state.readings.shape == (5, 16)
    assert tensors.control.propeller.dtype.is_floating_point is False


def test_masked_reset_changes_exactly_the_chosen_boats(device, rng):
    count = 12
    config = EBoatSimulatorConfig(wind=ow.WindConfig(speed=6.0, gust_speed_std=1.0, gust_direction_std=0.1),
                                  sensors=ow.SensorConfig.noise_free())
    sim = EBoatSimulator(config, count, device=device)
    sim.reset(position=np.column_stack([rng.uniform(-40, 40, (count, 2)), np.full(count, 0.05)]),
              heading=rng.uniform(-math.pi, math.pi, count), velocity=[1.0, 0, 0, 0, 0, 0], sheet=0.6)
    control = sim.tensors.control
    control.rudder[:] = control.rudder.new_tensor(rng.uniform(-0.3, 0.3, count))
    control.propeller[:] = 2
    for _ in range(10):
        sim.step()
    before = {name: getattr(sim.state, name).numpy().copy() for name in sim.state.names()}
    chosen = rng.permutation(count)[:5]
    mask = np.zeros(count, dtype=np.int32)
    mask[chosen] = 1
    positions = np.column_stack([rng.uniform(-50, 50, (count, 2)), rng.uniform(0.0, 0.1, count)])
    headings = rng.uniform(-math.pi, math.pi, count)
    start = sim.tensors.start
    start.position[:] = start.position.new_tensor(positions)
    start.orientation[:] = start.orientation.new_tensor(quaternion_from_roll_pitch_yaw(
        np.column_stack([np.zeros(count), np.zeros(count), headings])))
    start.velocity.zero_()
    start.sheet[:] = start.sheet.new_tensor(rng.uniform(0.1, 1.0, count))
    start.wind_speed[:] = start.wind_speed.new_tensor(rng.uniform(2, 10, count))
    start.wind_direction[:] = start.wind_direction.new_tensor(rng.uniform(-3, 3, count))
    with ordered_with_torch(sim.device):
        sim.reset_masked(wp.array(mask, dtype=wp.int32, device=device))
    after = {name: getattr(sim.state, name).numpy() for name in sim.state.names()}
    others = np.setdiff1d(np.arange(count), chosen)
    for name in sim.state.names():
        if name != "time":
            np.testing.assert_array_equal(after[name][others], before[name][others], err_msg=name)
    np.testing.assert_allclose(after["position"][chosen], positions[chosen], atol=1e-6)
    np.testing.assert_allclose(after["velocity"][chosen], 0.0)
    np.testing.assert_allclose(after["wind_mean_speed"][chosen], start.wind_speed.cpu().numpy()[chosen], rtol=1e-6)
    np.testing.assert_allclose(after["wind_speed"][chosen], after["wind_mean_speed"][chosen])
    np.testing.assert_allclose(after["sheet_limit"][chosen], start.sheet.cpu().numpy()[chosen], rtol=1e-6)
    np.testing.assert_array_equal(after["rudder_angle"][chosen], 0.0)
    np.testing.assert_array_equal(after["boom_angle"][chosen], 0.0)
    np.testing.assert_array_equal(sim.control.propeller.numpy()[chosen], 0)
    np.testing.assert_array_equal(sim.control.propeller.numpy()[others], 2)
    # The sensors read the new state at once: GNSS at the new place, compass on the new heading.
    np.testing.assert_allclose(after["truth"][chosen, 0:3], positions[chosen], atol=1e-5)
    np.testing.assert_allclose(np.angle(np.exp(1j * (after["truth"][chosen, 12] - headings[chosen]))), 0.0, atol=1e-5)
    np.testing.assert_array_equal(after["readings"][chosen], after["truth"][chosen])
