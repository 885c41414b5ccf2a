"""The seed paper's SB3 recipe (benchmarks/studies/sb3_seed_recipe.py): its hyperparameters, its success count, a tiny run.

The hyperparameters are checked against the seed's numbers written out here, read off the built PPO
object and its networks. Success counting is checked on tasks whose outcome is known beforehand: a
reach radius of 150 m around a waypoint 100 m away (every episode succeeds in its first decision) and
a 3 s time limit with the usual 5 m radius (none can). The end-to-end run is 256 steps of 4 boats
with 20 s episodes.
"""

import json
import os

import pytest
import torch

pytest.importorskip("stable_baselines3")

from stable_baselines3 import PPO  # noqa: E402

from benchmarks.studies import sb3_seed_recipe as recipe  # noqa: E402
from ocean_warp.envs import WaypointConfig  # noqa: E402
from ocean_warp.envs.interfaces.sb3_env import Sb3VecEnv  # noqa: E402

SUMMARY_KEYS = {"steps", "num_envs", "train_wall_s", "success_rate", "mean_return", "episodes", "device"}
QUICK_TASK = WaypointConfig(episode_time=20.0)
"""The seed task with 20 decisions per episode."""
REACH_AT_ONCE = WaypointConfig(reach_radius=150.0)
"""The waypoint (100 m away) is within reach from the start: every episode ends in success after 1 decision."""
NEVER_REACHED = WaypointConfig(episode_time=3.0)
"""3 decisions per episode, too few to sail 95 m: every episode times out unsuccessful."""



def _mlp_layers(module: torch.nn.Module) -> list[tuple]:
    return [(type(layer).__name__, getattr(layer, "in_features", None), getattr(layer, "out_features", None))
            for layer in module]


@pytest.mark.filterwarnings("ignore:You have specified a mini-batch size")  # 3 x 682 = 2046 is no multiple of 64
@pytest.mark.parametrize("num_envs, n_steps", [(1, 2048), (4, 512), (3, 682)])
def test_seed_hyperparameters(num_envs, n_steps):
    model = recipe.build_model(Sb3VecEnv(QUICK_TASK, num_envs=num_envs), seed=0)
    assert (model.n_envs, model.n_steps) == (num_envs, n_steps)
    if 2048 % num_envs == 0:
        assert model.n_steps * model.n_envs == 2048  # the seed's rollout
    assert (model.batch_size, model.n_epochs) == (64, 10)
    assert (model.gamma, model.gae_lambda, model.ent_coef) == (0.99, 0.95, 0.001)
    assert model.learning_rate == 3e-4 and model.lr_schedule(1.0) == model.lr_schedule(0.0) == 3e-4
    assert model.clip_range(1.0) == model.clip_range(0.0) == 0.2 and model.clip_range_vf is None
    assert model.device == torch.device("cpu")
    policy = model.policy
    assert policy.net_arch == {"pi": [32, 32], "vf": [32, 32]}
    assert policy.activation_fn is torch.nn.ReLU
    hidden = [("Linear", 5, 32), ("ReLU", None, None), ("Linear", 32, 32), ("ReLU", None, None)]
    assert _mlp_layers(policy.mlp_extractor.policy_net) == hidden
    assert _mlp_layers(policy.mlp_extractor.value_net) == hidden
    assert (policy.action_net.in_features, policy.action_net.out_features) == (32, 3)
    assert (policy.value_net.in_features, policy.value_net.out_features) == (32, 1)


def test_n_steps_keeps_the_rollout_and_help_says_so(capsys):
    assert [recipe.seed_n_steps(n) for n in (1, 2, 16, 1024)] == [2048, 1024, 128, 2]
    with pytest.raises(ValueError):
        recipe.seed_n_steps(0)
    with pytest.raises(SystemExit):
        recipe.main(["--help"])
    assert "n_steps = 2048 // N" in " ".join(capsys.readouterr().out.split())


def test_evaluate_counts_episodes_and_successes(one_torch_thread):
    model = recipe.build_model(Sb3VecEnv(QUICK_TASK, num_envs=3), seed=0, n_steps=64)
    reached = recipe.evaluate(model, REACH_AT_ONCE, num_envs=3, device="cpu", seed=5, episodes=7)
    assert (reached["episodes"], reached["successes"], reached["success_rate"]) == (7, 7, 1.0)
    assert reached["mean_return"] == pytest.approx(1.0, abs=0.02)  # +1 bonus, ~0 progress in 1 s
    missed = recipe.evaluate(model, NEVER_REACHED, num_envs=3, device="cpu", seed=5, episodes=7)
    assert (missed["episodes"], missed["successes"], missed["success_rate"]) == (7, 0, 0.0)
    assert abs(missed["mean_return"]) < 0.2  # 3 s of progress (and propeller cost) only


def test_progress_callback_counts_training_episodes(one_torch_thread):
    env = Sb3VecEnv(REACH_AT_ONCE, num_envs=4, seed=2)
    model = recipe.build_model(env, seed=2, n_steps=16)
    callback = recipe.EpisodeProgress(total=64, show=False)
    model.learn(total_timesteps=64, callback=callback)
    assert callback.episodes == 64  # one decision per episode
    assert list(callback.successes) == [True] * 64
    # +1 bonus, a propeller cost of at most 0.01 x 5, and 1 s of progress (< 0.01)
    assert all(abs(value - 1.0) < 0.06 for value in callback.returns)


def test_run_trains_evaluates_and_saves(tmp_path, one_torch_thread):
    out = tmp_path / "sb3_seed"
    summary = recipe.run(steps=256, num_envs=4, device="cpu", seed=3, out=str(out), eval_episodes=4,
                         progress=True, task=QUICK_TASK, n_steps=64)
    assert SUMMARY_KEYS <= summary.keys()
    assert (summary["steps"], summary["num_envs"], summary["n_steps"], summary["device"]) == (256, 4, 64, "cpu")
    assert summary["episodes"] == 4 and 0.0 <= summary["success_rate"] <= 1.0
    assert summary["success_rate"] == summary["successes"] / 4
    assert summary["train_wall_s"] > 0 and summary["eval_wall_s"] > 0
    assert summary["train_episodes"] >= 4 * (64 // 20)  # 64 decisions per boat, episodes of at most 20
    assert sorted(os.listdir(out)) == ["model.zip", "summary.json"]  # no temporary files left
    assert json.loads((out / "summary.json").read_text()) == summary
    loaded = PPO.load(out / "model.zip", device="cpu")
    assert (loaded.n_steps, loaded.batch_size, loaded.n_epochs, loaded.gamma) == (64, 64, 10, 0.99)
    assert loaded.policy.net_arch == {"pi": [32, 32], "vf": [32, 32]}
    action, _ = loaded.predict(Sb3VecEnv(QUICK_TASK, num_envs=1).reset(), deterministic=True)
    assert action.shape == (1, 3)
