"""Wind gusts against Ornstein-Uhlenbeck statistics; sensors against exact values and their noise."""

import math

import numpy as np
import pytest

import ocean_warp as ow
from ocean_warp.eboat import EBoatSimulator
from ocean_warp.frames import quaternion_from_roll_pitch_yaw, roll_pitch_yaw
from ocean_warp.sensors import CHANNEL_NAMES


class _Stub:
    """The least a model needs from a simulator."""


def gust_series(device, config, envs, steps, dt):
    wind = ow.Wind(config, envs, device=device)
    wind.bind(dt)
    speeds, directions = [], []
    for _ in range(steps):
        wind.substep(_Stub())
        speeds.append(wind.speed.numpy().copy())  # on the CPU numpy() is a view: copy each step
        directions.append(wind.direction.numpy().copy())
    return np.array(speeds), np.array(directions), wind


def test_gusts_have_the_configured_spread_and_correlation_time(device, rng):
    config = ow.WindConfig(speed=float(rng.uniform(6, 10)), direction=float(rng.uniform(-3, 3)),
                           gust_speed_std=float(rng.uniform(0.5, 1.5)), gust_speed_time=float(rng.uniform(2, 6)),
                           gust_direction_std=float(rng.uniform(0.05, 0.2)), gust_direction_time=float(rng.uniform(2, 6)),
                           seed=int(rng.integers(2**31)))
    dt = 0.1
    speeds, directions, _ = gust_series(device, config, envs=256, steps=600, dt=dt)
    settled = speeds[100:]  # started at the mean: let the spread build up first
    assert settled.mean() == pytest.approx(config.speed, abs=0.05 * config.gust_speed_std + 0.02)
    assert settled.std() == pytest.approx(config.gust_speed_std, rel=0.05)
    assert directions[100:].std() == pytest.approx(config.gust_direction_std, rel=0.05)
    # Autocorrelation at one correlation time is 1/e.
    lag = int(round(config.gust_speed_time / dt))
    a, b = settled[:-lag] - config.speed, settled[lag:] - config.speed
    assert (a * b).mean() / (a * a).mean() == pytest.approx(math.exp(-1), abs=0.05)


def test_gusts_are_seeded(device):
    config = ow.WindConfig(speed=8.0, gust_speed_std=1.0, gust_direction_std=0.1, seed=11)
    first, _, _ = gust_series(device, config, envs=4, steps=50, dt=0.1)
    again, _, _ = gust_series(device, config, envs=4, steps=50, dt=0.1)
    other, _, _ = gust_series(device, ow.WindConfig(speed=8.0, gust_speed_std=1.0, seed=12), envs=4, steps=50, dt=0.1)
    np.testing.assert_array_equal(first, again)
    assert not np.allclose(first, other)


def test_wind_profile_and_bad_config():
    with pytest.raises(ValueError, match=r"WindConfig.profile_exponent must be in \[0, 1\]"):
        ow.WindConfig(profile_exponent=2.0)
    with pytest.raises(ValueError, match="WindConfig.speed must be >= 0"):
        ow.WindConfig(speed=-1.0)


def sensor_run(device, sensors, steps, *, wind_speed=5.0, count=64, rng=None):
    sim = EBoatSimulator(count, wind=ow.WindConfig(speed=wind_speed, direction=1.0), sensors=sensors, device=device)
    rng = rng or np.random.default_rng(0)
    angles = np.column_stack([np.zeros(count), np.zeros(count), rng.uniform(-math.pi, math.pi, count)])
    sim.reset(position=np.column_stack([rng.uniform(-50, 50, (count, 2)), np.full(count, 0.04)]),
              heading=angles[:, 2])
    truths, readings = [], []
    for _ in range(steps):
        sim.step()
        truths.append(sim.sensors.truth.numpy().copy())
        readings.append(sim.sensors.readings.numpy().copy())
    return sim, np.array(truths), np.array(readings)


def test_noise_free_sensors_read_the_exact_state(device, rng):
    every_step = dict(gnss_rate=0.0, compass_rate=0.0, wind_rate=0.0, water_speed_rate=0.0)
    sim, truths, readings = sensor_run(device, ow.SensorConfig.noise_free(**every_step), 40, rng=rng)
    np.testing.assert_array_equal(readings[-1], truths[-1])
    state = sim.fleet.numpy()
    truth = truths[-1]
    np.testing.assert_allclose(truth[:, 0:3], state["position"], atol=1e-6)
    np.testing.assert_allclose(truth[:, 12], roll_pitch_yaw(state["orientation"])[:, 2], atol=1e-5)
    np.testing.assert_allclose(truth[:, 9:12], state["velocity"][:, 3:], atol=1e-6)
    # The accelerometer: R^T (dv/dt + g z) with dv/dt from the last two GNSS velocities (world frame).
    from tests.hull_setups import rotation_matrix

    acceleration = (truths[-1][:, 3:6] - truths[-2][:, 3:6]) / 0.05
    expected = np.array([rotation_matrix(q).T @ (a + [0.0, 0.0, 9.81])
                         for q, a in zip(state["orientation"], acceleration)])
    np.testing.assert_allclose(truth[:, 6:9], expected, atol=1e-3)
    # Barely moving: the vane and the anemometer see about the true wind.
    wind_from = 1.0 + math.pi - roll_pitch_yaw(state["orientation"])[:, 2]  # the wind blows towards +1 rad
    error = np.angle(np.exp(1j * (truth[:, 13] - wind_from)))
    assert np.abs(error).max() < 0.15
    assert np.abs(truth[:, 14] - 5.0).max() < 0.6


def test_sensor_noise_has_the_configured_deviation(device, rng):
    config = ow.SensorConfig(gnss_rate=0, compass_rate=0, wind_rate=0, water_speed_rate=0, seed=int(rng.integers(2**31)),
                             gnss_position_std=0.7, gnss_velocity_std=0.08, accelerometer_std=0.06,
                             gyroscope_std=0.004, compass_std=0.03, wind_angle_std=0.04, wind_speed_std=0.3,
                             water_speed_std=0.05, accelerometer_bias_std=0.0, gyroscope_bias_std=0.0)
    _, truths, readings = sensor_run(device, config, 60, count=128, rng=rng)
    errors = readings - truths
    errors[..., [12, 13]] = np.angle(np.exp(1j * errors[..., [12, 13]]))
    measured = errors.reshape(-1, len(CHANNEL_NAMES)).std(axis=0)
    np.testing.assert_allclose(measured, config.channel_noise(), rtol=0.05)


def test_imu_bias_is_constant_per_boat_with_the_configured_spread(device, rng):
    config = ow.SensorConfig.noise_free(imu_rate=0.0)
    config = ow.SensorConfig(**{**config.__dict__, "accelerometer_bias_std": 0.1, "gyroscope_bias_std": 0.01,
                                "seed": int(rng.integers(2**31))})
    _, truths, readings = sensor_run(device, config, 10, count=512, rng=rng)
    bias = readings[:, :, 6:12] - truths[:, :, 6:12]
    np.testing.assert_allclose(bias, np.broadcast_to(bias[0], bias.shape), atol=1e-5)  # constant in time
    np.testing.assert_allclose(bias[0].std(axis=0), [0.1] * 3 + [0.01] * 3, rtol=0.1)


def test_readings_refresh_at_their_rate(device):
    config = ow.SensorConfig(gnss_rate=5.0, seed=3)  # steps of 0.05 s: every 4th step
    _, _, readings = sensor_run(device, config, 12, count=4)
    changed = np.any(readings[1:, :, 0] != readings[:-1, :, 0], axis=1)
    np.testing.assert_array_equal(np.flatnonzero(changed) + 1, [4, 8])
