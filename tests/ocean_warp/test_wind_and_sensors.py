"""Wind gusts against Ornstein-Uhlenbeck statistics; sensors against exact values and their noise."""

import math

import numpy as np
import pytest

import ocean_warp as ow
from ocean_warp.eboat import EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.sensors import CHANNEL_NAMES
from tests.hull_setups import rotation_matrix


class _Stub:
    """The least a model needs from a simulator."""


def gust_series(device, config, envs, steps, dt):
    wind = ow.Wind(config, envs, substep=dt, device=device)
    speeds, directions = [], []
    for _ in range(steps):
        wind.substep(_Stub())
        speeds.append(wind.state.speed.numpy().copy())  # on the CPU numpy() is a view: copy each step
        directions.append(wind.state.direction.numpy().copy())
    return np.array(speeds), np.array(directions)


def test_gusts_have_the_configured_spread_and_correlation_time(device, rng):
    config = ow.WindConfig(speed=float(rng.uniform(6, 10)), direction=float(rng.uniform(-3, 3)),
                           gust_speed_std=float(rng.uniform(0.5, 1.5)), gust_speed_time=float(rng.uniform(2, 6)),
                           gust_direction_std=float(rng.uniform(0.05, 0.2)), gust_direction_time=float(rng.uniform(2, 6)),
                           seed=int(rng.integers(2**31)))
    dt = 0.1
    speeds, directions = gust_series(device, config, envs=1024, steps=600, dt=dt)
    # Started at the mean: let the spread build up first. 1024 environments over 50 s give standard
    # errors of about 0.02 sigma for the mean and 1.2 % for the spread.
    for series, mean, sigma, time in ((speeds[100:], config.speed, config.gust_speed_std, config.gust_speed_time),
                                      (directions[100:], config.direction, config.gust_direction_std,
                                       config.gust_direction_time)):
        assert series.mean() == pytest.approx(mean, abs=0.1 * sigma)
        assert series.std() == pytest.approx(sigma, rel=0.06)
        # Autocorrelation at one correlation time is 1/e.
        lag = int(round(time / dt))
        a, b = series[:-lag] - mean, series[lag:] - mean
        assert (a * b).mean() / (a * a).mean() == pytest.approx(math.exp(-1), abs=0.05)


def test_gusts_are_seeded(device):
    config = ow.WindConfig(speed=8.0, gust_speed_std=1.0, gust_direction_std=0.1, seed=11)
    first, _ = gust_series(device, config, envs=4, steps=50, dt=0.1)
    again, _ = gust_series(device, config, envs=4, steps=50, dt=0.1)
    other, _ = gust_series(device, ow.WindConfig(speed=8.0, gust_speed_std=1.0, seed=12), envs=4, steps=50, dt=0.1)
    np.testing.assert_array_equal(first, again)
    assert not np.allclose(first, other)


def test_bad_wind_config_is_refused():
    with pytest.raises(ValueError, match=r"WindConfig.profile_exponent must be in \[0, 1\]"):
        ow.WindConfig(profile_exponent=2.0)
    with pytest.raises(ValueError, match="WindConfig.speed must be >= 0"):
        ow.WindConfig(speed=-1.0)


def sensor_run(device, sensors, steps, *, wind_speed=5.0, count=64, rng=None):
    """Boats reset at random places and headings, then ``steps`` steps: the simulator and the truth
    and readings after the reset (index 0) and after every step."""
    sim = EBoatSimulator(EBoatSimulatorConfig(wind=ow.WindConfig(speed=wind_speed, direction=1.0), sensors=sensors), count,
                         device=device)
    rng = rng or np.random.default_rng(0)
    angles = np.column_stack([np.zeros(count), np.zeros(count), rng.uniform(-math.pi, math.pi, count)])
    sim.reset(position=np.column_stack([rng.uniform(-50, 50, (count, 2)), np.full(count, 0.04)]),
              heading=angles[:, 2])
    truths, readings = [sim.state.truth.numpy().copy()], [sim.state.readings.numpy().copy()]
    for _ in range(steps):
        sim.step()
        truths.append(sim.state.truth.numpy().copy())
        readings.append(sim.state.readings.numpy().copy())
    return sim, np.array(truths), np.array(readings)


def masthead_apparent_wind(sim, state, wind_world):
    """(angle the wind comes from [rad, from the bow, positive to port], speed [m/s]) at the masthead,
    in the deck plane, computed here from the state and the wind at the masthead."""
    angles, speeds = [], []
    for q, nu, wind in zip(state["orientation"], state["velocity"].astype(np.float64), wind_world):
        turn = rotation_matrix(q)
        apparent = turn.T @ wind - (nu[:3] + np.cross(nu[3:], sim.eboat.masthead))
        angles.append(math.atan2(-apparent[1], -apparent[0]))
        speeds.append(math.hypot(apparent[0], apparent[1]))
    return np.array(angles), np.array(speeds)


def test_noise_free_sensors_read_the_exact_state(device, rng):
    every_step = dict(gnss_rate=0.0, compass_rate=0.0, wind_rate=0.0, water_speed_rate=0.0)
    sim, truths, readings = sensor_run(device, ow.SensorConfig.noise_free(**every_step), 40, rng=rng)
    np.testing.assert_array_equal(readings[-1], truths[-1])
    state = sim.fleet.numpy()
    truth = truths[-1]
    np.testing.assert_allclose(truth[:, 0:3], state["position"], atol=1e-6)
    bow = np.array([rotation_matrix(q)[:, 0] for q in state["orientation"]])
    np.testing.assert_allclose(np.cos(truth[:, 12]), bow[:, 0] / np.hypot(bow[:, 0], bow[:, 1]), atol=1e-5)
    np.testing.assert_allclose(np.sin(truth[:, 12]), bow[:, 1] / np.hypot(bow[:, 0], bow[:, 1]), atol=1e-5)
    np.testing.assert_allclose(truth[:, 9:12], state["velocity"][:, 3:], atol=1e-6)
    # The accelerometer: R^T (dv/dt + g z) with dv/dt from the last two GNSS velocities (world frame).
    acceleration = (truths[-1][:, 3:6] - truths[-2][:, 3:6]) / 0.05
    expected = np.array([rotation_matrix(q).T @ (a + [0.0, 0.0, 9.81])
                         for q, a in zip(state["orientation"], acceleration)])
    np.testing.assert_allclose(truth[:, 6:9], expected, atol=1e-3)
    # The vane and the anemometer: the wind (5 m/s towards +1 rad, no profile) less the masthead's motion.
    wind = np.tile([5.0 * math.cos(1.0), 5.0 * math.sin(1.0), 0.0], (len(truth), 1))
    angle, speed = masthead_apparent_wind(sim, state, wind)
    np.testing.assert_allclose(np.angle(np.exp(1j * (truth[:, 13] - angle))), 0.0, atol=1e-4)
    np.testing.assert_allclose(truth[:, 14], speed, rtol=1e-4)


def test_sensor_noise_has_the_configured_deviation(device, rng):
    config = ow.SensorConfig(gnss_rate=0, compass_rate=0, wind_rate=0, water_speed_rate=0, seed=int(rng.integers(2**31)),
                             gnss_position_std=0.7, gnss_velocity_std=0.08, accelerometer_std=0.06,
                             gyroscope_std=0.004, compass_std=0.03, wind_angle_std=0.04, wind_speed_std=0.3,
                             water_speed_std=0.05, accelerometer_bias_std=0.0, gyroscope_bias_std=0.0)
    _, truths, readings = sensor_run(device, config, 60, count=128, rng=rng)
    errors = readings - truths
    errors[..., [12, 13]] = np.angle(np.exp(1j * errors[..., [12, 13]]))
    measured = errors.reshape(-1, len(CHANNEL_NAMES)).std(axis=0)
    expected = [0.7] * 3 + [0.08] * 3 + [0.06] * 3 + [0.004] * 3 + [0.03, 0.04, 0.3, 0.05]  # in CHANNEL_NAMES order
    np.testing.assert_allclose(measured, expected, rtol=0.05)


def test_imu_bias_is_constant_per_boat_with_the_configured_spread(device, rng):
    config = ow.SensorConfig.noise_free(imu_rate=0.0)
    config = ow.SensorConfig(**{**config.__dict__, "accelerometer_bias_std": 0.1, "gyroscope_bias_std": 0.01,
                                "seed": int(rng.integers(2**31))})
    _, truths, readings = sensor_run(device, config, 10, count=16, rng=rng)
    bias = readings[:, :, 6:12] - truths[:, :, 6:12]
    np.testing.assert_allclose(bias, np.broadcast_to(bias[0], bias.shape), atol=1e-5)  # constant in time
    # The spread over many boats, as the reset reads them (standard error about 1.1 %).
    _, truths, readings = sensor_run(device, config, 0, count=4096, rng=rng)
    np.testing.assert_allclose((readings[0] - truths[0])[:, 6:12].std(axis=0), [0.1] * 3 + [0.01] * 3, rtol=0.06)


def test_reset_reads_the_new_state_at_once(device, rng):
    """No reading of the last episode survives a reset, whatever the channels' rates; the anemometer
    at the masthead sees the wind's power-law height profile."""
    exponent = float(rng.uniform(0.1, 0.2))
    count = 8
    config = EBoatSimulatorConfig(wind=ow.WindConfig(speed=6.0, direction=-0.5, profile_exponent=exponent),
                                  sensors=ow.SensorConfig.noise_free())
    sim = EBoatSimulator(config, count, device=device)
    sim.reset(position=[0.0, 0.0, 0.05])
    for _ in range(3):
        sim.step()
    moved = rng.permutation(count)[: count // 2]
    places = np.column_stack([rng.uniform(-100, 100, (len(moved), 2)), rng.uniform(0.0, 0.1, len(moved))])
    headings = rng.uniform(-math.pi, math.pi, len(moved))
    sim.reset(moved, position=places, heading=headings)
    truth, readings = sim.state.truth.numpy()[moved], sim.state.readings.numpy()[moved]
    np.testing.assert_array_equal(readings, truth)
    np.testing.assert_allclose(truth[:, 0:3], places, atol=1e-5)
    np.testing.assert_allclose(truth[:, 3:6], 0.0, atol=1e-6)
    np.testing.assert_allclose(truth[:, 6:9], np.tile([0.0, 0.0, 9.81], (len(moved), 1)), atol=1e-5)  # at rest
    np.testing.assert_allclose(np.angle(np.exp(1j * (truth[:, 12] - headings))), 0.0, atol=1e-5)
    masthead_height = places[:, 2] + sim.eboat.masthead[2]
    np.testing.assert_allclose(truth[:, 14], 6.0 * (masthead_height / 10.0) ** exponent, rtol=1e-5)
    wind_from = -0.5 + math.pi - headings
    np.testing.assert_allclose(np.angle(np.exp(1j * (truth[:, 13] - wind_from))), 0.0, atol=1e-5)


def test_readings_refresh_at_their_rate(device):
    config = ow.SensorConfig(gnss_rate=5.0, seed=3)  # steps of 0.05 s: every 4th step
    _, _, readings = sensor_run(device, config, 12, count=4)
    # Index 0 is the reset's reading; steps 1, 5 and 9 refresh the GNSS (the first step, then every 4th).
    changed = np.any(readings[1:, :, 0] != readings[:-1, :, 0], axis=1)
    np.testing.assert_array_equal(np.flatnonzero(changed) + 1, [1, 5, 9])
