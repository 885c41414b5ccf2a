"""The sharded environment: the same numbers as one SailingEnv, worker deaths and errors reported and
cleaned up, no process left behind, and the rsl-rl and gymnasium faces on top of it.

CPU only by nature (the workers are CPU processes). Fast settings: four-point hydrostatics on the seed's
gentle sea (waves included, so every worker's ocean must match), few environments, short episodes.
"""

import dataclasses
import os
import signal
import time

import numpy as np
import pytest
import torch

from ocean_warp import WindConfig
from ocean_warp.eboat import Hydrostatics
from ocean_warp.envs import BatchedEnv, EnvBuffers, SailingEnv, StartConfig, WaypointConfig
from ocean_warp.envs.interfaces.gym_env import SailingVectorEnv
from ocean_warp.envs.interfaces.rsl_rl_env import RslRlVecEnv
from ocean_warp.envs.parallel.sharded import ShardedSailingEnv, shard_bounds
from ocean_warp.envs.tasks.task_configs import AvoidConfig
from ocean_warp.sensors import SensorConfig
from tests.env_buffers import bit_equal, sail_in_lockstep

COMPARED = tuple(field.name for field in dataclasses.fields(EnvBuffers))
"""Every buffer of the batched-env protocol."""


def fast_config(**changes) -> WaypointConfig:
    """The seed waypoint task on four-point hydrostatics, 3 s episodes (a reset every 3 decisions), with
    everything that draws per boat switched on: gusts, noisy sensors seen by the policy (the Waypoint+
    observation), three mass variants and domain randomisation of the foils; ``changes`` applied."""
    base = WaypointConfig()
    simulator = dataclasses.replace(
        base.simulator, boat=dataclasses.replace(base.simulator.boat, hydrostatics=Hydrostatics.POINTS),
        wind=WindConfig(gust_speed_std=1.0, gust_direction_std=0.1), sensors=SensorConfig(),
        mass_variation=0.05, mass_variants=3)
    fields = {"simulator": simulator, "episode_time": 3.0, "observation": "plus",
              "start": StartConfig(foil_variation=0.3, sensor_noise_scale=(0.5, 1.5))} | changes
    return dataclasses.replace(base, **fields)


def _alive(pid: int) -> bool:
    """Whether a process ``pid`` exists and is not a zombie."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def _wait_gone(pids: list[int], seconds: float = 5.0) -> list[int]:
    """The ``pids`` still alive after up to ``seconds`` [s]."""
    deadline = time.monotonic() + seconds
    while (alive := [pid for pid in pids if _alive(pid)]) and time.monotonic() < deadline:
        time.sleep(0.05)
    return alive


def test_shards_are_contiguous_and_balanced():
    assert shard_bounds(5, 2) == [(0, 3), (3, 2)]
    assert shard_bounds(7, 3) == [(0, 3), (3, 2), (5, 2)]
    assert shard_bounds(4, 4) == [(0, 1), (1, 1), (2, 1), (3, 1)]


def test_bad_worker_counts_are_clear_errors():
    with pytest.raises(ValueError, match="workers"):
        ShardedSailingEnv(fast_config(), 4, workers=0)
    with pytest.raises(ValueError, match="workers"):
        ShardedSailingEnv(fast_config(), 4, workers=5)


def test_first_env_makes_a_slice_of_the_larger_batch():
    """SailingEnv(first_env=a) of n environments is environments [a, a + n) of one batch, step for step."""
    whole = SailingEnv(fast_config(), 5, device="cpu", seed=11)
    tail = SailingEnv(fast_config(), 2, device="cpu", seed=11, first_env=3)
    generator = torch.Generator().manual_seed(1)
    for _ in range(7):
        actions = 2.0 * torch.rand(5, 3, generator=generator) - 1.0
        whole.step(actions)
        tail.step(actions[3:])
        for name in COMPARED:
            assert bit_equal(getattr(whole.buffers, name)[3:], getattr(tail.buffers, name)), name


def test_sharded_env_matches_one_process_step_for_step():
    """5 environments over 2 workers (shards of 3 and 2) against one SailingEnv with the same seed: every
    buffer bit for bit, through several same-step resets and a re-seeded reset. Both are BatchedEnvs."""
    task = fast_config()
    single = SailingEnv(task, 5, device="cpu", seed=7)
    generator = torch.Generator().manual_seed(0)
    with ShardedSailingEnv(task, 5, workers=2, seed=7) as sharded:
        assert isinstance(single, BatchedEnv) and isinstance(sharded, BatchedEnv)
        assert not hasattr(sharded, "simulator")  # nothing reaches through it
        resets = sail_in_lockstep(single, sharded, generator, steps=12, reset_step=8, reset_seed=3)
        assert resets >= 10, "the comparison must cross same-step resets"
        log, expected = sharded.episode_log(), single.episode_log()
        assert log.keys() == expected.keys() and all(torch.equal(log[k], expected[k]) for k in log)


def test_an_obstacle_course_over_workers_matches_one_process():
    """The avoidance task (layouts drawn per environment at every reset, the lidar's sectors in the observation,
    contact) over 2 workers against one SailingEnv: every buffer bit for bit, the obstacle tables (5, 12, 4)
    included, through same-step resets (2 s episodes) and a re-seeded reset."""
    base = AvoidConfig()
    simulator = dataclasses.replace(base.simulator,
                                    boat=dataclasses.replace(base.simulator.boat, hydrostatics=Hydrostatics.POINTS))
    task = dataclasses.replace(base, simulator=simulator, episode_time=2.0)
    single = SailingEnv(task, 5, device="cpu", seed=4)
    generator = torch.Generator().manual_seed(2)
    with ShardedSailingEnv(task, 5, workers=2, seed=4) as sharded:
        assert sharded.buffers.obstacles.shape == (5, 12, 4) and sharded.buffers.policy_obs.shape == (5, 5 + 1 + 24)
        sail_in_lockstep(single, sharded, generator, steps=5, reset_step=3, reset_seed=8)
        assert bool((single.buffers.obstacles[:, :, 3] > 0).any())


def test_shared_ocean_follows_sea_state_changes_and_every_substep_updates():
    """The sea evaluated once by the parent, one decision ahead: a change of sea state between decisions,
    a re-seeded reset and an ocean updated every substep (5 updates a step) keep it bit for bit equal to
    one SailingEnv and to workers that evaluate their own sea."""
    base = fast_config()
    task = dataclasses.replace(base, simulator=dataclasses.replace(base.simulator, ocean_every_substep=True))
    single = SailingEnv(task, 4, device="cpu", seed=2)
    generator = torch.Generator().manual_seed(1)
    with ShardedSailingEnv(task, 4, workers=2, seed=2) as shared, \
            ShardedSailingEnv(task, 4, workers=2, seed=2, shared_ocean=False) as own:
        for step in range(7):
            if step == 2:
                for env in (single, shared, own):
                    assert env.set_significant_wave_height(0.6) == env.significant_wave_height
            if step == 5:
                for env in (single, shared, own):
                    env.reset(seed=9)
            actions = 2.0 * torch.rand(4, 3, generator=generator) - 1.0
            for env in (single, shared, own):
                env.step(actions)
            for name in COMPARED:
                expected = getattr(single.buffers, name)
                assert bit_equal(expected, getattr(shared.buffers, name)), (step, name)
                assert bit_equal(expected, getattr(own.buffers, name)), (step, name)
        assert shared.significant_wave_height == single.significant_wave_height == \
            single.simulator.ocean.significant_wave_height
    with pytest.raises(ValueError, match="hs must be a number from 0 to 5"):
        with ShardedSailingEnv(task, 2, workers=1) as env:
            env.set_significant_wave_height(-1.0)


def test_a_killed_worker_is_reported_and_every_worker_stops():
    env = ShardedSailingEnv(fast_config(), 4, workers=2, seed=1)
    env.step(torch.zeros(4, 3))
    os.kill(env.pids[1], signal.SIGKILL)
    with pytest.raises(RuntimeError, match=r"worker 1 \(envs 2-3\) died: killed by SIGKILL"):
        env.step(torch.zeros(4, 3))
    assert _wait_gone(env.pids) == []
    with pytest.raises(RuntimeError, match="closed"):
        env.step()


def test_an_exception_in_a_worker_is_reported_with_its_traceback():
    env = ShardedSailingEnv(fast_config(), 3, workers=2, seed=1)
    expected = r"(?s)worker (0 \(envs 0-1\)|1 \(env 2\)) raised an exception.*crash requested: boom"
    with pytest.raises(RuntimeError, match=expected):
        env._command("crash", "boom")
    assert _wait_gone(env.pids) == []


def test_close_leaves_no_process_and_is_idempotent():
    env = ShardedSailingEnv(fast_config(), 3, workers=2, seed=2)
    pids = list(env.pids)
    assert all(_alive(pid) for pid in pids)
    env.close()
    env.close()
    assert env.closed and _wait_gone(pids, 0.0) == []


def test_rsl_rl_and_gymnasium_faces_over_the_sharded_env():
    env = ShardedSailingEnv(fast_config(episode_time=600.0), 4, workers=2, seed=5)
    pids = list(env.pids)
    vec = RslRlVecEnv(env)
    observations = vec.get_observations()
    assert observations["policy"].shape == (4, 15) and observations["critic"].shape == (4, 27)
    vec.episode_length_buf = torch.tensor([0, 5, 10, 599], dtype=torch.int32)
    observations, rewards, dones, extras = vec.step(torch.zeros(4, 3))
    assert rewards.shape == (4,) and dones.dtype == torch.bool
    # The written episode lengths reach the workers: the env at 599 decisions times out now.
    assert dones.tolist() == [False, False, False, True] and extras["time_outs"].tolist() == [False] * 3 + [True]
    assert vec.episode_length_buf.tolist() == [1, 6, 11, 0]
    assert "/episode/return" in extras["log"]

    gym_env = SailingVectorEnv.from_env(env)
    obs, _ = gym_env.reset(seed=4)
    assert obs.shape == (4, 15) and obs.dtype == np.float32
    for _ in range(3):
        obs, rewards, terminations, truncations, _ = gym_env.step(gym_env.action_space.sample())
        assert obs.shape == (4, 15) and rewards.shape == (4,) and np.all(np.isfinite(obs))
    gym_env.close()
    assert env.closed and _wait_gone(pids) == []
