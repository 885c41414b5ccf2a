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

import numpy as np
import pytest
import torch

from ocean_warp.envs.training import train_loop as training
from ocean_warp.envs.training.distributed import RankContext, rank_device
from ocean_warp.envs.training.distributed_launch import describe_failure, hosts_problem, torchrun_command
from ocean_warp.envs.training.rendezvous import Rendezvous, parse_endpoint, rendezvous_from_options
from tests.envs.training.test_distributed import SUMMARY


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
