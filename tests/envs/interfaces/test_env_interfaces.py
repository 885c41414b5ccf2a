"""The interfaces over SailingEnv: rsl-rl's VecEnv, gymnasium's Env / VectorEnv (and their ids), SB3's VecEnv.

Each contract is checked against numbers the test knows independently of the adapter: the step on
which a time limit must fall, the seed task's start observation (waypoint 100 m away, lost at 125 m,
boat at rest: distance entry 2 * 100 / 125 - 1 = 0.6, surge entry 0 / 5 - 1 = -1), the Warp arrays'
own addresses. Fast settings (four-point hydrostatics, still water) keep the file CI-affordable.
"""

import dataclasses
import re
import subprocess
import sys
import warnings

import gymnasium as gym
import numpy as np
import pytest
import torch
from gymnasium.utils.env_checker import check_env
from gymnasium.vector import AutoresetMode

from ocean_warp.eboat import Hydrostatics
from ocean_warp.eboat.simulator_config import still_water
from ocean_warp.envs import SailingEnv, WaypointConfig
from ocean_warp.envs.interfaces.gym_env import SailingEnvSingle, SailingVectorEnv
from ocean_warp.envs.registration import TASK_IDS, make_task_config, register_envs
from ocean_warp.envs.interfaces.rsl_rl_env import RslRlVecEnv

START_DISTANCE_OBS = 2.0 * 100.0 / 125.0 - 1.0
"""Seed observation 0 at a start of the default waypoint task: waypoint 100 m away, lost at 100 + 25 m."""
AT_REST_SURGE_OBS = -1.0
"""Seed observation 2 of a boat at rest: u / 5 - 1 with u = 0."""


def fast_config(**changes) -> WaypointConfig:
    """The seed waypoint task on four-point hydrostatics and still water, with ``changes`` applied."""
    base = WaypointConfig()
    simulator = dataclasses.replace(
        base.simulator, ocean=still_water(),
        boat=dataclasses.replace(base.simulator.boat, hydrostatics=Hydrostatics.POINTS))
    return dataclasses.replace(base, simulator=simulator, **changes)



# --- rsl-rl -------------------------------------------------------------------------------------------


def test_rsl_rl_shapes_dtypes_devices(device):
    env = RslRlVecEnv(SailingEnv(fast_config(), 6, device=device, seed=1))
    assert (env.num_envs, env.num_actions) == (6, 3)
    assert env.max_episode_length == 600  # 600 s / 1 s decisions
    assert env.device == torch.device(device)
    assert isinstance(env.cfg, WaypointConfig)
    obs = env.get_observations()
    assert obs.batch_size == torch.Size([6])
    assert set(obs.keys()) == {"policy", "critic"}
    assert obs["policy"].shape == (6, 5) and obs["critic"].shape == (6, 17)
    assert obs["policy"].dtype == torch.float32 and obs["policy"].device == torch.device(device)
    obs, rewards, dones, extras = env.step(torch.zeros(6, 3, device=device))
    assert obs["critic"].shape == (6, 17)
    assert rewards.shape == (6,) and rewards.dtype == torch.float32 and rewards.device == torch.device(device)
    assert dones.shape == (6,) and dones.dtype == torch.bool
    assert extras["time_outs"].shape == (6,) and extras["time_outs"].dtype == torch.bool
    assert extras["log"] and all(key.startswith("/") for key in extras["log"])


def test_rsl_rl_views_are_the_warp_memory(device):
    core = SailingEnv(fast_config(), 4, device=device)
    env = RslRlVecEnv(core)
    assert env.observation_views["policy"].data_ptr() == core.policy_obs.ptr
    assert env.observation_views["critic"].data_ptr() == core.critic_obs.ptr
    assert env.episode_length_buf.data_ptr() == core.episode_length.ptr
    _, rewards, dones, extras = env.step(torch.zeros(4, 3, device=device))
    assert rewards.data_ptr() == core.reward.ptr
    assert dones.data_ptr() == core.done.ptr
    assert extras["time_outs"].data_ptr() == core.time_out.ptr


def test_rsl_rl_episode_length_setter_writes_the_warp_array(device):
    core = SailingEnv(fast_config(episode_time=10.0), 5, device=device)
    env = RslRlVecEnv(core)
    pointer = env.episode_length_buf.data_ptr()
    env.episode_length_buf = torch.tensor([9, 8, 0, 3, 9], dtype=torch.int32, device=device)
    assert env.episode_length_buf.data_ptr() == pointer  # still the alias, not the assigned tensor
    np.testing.assert_array_equal(core.episode_length.numpy(), [9, 8, 0, 3, 9])
    # The simulator times out from the written lengths: envs at 9 of 10 decisions end now, the rest go on.
    _, _, dones, extras = env.step(torch.zeros(5, 3, device=device))
    np.testing.assert_array_equal(extras["time_outs"].cpu().numpy(), [True, False, False, False, True])
    np.testing.assert_array_equal(dones.cpu().numpy(), [True, False, False, False, True])
    np.testing.assert_array_equal(core.episode_length.numpy(), [0, 9, 1, 4, 0])


def test_rsl_rl_time_limit_is_a_time_out_not_a_termination(device):
    env = RslRlVecEnv(SailingEnv(fast_config(episode_time=4.0), 8, device=device, seed=3))
    assert env.max_episode_length == 4
    for step in range(1, 5):
        _, _, dones, extras = env.step(torch.zeros(8, 3, device=device))
        assert bool(dones.all()) == (step == 4) and bool(dones.any()) == (step == 4)
    assert bool(extras["time_outs"].all())
    assert not bool(env.env.buffers.terminated.any())
    log = extras["log"]
    np.testing.assert_allclose(log["/episode/length"].cpu().numpy(), np.full(8, 4.0))
    np.testing.assert_allclose(log["/episode/time_out_rate"].cpu().numpy(), np.ones(8))
    assert int(env.episode_length_buf.sum()) == 0  # all reset in the same step


def test_rsl_rl_observations_survive_the_next_step(device):
    """rsl-rl keeps the TensorDict it acted on and copies it into storage after env.step: a returned
    observation must not be the simulator's memory, which the next step overwrites (it stays valid
    through one more step)."""
    env = RslRlVecEnv(SailingEnv(fast_config(), 4, device=device, seed=2))
    full_ahead = torch.tensor([[1.0, 0.0, 0.0]] * 4, device=device)
    first = env.get_observations()
    first_values = first.clone()
    second = env.step(full_ahead)[0]
    assert torch.equal(first["policy"], first_values["policy"])  # one step later: still what it was
    second_values = second.clone()
    env.step(full_ahead)
    assert torch.equal(second["critic"], second_values["critic"])
    assert not torch.equal(first_values["policy"], second_values["policy"])  # the boats did move
    # ... and they match what the simulator showed at the time.
    assert torch.allclose(first_values["policy"][:, 0], torch.full((4,), START_DISTANCE_OBS, device=device))
    assert torch.allclose(first_values["policy"][:, 2], torch.full((4,), AT_REST_SURGE_OBS, device=device))


def _ppo_config(num_steps_per_env: int) -> dict:
    return {
        "num_steps_per_env": num_steps_per_env,
        "save_interval": 1000,
        "obs_groups": {"actor": ["policy"], "critic": ["critic"]},
        "actor": {"class_name": "MLPModel", "hidden_dims": [32, 32], "activation": "elu", "obs_normalization": True,
                  "distribution_cfg": {"class_name": "GaussianDistribution", "init_std": 0.6}},
        "critic": {"class_name": "MLPModel", "hidden_dims": [32, 32], "activation": "elu", "obs_normalization": True},
        "algorithm": {"class_name": "PPO", "num_learning_epochs": 4, "num_mini_batches": 4, "learning_rate": 3e-3,
                      "gamma": 0.95, "lam": 0.95, "entropy_coef": 0.0, "desired_kl": 0.01, "schedule": "adaptive"},
    }


def test_rsl_rl_storage_records_the_observation_acted_on():
    from rsl_rl.runners import OnPolicyRunner

    torch.manual_seed(0)
    env = RslRlVecEnv(SailingEnv(fast_config(), 8, device="cpu", seed=4))
    runner = OnPolicyRunner(env, _ppo_config(3), log_dir=None, device="cpu")
    acted_on = []
    with torch.inference_mode():
        obs = env.get_observations()
        for _ in range(3):
            acted_on.append(obs["policy"].clone())
            obs, rewards, dones, extras = env.step(runner.alg.act(obs))
            runner.alg.process_env_step(obs, rewards, dones, extras)
    for step, expected in enumerate(acted_on):
        assert torch.equal(runner.alg.storage.observations["policy"][step], expected)


def test_rsl_rl_runner_logs_episode_statistics(tmp_path, capsys, one_torch_thread):
    pytest.importorskip("tensorboard")
    from rsl_rl.runners import OnPolicyRunner

    torch.manual_seed(0)
    env = RslRlVecEnv(SailingEnv(fast_config(episode_time=4.0), 8, device="cpu", seed=6))
    runner = OnPolicyRunner(env, _ppo_config(5), log_dir=str(tmp_path), device="cpu")
    runner.learn(2)
    printed = capsys.readouterr().out
    assert re.search(r"/episode/length:\s+4\.0000", printed)  # every episode times out after 4 decisions
    assert re.search(r"/episode/time_out_rate:\s+1\.0000", printed)
    assert any(tmp_path.glob("events.out.tfevents.*"))
    assert list(tmp_path.glob("model_*.pt"))


def easy_waypoint() -> WaypointConfig:
    """A waypoint 15 m dead ahead on the +x axis, steady 4 m/s wind, a free propeller, 30 s episodes."""
    base = fast_config()
    return fast_config(
        episode_time=30.0, lost_margin=15.0,
        start=dataclasses.replace(base.start, waypoint_distance=(15.0, 15.0), wind_speed=(4.0, 4.0),
                                  wind_direction_deg=(0.0, 0.0)),
        reward=dataclasses.replace(base.reward, propeller_gain=0.0, propeller_cost=0.0, progress_scale=15.0))


def _evaluate(policy, env: RslRlVecEnv) -> tuple[float, float]:
    """Mean return per env over one episode length from a seeded reset, and the success rate of the
    episodes that ended in it (deterministic policy)."""
    env.reset(seed=123)
    total = torch.zeros(env.num_envs)
    successes = []
    with torch.inference_mode():
        obs = env.get_observations()
        for _ in range(env.max_episode_length):
            obs, rewards, _, extras = env.step(policy(obs))
            total += rewards
            successes.append(extras["log"]["/episode/success_rate"])
    return total.mean().item(), torch.cat(successes).mean().item()


def test_rsl_rl_ppo_learns_the_easy_waypoint(one_torch_thread):
    from rsl_rl.runners import OnPolicyRunner

    torch.manual_seed(0)
    env = RslRlVecEnv(SailingEnv(easy_waypoint(), 64, device="cpu", seed=0))
    runner = OnPolicyRunner(env, _ppo_config(16), log_dir=None, device="cpu")
    return_before, success_before = _evaluate(runner.get_inference_policy("cpu"), env)
    runner.learn(15, init_at_random_ep_len=True)
    return_after, success_after = _evaluate(runner.get_inference_policy("cpu"), env)
    print(f"return {return_before:.3f} -> {return_after:.3f}, success {success_before:.2f} -> {success_after:.2f}")
    # Reaching the waypoint is worth 1 (progress) + 1 (bonus): the trained fleet must get most of it.
    assert return_after > return_before + 0.8
    assert success_after > success_before + 0.3


# --- gymnasium ----------------------------------------------------------------------------------------


def test_vector_env_spaces_and_dtypes(device):
    env = SailingVectorEnv(fast_config(), num_envs=5, device=device, seed=0)
    assert env.metadata["autoreset_mode"] is AutoresetMode.SAME_STEP
    assert env.single_observation_space == gym.spaces.Box(-np.inf, np.inf, (5,), np.float32)
    assert env.observation_space.shape == (5, 5) and env.observation_space.dtype == np.float32
    assert env.single_action_space == gym.spaces.Box(-1.0, 1.0, (3,), np.float32)
    assert env.action_space.shape == (5, 3)
    obs, info = env.reset(seed=7)
    assert obs.shape == (5, 5) and obs.dtype == np.float32 and info == {}
    np.testing.assert_allclose(obs[:, 0], START_DISTANCE_OBS, atol=1e-6)
    obs, rewards, terminations, truncations, infos = env.step(env.action_space.sample())
    assert obs in env.observation_space
    assert rewards.shape == (5,) and np.issubdtype(rewards.dtype, np.floating)
    assert terminations.dtype == np.bool_ and truncations.dtype == np.bool_
    assert not np.shares_memory(obs, env.step(np.zeros((5, 3)))[0])


def test_vector_env_same_step_autoreset(device):
    env = SailingVectorEnv(fast_config(), num_envs=6, device=device, seed=5, max_episode_steps=5)
    env.reset(seed=5)
    full_ahead = np.tile([1.0, 0.0, 0.0], (6, 1))
    for _ in range(3):
        obs, _, terminations, truncations, infos = env.step(full_ahead)
        assert not (terminations | truncations).any() and "final_obs" not in infos
    env.env.buffers.episode_length[[1, 4]] = 4  # these two reach the 5-decision limit on the next step
    before = obs.copy()
    obs, _, terminations, truncations, infos = env.step(full_ahead)
    ended = np.array([False, True, False, False, True, False])
    np.testing.assert_array_equal(truncations, ended)
    assert not terminations.any()
    np.testing.assert_array_equal(infos["_final_obs"], ended)
    assert [index for index, final in enumerate(infos["final_obs"]) if final is not None] == [1, 4]
    for index in (1, 4):
        final = infos["final_obs"][index]
        assert final.shape == (5,) and final.dtype == np.float32
        assert final[2] > AT_REST_SURGE_OBS + 0.05  # 4 s under full propeller: moving
        # The observation returned for an ended env is the next episode's first: at rest, 100 m out.
        assert obs[index, 2] == pytest.approx(AT_REST_SURGE_OBS, abs=1e-6)
        assert obs[index, 0] == pytest.approx(START_DISTANCE_OBS, abs=1e-5)
    running = ~ended
    assert (obs[running, 2] > AT_REST_SURGE_OBS + 0.05).all()
    assert not np.allclose(obs[running], before[running])


def test_vector_env_rejects_options_and_bad_actions():
    env = SailingVectorEnv(fast_config(), num_envs=2)
    with pytest.raises(ValueError, match="options"):
        env.reset(options={"reset_mask": np.array([True, False])})
    with pytest.raises(ValueError, match=r"\(2, 3\)"):
        env.step(np.zeros((3, 3)))


def test_single_env_passes_check_env():
    env = SailingEnvSingle(fast_config())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the unbounded observation Box is deliberate
        check_env(env)


def test_single_env_returns_the_final_observation(device):
    env = SailingEnvSingle(fast_config(), device=device, max_episode_steps=3)
    obs, info = env.reset(seed=11)
    assert obs.shape == (5,) and obs.dtype == np.float32 and info == {}
    assert obs[0] == pytest.approx(START_DISTANCE_OBS, abs=1e-5)
    for step in range(1, 4):
        obs, reward, terminated, truncated, info = env.step(np.array([1.0, 0.0, 0.0], dtype=np.float32))
        assert type(reward) is float and type(terminated) is bool and type(truncated) is bool
        assert (terminated, truncated) == (False, step == 3)
    # The last episode's last observation (moving), not the simulator's post-reset one (at rest).
    assert obs[2] > AT_REST_SURGE_OBS + 0.05
    np.testing.assert_array_equal(obs, env.env.buffers.final_policy_obs[0].cpu().numpy())
    obs, _ = env.reset()
    assert obs[2] == pytest.approx(AT_REST_SURGE_OBS, abs=1e-6)


@pytest.mark.parametrize("task_id", TASK_IDS)
def test_gymnasium_make_and_make_vec(task_id):
    # the plus observation's 15 values or the seed's 5, then the reef level (every task but the seed's waypoint
    # task), then the lidar's 24 sectors (the avoidance tasks); VRX's tasks: 10 values and the WAM-V's 2 actions
    policy_size = {"EBoatWaypointPlus-v0": 15 + 1, "EBoatMissionSail-v0": 15 + 1, "EBoatMission-v0": 5 + 1,
                   "EBoatAvoid-v0": 5 + 1 + 24, "EBoatAvoidSail-v0": 5 + 1 + 24}.get(task_id, 5)
    if task_id.startswith("Wamv"):
        policy_size = 10 + 2
    single = gym.make(f"ocean_warp/{task_id}")
    assert isinstance(single.unwrapped, SailingEnvSingle)
    assert single.observation_space.shape == (policy_size,)
    obs, _ = single.reset(seed=0)
    assert obs.shape == (policy_size,)
    single.step(single.action_space.sample())
    fleet = gym.make_vec(f"ocean_warp/{task_id}", num_envs=3, vectorization_mode="vector_entry_point",
                         max_episode_steps=7)
    assert isinstance(fleet, SailingVectorEnv) and fleet.num_envs == 3
    assert fleet.env.max_episode_length == 7
    assert fleet.observation_space.shape == (3, policy_size)
    fleet.reset(seed=0)
    obs = fleet.step(fleet.action_space.sample())[0]
    assert obs.shape == (3, policy_size)


def test_register_envs_is_idempotent():
    specs = {name: gym.spec(f"ocean_warp/{name}") for name in TASK_IDS}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # gymnasium warns when an id is registered over
        register_envs()
    assert all(gym.spec(f"ocean_warp/{name}") is spec for name, spec in specs.items())
    assert specs["EBoatMission-v0"].max_episode_steps is None  # no TimeLimit wrapper on top of the simulator's


# --- Stable-Baselines3 --------------------------------------------------------------------------------


def test_sb3_vec_env_contract(device):
    pytest.importorskip("stable_baselines3")
    from ocean_warp.envs.interfaces.sb3_env import Sb3VecEnv

    env = Sb3VecEnv(fast_config(), num_envs=4, device=device, max_episode_steps=3)
    env.seed(21)
    obs = env.reset()
    assert obs.shape == (4, 5) and obs.dtype == np.float32
    for step in range(1, 4):
        obs, rewards, dones, infos = env.step(np.tile([1.0, 0.0, 0.0], (4, 1)).astype(np.float32))
        assert rewards.dtype == np.float32 and dones.dtype == np.bool_ and len(infos) == 4
        assert dones.all() == (step == 3) and dones.any() == (step == 3)
    for index, info in enumerate(infos):
        assert info["TimeLimit.truncated"] is True
        assert info["episode"]["l"] == 3
        terminal = info["terminal_observation"]
        assert terminal.shape == (5,) and terminal[2] > AT_REST_SURGE_OBS + 0.05
        np.testing.assert_array_equal(terminal, env.env.buffers.final_policy_obs[index].cpu().numpy())
    np.testing.assert_allclose(obs[:, 2], AT_REST_SURGE_OBS, atol=1e-6)
    assert env.get_attr("max_episode_length", [0, 2]) == [3, 3]
    assert env.get_attr("render_mode") == [None] * 4
    assert env.env_is_wrapped(gym.Wrapper) == [False] * 4
    assert env.env_method("episode_log")[0].keys() == env.env.episode_log().keys()
    with pytest.raises(ValueError, match="shared simulator"):
        env.set_attr("seed", 3, indices=[0])
    with pytest.raises(AttributeError):
        env.get_attr("no_such_attribute")


def test_sb3_ppo_runs_updates(one_torch_thread):
    pytest.importorskip("stable_baselines3")
    from stable_baselines3 import PPO

    from ocean_warp.envs.interfaces.sb3_env import Sb3VecEnv

    env = Sb3VecEnv(fast_config(), num_envs=8, seed=0, max_episode_steps=8)
    model = PPO("MlpPolicy", env, n_steps=16, batch_size=64, n_epochs=2, seed=0, device="cpu",
                policy_kwargs={"net_arch": [32, 32]})
    before = [parameter.detach().clone() for parameter in model.policy.parameters()]
    model.learn(total_timesteps=3 * 16 * 8)
    assert model.num_timesteps == 3 * 16 * 8
    assert [info["l"] for info in model.ep_info_buffer] == [8] * len(model.ep_info_buffer)
    assert len(model.ep_info_buffer) == 3 * 16 * 8 // 8  # every episode lasts 8 decisions
    assert any(not torch.equal(a, b) for a, b in zip(before, model.policy.parameters()))


def test_envs_import_without_sb3():
    """``import ocean_warp.envs`` must not need the optional SB3 extra; the SB3 module says how to get it."""
    code = (
        "import sys; sys.modules['stable_baselines3'] = None\n"
        "import gymnasium, ocean_warp.envs\n"
        "assert 'ocean_warp/EBoatWaypoint-v0' in gymnasium.registry\n"
        "try:\n"
        "    import ocean_warp.envs.interfaces.sb3_env\n"
        "except ImportError as error:\n"
        "    assert '.[sb3]' in str(error), error\n"
        "else:\n"
        "    raise SystemExit('sb3_env imported without stable_baselines3')\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr[-2000:]


# --- the avoidance tasks through every interface --------------------------------------------------


@pytest.mark.parametrize("task_id", ["EBoatAvoid-v0", "EBoatAvoidSail-v0"])
def test_avoid_tasks_through_every_interface(task_id, one_torch_thread):
    """The registered avoidance tasks (mesh hull, obstacles, contact, lidar) pass gymnasium's ``check_env``
    and run through rsl-rl's and SB3's adapters: 5 seed values, the reef level and 24 lidar sectors for the
    policy, the critic's 12 privileged values on top, and the lidar's sectors (nearest return / 50 m) in [0,
    1]."""
    policy_size, critic_size = 5 + 1 + 24, 5 + 1 + 12 + 24
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the unbounded observation Box is deliberate
        check_env(SailingEnvSingle(task_id, max_episode_steps=4))

    env = RslRlVecEnv.from_task(make_task_config(task_id), num_envs=2, seed=3)
    observations = env.get_observations()
    assert observations["policy"].shape == (2, policy_size) and observations["critic"].shape == (2, critic_size)
    observations, rewards, dones, extras = env.step(torch.tensor([[0.5, 0.0, 0.1], [-0.2, 0.3, -0.4]]))
    sectors = observations["policy"][:, 6:]
    assert torch.all((sectors >= 0.0) & (sectors <= 1.0)) and torch.all(torch.isfinite(rewards))
    torch.testing.assert_close(observations["critic"][:, 18:], sectors, rtol=0.0, atol=0.0)

    pytest.importorskip("stable_baselines3")
    from ocean_warp.envs.interfaces.sb3_env import Sb3VecEnv

    vec = Sb3VecEnv(task_id, num_envs=2, seed=5, max_episode_steps=2)
    obs = vec.reset()
    assert obs.shape == (2, policy_size) and obs.dtype == np.float32
    for _ in range(2):
        obs, rewards, dones, infos = vec.step(np.tile([0.4, 0.0, 0.0], (2, 1)).astype(np.float32))
    assert dones.all() and all(info["terminal_observation"].shape == (policy_size,) for info in infos)
