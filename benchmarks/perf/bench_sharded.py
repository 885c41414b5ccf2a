"""How training's environment side scales over CPU cores: ShardedSailingEnv against one SailingEnv.

For each hull (the four-point buoyancy and the mesh hull) and each worker count, a fixed total number
of environments of the seed waypoint task steps with uniform random actions; the table gives
environment decisions per second, the aggregate real-time factor (simulated boat-seconds per wall
second = decisions/s x decision period) and the speed-up over the single-process SailingEnv (the
baseline, "1 process"). Every configuration is timed for about ``--seconds`` of wall time after one
warm-up decision; building the env (spawning the workers) is not timed.

    python -m benchmarks.perf.bench_sharded                                # 256 envs, workers 1, 2, 4, 8, 16
    python -m benchmarks.perf.bench_sharded --workers 1,2 --hull points    # capped at the machine's cores

Prints a markdown table, with the CPU count, the decision period, dt, substeps, hull and sea.
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
import os
import platform
import sys
import time

import torch
import warp as wp

from ocean_warp.eboat import Hydrostatics
from ocean_warp.envs import SailingEnv, WaypointConfig
from ocean_warp.envs.parallel.sharded import ShardedSailingEnv

HULLS = {"points": Hydrostatics.POINTS, "mesh": Hydrostatics.MESH}


def cpu_count() -> int:
    """Cores this process may run on (the affinity mask where the OS has one)."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def task_for(hull: str, capture: bool = True) -> WaypointConfig:
    """The seed waypoint task (its gentle sea, 1 s decisions of 20 x 0.05 s) on ``hull``; ``capture``
    False launches every kernel anew each decision instead of replaying the captured decision."""
    base = WaypointConfig()
    boat = dataclasses.replace(base.simulator.boat, hydrostatics=HULLS[hull])
    simulator = dataclasses.replace(base.simulator, boat=boat, capture_graph=capture)
    return dataclasses.replace(base, simulator=simulator)


def time_decisions(env, seconds: float, seed: int) -> float:
    """Decisions per second [1/s] of ``env`` (SailingEnv or ShardedSailingEnv) with random actions, over
    about ``seconds`` [s] of wall time (at least 2 decisions) after one warm-up decision."""
    generator = torch.Generator().manual_seed(seed)
    actions = torch.empty(env.num_envs, 3)

    def step() -> None:
        actions.uniform_(-1.0, 1.0, generator=generator)
        env.step(actions)

    step()
    count, started = 0, time.perf_counter()
    while count < 2 or time.perf_counter() - started < seconds:
        step()
        count += 1
    return count * env.num_envs / (time.perf_counter() - started)


def measure(hull: str, workers: int | None, num_envs: int, seconds: float, seed: int, capture: bool = True,
            shared_ocean: bool = True) -> float:
    """Decisions per second for ``hull`` with ``workers`` processes (None: one SailingEnv in this process)."""
    task = task_for(hull, capture)
    if workers is None:
        return time_decisions(SailingEnv(task, num_envs, device="cpu", seed=seed), seconds, seed)
    with ShardedSailingEnv(task, num_envs, workers=workers, seed=seed, shared_ocean=shared_ocean) as env:
        return time_decisions(env, seconds, seed)


def describe(task: WaypointConfig, shared_ocean: bool) -> str:
    """The settings the numbers depend on, as markdown lines."""
    sim, sea = task.simulator, task.simulator.ocean
    return (f"- task: seed waypoint task (EBoatWaypoint-v0's simulator, hull varied), random actions\n"
            f"- decision period {task.decision_period} s = {task.steps_per_decision} steps of dt {sim.dt} s, "
            f"substeps {sim.substeps}, ocean evaluated every substep: {sim.ocean_every_substep}\n"
            f"- sea: Hs {sea.significant_wave_height} m, Tp {sea.peak_period} s, {sea.resolution}^2 grid over "
            f"{sea.tile_size} m ("
            + ("evaluated once, by the parent, for every worker)" if shared_ocean else "each worker evaluates its own)"))


def parse_list(text: str, kind=str) -> list:
    return [kind(item) for item in text.split(",") if item.strip()]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--num-envs", type=int, default=256, help="environments in all (default 256)")
    parser.add_argument("--workers", default="1,2,4,8,16", help="comma-separated worker counts, capped at the cores")
    parser.add_argument("--hull", default="points,mesh", help="comma-separated: points, mesh (default both)")
    parser.add_argument("--seconds", type=float, default=3.0, help="wall time per configuration [s] (default 3)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--uncaptured", action="store_true",
                        help="launch every kernel anew each decision (no captured graph), for comparison")
    parser.add_argument("--own-oceans", action="store_true",
                        help="every worker evaluates its own ocean (no shared ocean), for comparison")
    args = parser.parse_args(argv)
    hulls = parse_list(args.hull)
    if bad := [hull for hull in hulls if hull not in HULLS]:
        parser.error(f"--hull: unknown {bad}; choose from {sorted(HULLS)}")
    cores = cpu_count()
    requested = parse_list(args.workers, int)
    if any(w < 1 for w in requested):
        parser.error(f"--workers must be positive, got {requested}")
    workers = sorted({w for w in requested if w <= min(cores, args.num_envs)})
    skipped = sorted(set(requested) - set(workers))

    wp.config.log_level = logging.WARNING  # no banner or module-load lines in the table
    print(f"## ShardedSailingEnv scaling on the CPU: {args.num_envs} environments\n")
    print(f"- machine: {platform.processor() or platform.machine()}, {cores} usable cores "
          f"(os.cpu_count() = {os.cpu_count()}); Python {platform.python_version()}, torch {torch.__version__}, "
          f"Warp {wp.__version__}")
    print(describe(task_for(hulls[0]), not args.own_oceans))
    print(f"- each decision {'launched kernel by kernel' if args.uncaptured else 'replayed from its capture'}")
    if skipped:
        print(f"- skipped worker counts above the {cores} usable cores (or the env count): {skipped}")
    print(f"- timed for about {args.seconds:g} s per row after a warm-up decision; worker start-up not timed\n")
    print("| hull | setup | workers | decisions/s | real-time factor (boat-s/s) | speed-up | efficiency |")
    print("|---|---|---:|---:|---:|---:|---:|")
    period = task_for(hulls[0]).decision_period
    for hull in hulls:
        capture = not args.uncaptured
        baseline = measure(hull, None, args.num_envs, args.seconds, args.seed, capture)
        rows = [("1 process (SailingEnv)", 1, baseline)]
        rows += [("sharded", w, measure(hull, w, args.num_envs, args.seconds, args.seed, capture, not args.own_oceans))
                 for w in workers]
        for setup, count, rate in rows:
            speedup = rate / baseline
            print(f"| {hull} | {setup} | {count} | {rate:,.0f} | {rate * period:,.0f} | {speedup:.2f}x | "
                  f"{speedup / count:.0%} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
