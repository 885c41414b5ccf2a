"""Check training on several GPUs end to end, on a host with G GPUs (G = 1 runs what one GPU allows).

    python -m benchmarks.perf.multi_gpu_check --gpus 2
    python -m benchmarks.perf.multi_gpu_check --gpus 1          # one GPU: in-process training, the failure cases

Each case is a real command, a tiny setting of the waypoint task (``--num-envs`` per GPU, 8 decisions
each, 4 iterations, checkpoints every 2):

1. ``ocean-warp train --gpus G``: exits 0; with G > 1 the run's ``distributed.json`` records that every
   rank ended with identical networks and its checkpoint records G ranks.
2. its last checkpoint resumed on one GPU (``--device cuda``) for 2 iterations: the history goes on.
3. (G > 1) that one-GPU checkpoint resumed on G GPUs for 2 iterations: the other way round.
4. a rank whose GPU does not exist (torchrun with G + 1 ranks): the job stops, rank 0 names that rank.
5. (G > 1) NaN injected into the last rank's batch (``OCEAN_WARP_FAULT``): the job stops within the
   timeout, rank 0 names the rank.

Prints a markdown table (case, result, seconds) with the GPU's name and the date; exits 1 if any failed.
Run dirs go under ``--out``.
"""

from __future__ import annotations

import argparse
import datetime
import glob
import json
import os
import subprocess
import sys
import time

import torch

TINY = ["--task", "EBoatWaypoint-v0", "--set", "steps_per_env=8", "--set", "save_interval=2", "--seed", "1",
        "--no-progress", "--dist-timeout", "120"]


def run(command: list[str], *, fault: str | None = None, limit_s: float = 900.0) -> tuple[int, str, float]:
    """(exit status, stdout + stderr, seconds) of ``command``; echoes the output's last lines."""
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    env.pop("OCEAN_WARP_FAULT", None)
    if fault:
        env["OCEAN_WARP_FAULT"] = fault
    started = time.monotonic()
    result = subprocess.run(command, env=env, capture_output=True, text=True, timeout=limit_s)
    elapsed = time.monotonic() - started
    output = result.stdout + result.stderr
    tail = [line for line in output.splitlines() if not line.startswith(("Module ", "Warp ", "   "))][-8:]
    print(f"$ {' '.join(command)}\n  -> status {result.returncode} in {elapsed:.0f} s\n    " + "\n    ".join(tail),
          flush=True)
    return result.returncode, output, elapsed


def train_command(*args: str) -> list[str]:
    return [sys.executable, "-m", "ocean_warp.cli", "train", *TINY, *args]


def torchrun_command(ranks: int, *args: str) -> list[str]:
    return [sys.executable, "-m", "torch.distributed.run", "--standalone", f"--nproc_per_node={ranks}",
            "-m", "ocean_warp.envs.training.train", *TINY, *args]


def last_checkpoint(run_dir: str) -> str:
    return max(glob.glob(os.path.join(run_dir, "model_*.pt")), key=lambda p: int(p.rsplit("_", 1)[1][:-3]))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--gpus", type=int, default=2, help="GPUs to train on (default 2)")
    parser.add_argument("--num-envs", type=int, default=256, help="environments per GPU (default 256)")
    parser.add_argument("--out", default="out/multi_gpu_check", help="runs root (default out/multi_gpu_check)")
    args = parser.parse_args(argv)
    from ocean_warp.envs.training.policy_io import read_checkpoint

    visible = torch.cuda.device_count()
    if not 1 <= args.gpus <= visible:
        print(f"multi_gpu_check: --gpus {args.gpus} needs that many GPUs; torch sees {visible}", file=sys.stderr)
        return 2
    g, root = args.gpus, os.path.abspath(args.out)
    common = ["--num-envs", str(args.num_envs), "--runs-root", root]
    rows: list[tuple[str, bool, str, float]] = []

    def case(name: str, ok: bool, detail: str, seconds: float) -> None:
        rows.append((name, bool(ok), detail, seconds))

    status, output, seconds = run(train_command("--gpus", str(g), "--iterations", "4", "--run-name", f"g{g}", *common))
    runs = sorted(glob.glob(os.path.join(root, "EBoatWaypoint-v0", f"*_g{g}")))
    ok = status == 0 and bool(runs)
    detail = f"status {status}"
    if ok:
        run_dir = runs[-1]
        checkpoint = read_checkpoint(last_checkpoint(run_dir))
        detail += f", checkpoint of {checkpoint.get('world_size')} rank(s)"
        ok = checkpoint.get("world_size") == g
        if g > 1:
            with open(os.path.join(run_dir, "distributed.json")) as stream:
                record = json.load(stream)
            same = record["identical_parameters"] and len(set(record["parameter_checksums"])) == 1
            ok = ok and same
            detail += f", identical networks on {len(record['parameter_checksums'])} ranks: {same}"
    case(f"train on {g} GPU(s) (--gpus {g})", ok, detail, seconds)

    if runs:
        run_dir = runs[-1]
        before = read_checkpoint(last_checkpoint(run_dir))["iteration"]
        status, output, seconds = run(train_command("--device", "cuda", "--iterations", "2", "--resume",
                                                    last_checkpoint(run_dir), *common))
        after = read_checkpoint(last_checkpoint(run_dir))
        ok = status == 0 and after["iteration"] == before + 2 and after.get("world_size") == 1
        case(f"resume the {g}-GPU checkpoint on 1 GPU", ok,
             f"status {status}, iteration {before} -> {after['iteration']}, {len(after['history'])} rows", seconds)
        if g > 1:
            status, output, seconds = run(train_command("--gpus", str(g), "--iterations", "2", "--resume",
                                                        last_checkpoint(run_dir), *common))
            back = read_checkpoint(last_checkpoint(run_dir))
            ok = status == 0 and back["iteration"] == after["iteration"] + 2 and back.get("world_size") == g
            case(f"resume the 1-GPU checkpoint on {g} GPUs", ok,
                 f"status {status}, iteration {after['iteration']} -> {back['iteration']}", seconds)

    status, output, seconds = run(torchrun_command(g + 1, "--device", "cuda", "--iterations", "2", *common),
                                  limit_s=600)
    expected = f"rank {g} failed at startup"
    case(f"a rank without a GPU ({g + 1} ranks on {g} GPU(s))", status != 0 and expected in output,
         f"status {status}, rank 0 said {expected!r}: {expected in output}", seconds)

    if g > 1:
        status, output, seconds = run(train_command("--gpus", str(g), "--iterations", "3", *common),
                                      fault=f"{g - 1}:1:nan", limit_s=600)
        expected = f"rank {g - 1} failed at iteration 1: NonFiniteBatch"
        case(f"NaN in rank {g - 1}'s batch", status != 0 and expected in output,
             f"status {status}, rank 0 said {expected!r}: {expected in output}", seconds)

    name = torch.cuda.get_device_name(0)
    print(f"\n### multi-GPU check: {g} x {name}, {datetime.date.today()}, {args.num_envs} envs per GPU\n")
    print("| case | result | detail | s |\n|---|---|---|---:|")
    for title, ok, detail, seconds in rows:
        print(f"| {title} | {'PASS' if ok else 'FAIL'} | {detail} | {seconds:.0f} |")
    return 0 if all(ok for _, ok, _, _ in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
