"""``ocean-warp eval``'s options: its parser, light to import (no Warp, no torch), so that ``--help`` and a
mistyped option answer at once. The job itself is ``evaluation`` (its docstring: ``--help-long``)."""

from __future__ import annotations

import argparse

from ocean_warp.cli_support import add_device_argument, job_parser

from ..registration import DEFAULT_TASK, TASK_IDS

__all__ = ["parser"]


def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp eval``."""
    parser = job_parser(
        "eval", f"Sail a task (default {DEFAULT_TASK}, the BCDACA mission) many times in waves with a policy and "
        "with the classical autopilot, on the same runs; writes trajectories.png, results.csv, runs.csv and "
        "trajectories.npz into --out and prints the results table. --help-long says what each file and column "
        "holds.", long_help_from="ocean_warp.envs.apps.evaluation",
        examples=("ocean-warp eval", "ocean-warp eval --policy out/train/EBoatMission-v0/<date>/policy.pt",
                  "ocean-warp eval --no-policy --runs 5 --sea-state 0.5 --wind 8 --seed 1",
                  "ocean-warp eval --task EBoatWaypoint-v0 --runs 50 --wind 6"))
    parser.add_argument("--task", default=DEFAULT_TASK, metavar="ID",
                        help=f"the task to sail: {', '.join(TASK_IDS)}, with or without 'ocean_warp/' "
                             f"(default {DEFAULT_TASK})")
    parser.add_argument("--policy", default=None, metavar="PATH",
                        help="policy checkpoint to evaluate: a policy.pt or model_<it>.pt that train wrote "
                             "(default: the task's shipped policy, where it has one)")
    parser.add_argument("--no-policy", action="store_true", help="sail the autopilot only")
    parser.add_argument("--no-autopilot", action="store_true", help="sail the policy only")
    parser.add_argument("--autopilot", choices=("line", "legacy"), default="line",
                        help="the classical controller, named 'autopilot' in the results: line, the line follower "
                             "of Jaulin and Le Bars (default), or legacy, the line-of-sight autopilot; on the "
                             "WAM-V's tasks line is the default baseline (station keeping in transit, back-and-fill "
                             "and holding modes; LOS through the gates clear of the buoys) and legacy the earlier "
                             "(PID station keeping; LOS along the legs), each named as it is")
    parser.add_argument("--runs", type=int, default=20,
                        help="runs per controller: missions, or episodes of a waypoint task (default 20)")
    parser.add_argument("--sea-state", type=float, default=None, metavar="HS",
                        help="significant wave height Hs of the task's sea [m] (default: the task's, 0.3 for the "
                             "missions)")
    parser.add_argument("--wind", type=float, default=None,
                        help="mean true wind speed of every run [m/s] (default: the task's, 10 for the missions; "
                             "the waypoint tasks draw it per run from their range unless this fixes it)")
    parser.add_argument("--reef", default="auto", choices=("auto", "0", "1", "2"),
                        help="the sail's reef level in every run: auto (default) chooses it per run by the task's "
                             "rule from the run's true wind (full below 6 m/s, reef 1 to 8, reef 2 above); 0 (the "
                             "full sail), 1 (about 2.0 m2) or 2 (about 1.15 m2) sets it. Not on EBoatWaypoint-v0, "
                             "which sails the full sail as the seed did")
    parser.add_argument("--seed", type=int, default=0,
                        help="seed of the sea, the gusts, the starts and the waypoints (default 0)")
    parser.add_argument("--time-limit", type=float, default=None, metavar="SECONDS",
                        help="simulated time per run [s] (default: the task's episode time, 1800 for the missions)")
    parser.add_argument("--out", default="out/eval", help="folder for the PNG, CSVs and NPZ (default out/eval)")
    parser.add_argument("--record", default=None, metavar="FILE.mcap",
                        help="also write a rosbag2 MCAP log of every controller's runs, each under /<controller> "
                             "(needs the mcap extra: pip install 'ocean-warp[mcap]')")
    add_device_argument(parser)
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    return parser

