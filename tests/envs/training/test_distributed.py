"""Training on several ranks (torchrun), on the CPU: ranks read from torchrun's variables, each rank's seed and
share of the environments, the ``--gpus`` launcher's command line and errors, and two real CPU processes
(gloo) that train one policy: rank 0 alone writes, both end with the same networks, the checkpoint resumes
in one process, and a rank that fails (NaN, killed, stuck) stops the whole job in bounded time with no
process left behind.

The multi-process tests start ``python -m torch.distributed.run`` with tiny settings (8 environments per
rank, 4 decisions each, two iterations); each takes about ten seconds, most of it importing.
"""

from __future__ import annotations

import dataclasses
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
import uuid

import pytest
import torch

from ocean_warp.envs import RslRlVecEnv, SailingEnv, WaypointConfig
from ocean_warp.envs.training import train_loop as training
from ocean_warp.envs.training.agents import agent_config
from ocean_warp.envs.training.distributed import RankContext, derived_seed, parameter_checksum, rank_device, rank_seed
from ocean_warp.envs.training.distributed_launch import describe_failure, gpus_problem, launch, torchrun_command
from ocean_warp.envs.training.policy_io import read_checkpoint
from ocean_warp.envs.training.train_loop import Placement, RunOutput, TrainLength, apply_overrides, train

TINY = ["--task", "EBoatWaypoint-v0", "--device", "cpu", "--num-envs", "8", "--set", "steps_per_env=4",
        "--set", "save_interval=2", "--set", "train_task.episode_time=6.0", "--set", "ppo.hidden_dims=(16, 16)",
        "--seed", "5", "--no-progress"]
"""8 environments per rank, 4 decisions each per iteration, 6 s episodes, [16, 16] networks."""


# --- ranks, seeds, shares ------------------------------------------------------------------------------

def test_rank_context_reads_torchrun_variables_and_rejects_bad_ones():
    assert RankContext.from_env({}) == RankContext(0, 0, 1)
    context = RankContext.from_env({"RANK": "3", "LOCAL_RANK": "1", "WORLD_SIZE": "4", "LOCAL_WORLD_SIZE": "2"})
    assert (context.rank, context.local_rank, context.world_size) == (3, 1, 4)
    assert context.distributed and not context.is_main and context.first_env(256) == 768
    for environ, message in (({"WORLD_SIZE": "two"}, "WORLD_SIZE='two' is not a whole number"),
                             ({"WORLD_SIZE": "2", "RANK": "1"}, "LOCAL_RANK is not set"),
                             ({"WORLD_SIZE": "2", "LOCAL_RANK": "0"}, "RANK is not set"),
                             ({"WORLD_SIZE": "2", "RANK": "2", "LOCAL_RANK": "0"}, r"RANK must be in 0\.\.1"),
                             ({"WORLD_SIZE": "2", "RANK": "-1", "LOCAL_RANK": "0"}, r"RANK must be in 0\.\.1"),
                             ({"WORLD_SIZE": "0"}, "WORLD_SIZE must be >= 1"),
                             ({"WORLD_SIZE": "2", "RANK": "1", "LOCAL_RANK": "1.0"}, "LOCAL_RANK='1.0'"),
                             ({"WORLD_SIZE": "4", "RANK": "3", "LOCAL_RANK": "2", "LOCAL_WORLD_SIZE": "2"},
                              "below LOCAL_WORLD_SIZE 2")):
        with pytest.raises(ValueError, match=message):
            RankContext.from_env(environ)


def test_rank_seeds_devices_and_shares_are_distinct_and_deterministic():
    for seed in (0, 1, 12345):
        seeds = [rank_seed(seed, rank) for rank in range(16)]
        assert seeds[0] == seed and len(set(seeds)) == 16  # rank 0 seeds as a plain run does
        assert seeds == [rank_seed(seed, rank) for rank in range(16)]
        assert all(0 <= s < 2**31 for s in seeds)
    assert rank_seed(0, 1) != rank_seed(1, 1)
    state = torch.Generator().manual_seed(9).get_state()
    derived = [derived_seed(state, rank) for rank in range(1, 8)]
    assert len(set(derived)) == 7 and derived == [derived_seed(state, rank) for rank in range(1, 8)]
    assert [RankContext(r, r, 4).first_env(100) for r in range(4)] == [0, 100, 200, 300]
    two = RankContext(1, 1, 2)
    assert rank_device(two, "cuda") == rank_device(two, "cuda:1") == "cuda:1"
    assert rank_device(two, "cpu") == "cpu" and rank_device(RankContext(), "cuda:3") == "cuda:3"
    with pytest.raises(ValueError, match="trains on cuda:1, not cuda:0"):
        rank_device(two, "cuda:0")


def _tiny_task() -> WaypointConfig:
    return dataclasses.replace(WaypointConfig(), episode_time=6.0)


def test_each_rank_restarts_its_own_slice_of_one_batch():
    """Two ranks of 3 environments restart segments exactly as environments [0, 3) and [3, 6) of one batch
    of 6: the same starts (random streams numbered from the global index) and episode clocks."""
    config = agent_config("EBoatWaypoint-v0")
    assert config.random_episode_start
    whole = RslRlVecEnv(SailingEnv(_tiny_task(), 6, device="cpu", seed=4))
    training._restart_segment(whole, config, 4, 50, torch.zeros(6, dtype=torch.bool))
    for rank in (0, 1):
        share = RslRlVecEnv(SailingEnv(_tiny_task(), 3, device="cpu", seed=4, first_env=3 * rank))
        training._restart_segment(share, config, 4, 50, torch.zeros(3, dtype=torch.bool), first_env=3 * rank)
        rows = slice(3 * rank, 3 * rank + 3)
        assert torch.equal(share.episode_length_buf, whole.episode_length_buf[rows])
        assert torch.equal(share.env.buffers.policy_obs, whole.env.buffers.policy_obs[rows])
    assert len(set(whole.episode_length_buf.tolist())) > 1  # the clocks are spread


# --- the launcher ----------------------------------------------------------------------------------------

def test_launcher_command_line():
    head = ["/py", "-m", "torch.distributed.run", "--standalone", "--nproc_per_node=2",
            "-m", "ocean_warp.envs.training.train"]
    args = ["--task", "EBoatMission-v0", "--minutes", "5"]
    assert torchrun_command(["--gpus", "2", *args], 2, "/py") == head + args + ["--device", "cuda"]
    assert torchrun_command([*args, "--gpus=2", "--device", "cuda"], 2, "/py") == head + args + ["--device", "cuda"]
    assert torchrun_command(["--gpu", "2", "--dev=cuda", *args, "--dist-timeout", "60"], 2, "/py") == \
        head + ["--dev=cuda", *args, "--dist-timeout", "60"]
    four = torchrun_command(["--gpus", "4", "--set", "ppo.learning_rate=3e-4"], 4)
    assert four[0] == sys.executable and "--nproc_per_node=4" in four and "--gpus" not in four
    assert four[-4:] == ["--set", "ppo.learning_rate=3e-4", "--device", "cuda"]


def test_bad_gpus_are_one_line_errors():
    assert gpus_problem("2", None, visible=2, environ={}) is None
    assert gpus_problem("1", "cuda", visible=1, environ={}) is None
    for gpus, device, visible, message in (
            ("0", None, 2, "whole number of GPUs >= 1, got 0"), ("-1", None, 2, "got -1"),
            ("two", None, 2, "got 'two'"), ("1.5", None, 2, "got '1.5'"),
            ("3", None, 2, "--gpus 3: only 2 GPU"), ("1", None, 0, "only 0 GPU"),
            ("2", "cpu", 2, "use --device cuda .* not cpu; for several CPU processes start torchrun"),
            ("2", "cuda:1", 2, "not cuda:1")):
        problem = gpus_problem(gpus, device, visible=visible, environ={})
        assert problem is not None and "\n" not in problem
        assert re.search(message, problem), problem
    assert "leave it out" in gpus_problem("2", None, 2, environ={"WORLD_SIZE": "2"})


def test_train_command_gpus_errors_and_launch(monkeypatch, capsys):
    monkeypatch.setattr(training, "visible_gpus", lambda: 1)
    for argv, message in ((["--gpus", "0"], "got 0"), (["--gpus", "x"], "got 'x'"),
                          (["--gpus", "2"], "--gpus 2: only 1 GPU(s) visible"),
                          (["--gpus", "1", "--device", "cpu"], "not cpu")):
        assert training.main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and message in err and err.startswith("ocean-warp train: "), err
    launched = []
    monkeypatch.setattr(training, "visible_gpus", lambda: 2)
    monkeypatch.setattr(training, "launch", lambda command, job: launched.append((command, job)) or 7)
    assert training.main(["--gpus", "2", "--iterations", "3"]) == 7
    assert launched == [(torchrun_command(["--iterations", "3"], 2), "training on 2 GPUs")]


SUMMARY = """torch.distributed.elastic.multiprocessing.errors.ChildFailedError:
============================================================
ocean_warp.envs.training.train FAILED
------------------------------------------------------------
Failures:
[1]:
  rank      : 0 (local_rank: 0)
  exitcode  : -15 (pid: 11)  (SIGTERM)
------------------------------------------------------------
Root Cause (first observed failure):
[0]:
  time      : 2026-11-23_23:25:47
  host      : localhost
  rank      : 1 (local_rank: 1)
  exitcode  : -9 (pid: 12)  (SIGKILL)
============================================================
"""


def test_a_failed_launch_ends_with_one_line_naming_the_rank(capsys):
    assert "rank 1 exited first, killed by signal 9 (SIGKILL)" in describe_failure(SUMMARY, 1, "training on 2 GPUs")
    assert "torchrun exited with status 3" in describe_failure("no summary", 3, "training on 2 GPUs")
    command = [sys.executable, "-c", f"import sys; sys.stderr.write({SUMMARY!r}); sys.exit(1)"]
    assert launch(command, "training on 2 GPUs") == 1
    err = capsys.readouterr().err
    assert err.rstrip().splitlines()[-1] == ("ocean-warp train: training on 2 GPUs failed: rank 1 exited first, "
                                             "killed by signal 9 (SIGKILL), and torchrun stopped the others; "
                                             "the messages above say why")


def _child_noting(signal_name: str, ready, caught) -> str:
    """A child program that creates ``ready``, then waits; ``signal_name`` makes it append the name to
    ``caught`` and exit with status 3."""
    return (f"import signal, sys, time\n"
            f"signal.signal(signal.{signal_name}, lambda *_: (open({str(caught)!r}, 'a').write('{signal_name} '), "
            f"sys.exit(3)))\n"
            f"open({str(ready)!r}, 'w').close()\n"
            f"time.sleep(600)\n")


def test_ctrl_c_is_passed_to_torchrun_and_raised_once_it_has_exited(tmp_path):
    """The launcher forwards Ctrl-C (SIGINT) to its child exactly once, waits for it, and re-raises."""
    ready, caught = tmp_path / "ready", tmp_path / "caught"
    child = _child_noting("SIGINT", ready, caught)

    def interrupt_when_ready() -> None:
        deadline = time.monotonic() + 30.0
        while not ready.exists() and time.monotonic() < deadline:
            time.sleep(0.02)
        os.kill(os.getpid(), signal.SIGINT)

    # A job started in the background by a shell without job control (nohup, CI runners) begins with SIGINT
    # ignored, and Python then installs no KeyboardInterrupt handler: give this test the one a terminal gives
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        threading.Thread(target=interrupt_when_ready, daemon=True).start()
        with pytest.raises(KeyboardInterrupt):
            launch([sys.executable, "-c", child], "training on 2 GPUs")
    finally:
        signal.signal(signal.SIGINT, previous)
    assert caught.read_text() == "SIGINT "  # forwarded (the child would otherwise sleep its 60 s and write nothing)


def test_launch_passes_sigterm_on_to_torchrun(tmp_path):
    """SIGTERM to ``ocean-warp train --gpus G`` (the handler ocean-warp installs) reaches torchrun as SIGTERM,
    and the launcher ends with Terminated (status 143) once it has exited."""
    from ocean_warp.termination import Terminated, exit_cleanly_on_sigterm

    ready, caught = tmp_path / "ready", tmp_path / "caught"
    child = _child_noting("SIGTERM", ready, caught)

    def terminate_when_ready() -> None:
        while not ready.exists():
            time.sleep(0.02)
        os.kill(os.getpid(), signal.SIGTERM)

    previous = signal.getsignal(signal.SIGTERM)
    try:
        exit_cleanly_on_sigterm(["train"])
        threading.Thread(target=terminate_when_ready, daemon=True).start()
        with pytest.raises(Terminated) as raised:
            launch([sys.executable, "-c", child], "training on 2 GPUs")
    finally:
        signal.signal(signal.SIGTERM, previous)
    assert raised.value.code == 143 and caught.read_text() == "SIGTERM "


# --- two CPU ranks (gloo) ----------------------------------------------------------------------------------

def _tagged(tag: str) -> list[int]:
    """Processes (pids) whose environment carries ``OCEAN_WARP_TEST_TAG=tag``: the job's, wherever they are."""
    needle = f"OCEAN_WARP_TEST_TAG={tag}".encode()
    found = []
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/environ", "rb") as stream:
                if needle in stream.read().split(b"\0"):
                    found.append(int(name))
        except OSError:
            continue
    return found


def _torchrun(arguments: list[str], cwd, *, fault: str | None = None, limit_s: float = 240.0):
    """Run two CPU ranks of ``python -m ocean_warp.envs.training.train arguments``; (completed process, seconds,
    leftover pids of the job a few seconds after torchrun exited). Kills the job if it outlives ``limit_s``."""
    tag = uuid.uuid4().hex
    env = dict(os.environ, OCEAN_WARP_TEST_TAG=tag, OMP_NUM_THREADS="1", PYTHONUNBUFFERED="1")
    env.pop("OCEAN_WARP_FAULT", None)
    if fault:
        env["OCEAN_WARP_FAULT"] = fault
    command = [sys.executable, "-m", "torch.distributed.run", "--standalone", "--nproc_per_node=2",
               "-m", "ocean_warp.envs.training.train", *arguments]
    started = time.monotonic()
    try:
        result = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=limit_s)
    finally:
        elapsed = time.monotonic() - started
        deadline = time.monotonic() + 5.0
        while (left := _tagged(tag)) and time.monotonic() < deadline:
            time.sleep(0.1)
        for pid in left:  # never leave a stray job behind, even when the test fails
            os.kill(pid, signal.SIGKILL)
    return result, elapsed, left


def test_two_cpu_ranks_train_one_policy_that_resumes_in_one_process(tmp_path, one_torch_thread):
    root, cwd = tmp_path / "runs", tmp_path / "cwd"
    cwd.mkdir()
    result, _, left = _torchrun([*TINY, "--iterations", "2", "--runs-root", str(root), "--run-name", "pair",
                                 "--dist-timeout", "60"], cwd)
    assert result.returncode == 0, result.stderr[-3000:]
    assert not left
    runs = list((root / "EBoatWaypoint-v0").iterdir())
    assert len(runs) == 1 and not list(cwd.iterdir())  # rank 1 wrote nothing, anywhere
    run = runs[0]
    assert sorted(p.name for p in run.iterdir() if not p.name.startswith("events.")) == \
        ["config.json", "distributed.json", "model_1.pt", "policy.pt", "progress.csv"]
    assert len(list(run.glob("events.out.tfevents.*"))) == 1
    assert "2 ranks ended with identical networks" in result.stdout
    record = json.loads((run / "distributed.json").read_text())
    assert record["world_size"] == 2 and record["backend"] == "gloo" and record["identical_parameters"]
    assert record["num_envs_per_rank"] == 8 and len(set(record["parameter_checksums"])) == 1
    assert json.loads((run / "config.json").read_text())["world_size"] == 2

    checkpoint = read_checkpoint(run / "model_1.pt")
    assert checkpoint["world_size"] == 2 and len(checkpoint["rank_rng_states"]) == 1
    assert parameter_checksum(checkpoint["actor_state_dict"], checkpoint["critic_state_dict"]) == \
        record["parameter_checksums"][0]
    assert [row["samples"] for row in checkpoint["history"]] == [64, 128]  # 2 ranks x 8 envs x 4 decisions

    config = apply_overrides(agent_config("EBoatWaypoint-v0"), [TINY[i + 1] for i, t in enumerate(TINY) if t == "--set"])
    resumed = train(config, seed=5, placement=Placement(num_envs=8), length=TrainLength(iterations=1),
                    output=RunOutput(progress=False), resume=str(run / "model_1.pt"))
    assert resumed.run_dir == str(run) and resumed.checkpoint.endswith("model_2.pt") and resumed.world_size == 1
    assert resumed.parameter_checksums is None
    after = read_checkpoint(resumed.checkpoint)
    assert after["world_size"] == 1 and "rank_rng_states" not in after
    assert [row["samples"] for row in after["history"]] == [64, 128, 160]
    assert not torch.equal(after["actor_state_dict"]["mlp.0.weight"], checkpoint["actor_state_dict"]["mlp.0.weight"])


@pytest.mark.parametrize("fault", ["nan", "kill", "hang"])
def test_a_failing_rank_stops_the_whole_job(tmp_path, fault):
    """Rank 1 fails after collecting iteration 1: every process exits, non-zero, within the timeout, and
    rank 0 says which rank failed and how (or, killed, torchrun's summary does)."""
    timeout_s = 8
    result, _, left = _torchrun([*TINY, "--iterations", "3", "--runs-root", str(tmp_path),
                                 "--dist-timeout", str(timeout_s)], tmp_path, fault=f"1:1:{fault}")
    assert result.returncode != 0
    assert not left, f"processes left behind: {left}"
    err = result.stderr
    if fault == "nan":
        assert ("ocean-warp train: rank 1 failed at iteration 1: NonFiniteBatch: NaN or infinity in the batch "
                "collected at iteration 1: rewards") in err
    elif fault == "kill":
        # Usually torchrun sees the killed rank 1 first; under load, rank 0's collective can abort on the
        # vanished peer before torchrun polls rank 1 (seen once in a full CPU run), and then rank 0 is first.
        said = describe_failure(err, result.returncode, "training on 2 GPUs")
        assert ("rank 1 exited first, killed by signal 9 (SIGKILL)" in said
                or "rank 0 exited first, killed by signal 6 (SIGABRT)" in said), said
    else:
        assert f"rank 0 lost contact with the other ranks (one failed, was killed or is stuck for more than the " \
               f"{timeout_s} s timeout)" in err
    # save_interval 2: no periodic checkpoint was reached. Rank 0 may save the iteration it completed before the
    # failure, 0, as an interrupted run does: torchrun ends it with SIGTERM when rank 1 is killed
    saved = list(tmp_path.glob("*/*/model_*.pt"))
    assert [path.name for path in saved] in ([], ["model_0.pt"]), saved
    assert all(read_checkpoint(str(path))["iteration"] == 0 for path in saved)
