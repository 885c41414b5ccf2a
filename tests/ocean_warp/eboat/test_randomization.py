"""Domain randomisation: mass variants, foil coefficients, sensor noise and the sea state."""

import dataclasses
import math

import numpy as np
import pytest

import ocean_warp as ow
from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.envs import SailingEnv, StartConfig, WaypointConfig
from ocean_warp.sensors import CHANNEL_NAMES

THRUST_PER_LEVEL = 24.02
"""[N] a propeller level ahead (the sheet)."""


# --- mass ------------------------------------------------------------------------------------------

@pytest.mark.parametrize("hydrostatics", ["points", "mesh"])
def test_mass_variants_accelerate_as_their_mass(device, hydrostatics):
    """Boats at rest in still water and calm air, propeller at level 5: the thrust's share of the first
    step's surge acceleration (the difference to a twin without thrust) goes as 1 / mass."""
    k, variation = 3, 0.2
    config = EBoatSimulatorConfig(boat=EBoatConfig(hydrostatics=hydrostatics), wind=ow.WindConfig(speed=0.0),
                                  sensors=ow.SensorConfig.noise_free(), mass_variation=variation, mass_variants=k)
    sim = EBoatSimulator(config, 2 * k, device=device)
    factors = np.linspace(1.0 - variation, 1.0 + variation, k)
    np.testing.assert_allclose(sim.mass_scale, np.tile(factors, 2))
    base = sim.eboat.boat_type
    assert len(sim.fleet.model.boat_types) == k
    np.testing.assert_array_equal(sim.fleet.model.hull_type.numpy(), np.arange(2 * k) % k)
    for factor, variant in zip(factors, sim.fleet.model.boat_types):
        assert variant.mass == pytest.approx(factor * base.mass)
        np.testing.assert_allclose(variant.inertia, factor * base.inertia)
        np.testing.assert_array_equal(variant.center_of_mass, base.center_of_mass)
        np.testing.assert_array_equal(variant.added_mass, base.added_mass)  # the water's, not the boat's
        np.testing.assert_array_equal(variant.linear_damping, base.linear_damping)
        assert variant.hull is base.hull
    assert base.added_mass[0, 0] == 0.0  # the E-Boat has no surge added mass (sheet)

    height = 0.0 if hydrostatics == "points" else sim.eboat.rest_height("cpu", config.water)
    sim.reset(position=[0.0, 0.0, height], wind_speed=0.0)
    sim.tensors.control.propeller[:k] = 5
    sim.step()
    nu = sim.state.velocity.numpy()
    surge = (nu[:k, 0] - nu[k:, 0]) / config.dt
    thrust = 5 * THRUST_PER_LEVEL
    # Ratios between variants: the inverse mass ratio.
    np.testing.assert_allclose(surge / surge[k // 2], 1.0 / factors, rtol=0.02)
    # Absolute: the rigid body's answer M^-1 f to the thrust at the propeller ...
    propeller = np.array(sim.rig.parameters.propeller_position)
    wrench = np.concatenate([[thrust, 0.0, 0.0], np.cross(propeller, [thrust, 0.0, 0.0])])
    expected = np.array([np.linalg.solve(variant.mass_matrix, wrench)[0] for variant in sim.fleet.model.boat_types])
    np.testing.assert_allclose(surge, expected, rtol=0.02)
    # ... which is T / m but for the pitch the thrust below the centre of mass starts (about 6 %).
    np.testing.assert_allclose(surge, thrust / (factors * base.mass), rtol=0.1)


def test_no_mass_variation_builds_the_single_type_fleet_as_before(device):
    sim = EBoatSimulator(EBoatSimulatorConfig(mass_variants=7), 4, device=device)
    assert sim.fleet.model.boat_types == [sim.eboat.boat_type]
    np.testing.assert_array_equal(sim.fleet.model.hull_type.numpy(), 0)
    np.testing.assert_array_equal(sim.mass_scale, 1.0)
    assert EBoatSimulatorConfig(mass_variation=0.1, mass_variants=1).mass_factors().tolist() == [1.0]


@pytest.mark.parametrize("field,value,message", [
    ("mass_variation", 0.31, r"mass_variation must be in \[0.0, 0.3\]"),
    ("mass_variation", -0.1, r"mass_variation must be in \[0.0, 0.3\]"),
    ("mass_variants", 0, r"mass_variants must be an integer in \[1, 64\]"),
    ("mass_variants", 2.0, r"mass_variants must be an integer in \[1, 64\]"),
])
def test_bad_mass_randomisation_names_the_field(field, value, message):
    with pytest.raises(ValueError, match=r"EBoatSimulatorConfig\." + message):
        EBoatSimulatorConfig(**{field: value})


# --- foils -----------------------------------------------------------------------------------------

def test_foil_factors_scale_each_foils_force_exactly(device):
    """Boats in the same state under the same commands, each with one foil (or none) switched on by its
    start row: the rig's wrench less the no-foil boat's (windage and thrust) scales with the factor."""
    scales = np.array([[0.0, 0.0, 0.0],
                       [1.0, 0.0, 0.0], [1.07, 0.0, 0.0],
                       [0.0, 1.0, 0.0], [0.0, 1.07, 0.0],
                       [0.0, 0.0, 1.0], [0.0, 0.0, 1.07]], dtype=np.float32)
    count = len(scales)
    config = EBoatSimulatorConfig(boat=EBoatConfig(hydrostatics="points"), sensors=ow.SensorConfig.noise_free())
    sim = EBoatSimulator(config, count, device=device)
    sim.reset(heading=0.4, velocity=[1.2, 0.3, 0.0, 0.0, 0.0, 0.05], sheet=0.6, wind_speed=6.0, wind_direction=2.0,
              foil_scale=scales)
    np.testing.assert_array_equal(sim.state.foil_scale.numpy(), scales)
    sim.tensors.control.rudder[:] = 0.3
    sim.tensors.control.propeller[:] = 2
    sim.fleet.forces.model_wrench.zero_()
    sim.rig.substep(sim.simulator)
    wrench = sim.fleet.forces.model_wrench.numpy().astype(np.float64)
    foils = wrench[1:] - wrench[0]
    for one, scaled in ((0, 1), (2, 3), (4, 5)):
        assert np.linalg.norm(foils[one][:3]) > 1.0  # a real force [N]
        np.testing.assert_allclose(foils[scaled], 1.07 * foils[one], rtol=2e-5, atol=1e-5 * np.abs(foils[one]).max())
    # The default reset and the default start rows: as tabulated.
    sim.reset()
    np.testing.assert_array_equal(sim.state.foil_scale.numpy(), 1.0)
    np.testing.assert_array_equal(sim.start.foil_scale.numpy(), 1.0)
    with pytest.raises(ValueError, match="EBoatSimulator.reset.foil_scale must be >= 0"):
        sim.reset(foil_scale=[1.0, -0.1, 1.0])
    with pytest.raises(ValueError, match=r"EBoatSimulator.reset.foil_scale must have shape \(7, 3\)"):
        sim.reset(foil_scale=[1.0, 1.0])
    with pytest.raises(ValueError, match="EBoatSimulator.reset.noise_scale holds NaN"):
        sim.reset(noise_scale=math.nan)


def small_waypoint_task(**start_fields):
    task = WaypointConfig()
    simulator = dataclasses.replace(task.simulator, ocean=ow.OceanConfig(tile_size=64.0, resolution=16,
                                                                         significant_wave_height=0.3, peak_period=3.0))
    return dataclasses.replace(task, simulator=simulator, start=dataclasses.replace(task.start, **start_fields))


def test_episode_draws_of_foil_and_noise_factors(device):
    n, v, noise = 32, 0.1, (0.5, 2.0)
    env = SailingEnv(small_waypoint_task(foil_variation=v, sensor_noise_scale=noise), n, device=device, seed=5)
    sim = env.simulator
    foil = sim.state.foil_scale.numpy().copy()
    np.testing.assert_array_equal(foil, sim.start.foil_scale.numpy())  # copied in by the reset
    assert np.all(foil >= 1.0 - v - 1e-6) and np.all(foil <= 1.0 + v + 1e-6)
    assert len(np.unique(foil)) == foil.size  # differ between environments and between sail, keel and rudder
    assert abs(np.corrcoef(foil[:, 0], foil[:, 1])[0, 1]) < 0.5
    scale = sim.state.noise_scale.numpy().copy()
    assert np.all(scale >= noise[0]) and np.all(scale <= noise[1]) and len(np.unique(scale)) == n
    # Reproducible: the same seed, the same factors; the next episode, new ones.
    again = SailingEnv(small_waypoint_task(foil_variation=v, sensor_noise_scale=noise), n, device=device, seed=5)
    np.testing.assert_array_equal(again.simulator.state.foil_scale.numpy(), foil)
    np.testing.assert_array_equal(again.simulator.state.noise_scale.numpy(), scale)
    env.reset()
    assert not np.any(sim.state.foil_scale.numpy() == foil)
    env.reset(seed=5)
    np.testing.assert_array_equal(sim.state.foil_scale.numpy(), foil)
    # Without randomisation: exactly 1, and every other draw of the episode as it was.
    plain = SailingEnv(small_waypoint_task(), n, device=device, seed=5)
    np.testing.assert_array_equal(plain.simulator.state.foil_scale.numpy(), 1.0)
    np.testing.assert_array_equal(plain.simulator.state.noise_scale.numpy(), 1.0)
    for name in ("position", "orientation", "velocity", "sheet", "wind_speed", "wind_direction", "gust_scale"):
        np.testing.assert_array_equal(getattr(plain.simulator.start, name).numpy(),
                                      getattr(sim.start, name).numpy(), err_msg=name)


def test_bad_randomisation_ranges_name_the_field():
    with pytest.raises(ValueError, match=r"StartConfig.foil_variation must be in \[0.0, 0.5\]"):
        StartConfig(foil_variation=0.6)
    with pytest.raises(ValueError, match=r"StartConfig.sensor_noise_scale must be in \[0.0, 10.0\]"):
        StartConfig(sensor_noise_scale=(0.5, 11.0))
    with pytest.raises(ValueError, match="StartConfig.sensor_noise_scale must have low <= high"):
        StartConfig(sensor_noise_scale=(2.0, 1.0))


# --- sensor noise ----------------------------------------------------------------------------------

def test_sensor_noise_scales_with_the_boats_factor(device):
    every_step = dict(gnss_rate=0.0, compass_rate=0.0, wind_rate=0.0, water_speed_rate=0.0, imu_rate=0.0)
    config = EBoatSimulatorConfig(wind=ow.WindConfig(speed=5.0, direction=1.0),
                                  sensors=ow.SensorConfig(seed=17, **every_step))
    group = 24
    factors = np.repeat([0.5, 2.0, 0.0], group)
    sim = EBoatSimulator(config, len(factors), device=device)
    rng = np.random.default_rng(4)
    sim.reset(position=np.column_stack([rng.uniform(-50, 50, (len(factors), 2)), np.full(len(factors), 0.04)]),
              heading=rng.uniform(-math.pi, math.pi, len(factors)), noise_scale=factors)
    np.testing.assert_array_equal(sim.state.noise_scale.numpy(), factors)
    errors = []
    for _ in range(8):
        sim.step()
        errors.append(sim.state.readings.numpy() - sim.state.truth.numpy())
    errors = np.array(errors)  # (steps, boats, channels)
    errors[..., [12, 13]] = np.angle(np.exp(1j * errors[..., [12, 13]]))
    std = sim.sensors.config.channel_noise().astype(np.float64)
    # Channels without bias, each in units of its own deviation: 8 steps x 24 boats x 10 channels.
    plain = [c for c in range(len(CHANNEL_NAMES)) if not 6 <= c <= 11]
    normalised = errors[..., plain] / std[plain]
    low, high = (normalised[:, factors == f].std() for f in (0.5, 2.0))
    assert low == pytest.approx(0.5, rel=0.08) and high == pytest.approx(2.0, rel=0.08)
    assert high / low == pytest.approx(4.0, rel=0.1)
    # The IMU bias is drawn with the factor, too: its spread over the boats.
    imu = errors[..., 6:12].mean(axis=0) / std[6:12]
    assert imu[factors == 2.0].std() > 2.0 * imu[factors == 0.5].std()
    np.testing.assert_array_equal(errors[:, factors == 0.0], 0.0)  # factor 0: the exact state


# --- sea state -------------------------------------------------------------------------------------

def small_sea(**fields):
    return ow.OceanConfig(**{**dict(tile_size=64.0, resolution=16, significant_wave_height=0.5, peak_period=3.0,
                                    choppiness=0.5), **fields})


def test_significant_wave_height_rescales_the_sea_in_place(device):
    ocean = ow.Ocean(small_sea(), device=device)
    t = 2.7
    ocean.update(t)
    original = ocean.fields.numpy().copy()
    grid_hs = ocean.significant_wave_height
    pointer = ocean._cells.ptr
    for hs in (1.25, 0.1, 0.5 * 1.25):
        ocean.set_significant_wave_height(hs)
        ocean.update(t)
        ratio = hs / 0.5
        np.testing.assert_allclose(ocean.fields.numpy(), ratio * original, rtol=1e-5,
                                   atol=1e-6 * ratio * np.abs(original).max())
        assert ocean.significant_wave_height == pytest.approx(ratio * grid_hs)
        assert ocean.spectrum_significant_wave_height == pytest.approx(hs)
        height = ocean.field_numpy("height")
        assert 4.0 * height.std() == pytest.approx(ratio * 4.0 * original[0, :, :, 0].std(), rel=1e-5)
    assert ocean._cells.ptr == pointer  # written in place: a captured graph stays valid
    ocean.set_significant_wave_height(0.0)
    ocean.update(t)
    np.testing.assert_array_equal(ocean.fields.numpy(), 0.0)
    assert ocean.significant_wave_height == 0.0
    ocean.set_significant_wave_height(0.5)  # back from the config's amplitudes: no accumulated rounding
    ocean.update(t)
    np.testing.assert_array_equal(ocean.fields.numpy(), original)


def test_significant_wave_height_of_a_wind_sea(device):
    config = small_sea(spectrum="pierson_moskowitz", wind_speed=4.0)
    ocean = ow.Ocean(config, device=device)
    base = ow.spectra.pierson_moskowitz_wind_sea_state(4.0, config.water.gravity)[0]
    assert ocean.spectrum_significant_wave_height == pytest.approx(base)
    original = ocean.field_numpy("height").copy()
    ocean.set_significant_wave_height(2.0 * base)
    ocean.update(0.0)
    np.testing.assert_allclose(ocean.field_numpy("height"), 2.0 * original, rtol=1e-5, atol=1e-6)


def test_bad_significant_wave_heights_are_refused():
    ocean = ow.Ocean(small_sea(), device="cpu")
    for bad in (-0.1, math.nan, math.inf, True, "1"):
        with pytest.raises(ValueError,
                           match=r"Ocean.set_significant_wave_height: hs must be a number from 0 to 5 \[m\]"):
            ocean.set_significant_wave_height(bad)
    with pytest.raises(ValueError, match="built with significant_wave_height 0"):
        ow.Ocean(small_sea(significant_wave_height=0.0), device="cpu").set_significant_wave_height(0.5)
    with pytest.raises(ValueError, match="regular"):
        ow.Ocean(small_sea(spectrum="regular", period=3.2), device="cpu").set_significant_wave_height(0.5)
