"""A trial for moving the motor-allowed mission onto the physics profile: train its agent there and sail it.

    python -m benchmarks.mission_on_physics --device cuda:0 --minutes 4.5 --out out/mission_on_physics

``EBoatMission-v0`` still sails ``shipped_policy_boat()`` (the seed's forces on the mesh hull). This trains
the mission's default agent (``agent_config("EBoatMission-v0")``: practice legs, curriculum, PPO) on the
same task with the physics profile's boat (``EBoatConfig()``), then sails the BCDACA mission twenty times
at each ``--winds`` speed with the trained policy and with the autopilot's defaults (motor assist), as
``ocean-warp eval`` does. Writes into ``--out``: the run folder (``train/``: checkpoints, ``policy.pt``) and
per wind speed ``eval_<wind>/`` (results.csv with the motor use, runs.csv, trajectories).
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import time

from ocean_warp.eboat import EBoatConfig
from ocean_warp.envs.agents import agent_config, mission_practice
from ocean_warp.envs.evaluation import evaluate_mission
from ocean_warp.envs.tasks import MissionConfig, mission_simulator
from ocean_warp.envs.training import train


def physics_mission() -> MissionConfig:
    """BCDACA with the motor allowed, on the physics profile's boat."""
    return dataclasses.replace(MissionConfig(), simulator=mission_simulator(EBoatConfig()))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.mission_on_physics", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--device", default="cuda:0", help="Warp and torch device (default cuda:0)")
    parser.add_argument("--minutes", type=float, default=4.5, help="training wall time (default 4.5)")
    parser.add_argument("--winds", type=float, nargs="+", default=[10.0, 5.0], help="mean true wind speeds [m/s]")
    parser.add_argument("--runs", type=int, default=20, help="missions per controller and wind (default 20)")
    parser.add_argument("--out", default="out/mission_on_physics", help="output folder")
    args = parser.parse_args(argv)
    if not args.minutes > 0.0 or args.runs < 1 or any(not w >= 0.0 for w in args.winds):
        parser.error("--minutes must be > 0, --runs >= 1 and every --winds value >= 0")
    task = physics_mission()
    config = dataclasses.replace(agent_config("EBoatMission-v0"), train_task=mission_practice(task))
    started = time.perf_counter()
    train(config, device=args.device, minutes=args.minutes, run_dir=os.path.join(args.out, "train"))
    print(f"trained in {time.perf_counter() - started:.0f} s")
    policy = os.path.join(args.out, "train", "policy.pt")
    for wind in args.winds:
        evaluation = evaluate_mission(policy, args.runs, wind=wind, device=args.device, task=task, autopilot=True)
        paths = evaluation.write(os.path.join(args.out, f"eval_{wind:g}"))
        print(f"wind {wind:g} m/s:")
        with open(paths["results.csv"]) as table:
            print(table.read())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
