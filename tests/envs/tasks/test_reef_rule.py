"""The reef rule of the tasks: levels by the episode's wind at and around the thresholds, the fixed level, the
random level's frequency, the level the policy sees, the masked reset writing it, the presets, ``ocean-warp
eval --reef``, and bad rules."""

import dataclasses
import math

import numpy as np
import pytest
import torch

import ocean_warp as ow
from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.envs import (
    AvoidConfig,
    AvoidSailConfig,
    MissionConfig,
    MissionSailConfig,
    ReefRule,
    SailingEnv,
    WaypointConfig,
    WaypointPlusConfig,
)
from ocean_warp.envs.training.agents import agent_config
from ocean_warp.masks import mask_of

THRESHOLDS = (6.0, 8.0)
"""Issue 34's rule [m/s]: full below 6, reef 1 from 6 to 8, reef 2 from 8."""


def rule_level(speed: float) -> int:
    """The rule, written out: 0 below 6 m/s, 1 from 6 (inclusive) to 8, 2 from 8 (inclusive)."""
    if speed < 6.0:
        return 0
    return 1 if speed < 8.0 else 2


def cheap(task, **changes):
    """``task`` on the four-point hull and a small sea (a CPU test's budget), then ``changes``."""
    simulator = dataclasses.replace(task.simulator, boat=EBoatConfig(hydrostatics="points"),
                                    ocean=ow.OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.3,
                                                         peak_period=3.0))
    return dataclasses.replace(task, simulator=simulator, **changes)


def with_wind(task, low, high, **reef):
    start = dataclasses.replace(task.start, wind_speed=(low, high), wind_direction_step_deg=0.0)
    return cheap(task, start=start, reef=ReefRule(**reef))


@pytest.mark.parametrize("speed, level", [(0.0, 0), (5.99, 0), (6.0, 1), (6.01, 1), (7.99, 1), (8.0, 2),
                                          (8.01, 2), (12.0, 2)])
def test_rule_levels_at_and_around_the_thresholds(speed, level):
    assert ReefRule().thresholds == THRESHOLDS
    assert ReefRule().level_for(speed) == level == rule_level(speed)
    assert ReefRule(level=1).level_for(speed) == 1


@pytest.mark.parametrize("speed", [5.99, 6.0, 7.99, 8.0])
def test_episodes_start_at_the_rules_level_on_the_threshold(device, speed):
    """The device's draw at a wind exactly on (or just below) a threshold; float32 holds 5.99, 6, 7.99, 8 on the
    right side of the thresholds."""
    env = SailingEnv(with_wind(WaypointPlusConfig(), speed, speed), 4, device=device, seed=1)
    np.testing.assert_array_equal(env.simulator.state.reef_level.numpy(), rule_level(speed))


def test_episode_levels_follow_the_drawn_mean_wind_and_the_policy_sees_them(device, rng):
    """Winds drawn over 0-12 m/s: each environment's level is the rule's at its drawn mean speed (before gusts,
    which the WaypointPlus task has); the policy's value after the plus set's 15 is level / 2; the critic's the
    same value at the same place. After one-decision episodes, the masked reset writes the new episodes'
    levels."""
    n = 64
    task = with_wind(WaypointPlusConfig(), 0.0, 12.0)
    task = dataclasses.replace(task, episode_time=task.decision_period)
    env = SailingEnv(task, n, device=device, seed=int(rng.integers(1 << 30)))
    for _ in range(2):
        speeds = env.simulator.state.wind_mean_speed.numpy()
        np.testing.assert_array_equal(env.simulator.start.wind_speed.numpy(), speeds)
        levels = env.simulator.state.reef_level.numpy()
        np.testing.assert_array_equal(levels, [rule_level(float(v)) for v in speeds])
        np.testing.assert_array_equal(env.simulator.start.reef_level.numpy(), levels)
        assert set(levels) == {0, 1, 2}
        assert env.num_policy_obs == 16 and env.num_critic_obs == 28
        np.testing.assert_array_equal(env.buffers.policy_obs[:, 15].cpu().numpy(), levels / 2.0)
        np.testing.assert_array_equal(env.buffers.critic_obs[:, 15].cpu().numpy(), levels / 2.0)
        before = levels.copy()
        env.step(torch.zeros(n, 3, device=env.torch_device))
        assert bool(env.buffers.done.all())
        assert not np.array_equal(env.simulator.state.reef_level.numpy(), before)  # new winds, new levels


def test_the_seed_set_sees_its_level_sixth_and_the_seed_task_has_none(device):
    env = SailingEnv(with_wind(MissionConfig(), 10.0, 10.0), 2, device=device)
    assert env.num_policy_obs == 6
    np.testing.assert_array_equal(env.buffers.policy_obs[:, 5].cpu().numpy(), 1.0)  # reef 2 of 2 in 10 m/s
    seed_task = SailingEnv(cheap(WaypointConfig()), 2, device=device)
    assert seed_task.task.reef is None and seed_task.num_policy_obs == 5
    np.testing.assert_array_equal(seed_task.simulator.state.reef_level.numpy(), 0)


def test_fixed_level_overrides_the_rule(device):
    env = SailingEnv(with_wind(WaypointPlusConfig(), 2.0, 4.0, level=2), 8, device=device, seed=3)
    np.testing.assert_array_equal(env.simulator.state.reef_level.numpy(), 2)


def test_random_level_is_drawn_as_often_as_asked_and_leaves_the_other_draws(device, rng):
    """random_level 0.5 at 3 m/s (the rule: full sail): a uniform draw over three levels half the time, so a
    reef (1 or 2) in 1/3 of the episodes and each reef in 1/6; 1024 episodes put 4.5 standard deviations
    (0.066 of the fraction) within the bound. Every other start draw (pose, wind, foils, noise) is the same as
    without the random level: the level's numbers come from a stream of their own."""
    n, seed = 1024, int(rng.integers(1 << 30))
    env = SailingEnv(with_wind(WaypointPlusConfig(), 3.0, 3.0, random_level=0.5), n, device=device, seed=seed)
    levels = env.simulator.state.reef_level.numpy()
    assert abs(np.mean(levels > 0) - 1.0 / 3.0) < 4.5 * math.sqrt((1 / 3) * (2 / 3) / n)
    for level in (1, 2):
        assert abs(np.mean(levels == level) - 1.0 / 6.0) < 4.5 * math.sqrt((1 / 6) * (5 / 6) / n)
    plain = SailingEnv(with_wind(WaypointPlusConfig(), 3.0, 3.0), n, device=device, seed=seed)
    np.testing.assert_array_equal(plain.simulator.state.reef_level.numpy(), 0)
    for name in ("position", "orientation", "velocity", "sheet", "wind_speed", "wind_direction", "gust_scale",
                 "foil_scale", "noise_scale", "current_speed", "current_direction"):
        np.testing.assert_array_equal(getattr(env.simulator.start, name).numpy(),
                                      getattr(plain.simulator.start, name).numpy(), err_msg=name)
    # Seeded: the same seed, the same levels.
    again = SailingEnv(with_wind(WaypointPlusConfig(), 3.0, 3.0, random_level=0.5), n, device=device, seed=seed)
    np.testing.assert_array_equal(again.simulator.state.reef_level.numpy(), levels)


def test_reset_kernel_writes_the_start_rows_level(device):
    """``EBoatSimulator.reset_masked`` takes each masked boat's level from its start row, the others keep
    theirs."""
    sim = EBoatSimulator(EBoatSimulatorConfig(boat=EBoatConfig(hydrostatics="points")), 4, device=device)
    sim.reset(reef_level=[2, 2, 2, 2])
    sim.start.reef_level.assign(np.array([0, 1, 0, 1], dtype=np.int32))
    sim.reset_masked(mask_of([1, 2], 4, device))
    np.testing.assert_array_equal(sim.state.reef_level.numpy(), [2, 1, 0, 2])
    np.testing.assert_allclose(sim.sail_scales(), np.sqrt(np.array([1.15, 2.0, 3.188, 1.15]) / 3.188), rtol=1e-12)


def test_every_task_but_the_seeds_reefs_by_default_and_training_randomises():
    assert WaypointConfig().reef is None
    for task in (WaypointPlusConfig, MissionConfig, MissionSailConfig, AvoidConfig, AvoidSailConfig):
        assert task().reef == ReefRule(thresholds=THRESHOLDS, level=None, random_level=0.0), task
    for name in ("EBoatWaypointPlus-v0", "EBoatMission-v0", "EBoatMissionSail-v0", "EBoatAvoid-v0",
                 "EBoatAvoidSail-v0"):
        assert agent_config(name).train_task.reef.random_level == 0.25, name
    assert agent_config("EBoatWaypoint-v0").train_task.reef is None


def test_eval_reef_option_fixes_the_level():
    from ocean_warp.envs.apps import evaluation_options
    from ocean_warp.envs.evaluation import evaluation_task

    assert evaluation_options.parser().parse_args([]).reef == "auto"
    assert evaluation_options.parser().parse_args(["--reef", "2"]).reef == "2"
    with pytest.raises(SystemExit):
        evaluation_options.parser().parse_args(["--reef", "3"])
    assert evaluation_task("EBoatMission-v0").reef == ReefRule()
    assert evaluation_task("EBoatMission-v0", reef=1).reef == ReefRule(level=1)
    with pytest.raises(ValueError, match="WaypointConfig sails without a reef rule"):
        evaluation_task("EBoatWaypoint-v0", reef=1)


@pytest.mark.parametrize("changes, message", [
    (dict(thresholds=(-1.0, 8.0)), r"ReefRule\.thresholds must be finite wind speeds >= 0"),
    (dict(thresholds=(8.0, 6.0)), r"ReefRule\.thresholds must increase"),
    (dict(thresholds=(6.0, 6.0)), r"ReefRule\.thresholds must increase"),
    (dict(thresholds=(math.nan, 8.0)), r"ReefRule\.thresholds must be finite"),
    (dict(thresholds=(6.0, math.inf)), r"ReefRule\.thresholds must be finite"),
    (dict(thresholds=("six",)), r"ReefRule\.thresholds must be a sequence"),
    (dict(level=-1), r"ReefRule\.level must be None or a reef level >= 0"),
    (dict(level=1.0), r"ReefRule\.level must be None or a reef level >= 0"),
    (dict(level=True), r"ReefRule\.level must be None or a reef level >= 0"),
    (dict(random_level=math.nan), r"ReefRule\.random_level"),
    (dict(random_level=1.5), r"ReefRule\.random_level must be in \[0.0, 1.0\]"),
    (dict(random_level=-0.1), r"ReefRule\.random_level must be in \[0.0, 1.0\]"),
])
def test_bad_rules_name_the_field(changes, message):
    with pytest.raises(ValueError, match=message):
        ReefRule(**changes)


def test_a_rule_the_boat_cannot_sail_names_the_field():
    with pytest.raises(ValueError, match=r"MissionConfig\.reef: ReefRule\.level 3 is outside the boat's reef "
                                         r"levels 0-2"):
        MissionConfig(reef=ReefRule(level=3))
    with pytest.raises(ValueError, match=r"MissionConfig\.reef: ReefRule\.thresholds \(6.0, 8.0, 10.0\)"):
        MissionConfig(reef=ReefRule(thresholds=(6.0, 8.0, 10.0)))
    one_reef = dataclasses.replace(MissionConfig().simulator, boat=EBoatConfig(reef_areas=(1.5,)))
    with pytest.raises(ValueError, match=r"MissionConfig\.reef: ReefRule\.thresholds"):
        MissionConfig(simulator=one_reef)
    assert MissionConfig(simulator=one_reef, reef=ReefRule(thresholds=(7.0,))).reef.level_for(7.5) == 1
    with pytest.raises(ValueError, match=r"MissionConfig\.reef must be a ReefRule or None"):
        MissionConfig(reef=(6.0, 8.0))
