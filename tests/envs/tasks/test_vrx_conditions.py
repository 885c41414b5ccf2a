"""VRX's task conditions (envs/tasks/vrx_conditions.py): VRX's wave heights and the dataclass's validation."""

import math

import pytest

from ocean_warp.envs.tasks.vrx_conditions import VrxConditions, vrx_significant_wave_height


def test_wave_height_of_vrx_field():
    # Gain 1, period 6 s: omega_p = 1.0472 rad/s, S(omega_p) = 0.0081 * 9.81^2 / 1.0472^5 * exp(-1.25)
    # = 0.0081 * 96.236 / 1.2593 * 0.28650 = 0.17735 m^2 s; the three bands together span
    # omega_p (0.0909 + 0.0955 + 0.1) = 0.2999 rad/s, so m0 ~ 0.17735 * 0.2999 = 0.05319 m^2 and
    # Hs ~ 4 sqrt(m0) = 0.922 m with all three at the peak's density (the side bands hold less: a few % below).
    hs = vrx_significant_wave_height(1.0, 6.0)
    assert 0.95 * 0.922 < hs < 0.922
    # The amplitudes scale with the gain; no gain, no waves.
    assert vrx_significant_wave_height(0.8, 6.0) == pytest.approx(0.8 * hs)
    assert vrx_significant_wave_height(0.0, 4.0) == 0.0


def test_task_presets_hold_vrx_ranges():
    sk, wf, fp = VrxConditions.station_keeping(), VrxConditions.wayfinding(), VrxConditions.follow_path()
    assert sk.waypoints == (1, 1) and wf.waypoints == (3, 5) and fp.waypoints == (3, 9)
    # the worlds' strongest seas: gain 0.8 at 6 s (station keeping, wayfinding), 0.6 at 6 s (follow the path)
    assert sk.wave_height[1] == pytest.approx(vrx_significant_wave_height(0.8, 6.0), abs=0.005)
    assert fp.wave_height[1] == pytest.approx(vrx_significant_wave_height(0.6, 6.0), abs=0.005)
    assert sk.current_speed == wf.current_speed == fp.current_speed == (0.0, 0.0)
    assert sk.duration == 300.0 and fp.obstacles == (1, 17)
    assert VrxConditions.station_keeping(wind_speed=(5.0, 5.0)).wind_speed == (5.0, 5.0)


@pytest.mark.parametrize("overrides, message", [
    (dict(wind_speed=(3.0, 1.0)), "VrxConditions.wind_speed must have low <= high"),
    (dict(wind_speed=(-1.0, 1.0)), "VrxConditions.wind_speed must be in"),
    (dict(wave_height=(0.0, float("nan"))), "VrxConditions.wave_height must be finite"),
    (dict(goal_heading=(-4.0, 0.0)), "VrxConditions.goal_heading must be in"),
    (dict(wave_period=5.0), "VrxConditions.wave_period must be a \\(low, high\\) pair"),
    (dict(waypoints=(0, 3)), "VrxConditions.waypoints must be an integer in \\[1, 100\\]"),
    (dict(waypoints=(2.5, 3)), "VrxConditions.waypoints must be an integer"),
    (dict(obstacles=(5, 2)), "VrxConditions.obstacles must have low <= high"),
    (dict(duration=0.0), "VrxConditions.duration must be > 0"),
    (dict(wind_gust_time_constant=math.inf), "VrxConditions.wind_gust_time_constant must be"),
])
def test_validation_names_the_field(overrides, message):
    with pytest.raises(ValueError, match=message):
        VrxConditions.follow_path(**overrides)


def test_frozen():
    with pytest.raises(AttributeError):
        VrxConditions.wayfinding().wind_speed = (0.0, 1.0)


def test_wave_height_rejects_bad_input():
    with pytest.raises(ValueError, match="period"):
        vrx_significant_wave_height(1.0, 0.0)
    with pytest.raises(ValueError, match="gain"):
        vrx_significant_wave_height(float("nan"), 6.0)
