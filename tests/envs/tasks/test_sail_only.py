"""Missions under sail alone (issue 19, item 6): a task without propeller (``TaskConfig.propeller`` False), the
``ocean_warp/EBoatMissionSail-v0`` id, and the autopilot sailing it without motor assist.

The propeller-off task is checked against numbers the test computes itself: the level the motor-allowed
task would command (int(5 a0), truncated toward zero) and the reward of ``RewardConfig``'s docstring
formula, worked out here from the boats' positions before and after each decision."""

from __future__ import annotations

import dataclasses
import math
import warnings

import gymnasium as gym
import numpy as np
import pytest
import torch
from gymnasium.utils.env_checker import check_env

from ocean_warp.eboat import EBoatConfig, Hydrostatics, Profile
from ocean_warp.envs import MissionConfig, SailingEnv, TaskConfig, make_task_config
from ocean_warp.envs.controllers.sailing_autopilot import AutopilotConfig
from ocean_warp.envs.evaluation import MOTOR_ASSIST_LEVEL, AutopilotController
from ocean_warp.envs.controllers.line_following import LineFollowingConfig
from ocean_warp.envs.interfaces.gym_env import SailingEnvSingle
from ocean_warp.envs.tasks.task_configs import BCDACA_ROUTE, MissionSailConfig
from ocean_warp.ocean_config import OceanConfig

SAIL_ID = "EBoatMissionSail-v0"


def cheap(task: TaskConfig) -> TaskConfig:
    """``task`` on the four-point hydrostatics (its profile kept) and a coarse sea: fast on the CPU."""
    simulator = dataclasses.replace(
        task.simulator, boat=dataclasses.replace(task.simulator.boat, hydrostatics=Hydrostatics.POINTS),
        ocean=OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.3, peak_period=3.0),
        ocean_every_substep=False)
    return dataclasses.replace(task, simulator=simulator)


def docstring_reward(progress: np.ndarray, level: np.ndarray, reward) -> np.ndarray:
    """``RewardConfig``'s formula for boats that neither reached, got lost nor were flagged: progress
    r = (d_prev - d) / progress_scale; if r > 0, r *= 1 - propeller_gain |level| / 5, else
    r -= propeller_cost |level|; minus smoothness and time cost (0 in the mission)."""
    assert reward.smoothness == 0.0 and reward.time_cost == 0.0
    r = progress / reward.progress_scale
    return np.where(r > 0.0, r * (1.0 - reward.propeller_gain * np.abs(level) / 5.0),
                    r - reward.propeller_cost * np.abs(level))


def planar_distance(env: SailingEnv, targets: np.ndarray) -> np.ndarray:
    """Each boat's horizontal distance to ``targets`` (N, 3) world [m]."""
    return np.linalg.norm((targets - env.simulator.state.position.numpy())[:, :2], axis=1)


def test_sail_task_config_and_bad_values():
    config = make_task_config(SAIL_ID)
    assert isinstance(config, MissionSailConfig) and config.propeller is False
    assert make_task_config(f"ocean_warp/{SAIL_ID}") == config
    boat = config.simulator.boat
    assert boat == EBoatConfig() and boat.profile is Profile.PHYSICS and boat.hydrostatics is Hydrostatics.MESH
    mission = MissionConfig()
    assert mission.propeller is True and config.route == mission.route == BCDACA_ROUTE
    for field in ("ocean", "wind", "sensors"):
        assert getattr(config.simulator, field) == getattr(mission.simulator, field), field
    assert (config.start, config.reward, config.episode_time) == (mission.start, mission.reward, mission.episode_time)
    with pytest.raises(ValueError, match="MissionConfig.propeller must be True or False"):
        MissionConfig(propeller=0)


def test_propeller_off_ignores_a0_and_rewards_level_zero(rng):
    """Random actions (a0 over [-1.2, 1.2], clipped), the same for a propeller-off mission, the same task with
    the motor allowed, and the propeller-off task with a0 zeroed: off, the level is 0 at every decision
    and a0 changes nothing else; its reward is the docstring formula with level 0, while the motor-
    allowed twin's is the same formula with int(5 a0). (The plus observation's echo of the last action
    shows a0 as given.)"""
    sail = cheap(MissionSailConfig())
    tasks = {"off": sail, "motor": dataclasses.replace(sail, propeller=True), "off_a0_zero": sail}
    seed = int(rng.integers(1 << 30))
    envs = {name: SailingEnv(task, 8, device="cpu", seed=seed) for name, task in tasks.items()}
    checked = {"off": 0, "motor": 0}
    for _ in range(6):
        actions = rng.uniform(-1.0, 1.0, (8, 3)).astype(np.float32)
        actions[:, 0] = rng.uniform(-1.2, 1.2, 8)
        levels = np.trunc(5.0 * np.clip(actions[:, 0], -1.0, 1.0))
        for name, env in envs.items():
            targets = env.buffers.target.numpy().copy()
            before = planar_distance(env, targets)
            given = actions.copy()
            if name == "off_a0_zero":
                given[:, 0] = 0.0
            env.step(torch.from_numpy(given))
            if name == "off_a0_zero":
                continue
            commanded = env.simulator.control.propeller.numpy()
            np.testing.assert_array_equal(commanded, 0 if name == "off" else levels)
            b = env.buffers
            plain = ~b.done.numpy()  # sailing on: progress alone (no reach, loss or flag)
            progress = before - planar_distance(env, targets)
            expected = docstring_reward(progress, 0 * levels if name == "off" else levels, env.task.reward)
            np.testing.assert_allclose(b.reward.numpy()[plain], expected[plain], rtol=0, atol=2e-6)
            checked[name] += int(plain.sum())
        for array in ("reward", "done"):
            np.testing.assert_array_equal(getattr(envs["off"].buffers, array).numpy(),
                                          getattr(envs["off_a0_zero"].buffers, array).numpy())
        # the plus observation echoes the last action as given (column 12 is a0); the rest is the same
        observed = {name: envs[name].buffers.policy_obs.numpy() for name in ("off", "off_a0_zero")}
        np.testing.assert_array_equal(np.delete(observed["off"], 12, axis=1), np.delete(observed["off_a0_zero"], 12, axis=1))
        np.testing.assert_array_equal(envs["off"].simulator.state.position.numpy(),
                                      envs["off_a0_zero"].simulator.state.position.numpy())
    assert min(checked.values()) >= 24, checked  # most boats sailed on through most decisions


def test_gymnasium_make_and_check_env():
    env = gym.make(f"ocean_warp/{SAIL_ID}")
    assert isinstance(env.unwrapped, SailingEnvSingle) and env.unwrapped.env.task.propeller is False
    assert env.action_space.shape == (3,) and env.observation_space.shape == (16,)  # plus and reef level
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the unbounded observation Box is deliberate
        check_env(env.unwrapped)
    env.reset(seed=1)
    env.step(np.array([1.0, 0.0, 0.0], dtype=np.float32))
    assert env.unwrapped.env.simulator.control.propeller.numpy()[0] == 0


def test_autopilot_sails_without_motor_where_there_is_no_propeller():
    sail, mission = MissionSailConfig(), MissionConfig()
    legacy = AutopilotController(autopilot="legacy")
    default = legacy.config_for(sail)
    assert (default.assist_level, default.propeller_level) == (0, 0)
    assert default.decision_period == sail.decision_period
    assert default == AutopilotConfig.sail_only(decision_period=sail.decision_period)
    assert default.rudder_limit == pytest.approx(math.radians(18.0))  # near the physics rudder's stall (17.7 deg)
    assert legacy.config_for(mission) == AutopilotConfig(decision_period=mission.decision_period)
    motoring = AutopilotConfig(propeller_level=3, assist_level=4, heading_gain=0.5)
    assert AutopilotController(motoring).config_for(mission) == motoring
    assert AutopilotController(motoring).config_for(sail) == dataclasses.replace(motoring, propeller_level=0,
                                                                                 assist_level=0)
    # The default controller, the line follower: the motor assists only where the task has a propeller.
    line = AutopilotController()
    assert line.autopilot == "line"
    assert line.config_for(sail) == LineFollowingConfig(decision_period=sail.decision_period, assist_level=0)
    assert line.config_for(mission).assist_level == MOTOR_ASSIST_LEVEL > 0
    assisted = LineFollowingConfig(assist_level=3, rudder_gain=2.0)
    assert AutopilotController(assisted).config_for(mission) == assisted
    assert AutopilotController(assisted).config_for(sail) == dataclasses.replace(assisted, assist_level=0)
