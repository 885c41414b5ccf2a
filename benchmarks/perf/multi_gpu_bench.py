"""Training on 1 and on G GPUs with the same environments per GPU: collection throughput, scaling efficiency,
and wall time to a policy that sails BCDACA.

    python -m benchmarks.perf.multi_gpu_bench --gpus 1,2                      # EBoatMission-v0, 4 096 envs per GPU, 4.5 min
    python -m benchmarks.perf.multi_gpu_bench --gpus 1 --minutes 1 --skip-eval  # a quick look on one GPU

For each G in ``--gpus``: ``ocean-warp train --task EBoatMission-v0`` on G GPUs (``--gpus G``; G = 1 trains
in one process on cuda) for ``--minutes`` of training, checkpoints every ``--save-interval`` iterations.
From the run's progress.csv (rank 0's clock; every rank collects the same number of decisions):

- collection decisions/s: G x envs per GPU x decisions per env / collect_s, the median over the
  iterations after the first ``--warmup`` (kernel compilation, graph capture);
- loop decisions/s: the same over the whole iteration (collection and the PPO update with its all-reduces);
- speed-up and scaling efficiency (speed-up / G) against the G = 1 row.

Then the checkpoints are evaluated in order on BCDACA as ``ocean-warp eval`` sails it (``--runs`` seeded runs,
Hs 0.3 m, 10 m/s wind, seed 0, the policy alone): "time to BCDACA" is the training-loop wall time
(progress.csv's wall_time_s) of the first checkpoint that completes at least ``--threshold`` of the runs;
the final policy is evaluated too. Prints a markdown table with the GPU's name and the date, and writes
it with the raw numbers to ``--out``/results.json.
"""

from __future__ import annotations

import argparse
import csv
import datetime
import glob
import json
import os
import subprocess
import sys
import time

import numpy as np
import torch

from ocean_warp.atomic_files import atomic_output

TASK = "EBoatMission-v0"


def read_run(run_dir: str) -> tuple[dict, list[dict[str, float]]]:
    """(config.json, progress.csv rows as floats) of a training run."""
    with open(os.path.join(run_dir, "config.json")) as stream:
        config = json.load(stream)
    with open(os.path.join(run_dir, "progress.csv"), newline="") as stream:
        rows = [{key: float(value) for key, value in row.items()} for row in csv.DictReader(stream)]
    return config, rows


def throughput(config: dict, rows: list[dict[str, float]], warmup: int) -> dict[str, float]:
    """Median collection and whole-loop decisions per second after ``warmup`` iterations."""
    steps = int(config["train_config"]["steps_per_env"])
    per_iteration = int(config.get("world_size", 1)) * int(config["num_envs"]) * steps
    kept = rows[warmup:] or rows
    return {"collect_decisions_per_s": float(np.median([per_iteration / r["collect_s"] for r in kept])),
            "loop_decisions_per_s": float(np.median([per_iteration / (r["collect_s"] + r["learn_s"]) for r in kept])),
            "iterations": len(rows), "samples": int(rows[-1]["samples"]), "loop_s": rows[-1]["wall_time_s"]}


def completed_runs(policy_path: str, runs: int, device: str) -> int:
    """BCDACA runs (of ``runs``) the policy completes, as ``ocean-warp eval --no-autopilot`` sails them."""
    from ocean_warp.envs.evaluation import evaluate_mission

    evaluation = evaluate_mission(policy_path, runs, device=device, autopilot=False, progress=False)
    return int(next(iter(evaluation.results.values())).success.sum())


def time_to_capable(run_dir: str, rows: list[dict[str, float]], runs: int, threshold: int,
                    device: str) -> dict[str, float | int | None]:
    """The first checkpoint (in iteration order) that completes ``threshold`` of ``runs``: its iteration and
    training wall time; and the final policy's completions."""
    checkpoints = sorted(glob.glob(os.path.join(run_dir, "model_*.pt")), key=lambda p: int(p.rsplit("_", 1)[1][:-3]))
    wall = {int(r["iteration"]): r["wall_time_s"] for r in rows}
    found: dict[str, float | int | None] = {"capable_iteration": None, "capable_wall_s": None}
    for path in checkpoints:
        iteration = int(path.rsplit("_", 1)[1][:-3])
        done = completed_runs(path, runs, device)
        print(f"  {os.path.basename(path)}: {done}/{runs} BCDACA runs completed", flush=True)
        if done >= threshold:
            found = {"capable_iteration": iteration, "capable_wall_s": wall.get(iteration)}
            break
    found["final_completed"] = completed_runs(os.path.join(run_dir, "policy.pt"), runs, device)
    return found


def train(gpus: int, args) -> tuple[str, float]:
    """Train on ``gpus`` GPUs; (run dir, whole command's wall time [s])."""
    name = f"bench_g{gpus}_{datetime.datetime.now():%H%M%S}"
    placement = ["--gpus", str(gpus)] if gpus > 1 else ["--device", "cuda"]
    command = [sys.executable, "-m", "ocean_warp.cli", "train", "--task", TASK, *placement, "--num-envs",
               str(args.num_envs), "--minutes", str(args.minutes), "--seed", str(args.seed), "--set",
               f"save_interval={args.save_interval}", "--runs-root", args.out, "--run-name", name, "--no-progress"]
    print(f"$ {' '.join(command)}", flush=True)
    started = time.monotonic()
    subprocess.run(command, check=True, env=dict(os.environ, PYTHONUNBUFFERED="1"))
    elapsed = time.monotonic() - started
    (run_dir,) = glob.glob(os.path.join(args.out, TASK, f"*_{name}"))
    return run_dir, elapsed


def scaling(result: dict, base: dict | None) -> tuple[str, str]:
    """(speed-up, efficiency) of a run against the one-GPU run ``base`` of the same benchmark, as table cells:
    "1.85x", "93%"; "n/a" for both where no one-GPU run was measured (e.g. ``--gpus 2`` alone)."""
    if base is None:
        return "n/a", "n/a"
    speedup = result["collect_decisions_per_s"] / base["collect_decisions_per_s"]
    return f"{speedup:.2f}x", f"{speedup / result['gpus']:.0%}"


def format_table(results: list[dict], *, num_envs: int, minutes: float, runs: int, threshold: int, evaluated: bool,
                 device_name: str) -> str:
    """The markdown table of ``results`` (one dict per GPU count, as :func:`main` gathers them)."""
    base = next((r for r in results if r["gpus"] == 1), None)
    lines = [f"### Training on several GPUs: {TASK}, {num_envs} envs per GPU, {minutes:g} min "
             f"({device_name}, {datetime.date.today()}, torch {torch.__version__})", "",
             "| GPUs | envs | iterations | samples | collection dec/s | speed-up | efficiency | loop dec/s | "
             f"time to BCDACA {threshold}/{runs} | final BCDACA | command s |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---:|"]
    for r in results:
        speedup, efficiency = scaling(r, base)
        if not evaluated:
            capable = final = "not evaluated"
        else:
            capable = ("not reached" if r["capable_iteration"] is None else
                       f"{r['capable_wall_s']:.0f} s (iteration {r['capable_iteration']})")
            final = f"{r['final_completed']}/{runs}"
        lines.append(f"| {r['gpus']} | {r['gpus'] * num_envs} | {r['iterations']} | {r['samples'] / 1e6:.1f} M | "
                     f"{r['collect_decisions_per_s']:,.0f} | {speedup} | {efficiency} | "
                     f"{r['loop_decisions_per_s']:,.0f} | {capable} | {final} | {r['command_s']:.0f} |")
    if base is None:
        lines += ["", "speed-up and efficiency: n/a, no one-GPU run in this benchmark (add 1 to --gpus, e.g. 1,2)"]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--gpus", default="1,2", help="comma-separated GPU counts to compare (default 1,2)")
    parser.add_argument("--num-envs", type=int, default=4096, help="environments per GPU (default 4096)")
    parser.add_argument("--minutes", type=float, default=4.5, help="training wall time per run (default 4.5)")
    parser.add_argument("--save-interval", type=int, default=25, help="iterations between checkpoints (default 25)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--warmup", type=int, default=3, help="first iterations left out of the medians (default 3)")
    parser.add_argument("--runs", type=int, default=20, help="BCDACA runs per evaluation (default 20)")
    parser.add_argument("--threshold", type=int, default=None, help="completed runs that count as capable "
                        "(default: all of --runs)")
    parser.add_argument("--skip-eval", action="store_true", help="throughput only, no BCDACA evaluation")
    parser.add_argument("--out", default="out/multi_gpu_bench", help="runs root and results.json (default "
                        "out/multi_gpu_bench)")
    args = parser.parse_args(argv)
    args.out = os.path.abspath(args.out)
    try:
        counts = [int(g) for g in args.gpus.split(",")]
    except ValueError:
        parser.error(f"--gpus must be comma-separated whole numbers, e.g. 1,2; got {args.gpus!r}")
    visible = torch.cuda.device_count()
    if not counts or min(counts) < 1 or max(counts) > visible:
        print(f"multi_gpu_bench: --gpus {args.gpus} needs up to {max(counts, default=0)} GPUs; torch sees {visible}",
              file=sys.stderr)
        return 2
    threshold = args.runs if args.threshold is None else args.threshold
    results = []
    for gpus in counts:
        run_dir, command_s = train(gpus, args)
        config, rows = read_run(run_dir)
        result = {"gpus": gpus, "run_dir": run_dir, "command_s": command_s, **throughput(config, rows, args.warmup)}
        if not args.skip_eval:
            result.update(time_to_capable(run_dir, rows, args.runs, threshold, "cuda:0"))
        results.append(result)
        print(json.dumps(result), flush=True)

    name = torch.cuda.get_device_name(0)
    table = format_table(results, num_envs=args.num_envs, minutes=args.minutes, runs=args.runs, threshold=threshold,
                         evaluated=not args.skip_eval, device_name=name)
    print("\n" + table)
    with atomic_output(os.path.join(args.out, "results.json")) as temporary, open(temporary, "w") as stream:
        json.dump({"device": name, "date": str(datetime.date.today()), "settings": vars(args), "results": results,
                   "table": table}, stream, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
