"""A mission in every wind: ``ocean-warp eval``'s runs over a grid of true wind speeds and sea states.

    python -m benchmarks.studies.mission_wind_grid --device cuda:0                    # sail-only BCDACA
    python -m benchmarks.studies.mission_wind_grid --task EBoatMission-v0 --winds 10 --sea-states 0.3
    python -m benchmarks.studies.mission_wind_grid --policy path/to/policy.pt --no-autopilot --winds 10

Each cell is one ``evaluate_mission`` (the runner of ``ocean-warp eval``): ``--runs`` seeded runs of the
task at one mean true wind [m/s] and one significant wave height [m], sailed by the task's shipped policy
(or ``--policy``) and by the default classical autopilot on the same runs, the rig reefed by the task's
rule. One row per controller and cell goes to ``--out`` (a CSV written atomically): completed runs, mean
time of the completed ones, capsizes, lost runs, time-outs and the share of decisions with the motor on.
It exits 1 when a controller completes fewer than ``--required`` runs in some cell.
"""

from __future__ import annotations

import argparse
import csv
import io
import logging
import sys
import time

import warp as wp

from ocean_warp.atomic_files import atomic_output
from ocean_warp.envs.evaluation import evaluate_mission
from ocean_warp.envs.training.policies import shipped_policy_path

COLUMNS = ("task", "controller", "wind_m_s", "sea_state_m", "runs", "completed", "time_mean_s", "capsizes", "lost",
           "time_outs", "motor_use", "wall_s")


def grid_rows(task: str, *, policy, autopilot, winds, sea_states, runs: int, seed: int, device: str,
              time_limit: float | None = None) -> list[dict]:
    """One row per controller and (sea state, wind) cell, in that order."""
    rows = []
    for sea_state in sea_states:
        for wind in winds:
            started = time.perf_counter()
            evaluation = evaluate_mission(policy, runs, sea_state=sea_state, wind=wind, seed=seed, device=device,
                                          time_limit=time_limit, autopilot=autopilot, progress=False, task=task)
            wall = time.perf_counter() - started
            for name, result in evaluation.results.items():
                summary = result.summary()
                row = {"task": task, "controller": name, "wind_m_s": wind, "sea_state_m": sea_state, "runs": runs,
                       "completed": summary["completed"], "time_mean_s": round(summary["time_mean_s"], 1),
                       "capsizes": summary["capsizes"], "lost": summary["lost"],
                       "time_outs": summary["time_outs"], "motor_use": round(summary["motor_use"], 3),
                       "wall_s": round(wall, 1)}
                rows.append(row)
                print(", ".join(f"{key} {row[key]}" for key in COLUMNS), flush=True)
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--task", default="EBoatMissionSail-v0")
    parser.add_argument("--policy", default="shipped", help="checkpoint path, 'shipped' (default) or 'none'")
    parser.add_argument("--no-autopilot", action="store_true", help="the policy only")
    parser.add_argument("--autopilot", choices=("line", "legacy"), default="line", help="which classical controller")
    parser.add_argument("--winds", type=float, nargs="+", default=[3.0, 5.0, 7.0, 10.0], help="[m/s]")
    parser.add_argument("--sea-states", type=float, nargs="+", default=[0.3, 0.5], help="Hs [m]")
    parser.add_argument("--runs", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--time-limit", type=float, default=None, help="[s] (default: the task's)")
    parser.add_argument("--required", type=int, default=19, help="completions needed in every cell")
    parser.add_argument("--out", default=None, help="CSV to write")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    policy = {"shipped": lambda: str(shipped_policy_path(args.task)), "none": lambda: None}.get(
        args.policy, lambda: args.policy)()
    rows = grid_rows(args.task, policy=policy, autopilot=False if args.no_autopilot else args.autopilot, winds=args.winds,
                     sea_states=args.sea_states, runs=args.runs, seed=args.seed, device=args.device,
                     time_limit=args.time_limit)
    if args.out:
        text = io.StringIO()
        writer = csv.DictWriter(text, fieldnames=COLUMNS, lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)
        with atomic_output(args.out) as temporary, open(temporary, "w") as handle:
            handle.write(text.getvalue())
    short = [row for row in rows if row["completed"] < args.required]
    for row in short:
        print(f"below {args.required}: {row['controller']} at {row['wind_m_s']:g} m/s, Hs {row['sea_state_m']:g} m: "
              f"{row['completed']} / {row['runs']}")
    return 1 if short else 0


if __name__ == "__main__":
    sys.exit(main())
