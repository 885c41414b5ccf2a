"""The six-waypoint mission "BCDACA" sailed by the classical autopilot: many seeded runs in one batch.

    python -m benchmarks.studies.autopilot_mission                       # 20 runs on the CPU; exits 1 below 19/20
    python -m benchmarks.studies.autopilot_mission --runs 20 --device cuda:0 --seed 0 --sea-state 0.3

Each run is one environment of ``SailingEnv(MissionConfig())``: A (0, 0) -> B, C, D, A, C, A, each
reached within 5 m; true wind 10 m/s toward +x with gusts (1 m/s, 0.1 rad); a JONSWAP sea (Hs
``--sea-state``, Tp 3 s); each run has its own origin on the periodic tile (its own waves) and its own
random streams. The autopilot (``ocean_warp.envs.controllers.sailing_autopilot``) takes the place of the policy: it writes
the actions of every decision (1 s) from the environment's current waypoints. A run's first episode
is its result: success, time, waypoints, tacks, and how it ended (capsize, lost, time-out). The runs are
sailed by ``ocean_warp.envs.evaluation`` (the runner of ``ocean-warp eval``, which also draws the paths and
compares a policy with the autopilot).
"""

from __future__ import annotations

import argparse
import logging
import sys
import time

import numpy as np
import torch
import warp as wp


from ocean_warp.envs.controllers.sailing_autopilot import AutopilotConfig
from ocean_warp.envs.evaluation import evaluate_mission
from ocean_warp.fleet import BoatStatus


def run_mission(runs: int = 20, *, device="cpu", seed: int = 0, sea_state: float = 0.3,
                time_limit: float | None = None, autopilot: AutopilotConfig | None = None,
                task=None) -> dict[str, np.ndarray]:
    """Sail ``runs`` missions at once (``ocean_warp.envs.evaluation``'s runner, the legacy autopilot only, its
    defaults where ``autopilot`` is None); per run:
    success, time [s], waypoints, the autopilot's own tack count, status bits at the end, time-out.
    ``task``: the mission config to start from (default ``MissionConfig()``)."""
    evaluation = evaluate_mission(None, runs, sea_state=sea_state, seed=seed, device=device, time_limit=time_limit,
                                  autopilot=autopilot if autopilot is not None else "legacy", progress=False,
                                  task=task)
    result = evaluation.results["autopilot"]
    return {"success": result.success.astype(float), "time": result.time_s, "waypoints": result.waypoints.astype(float),
            "tacks": result.own_tacks.astype(float), "status": result.status.astype(float),
            "time_out": result.time_out.astype(float)}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=20)
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--seed", type=int, default=0, help="seed of the sea, the gusts and the starts")
    parser.add_argument("--sea-state", type=float, default=0.3, help="significant wave height Hs [m]")
    parser.add_argument("--time-limit", type=float, default=None, help="sim time per run [s] (default: the task's)")
    parser.add_argument("--required", type=int, default=None, help="completions needed (default 95 %% of runs)")
    parser.add_argument("--autopilot", nargs="*", default=[], metavar="FIELD=VALUE",
                        help="AutopilotConfig fields, e.g. assist_level=0")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    overrides = {}
    for item in args.autopilot:
        name, value = item.split("=", 1)
        overrides[name] = int(value) if value.lstrip("-").isdigit() else float(value)
    config = AutopilotConfig(**overrides)
    start = time.perf_counter()
    with torch.no_grad():
        result = run_mission(args.runs, device=args.device, seed=args.seed, sea_state=args.sea_state,
                             time_limit=args.time_limit, autopilot=config)
    wall = time.perf_counter() - start
    success = result["success"] > 0.5
    print(f"BCDACA with the autopilot ({', '.join(args.autopilot) or 'defaults'}): {args.runs} runs, seed {args.seed}, "
          f"Hs {args.sea_state} m, device {args.device}, {wall:.0f} s wall")
    print("| run | completed | time [s] | waypoints | tacks | end |")
    for i in range(args.runs):
        status = int(result["status"][i])
        end = ("capsized" if status & BoatStatus.CAPSIZED else f"flag {status}" if status else
               "time-out" if result["time_out"][i] else "done" if success[i] else "lost")
        print(f"| {i} | {'yes' if success[i] else 'no'} | {result['time'][i]:.0f} | {int(result['waypoints'][i])} | "
              f"{int(result['tacks'][i])} | {end} |")
    times = result["time"][success]
    print(f"completed {success.sum()} / {args.runs}; mission time mean {times.mean() if times.size else float('nan'):.0f} s, "
          f"spread {times.min() if times.size else 0:.0f}-{times.max() if times.size else 0:.0f} s; "
          f"tacks mean {result['tacks'][success].mean() if times.size else float('nan'):.1f}")
    required = args.required if args.required is not None else int(np.ceil(0.95 * args.runs))
    return 0 if success.sum() >= required else 1


if __name__ == "__main__":
    sys.exit(main())
