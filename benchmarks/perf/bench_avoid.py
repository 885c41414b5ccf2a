"""Benchmark: the avoidance task's decision against the mission task's, side by side in one run.

    python -m benchmarks.perf.bench_avoid --envs 4096 --json out.json
    python -m benchmarks.perf.bench_avoid --device cpu --envs 16 --decisions 2

For each number of environments it times ``SailingEnv.step`` (one captured graph; median of
``--decisions`` after a warm-up, seeded random actions with the propeller ahead) for:
- ``mission``: ``EBoatMission-v0`` (``MissionConfig()``), the reference of the issue's target;
- ``avoid_open``: ``EBoatAvoid-v0`` with its obstacles, contact and lidar removed (the same task on open
  water: what the obstacle course itself costs is the difference to the next row);
- ``avoid``: ``EBoatAvoid-v0`` (``AvoidConfig()``): 6-12 buoys and piles per environment drawn at every
  reset, the contact force model every substep, a 360-beam lidar scan and the gap to the nearest obstacle
  twice a decision (after the physics and after the resets), the 24 sectors appended to the observation.
It reports decisions per second and the aggregate real-time factor (simulated boat-seconds per wall
second), and the avoidance task's RTF over the mission's (the issue's target: at least 70 % at 4 096).

All three sail the physics profile's boat (mesh hull, 2 024 triangles) on the mission's JONSWAP sea (Hs
0.3 m, Tp 3 s, 64 x 64 grid over 256 m); decision 1 s = 20 steps of dt 0.05 s x 5 substeps.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import logging

import torch
import warp as wp

from benchmarks.perf.bench_envs import seconds_per_call
from benchmarks.perf.timing import device_description, write_results_json
from ocean_warp.envs import SailingEnv
from ocean_warp.envs.tasks import AvoidConfig, MissionConfig

CASES = ("mission", "avoid_open", "avoid")


def case_task(case: str):
    """The task config of a case (see the module docstring)."""
    if case == "mission":
        return MissionConfig()
    if case == "avoid_open":
        return dataclasses.replace(AvoidConfig(), obstacles=None, contact=None, lidar=None)
    return AvoidConfig()


def measure(case: str, envs: int, device, repeats: int) -> dict:
    """Seconds per decision of ``case`` with ``envs`` environments, and the episodes that ended meanwhile."""
    env = SailingEnv(case_task(case), envs, device=device, seed=1)
    torch_device = env.torch_device
    sync = (lambda: torch.cuda.synchronize(torch_device)) if torch_device.type == "cuda" else (lambda: None)
    generator = torch.Generator(device=torch_device).manual_seed(7)
    actions = 2.0 * torch.rand((envs, 3), generator=generator, device=torch_device) - 1.0
    actions[:, 0] = 0.7  # propeller ahead: the boats sail into their courses
    for _ in range(3):
        env.step(actions)
    seconds = seconds_per_call(lambda: env.step(actions), repeats, sync)
    return {"case": case, "envs": envs, "seconds": seconds, "decisions_per_s": envs / seconds,
            "real_time_factor": envs * env.decision_period / seconds,
            "policy_obs": env.num_policy_obs}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--device", default="cuda:0" if wp.get_cuda_device_count() else "cpu")
    parser.add_argument("--envs", type=int, nargs="+", default=[4096, 16384])
    parser.add_argument("--decisions", type=int, default=10, help="timed decisions per case (median)")
    parser.add_argument("--json", help="write the results here")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    device = wp.get_device(args.device)
    print(f"EBoatMission-v0 vs EBoatAvoid-v0: decision 1 s = 20 steps of dt 0.05 s x 5 substeps; mesh hull; JONSWAP "
          f"Hs 0.3 m, Tp 3 s; {device_description(device)}; {datetime.date.today()}")
    print("| envs | mission: ms, k dec/s, RTF | avoid, open water: ms, k dec/s, RTF | avoid: ms, k dec/s, RTF | "
          "avoid RTF / mission RTF |")
    rows = []
    for envs in args.envs:
        measured = {case: measure(case, envs, device, args.decisions) for case in CASES}
        ratio = measured["avoid"]["real_time_factor"] / measured["mission"]["real_time_factor"]
        rows.append({"envs": envs, "cases": measured, "avoid_over_mission": ratio})
        cells = [f"{m['seconds'] * 1e3:.2f}, {m['decisions_per_s'] / 1e3:.1f}, {m['real_time_factor']:,.0f}"
                 for m in measured.values()]
        print(f"| {envs} | " + " | ".join(cells) + f" | {100 * ratio:.1f} % |", flush=True)
    if args.json:
        write_results_json(args.json, device, dt=0.05, substeps=5, decision_period=1.0,
                           avoid=repr(AvoidConfig().obstacles), lidar=dataclasses.asdict(AvoidConfig().lidar),
                           rows=rows)


if __name__ == "__main__":
    main()
