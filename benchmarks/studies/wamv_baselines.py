"""The classical baselines of VRX's tasks on the WAM-V, old and new side by side on the same runs.

    python -m benchmarks.studies.wamv_baselines --runs 12 --json benchmarks/data/wamv/baselines_cpu.json

Each task (``WamvStationKeeping-v0``, ``WamvWayfinding-v0``, ``WamvFollowPath-v0``) is sailed by its old baseline
(PID station keeping with ``WAMV_STATION_KEEPING``, or LOS guidance along the legs) and by its new one
(``PivotStationKeepingController``, or ``GateGuidanceController``) on one environment restarted from its seed for
each (``ocean_warp.envs.evaluation.sail_mission``: the same starts, waves and gusts). Per controller: VRX's score
(mean and median over the runs), the runs completed and the collisions.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os

import numpy as np

from ocean_warp.atomic_files import atomic_output
from ocean_warp.envs.env_factory import make_env
from ocean_warp.envs.evaluation.evaluate import vrx_baseline
from ocean_warp.envs.evaluation.presets import evaluation_task
from ocean_warp.envs.evaluation.rollout import sail_mission

TASKS = ("WamvStationKeeping-v0", "WamvWayfinding-v0", "WamvFollowPath-v0")
SCORES = {"WamvStationKeeping-v0": "mean pose error d + 0.75^d |heading error| over the run [m], lower is better",
          "WamvWayfinding-v0": "mean over the goals of the least pose error reached [m], lower is better",
          "WamvFollowPath-v0": "points: 10 a gate passed in order plus bonuses, 3 off a collision; higher is better"}


def compare(task_id: str, runs: int, *, device: str = "cpu", seed: int = 0, sea_state: float | None = None,
            wind: float | None = None, time_limit: float | None = None) -> dict:
    """The old and the new baseline of ``task_id`` on the same ``runs`` runs: one row per controller."""
    config = evaluation_task(task_id, sea_state=sea_state, wind=wind, seed=seed, time_limit=time_limit)
    env = make_env(config, runs, device=device, seed=seed)
    rows = []
    for autopilot in ("legacy", "line"):
        result = sail_mission(env, vrx_baseline(config, autopilot))
        score = result.vrx_score
        rows.append({"controller": result.name, "baseline": "old" if autopilot == "legacy" else "new",
                     "vrx_score_mean": float(np.nanmean(score)), "vrx_score_median": float(np.nanmedian(score)),
                     "completed": int(result.success.sum()), "collisions": int(result.collided.sum()),
                     "waypoints_mean": float(result.waypoints.mean())})
        print(f"{task_id:24s} {result.name:22s} VRX score mean {rows[-1]['vrx_score_mean']:7.2f} median "
              f"{rows[-1]['vrx_score_median']:7.2f}, completed {rows[-1]['completed']}/{runs}, collisions "
              f"{rows[-1]['collisions']}", flush=True)
    return {"task": task_id, "vrx_score": SCORES[task_id], "episode_time_s": config.episode_time,
            "sea_state_m": config.simulator.ocean.significant_wave_height, "wind_m_s": list(config.start.wind_speed),
            "rows": rows}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tasks", nargs="+", default=list(TASKS), choices=TASKS)
    parser.add_argument("--runs", type=int, default=12)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--sea-state", type=float, default=None, help="Hs [m] (default: the task's)")
    parser.add_argument("--wind", type=float, default=None, help="[m/s] (default: the task's range)")
    parser.add_argument("--time-limit", type=float, default=None, help="[s] (default: the task's episode time)")
    parser.add_argument("--json", default=None, help="write the figures here (atomically)")
    parser.add_argument("--machine", default=f"{os.cpu_count()} cores", help="the device in words, for the record")
    args = parser.parse_args(argv)
    record = {"device": f"{args.device}, {args.machine}", "date": datetime.date.today().isoformat(),
              "runs": args.runs, "seed": args.seed, "tasks": []}
    for task_id in args.tasks:
        record["tasks"].append(compare(task_id, args.runs, device=args.device, seed=args.seed,
                                       sea_state=args.sea_state, wind=args.wind, time_limit=args.time_limit))
    if args.json:
        with atomic_output(args.json) as path:
            with open(path, "w") as handle:
                json.dump(record, handle, indent=1)


if __name__ == "__main__":
    main()
