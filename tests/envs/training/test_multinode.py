"""Training across hosts: ``--nnodes``, ``--node-rank``, ``--rdzv-endpoint`` and ``--rdzv-id`` checked and turned
into torchrun's rendezvous arguments, torchrun's host variables read, the random streams a checkpoint resumed on
another number of ranks continues, and two "hosts" (two ``ocean-warp train --nnodes 2`` launches on this
machine, each a torchrun agent with one CPU rank, meeting at a localhost c10d rendezvous) that train one policy,
whose checkpoint resumes on one host and on three ranks.

There is no second machine here: the two hosts are two process trees of one machine. The two-host test starts
three torchrun jobs (two hosts, then three ranks resuming) and one in-process resume: about a minute on two cores.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
import uuid

import numpy as np
import pytest
import torch

from ocean_warp.envs.training import train_loop as training
from ocean_warp.envs.training.distributed import RankContext, parameter_checksum, rank_device
from ocean_warp.envs.training.distributed_launch import describe_failure, hosts_problem, torchrun_command
from ocean_warp.envs.training.policy_io import read_checkpoint
from ocean_warp.envs.training.rendezvous import Rendezvous, parse_endpoint, rendezvous_from_options
from tests.envs.training.test_distributed import SUMMARY, TINY, _tagged


# --- options and torchrun's arguments ----------------------------------------------------------------------

def test_rendezvous_options_become_torchrun_arguments():
    c10d = rendezvous_from_options("2", None, "node01:29500", None)
    assert c10d == Rendezvous(2, 2, "node01", 29500, "ocean-warp-train", None)
    assert c10d.torchrun_arguments() == ["--nnodes=2", "--rdzv-backend=c10d", "--rdzv-endpoint=node01:29500",
                                         "--rdzv-id=ocean-warp-train"]
    elastic = rendezvous_from_options(" 2:8 ", None, "10.0.0.7:1234", "job_77")
    assert (elastic.min_nodes, elastic.max_nodes, elastic.nnodes) == (2, 8, "2:8")
    assert elastic.torchrun_arguments()[:3] == ["--nnodes=2:8", "--rdzv-backend=c10d", "--rdzv-endpoint=10.0.0.7:1234"]
    static = rendezvous_from_options("3", 2, "[fe80::1]:29400", "run.1")
    assert static.torchrun_arguments() == ["--nnodes=3", "--node-rank=2", "--rdzv-backend=static",
                                           "--rdzv-endpoint=[fe80::1]:29400", "--rdzv-id=run.1"]
    assert parse_endpoint("[::1]:29500") == ("::1", 29500) and parse_endpoint("localhost:1") == ("localhost", 1)
    assert rendezvous_from_options(None, None, None, None) is None


@pytest.mark.parametrize("nnodes, node_rank, endpoint, run_id, message", [
    ("2", None, None, None, "--nnodes 2 needs --rdzv-endpoint HOST:PORT"),
    ("0", None, "h:1", None, "--nnodes must be a whole number of hosts >= 1, or MIN:MAX .* got '0'"),
    ("-1", None, "h:1", None, "got '-1'"), ("two", None, "h:1", None, "got 'two'"),
    ("3:2", None, "h:1", None, "got '3:2'"), ("1:2:3", None, "h:1", None, "got '1:2:3'"),
    ("2", None, "node01", None, "--rdzv-endpoint must be HOST:PORT.* got 'node01'"),
    ("2", None, "node01:", None, "got 'node01:'"), ("2", None, ":29500", None, "got ':29500'"),
    ("2", None, "node01:port", None, "got 'node01:port'"), ("2", None, "a b:1", None, "got 'a b:1'"),
    ("2", None, "::1:29500", None, "got '::1:29500'"),
    ("2", None, "node01:0", None, "the port must be in 1..65535, got 0"),
    ("2", None, "node01:65536", None, "got 65536"),
    ("2", 2, "h:1", None, r"--node-rank must be in 0\.\.1 \(--nnodes 2\), got 2"),
    ("2", -1, "h:1", None, "got -1"),
    ("1:4", 0, "h:1", None, "needs a fixed --nnodes N, not 1:4"),
    ("2", None, "h:1", "my job", "--rdzv-id must be letters, digits"),
    (None, 1, None, None, "--node-rank only applies with several hosts: add --nnodes N"),
    (None, None, "h:1", "x", "--rdzv-endpoint and --rdzv-id only apply with several hosts"),
])
def test_bad_rendezvous_options_are_one_line_errors(nnodes, node_rank, endpoint, run_id, message):
    with pytest.raises(ValueError, match=message) as raised:
        rendezvous_from_options(nnodes, node_rank, endpoint, run_id)
    assert "\n" not in str(raised.value)


def test_the_launcher_keeps_its_options_from_the_ranks():
    rendezvous = Rendezvous(2, 2, "node01", 29500, "j")
    joined = ["--nnodes=2", "--rdzv-backend=c10d", "--rdzv-endpoint=node01:29500", "--rdzv-id=j"]
    argv = ["--nnodes", "2", "--rdzv-endpoint=node01:29500", "--rdzv-i", "j", "--num-envs", "8", "--node", "0",
            "--device", "cpu"]
    assert torchrun_command(argv, 1, "/py", rendezvous=rendezvous, on_gpus=False) == \
        ["/py", "-m", "torch.distributed.run", *joined, "--nproc_per_node=1", "-m", "ocean_warp.envs.training.train",
         "--num-envs", "8", "--device", "cpu"]
    gpus = torchrun_command(["--gpus", "4", "--nnodes", "2", "--rdzv-endpoint", "node01:29500", "--rdzv-id", "j"],
                            4, "/py", rendezvous=rendezvous)
    assert gpus[3:8] == [*joined, "--nproc_per_node=4"] and gpus[-2:] == ["--device", "cuda"]
    assert "failed: rank 1 exited first" in describe_failure(SUMMARY, 1, "training on 2 hosts (4 GPUs on this one)")


def test_train_command_hosts_errors_and_launch(monkeypatch, capsys):
    monkeypatch.setattr(training, "visible_gpus", lambda: 2)
    for argv, message in ((["--nnodes", "2"], "--nnodes 2 needs --rdzv-endpoint"),
                          (["--nnodes", "2", "--rdzv-endpoint", "node01"], "--rdzv-endpoint must be HOST:PORT"),
                          (["--nnodes", "0", "--rdzv-endpoint", "h:1"], "got '0'"),
                          (["--nnodes", "2", "--rdzv-endpoint", "h:1", "--node-rank", "5"], "got 5"),
                          (["--nnodes", "2", "--rdzv-endpoint", "h:1", "--device", "cuda:1"], "not cuda:1"),
                          (["--nnodes", "2", "--rdzv-endpoint", "h:1", "--gpus", "3"], "only 2 GPU")):
        assert training.main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and message in err and err.startswith("ocean-warp train: error: "), err
    launched = []
    monkeypatch.setattr(training, "launch", lambda command, job: launched.append((command, job)) or 0)
    hosts = ["--nnodes", "2", "--rdzv-endpoint", "h:1"]
    assert training.main([*hosts, "--device", "cpu", "--iterations", "3"]) == 0
    assert training.main(["--gpus", "1", *hosts]) == 0  # one GPU per host still starts torchrun
    rendezvous = Rendezvous(2, 2, "h", 1)
    assert launched == [
        (torchrun_command(["--device", "cpu", "--iterations", "3"], 1, rendezvous=rendezvous, on_gpus=False),
         "training on 2 hosts (1 rank on this one)"),
        (torchrun_command([], 1, rendezvous=rendezvous), "training on 2 hosts (1 GPU on this one)")]
    assert launched[0][0][-4:] == ["--device", "cpu", "--iterations", "3"]
    under_torchrun = {"TORCHELASTIC_RUN_ID": "x", "WORLD_SIZE": "1"}
    assert "leave it out when torchrun starts the ranks" in hosts_problem(None, None, environ=under_torchrun)


# --- ranks on several hosts ------------------------------------------------------------------------------------

def test_a_rank_on_the_second_host_takes_its_seed_and_share_from_its_global_rank_and_its_gpu_from_its_local():
    """Rank 5 of 8, the second of 4 on host 1 (torchrun's variables as on that host)."""
    context = RankContext.from_env({"RANK": "5", "LOCAL_RANK": "1", "WORLD_SIZE": "8", "LOCAL_WORLD_SIZE": "4",
                                    "GROUP_RANK": "1"})
    assert (context.rank, context.local_rank, context.world_size, context.node_rank) == (5, 1, 8, 1)
    assert context.first_env(256) == 5 * 256 and rank_device(context, "cuda") == "cuda:1"
    assert RankContext.from_env({}).node_rank == 0
    for environ, message in (({"RANK": "1", "LOCAL_RANK": "0", "WORLD_SIZE": "2", "GROUP_RANK": "-1"},
                              r"GROUP_RANK \(the host's index\) must be in 0\.\.1"),
                             ({"RANK": "1", "LOCAL_RANK": "0", "WORLD_SIZE": "2", "GROUP_RANK": "one"},
                              "GROUP_RANK='one' is not a whole number")):
        with pytest.raises(ValueError, match=message):
            RankContext.from_env(environ)


def _expected_derived_state(rank0_state: torch.Tensor, rank: int) -> torch.Tensor:
    """The documented rule, spelled out: SHA-256 of rank 0's saved state, its first 4 bytes little-endian, then
    31 bits of SeedSequence([that, rank]) seed the rank's generator."""
    digest = hashlib.sha256(rank0_state.numpy().tobytes()).digest()
    seed = int(np.random.SeedSequence([int.from_bytes(digest[:4], "little"), rank]).generate_state(1)[0]) & (2**31 - 1)
    return torch.Generator().manual_seed(seed).get_state()


def test_a_checkpoint_of_two_ranks_restores_each_ranks_random_stream_on_one_two_or_three():
    saved = [torch.Generator().manual_seed(11).get_state(), torch.Generator().manual_seed(12).get_state()]
    checkpoint = {"torch_rng_state": saved[0], "rank_rng_states": [{"torch": saved[1]}], "world_size": 2}
    before = torch.get_rng_state()
    try:
        restored = {}
        for world in (1, 2, 3):
            for rank in range(world):
                training._restore_random_state(checkpoint, RankContext(rank, rank, world), "cpu")
                restored[world, rank] = torch.get_rng_state()
    finally:
        torch.set_rng_state(before)
    assert torch.equal(restored[1, 0], saved[0])  # one rank: rank 0's stream
    assert torch.equal(restored[2, 0], saved[0]) and torch.equal(restored[2, 1], saved[1])  # as many: each its own
    assert torch.equal(restored[3, 0], saved[0])  # three: rank 0's, then seeds derived from it for ranks 1 and 2
    assert torch.equal(restored[3, 1], _expected_derived_state(saved[0], 1))
    assert torch.equal(restored[3, 2], _expected_derived_state(saved[0], 2))
    assert not torch.equal(restored[3, 1], restored[3, 2]) and not torch.equal(restored[3, 1], saved[1])


# --- two hosts on this machine -----------------------------------------------------------------------------------

def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _run_tagged(commands: list[list[str]], cwd, limit_s: float = 180.0) -> list[subprocess.CompletedProcess]:
    """Run ``commands`` at once (OMP_NUM_THREADS=1), each to its end; kill every process they started (found by a
    tag in their environment) if they outlive ``limit_s``, and any left a few seconds after they exited."""
    tag = uuid.uuid4().hex
    env = dict(os.environ, OCEAN_WARP_TEST_TAG=tag, OMP_NUM_THREADS="1", PYTHONUNBUFFERED="1")
    env.pop("OCEAN_WARP_FAULT", None)
    processes = [subprocess.Popen(command, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  text=True) for command in commands]
    results = []
    deadline = time.monotonic() + limit_s
    try:
        for process in processes:
            out, err = process.communicate(timeout=max(1.0, deadline - time.monotonic()))
            results.append(subprocess.CompletedProcess(process.args, process.returncode, out, err))
    finally:
        until = time.monotonic() + 5.0
        while (left := _tagged(tag)) and time.monotonic() < until:
            time.sleep(0.1)
        for pid in left:
            os.kill(pid, signal.SIGKILL)
    assert not left, f"processes left behind: {left}"
    return results


def test_two_hosts_at_a_localhost_rendezvous_train_one_policy_that_resumes_on_one_host_and_on_three_ranks(
        tmp_path, one_torch_thread):
    root, cwd = tmp_path / "runs", tmp_path / "cwd"
    cwd.mkdir()
    host = [sys.executable, "-m", "ocean_warp.envs.training.train", *TINY, "--iterations", "2", "--runs-root",
            str(root), "--run-name", "hosts", "--dist-timeout", "60", "--nnodes", "2",
            "--rdzv-endpoint", f"127.0.0.1:{_free_port()}", "--rdzv-id", uuid.uuid4().hex[:12]]
    first, second = _run_tagged([host, host], cwd)
    assert first.returncode == 0, first.stderr[-3000:]
    assert second.returncode == 0, second.stderr[-3000:]
    said = [result.stdout for result in (first, second) if "2 ranks ended with identical networks" in result.stdout]
    assert len(said) == 1  # rank 0's host alone reports
    runs = list((root / "EBoatWaypoint-v0").iterdir())
    assert len(runs) == 1 and not list(cwd.iterdir())
    run = runs[0]
    assert sorted(p.name for p in run.iterdir() if not p.name.startswith("events.")) == \
        ["config.json", "distributed.json", "model_1.pt", "policy.pt", "progress.csv"]
    assert len(list(run.glob("events.out.tfevents.*"))) == 1
    record = json.loads((run / "distributed.json").read_text())
    assert record["world_size"] == 2 and record["nodes"] == 2 and record["backend"] == "gloo"
    assert sorted(place["node_rank"] for place in record["ranks"]) == [0, 1]  # two torchrun agents ...
    assert [place["local_rank"] for place in record["ranks"]] == [0, 0]  # ... with one rank each
    assert record["identical_parameters"] and len(set(record["parameter_checksums"])) == 1
    checkpoint = read_checkpoint(run / "model_1.pt")
    assert checkpoint["world_size"] == 2 and checkpoint["iteration"] == 1 and len(checkpoint["rank_rng_states"]) == 1
    assert parameter_checksum(checkpoint["actor_state_dict"], checkpoint["critic_state_dict"]) == \
        record["parameter_checksums"][0]
    assert [row["samples"] for row in checkpoint["history"]] == [64, 128]  # 2 ranks x 8 envs x 4 decisions

    # Three ranks on one host resume a copy (in its own folder: a resume writes beside its checkpoint).
    (tmp_path / "three").mkdir()
    three_path = shutil.copy(run / "model_1.pt", tmp_path / "three" / "model_1.pt")
    three = [sys.executable, "-m", "torch.distributed.run", "--standalone", "--nproc_per_node=3", "-m",
             "ocean_warp.envs.training.train", *TINY, "--iterations", "1", "--resume", str(three_path),
             "--dist-timeout", "60"]
    (resumed_three,) = _run_tagged([three], cwd)
    assert resumed_three.returncode == 0, resumed_three.stderr[-3000:]
    after_three = read_checkpoint(tmp_path / "three" / "model_2.pt")
    assert after_three["world_size"] == 3 and len(after_three["rank_rng_states"]) == 2
    assert [row["samples"] for row in after_three["history"]] == [64, 128, 128 + 3 * 8 * 4]
    assert json.loads((tmp_path / "three" / "distributed.json").read_text())["identical_parameters"]

    # One host, one process: ocean-warp train --resume, from the iteration after the saved one.
    assert training.main([*TINY, "--iterations", "1", "--resume", str(run / "model_1.pt")]) == 0
    after = read_checkpoint(run / "model_2.pt")
    assert after["iteration"] == 2 and after["world_size"] == 1 and "rank_rng_states" not in after
    kept = ("iteration", "samples", "wall_time_s", "learning_rate")
    assert [[row[key] for key in kept] for row in after["history"][:2]] == \
        [[row[key] for key in kept] for row in checkpoint["history"]]
    assert [row["samples"] for row in after["history"]] == [64, 128, 128 + 8 * 4]
    assert not torch.equal(after["actor_state_dict"]["mlp.0.weight"], checkpoint["actor_state_dict"]["mlp.0.weight"])
    assert len((run / "progress.csv").read_text().splitlines()) == 1 + 3  # header and iterations 0, 1, 2
