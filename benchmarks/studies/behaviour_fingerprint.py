"""A fingerprint of what the simulator and the environments do, to show that a refactor changed nothing.

    python -m benchmarks.studies.behaviour_fingerprint --out fingerprint_after.json [--device cpu]
    python -m benchmarks.studies.behaviour_fingerprint --compare fingerprint_before.json fingerprint_after.json

It runs, from fixed seeds, only through interfaces a user has (the gymnasium ids and the ``ocean-warp``
command), so the same script can run on the code before and after a change:

- every registered task, 16 boats stepped 40 decisions with seeded random actions (``gymnasium.make_vec``):
  the SHA-256 of the observations, rewards, terminations and truncations, in order;
- ``ocean-warp train`` for 3 PPO iterations of every task with a shipped-policy-sized network, 16 envs:
  the exported actor's parameters and the per-iteration returns of ``progress.csv`` (wall times left out);
- ``ocean-warp eval`` of the mission (policy and autopilot, 2 runs of 120 s) and of the sail-only mission:
  the trajectories (``trajectories.npz``) and ``runs.csv``.
Bit-equal hashes mean bit-equal trajectories and training. Torch runs on one thread here so that its
reductions are ordered.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import io
import json
import os
import sys
import tempfile

import numpy as np

TASKS = ("EBoatWaypoint-v0", "EBoatWaypointPlus-v0", "EBoatMission-v0", "EBoatMissionSail-v0")
"""The task ids fingerprinted (gymnasium ids in the ``ocean_warp`` namespace)."""

TIMING_COLUMNS = {"wall_time_s", "decisions_per_s", "real_time_factor", "collect_s", "learn_s"}
"""progress.csv columns that measure the machine, not the behaviour."""


def _digest(chunks) -> str:
    hasher = hashlib.sha256()
    for chunk in chunks:
        hasher.update(np.ascontiguousarray(chunk).tobytes())
    return hasher.hexdigest()


def stepping(task: str, device: str, boats: int = 16, decisions: int = 40, seed: int = 7) -> str:
    """SHA-256 of a seeded random-action rollout of ``task`` through its gymnasium vector id."""
    import gymnasium as gym

    import ocean_warp.envs  # noqa: F401  (registers the ids)

    env = gym.make_vec(f"ocean_warp/{task}", num_envs=boats, vectorization_mode="vector_entry_point",
                       device=device, seed=seed)
    rng = np.random.default_rng(seed)
    observation, _ = env.reset(seed=seed)
    chunks = [observation]
    for _ in range(decisions):
        actions = rng.uniform(-1.0, 1.0, size=(boats, 3)).astype(np.float32)
        observation, reward, terminated, truncated, _ = env.step(actions)
        chunks += [observation, reward, terminated, truncated]
    env.close()
    return _digest(chunks)


def _run_cli(argv: list[str]) -> None:
    from ocean_warp.cli import main

    try:
        main(argv)
    except SystemExit as exit_info:
        if exit_info.code:
            raise RuntimeError(f"ocean-warp {' '.join(argv)} exited with {exit_info.code}") from None


def _csv_without(path: str, columns: set[str]) -> bytes:
    with open(path, newline="") as stream:
        rows = list(csv.DictReader(stream))
    kept = [{k: v for k, v in row.items() if k not in columns} for row in rows]
    return json.dumps(kept, sort_keys=True).encode()


def training(task: str, device: str, folder: str) -> str:
    """SHA-256 of 3 PPO iterations: the exported actor and the per-iteration statistics."""
    import torch

    _run_cli(["train", "--task", task, "--device", device, "--num-envs", "16", "--iterations", "3", "--seed", "5",
              "--runs-root", folder, "--run-name", "fingerprint", "--no-progress", "--set", "steps_per_env=8"])
    (run,) = [os.path.join(root, name) for root, dirs, _ in os.walk(folder) for name in dirs
              if name.endswith("fingerprint") and task in root]
    state = torch.load(os.path.join(run, "policy.pt"), map_location="cpu", weights_only=True)
    buffer = io.BytesIO()
    for key, value in sorted(_flatten(state).items()):
        buffer.write(key.encode())
        buffer.write(value)
    return _digest([np.frombuffer(buffer.getvalue(), np.uint8),
                    np.frombuffer(_csv_without(os.path.join(run, "progress.csv"), TIMING_COLUMNS), np.uint8)])


def _flatten(value, prefix: str = "") -> dict[str, bytes]:
    import torch

    if isinstance(value, dict):
        out = {}
        for key, item in value.items():
            out.update(_flatten(item, f"{prefix}/{key}"))
        return out
    if isinstance(value, torch.Tensor):
        return {prefix: value.detach().cpu().contiguous().numpy().tobytes()}
    return {prefix: repr(value).encode()}


def evaluation(task: str, device: str, folder: str) -> str:
    """SHA-256 of 2 evaluation runs of 120 s (policy and autopilot): trajectories and runs.csv."""
    out = os.path.join(folder, f"eval_{task}")
    _run_cli(["eval", "--task", task, "--device", device, "--runs", "2", "--time-limit", "120", "--out", out,
              "--no-progress"])
    arrays = np.load(os.path.join(out, "trajectories.npz"))
    chunks = [np.frombuffer(name.encode(), np.uint8) for name in sorted(arrays.files)]
    chunks += [arrays[name] for name in sorted(arrays.files)]
    with open(os.path.join(out, "runs.csv"), "rb") as stream:
        chunks.append(np.frombuffer(_without_empty_score(stream.read()), np.uint8))
    return _digest(chunks)


def _without_empty_score(runs_csv: bytes) -> bytes:
    """runs.csv as it was before its last column, vrx_score, where that column is empty in every row (a task
    without a VRX score: every E-Boat task), so that fingerprints taken before and after the column compare;
    as it is otherwise."""
    lines = runs_csv.split(b"\r\n")
    rows = [line for line in lines[1:] if line]
    if not lines[0].endswith(b",vrx_score") or not all(row.endswith(b",") for row in rows):
        return runs_csv
    return b"\r\n".join([lines[0].removesuffix(b",vrx_score")] + [line[:-1] if line else line for line in lines[1:]])


def fingerprint(device: str) -> dict[str, str]:
    """Every hash, by name."""
    import torch

    torch.set_num_threads(1)
    hashes = {}
    with tempfile.TemporaryDirectory() as folder:
        for task in TASKS:
            print(f"stepping {task}", flush=True)
            hashes[f"step/{task}"] = stepping(task, device)
        for task in TASKS:
            print(f"training {task}", flush=True)
            hashes[f"train/{task}"] = training(task, device, folder)
        for task in ("EBoatMission-v0", "EBoatMissionSail-v0"):
            print(f"evaluating {task}", flush=True)
            hashes[f"eval/{task}"] = evaluation(task, device, folder)
    return hashes


def compare(before: str, after: str) -> int:
    """Print each hash's verdict; 0 when all are equal."""
    with open(before) as stream:
        a = json.load(stream)["hashes"]
    with open(after) as stream:
        b = json.load(stream)["hashes"]
    differing = 0
    for name in sorted(set(a) | set(b)):
        same = a.get(name) == b.get(name)
        differing += not same
        print(f"{'equal' if same else 'DIFFERENT':9s} {name}")
    print(f"{len(set(a) | set(b)) - differing} equal, {differing} different")
    return 1 if differing else 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="behaviour_fingerprint", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--out", default="fingerprint.json", help="JSON file for the hashes")
    parser.add_argument("--device", default="cpu", help="Warp and torch device")
    parser.add_argument("--compare", nargs=2, metavar=("BEFORE", "AFTER"), help="compare two fingerprint files")
    args = parser.parse_args(argv)
    if args.compare:
        return compare(*args.compare)
    import subprocess

    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                            cwd=os.path.dirname(os.path.abspath(__file__))).stdout.strip()
    hashes = fingerprint(args.device)
    from ocean_warp.atomic_files import atomic_output

    with atomic_output(args.out) as temporary, open(temporary, "w") as stream:
        json.dump({"commit": commit, "device": args.device, "hashes": hashes}, stream, indent=2)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
