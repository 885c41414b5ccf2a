"""``ocean-warp train``: learning, exact resumption, checkpoint errors, overrides, the curriculum, the CLI."""

from __future__ import annotations

import dataclasses
import datetime
import subprocess
import sys

import numpy as np
import pytest
import torch

from ocean_warp.eboat.simulator_config import still_water
from ocean_warp.envs import RslRlVecEnv, SailingEnv, WaypointConfig
from ocean_warp.envs.training.agents import CurriculumConfig, PpoConfig, TrainConfig, agent_config
from ocean_warp.envs.training.policy_io import CheckpointError, build_actor, load_policy, read_checkpoint, save_checkpoint
from ocean_warp.envs.training.train_loop import (
    Placement,
    RunOutput,
    TrainLength,
    Training,
    _Curriculum,
    apply_overrides,
    main,
    train,
)
from ocean_warp.termination import Terminated



def quick_task(**changes) -> WaypointConfig:
    """The seed task in still water (four-point hydrostatics), with ``changes``."""
    base = WaypointConfig()
    simulator = dataclasses.replace(base.simulator, ocean=still_water())
    return dataclasses.replace(base, simulator=simulator, **changes)


def easy_task() -> WaypointConfig:
    """A waypoint 15 m dead ahead, a steady 4 m/s wind, a free propeller, 30 s episodes."""
    base = quick_task()
    return quick_task(episode_time=30.0, lost_margin=15.0,
                      start=dataclasses.replace(base.start, waypoint_distance=(15.0, 15.0), wind_speed=(4.0, 4.0),
                                                wind_direction_deg=(0.0, 0.0)),
                      reward=dataclasses.replace(base.reward, propeller_gain=0.0, propeller_cost=0.0,
                                                 progress_scale=15.0))


def small_config(task, **changes) -> TrainConfig:
    ppo = PpoConfig(hidden_dims=(32, 32), init_std=0.6, learning_rate=3e-3, gamma=0.95, entropy_coef=0.0,
                    num_learning_epochs=4)
    return dataclasses.replace(TrainConfig(task="EBoatWaypoint-v0", train_task=task, ppo=ppo), **changes)


def rollout_return(policy, task, num_envs: int = 64, seed: int = 123) -> tuple[float, float]:
    """Mean return per env over one episode length from a seeded reset, and the success rate of the
    episodes that ended (deterministic policy)."""
    env = RslRlVecEnv(SailingEnv(task, num_envs, device="cpu", seed=seed))
    total = torch.zeros(num_envs)
    successes = []
    with torch.inference_mode():
        for _ in range(env.max_episode_length):
            _, rewards, _, extras = env.step(policy(env.env.buffers.policy_obs))
            total += rewards
            successes.append(extras["log"]["/episode/success_rate"])
    return total.mean().item(), torch.cat(successes).mean().item()


def test_training_raises_the_return_on_an_easy_waypoint(tmp_path, one_torch_thread):
    config = small_config(easy_task(), steps_per_env=16, save_interval=100)
    before = train(config, seed=0, placement=Placement(num_envs=64), length=TrainLength(iterations=1),
                   output=RunOutput(run_dir=str(tmp_path / "a"), progress=False))
    after = train(config, seed=0, placement=Placement(num_envs=64), length=TrainLength(iterations=16),
                  output=RunOutput(run_dir=str(tmp_path / "b"), progress=False))
    return_before, success_before = rollout_return(load_policy(before.policy), easy_task())
    return_after, success_after = rollout_return(load_policy(after.policy), easy_task())
    print(f"return {return_before:.3f} -> {return_after:.3f}, success {success_before:.2f} -> {success_after:.2f}")
    # Reaching the waypoint is worth 1 (progress) + 1 (bonus): the trained fleet must get most of it.
    assert return_after > return_before + 0.8
    assert success_after > success_before + 0.3
    rows = after.history
    assert [row["iteration"] for row in rows] == list(range(16))
    assert [row["samples"] for row in rows] == [64 * 16 * (k + 1) for k in range(16)]
    assert (tmp_path / "b" / "progress.csv").read_text().count("\n") == 17
    assert list((tmp_path / "b").glob("events.out.tfevents.*"))


def test_training_driven_step_by_step_is_train(tmp_path, one_torch_thread):
    """The Training object's steps (setup, then prepare, collect, update and record per iteration, a
    checkpoint, close), driven by hand, give the networks train() gives, bit for bit."""
    from ocean_warp.envs.training.distributed import RankContext, Ranks

    config = small_config(quick_task(episode_time=6.0), steps_per_env=4, save_interval=2)
    whole = train(config, seed=2, placement=Placement(num_envs=8), length=TrainLength(iterations=3),
                  output=RunOutput(run_dir=str(tmp_path / "whole"), progress=False))
    ranks = Ranks.start(RankContext.from_env(), "cpu")
    training = Training(config, ranks, seed=2, length=TrainLength(iterations=3),
                        output=RunOutput(run_dir=str(tmp_path / "by_hand"), progress=False),
                        placement=Placement(num_envs=8), resume=None)
    training.setup()
    for iteration in range(3):
        training.prepare(iteration)
        rollout, failure = training.collect(iteration)
        assert failure is None
        losses, gathered = training.update(iteration, rollout, failure)
        row = training.record(iteration, losses, gathered, collect_time=1.0, learn_time=1.0)
        assert row["decisions_per_s"] == pytest.approx(8 * 4 / 2.0)
    path = training.checkpoint(2)
    training.close()
    training.close()  # idempotent
    ranks.close()
    mine, theirs = read_checkpoint(path), read_checkpoint(whole.checkpoint)
    assert mine["iteration"] == theirs["iteration"] == 2
    for key in ("actor_state_dict", "critic_state_dict"):
        for name, tensor in theirs[key].items():
            assert torch.equal(mine[key][name], tensor), (key, name)
    np.testing.assert_array_equal([row["mean_return"] for row in training.history],
                                  [row["mean_return"] for row in whole.history])


def test_resumed_training_matches_the_uninterrupted_run_bit_for_bit(tmp_path, one_torch_thread):
    config = small_config(quick_task(episode_time=6.0), steps_per_env=4, save_interval=2)
    straight = train(config, seed=3, placement=Placement(num_envs=8), length=TrainLength(iterations=4),
                     output=RunOutput(run_dir=str(tmp_path / "straight"), progress=False))
    first = train(config, seed=3, placement=Placement(num_envs=8), length=TrainLength(iterations=2),
                  output=RunOutput(run_dir=str(tmp_path / "split"), progress=False))
    assert first.checkpoint.endswith("model_1.pt")
    resumed = train(config, seed=3, placement=Placement(num_envs=8), length=TrainLength(iterations=2),
                    output=RunOutput(progress=False), resume=first.checkpoint)
    assert resumed.run_dir == first.run_dir and resumed.checkpoint.endswith("model_3.pt")
    a, b = read_checkpoint(straight.checkpoint), read_checkpoint(resumed.checkpoint)
    for key in ("actor_state_dict", "critic_state_dict"):
        for name, tensor in a[key].items():
            assert torch.equal(tensor, b[key][name]), f"{key}.{name}"
    state_a, state_b = a["optimizer_state_dict"]["state"], b["optimizer_state_dict"]["state"]
    for index in state_a:
        for name in ("exp_avg", "exp_avg_sq"):
            assert torch.equal(state_a[index][name], state_b[index][name])
    assert a["optimizer_state_dict"]["param_groups"][0]["lr"] == b["optimizer_state_dict"]["param_groups"][0]["lr"]
    returns_a = [row["mean_return"] for row in a["history"]]
    returns_b = [row["mean_return"] for row in b["history"]]
    np.testing.assert_array_equal(returns_a, returns_b)
    # ... and the run did learn something: the weights moved from their initial values.
    assert not torch.equal(a["actor_state_dict"]["mlp.0.weight"],
                           read_checkpoint(first.checkpoint)["actor_state_dict"]["mlp.0.weight"])


def _policy_checkpoint(path, **changes):
    actor_config = PpoConfig(hidden_dims=(16,)).actor_config()
    actor = build_actor(5, 3, actor_config)
    data = {"task": "EBoatWaypoint-v0", "observation": "seed", "num_obs": 5, "num_actions": 3,
            "actor_config": actor_config, "actor_state_dict": actor.state_dict()}
    data.update(changes)
    save_checkpoint(path, data)
    return path


def test_a_policy_checkpoint_round_trips(tmp_path):
    path = _policy_checkpoint(tmp_path / "policy.pt")
    policy = load_policy(path)
    observations = torch.from_numpy(np.random.default_rng(5).uniform(-1, 1, (7, 5)).astype(np.float32))
    actor = build_actor(5, 3, PpoConfig(hidden_dims=(16,)).actor_config())
    actor.load_state_dict(read_checkpoint(path)["actor_state_dict"])
    from tensordict import TensorDict

    expected = actor(TensorDict({"policy": observations}, batch_size=[7]))
    assert torch.equal(policy(observations), expected)
    with pytest.raises(ValueError, match=r"shape \(N, 5\)"):
        policy(torch.zeros(3, 4))
    with pytest.raises(CheckpointError, match="for EBoatWaypoint-v0, not EBoatMission-v0"):
        load_policy(path, task="EBoatMission-v0")


def test_bad_checkpoints_give_clear_errors(tmp_path):
    good = _policy_checkpoint(tmp_path / "good.pt")
    data = good.read_bytes()
    truncated = tmp_path / "truncated.pt"
    truncated.write_bytes(data[: len(data) // 2])
    with pytest.raises(CheckpointError, match="truncated.pt.*could not be read"):
        load_policy(truncated)
    with pytest.raises(CheckpointError, match="no such file"):
        load_policy(tmp_path / "missing.pt")
    foreign = tmp_path / "foreign.pt"
    torch.save({"model": torch.zeros(3)}, foreign)
    with pytest.raises(CheckpointError, match="not an ocean_warp policy checkpoint"):
        load_policy(foreign)
    code = tmp_path / "code.pt"
    torch.save({"format": "ocean_warp.policy/1", "made": datetime.date(2026, 11, 23)}, code)  # not plain data
    with pytest.raises(CheckpointError, match="holds datetime.date, not only tensors") as error:
        load_policy(code)
    assert "weights_only" not in str(error.value)
    misfit = _policy_checkpoint(tmp_path / "misfit.pt", num_obs=15)
    with pytest.raises(CheckpointError, match="do not fit"):
        load_policy(misfit)
    incomplete = tmp_path / "incomplete.pt"
    save_checkpoint(incomplete, {"task": "EBoatWaypoint-v0"})
    with pytest.raises(CheckpointError, match="lacks observation"):
        load_policy(incomplete)
    with pytest.raises(CheckpointError, match="exported policy, not a training checkpoint"):
        train(agent_config("EBoatWaypoint-v0"), resume=str(good), output=RunOutput(progress=False))


def test_train_command_reports_a_bad_resume_without_a_traceback(tmp_path, capsys):
    """--resume with anything but an ocean_warp checkpoint: one line naming the file and saying it is not one,
    exit status 2, never torch's advice to load unsafely, no run folder."""
    from tests.envs.apps.test_evaluation import unusable_checkpoints

    for name, message in unusable_checkpoints(tmp_path).items():
        path = str(tmp_path / name)
        assert main(["--resume", path, "--no-progress", "--runs-root", str(tmp_path / "runs")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith(f"ocean-warp train: error: checkpoint {path!r}"), (name, err)
        assert message in err[0] and "weights_only" not in err[0], (name, err)
    assert not (tmp_path / "runs").exists()


def test_train_command_checks_its_numbers_first(tmp_path, capsys):
    """--num-envs 0 says that --num-envs must be positive (it once said --workers must be at most num_envs);
    train() says the same of num_envs."""
    for argv, message in ((["--num-envs", "0"], "--num-envs must be a whole number >= 1, got 0"),
                          (["--num-envs", "4", "--workers", "0"], "--workers must be a whole number >= 1, got 0"),
                          (["--minutes", "-1"], "--minutes must be a number > 0, got -1.0")):
        assert main(argv + ["--no-progress", "--runs-root", str(tmp_path)]) == 2
        assert capsys.readouterr().err.strip().splitlines() == [f"ocean-warp train: error: {message}"]
    with pytest.raises(ValueError, match=r"^num_envs must be a whole number >= 1, got 0$"):
        train(agent_config("EBoatWaypoint-v0"), placement=Placement(num_envs=0),
              output=RunOutput(progress=False, runs_root=str(tmp_path)))
    assert list(tmp_path.iterdir()) == []


def test_overrides_reach_nested_fields_and_are_validated():
    config = apply_overrides(agent_config("EBoatMission-v0"),
                             ["ppo.learning_rate=3e-4", "steps_per_env=16", "train_task.decision_period=2.0",
                              "ppo.hidden_dims=(32, 16)", "curriculum.sea_states=()"])
    assert config.ppo.learning_rate == 3e-4 and config.steps_per_env == 16
    assert config.train_task.decision_period == 2.0 and config.ppo.hidden_dims == (32, 16)
    assert config.curriculum.sea_states == ()
    with pytest.raises(ValueError, match="no field 'learning_rat'"):
        apply_overrides(config, ["ppo.learning_rat=1"])
    with pytest.raises(ValueError, match="learning_rate"):
        apply_overrides(config, ["ppo.learning_rate=-1"])
    with pytest.raises(ValueError, match="decision_period"):
        apply_overrides(config, ["train_task.decision_period=0.07"])
    with pytest.raises(ValueError, match="field=value"):
        apply_overrides(config, ["ppo.learning_rate"])


def test_curriculum_moves_up_on_success_and_draws_reproducible_seas():
    curriculum = _Curriculum(CurriculumConfig(sea_states=(0.1, 0.3, 0.5), promote_success=0.8, window=3))
    for rate in (0.9, 0.9, 0.5):  # mean 0.77 over the window: stays
        curriculum.record(rate)
    assert curriculum.level == 0
    curriculum.record(0.96)  # window (0.9, 0.5, 0.96): 0.787, stays
    assert curriculum.level == 0
    curriculum.record(0.96)  # (0.5, 0.96, 0.96): 0.807, up
    assert curriculum.level == 1 and curriculum.window == []
    curriculum.record(float("nan"))  # an iteration in which no episode ended says nothing
    assert curriculum.window == []
    seas = [curriculum.sea_state(seed=4, iteration=k) for k in range(200)]
    assert all(0.0 <= h <= 0.3 for h in seas) and np.std(seas) > 0.05
    assert seas == [curriculum.sea_state(seed=4, iteration=k) for k in range(200)]
    restored = _Curriculum(curriculum.config, curriculum.state())
    assert restored.level == 1 and restored.window == curriculum.window
    for _ in range(10):
        curriculum.record(1.0)
    assert curriculum.level == 2  # the top level is the last
    fixed = _Curriculum(CurriculumConfig(sea_states=(0.2,), randomize=False))
    assert fixed.sea_state(seed=0, iteration=7) == 0.2
    assert _Curriculum(CurriculumConfig()).sea_state(seed=0, iteration=0) is None
    with pytest.raises(ValueError, match="sea_states"):
        CurriculumConfig(sea_states=(0.5, 0.1))


def test_curriculum_over_wind_and_legs_moves_the_start_the_envs_draw(rng):
    """Levels of wind and leg ranges without sea states: the curriculum moves up on success as with seas, and
    the start it gives is drawn by the environments from then on (every new episode's wind speed and
    waypoint distance inside the level's ranges, which the first level's exclude)."""
    winds = ((3.0, 5.0), (8.0, 9.0))
    legs = ((20.0, 30.0), (60.0, 70.0))
    config = CurriculumConfig(wind_speeds=winds, waypoint_distances=legs, promote_success=0.5, window=2)
    curriculum = _Curriculum(config)
    assert curriculum.active and config.levels == 2 and curriculum.sea_state(seed=0, iteration=0) is None
    base = quick_task().start
    assert config.start(base, 0).wind_speed == winds[0] and config.start(base, 0).heading_deg == base.heading_deg
    for rate in (0.6, 0.7):
        curriculum.record(rate)
    assert curriculum.level == 1
    env = SailingEnv(quick_task(), 16, device="cpu", seed=int(rng.integers(1000)))
    env.set_start(config.start(base, curriculum.level))
    env.reset()
    speeds = env.simulator.start.wind_speed.numpy()
    targets = env.buffers.target.numpy()[:, :2] - env.buffers.origin.numpy()[:, :2]
    distances = np.linalg.norm(targets, axis=1)
    assert np.all((speeds >= 8.0) & (speeds <= 9.0)), speeds
    assert np.all((distances >= 60.0 - 1e-3) & (distances <= 70.0 + 1e-3)), distances
    env.step(torch.zeros(16, 3))  # the recaptured decision runs with the new start
    with pytest.raises(ValueError, match="one entry per level"):
        CurriculumConfig(sea_states=(0.1, 0.3), wind_speeds=((3.0, 5.0),))
    with pytest.raises(ValueError, match=r"wind_speeds\[0\]"):
        CurriculumConfig(wind_speeds=((5.0, 3.0),))


def test_the_critic_sees_privileged_truth_unless_told_not_to():
    assert PpoConfig().runner_config(8)["obs_groups"] == {"actor": ["policy"], "critic": ["critic"]}
    plain = PpoConfig(privileged_critic=False).runner_config(8)["obs_groups"]
    assert plain == {"actor": ["policy"], "critic": ["policy"]}
    with pytest.raises(ValueError, match="privileged_critic"):
        PpoConfig(privileged_critic=1)


def test_every_task_has_a_valid_agent_config():
    from ocean_warp.envs import TASK_IDS

    for task in TASK_IDS:
        config = agent_config(task)
        assert config.task == task and config.iterations >= 1
    assert agent_config("EBoatMission-v0").train_task.route is None  # practice legs, drawn per episode
    with pytest.raises(ValueError, match="unknown task"):
        agent_config("EBoatNothing-v0")


@pytest.mark.parametrize("job", ["train"])
def test_cli_help(job):
    result = subprocess.run([sys.executable, "-m", "ocean_warp.cli", job, "--help"], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 0, result.stderr
    for option in ("--task", "--device", "--num-envs", "--iterations", "--minutes", "--seed", "--run-name",
                   "--resume"):
        assert option in result.stdout


def test_multi_gpu_benchmark_table_without_a_one_gpu_run():
    """``benchmarks/perf/multi_gpu_bench.py --gpus 2`` alone has no one-GPU baseline: speed-up and efficiency read
    "n/a" (they once read "nanx" and "nan%"); with one, they are against it."""
    from benchmarks.perf.multi_gpu_bench import format_table

    def row(gpus, rate):
        return {"gpus": gpus, "iterations": 10, "samples": 2e6, "collect_decisions_per_s": rate,
                "loop_decisions_per_s": rate / 2, "command_s": 60.0, "capable_iteration": None, "final_completed": 3}

    settings = dict(num_envs=4096, minutes=1.0, runs=20, threshold=20, evaluated=True, device_name="GPU")
    alone = format_table([row(2, 3.0e5)], **settings)
    assert "nan" not in alone.lower() and "| 300,000 | n/a | n/a |" in alone
    assert "no one-GPU run" in alone
    both = format_table([row(1, 2.0e5), row(2, 3.6e5)], **settings)
    assert "| 200,000 | 1.00x | 100% |" in both and "| 360,000 | 1.80x | 90% |" in both
    assert "n/a" not in both and "nan" not in both.lower()


@pytest.mark.parametrize("interruption", [KeyboardInterrupt, Terminated])
def test_an_interrupted_run_saves_its_last_completed_iteration(interruption, tmp_path, monkeypatch, capsys,
                                                               one_torch_thread):
    """Ctrl-C (or SIGTERM) while iteration 3 starts, far from a checkpoint (interval 50): model_2.pt and
    policy.pt are written, and they hold what an uninterrupted 3-iteration run ends with."""
    config = small_config(quick_task(episode_time=6.0), steps_per_env=4, save_interval=50)
    straight = train(config, seed=4, placement=Placement(num_envs=8), length=TrainLength(iterations=3),
                     output=RunOutput(run_dir=str(tmp_path / "straight"), progress=False))
    prepare = Training.prepare

    def prepare_until_interrupted(self, iteration):
        if iteration == 3:
            raise interruption()
        prepare(self, iteration)

    monkeypatch.setattr(Training, "prepare", prepare_until_interrupted)
    run_dir = tmp_path / "interrupted"
    with pytest.raises(interruption):
        train(config, seed=4, placement=Placement(num_envs=8), length=TrainLength(iterations=10),
              output=RunOutput(run_dir=str(run_dir), progress=False))
    assert sorted(p.name for p in run_dir.glob("*.pt")) == ["model_2.pt", "policy.pt"]
    assert not [p.name for p in run_dir.iterdir() if p.name.startswith(".")]
    saved, expected = read_checkpoint(run_dir / "model_2.pt"), read_checkpoint(straight.checkpoint)
    assert saved["iteration"] == 2 and len(saved["history"]) == 3
    for key in ("actor_state_dict", "critic_state_dict"):
        for name, tensor in expected[key].items():
            assert torch.equal(saved[key][name], tensor), (key, name)
    policy = load_policy(run_dir / "policy.pt")
    observations = torch.zeros(1, policy.num_obs)
    assert torch.equal(policy(observations), load_policy(straight.policy)(observations))
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"ocean-warp train: interrupted; iteration 2 saved as {run_dir / 'model_2.pt'} (and policy.pt "
                   f"beside it); --resume {run_dir / 'model_2.pt'} continues"]
