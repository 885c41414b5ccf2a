"""A WAM-V task through every face: gymnasium's checker, SB3's VecEnv and a few PPO updates, rsl-rl's VecEnv, and
the sharded CPU backend bit for bit against one process."""

import dataclasses
import warnings

import gymnasium as gym
import numpy as np
import pytest
import torch
from gymnasium.utils.env_checker import check_env

from ocean_warp.envs.interfaces.rsl_rl_env import RslRlVecEnv
from ocean_warp.envs.parallel.sharded import ShardedSailingEnv
from ocean_warp.envs.registration import make_task_config
from ocean_warp.envs.vrx import VrxEnv

from tests.env_buffers import sail_in_lockstep


def short_wayfinding(**changes):
    """WamvWayfinding-v0 with 4 s episodes (a reset every 8 decisions) and goals close enough to reach."""
    task = make_task_config("WamvWayfinding-v0", episode_time=4.0)
    start = dataclasses.replace(task.start, goal_distance=(1.0, 3.0), goal_spacing=(1.0, 2.0))
    return dataclasses.replace(task, start=start, **changes)


def test_gymnasium_checker_passes_on_a_wamv_task():
    env = gym.make("ocean_warp/WamvStationKeeping-v0")
    assert env.action_space.shape == (2,) and env.observation_space.shape == (12,)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the unbounded observation Box is deliberate
        check_env(env.unwrapped)


def test_sb3_ppo_trains_on_a_wamv_task(one_torch_thread):
    pytest.importorskip("stable_baselines3")
    from stable_baselines3 import PPO
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    from ocean_warp.envs.interfaces.sb3_env import Sb3VecEnv

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the unbounded observation Box is deliberate
        sb3_check_env(gym.make("ocean_warp/WamvWayfinding-v0").unwrapped, warn=False)
    env = Sb3VecEnv(short_wayfinding(), num_envs=4, seed=0)
    assert env.action_space.shape == (2,) and env.observation_space.shape == (12,)
    model = PPO("MlpPolicy", env, n_steps=16, batch_size=32, n_epochs=1, seed=0, device="cpu",
                policy_kwargs={"net_arch": [16, 16]})
    before = [parameter.detach().clone() for parameter in model.policy.parameters()]
    model.learn(total_timesteps=2 * 16 * 4)
    assert model.num_timesteps == 2 * 16 * 4 and len(model.ep_info_buffer) >= 4
    assert any(not torch.equal(a, b) for a, b in zip(before, model.policy.parameters()))


def test_rsl_rl_face_of_a_wamv_task(rng):
    env = RslRlVecEnv(VrxEnv(short_wayfinding(), 3, device="cpu", seed=int(rng.integers(1 << 30))))
    assert env.num_actions == 2
    observations = env.get_observations()
    assert observations["policy"].shape == (3, 12) and observations["critic"].shape == (3, 15)
    ended = torch.zeros(3, dtype=torch.bool)
    for _ in range(9):
        observations, rewards, dones, extras = env.step(torch.as_tensor(rng.uniform(-1, 1, (3, 2)),
                                                                        dtype=torch.float32))
        ended |= dones.bool()
        assert torch.isfinite(rewards).all() and torch.isfinite(observations["policy"]).all()
    assert bool(ended.all())  # 8-decision episodes: every env ended once


def test_a_wamv_task_over_workers_matches_one_process():
    """4 WAM-V environments over 2 workers against one VrxEnv with the same seed: every buffer bit for bit,
    through same-step resets and a re-seeded reset."""
    task = short_wayfinding()
    single = VrxEnv(task, 4, device="cpu", seed=5)
    generator = torch.Generator().manual_seed(1)
    with ShardedSailingEnv(task, 4, workers=2, seed=5) as sharded:
        assert sharded.num_actions == 2 and sharded.buffers.actions.shape == (4, 2)
        resets = sail_in_lockstep(single, sharded, generator, steps=12, reset_step=9, reset_seed=2)
        assert resets >= 4
        assert np.isfinite(single.buffers.policy_obs.numpy()).all()


def test_the_exported_metadata_names_a_wamv_policys_values_and_actions(rng):
    """The ROS/ONNX export reads the VRX block's names: one per value the env gives (12 on the WAM-V), the last
    two the WAM-V's thrusters; and the goal's distance column is the distance numpy computes from the buffers."""
    from ocean_warp.envs.ros.policy_export import action_meaning, observation_layout

    layout = observation_layout("WamvStationKeeping-v0", "vrx", 12)
    assert len(layout) == 12 and len(set(layout)) == 12
    assert layout[4].startswith("goal_distance") and layout[10].startswith("last_left_thrust")
    assert [text.split(":")[0] for text in action_meaning("WamvStationKeeping-v0")] == ["a0 left_thrust",
                                                                                        "a1 right_thrust"]
    env = VrxEnv(make_task_config("WamvStationKeeping-v0"), 3, device="cpu", seed=int(rng.integers(1 << 30)))
    env.step(torch.as_tensor(rng.uniform(-1, 1, (3, 2)), dtype=torch.float32))
    b = env.buffers
    distance = np.hypot(*(b.target.numpy()[:, :2] - b.position.numpy()[:, :2]).T)
    np.testing.assert_allclose(b.policy_obs.numpy()[:, 4], np.minimum(distance / 10.0, 5.0), atol=2e-4)
