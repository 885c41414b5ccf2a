"""Benchmark: what a lidar on every boat adds to a decision of the batched sailing environment.

    python -m benchmarks.perf.bench_lidar --envs 4096 16384 65536 --json out.json
    python -m benchmarks.perf.bench_lidar --device cpu --envs 16 --decisions 2

For each number of environments it times, one decision at a time (median of ``--decisions`` after a
warm-up), on one environment:
- ``env``: ``SailingEnv.step`` with fixed actions (one captured graph), as ``bench_envs`` does;
- ``env+lidar``: the same after ``env.attach(LidarHook(...))``: the scene refreshed (the sea's height band,
  the floating buoys) and every boat's lidar scanned after every round(1 / (rate dt)) physics steps,
  inside the decision's graph;
- ``scan``: one scan alone (``Lidar.scan``: the beams cast over the refreshed scene, the stream
  counter advanced), captured and replayed.
It reports the time added to the decision [%], decisions per second and the aggregate real-time factor
(simulated boat-seconds per wall second) with and without the lidar, and rays per second of a scan.

The task is Waypoint+ as ``bench_envs`` runs it (mesh hull, 2 024 triangles; JONSWAP Hs 0.5 m, Tp 3.5 s,
choppiness ``--choppiness``, 64 x 64 grid over 256 m; decision 1 s = 20 steps of dt 0.05 s x 5 substeps).
The lidar is ``LidarConfig.scan_2d()``: 360 beams (1 deg) level from the bow mount 0.8 m above the
waterline, 0.2-50 m, 3 cm noise, water returns on, at ``--rate`` (10 Hz: every 2 steps, 10 scans a
decision). Every environment holds two buoys riding the waves and two piles within 25 m of its start.
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
from ocean_warp.envs import SailingEnv, WaypointPlusConfig
from ocean_warp.envs.sensors import LidarHook
from ocean_warp.perception import LidarConfig, SceneObject
from ocean_warp.replay import ReplayedLaunches

OBJECTS = (SceneObject.buoy((15.0, 5.0)), SceneObject.buoy((-10.0, 12.0)), SceneObject.pillar((20.0, -8.0)),
           SceneObject.pillar((-5.0, -15.0)))
"""Every environment's objects, from its origin [m] (the boats start within a few metres of it)."""


def benchmark_task(dt: float, substeps: int, decision_period: float, choppiness: float) -> WaypointPlusConfig:
    """Waypoint+ with the given step [s], substeps, decision period [s] and choppiness."""
    task = WaypointPlusConfig()
    ocean = dataclasses.replace(task.simulator.ocean, choppiness=choppiness)
    simulator = dataclasses.replace(task.simulator, ocean=ocean, dt=dt, substeps=substeps)
    return dataclasses.replace(task, simulator=simulator, decision_period=decision_period)


def measure(task, envs: int, device, lidar: LidarConfig, repeats: int) -> dict:
    """Seconds per decision without and with the lidar hook, and per scan alone, for ``envs`` environments."""
    env = SailingEnv(task, envs, device=device, seed=1)
    torch_device = env.torch_device
    sync = (lambda: torch.cuda.synchronize(torch_device)) if torch_device.type == "cuda" else (lambda: None)
    fixed = torch.tensor([[0.0, 0.2, 0.1]], device=torch_device).repeat(envs, 1)
    for _ in range(3):  # sail away from the start first
        env.step(fixed)
    row = {"envs": envs, "env_s": seconds_per_call(lambda: env.step(fixed), repeats, sync)}
    hook = LidarHook(env, lidar, objects=OBJECTS)
    env.attach(hook)
    row["env+lidar_s"] = seconds_per_call(lambda: env.step(fixed), repeats, sync)
    scan = ReplayedLaunches(hook.lidar.scan, env.device, capture=task.simulator.capture_graph)
    row["scan_s"] = seconds_per_call(scan, repeats, sync)
    row["scans_per_decision"] = hook.scans_per_decision
    row["rays_per_scan"] = envs * hook.lidar.beam_count
    assert torch.all(torch.isfinite(hook.lidar.ranges)), "ranges must stay finite"
    return row


def derived(row: dict, decision_period: float) -> dict:
    """Decisions per second, real-time factors, the added fraction and rays per second from the times."""
    envs = row["envs"]
    for case in ("env", "env+lidar"):
        row[f"{case}_decisions_per_s"] = envs / row[f"{case}_s"]
        row[f"{case}_real_time_factor"] = envs * decision_period / row[f"{case}_s"]
    row["lidar_added_fraction"] = (row["env+lidar_s"] - row["env_s"]) / row["env_s"]
    row["scan_rays_per_s"] = row["rays_per_scan"] / row["scan_s"]
    row["scans_fraction_of_env"] = row["scans_per_decision"] * row["scan_s"] / row["env_s"]
    return row


def table_line(row: dict) -> str:
    cells = [f"{row[f'{case}_s'] * 1e3:.2f}, {row[f'{case}_decisions_per_s'] / 1e3:.2f}, "
             f"{row[f'{case}_real_time_factor']:,.0f}" for case in ("env", "env+lidar")]
    return (f"| {row['envs']} | " + " | ".join(cells) + f" | {100 * row['lidar_added_fraction']:+.1f} % | "
            f"{row['scan_s'] * 1e3:.3f} | {row['scan_rays_per_s'] / 1e9:.3f} | "
            f"{100 * row['scans_fraction_of_env']:.1f} % |")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--device", default="cuda:0" if wp.get_cuda_device_count() else "cpu")
    parser.add_argument("--envs", type=int, nargs="+", default=[4096, 16384, 65536])
    parser.add_argument("--dt", type=float, default=0.05, help="simulator step [s]")
    parser.add_argument("--substeps", type=int, default=5)
    parser.add_argument("--decision-period", type=float, default=1.0, help="[s]")
    parser.add_argument("--choppiness", type=float, default=0.5)
    parser.add_argument("--beams", type=int, default=360, help="lidar beams (one channel)")
    parser.add_argument("--rate", type=float, default=10.0, help="lidar scans per second [Hz]")
    parser.add_argument("--decisions", type=int, default=10, help="timed decisions per case (median)")
    parser.add_argument("--json", help="write the results here")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    device = wp.get_device(args.device)
    task = benchmark_task(args.dt, args.substeps, args.decision_period, args.choppiness)
    lidar = LidarConfig.scan_2d(beams=args.beams, rate=args.rate)
    ocean = task.simulator.ocean
    print(f"Waypoint+ decisions: period {task.decision_period} s = {task.steps_per_decision} steps of dt {args.dt} s "
          f"x {args.substeps} substeps; mesh hull; JONSWAP Hs {ocean.significant_wave_height} m, Tp "
          f"{ocean.peak_period} s, choppiness {ocean.choppiness}; lidar {lidar.beam_count} beams at {lidar.rate} Hz, "
          f"{lidar.min_range}-{lidar.max_range} m, {len(OBJECTS)} objects per env; {device_description(device)}; "
          f"{datetime.date.today()}")
    print("| envs | env: ms, k dec/s, RTF | env+lidar: ms, k dec/s, RTF | lidar adds | one scan [ms] | "
          "G rays/s | scans / env |")
    rows = []
    for envs in args.envs:
        row = derived(measure(task, envs, device, lidar, args.decisions), task.decision_period)
        rows.append(row)
        print(table_line(row), flush=True)
    if args.json:
        write_results_json(args.json, device, task="Waypoint+", dt=args.dt, substeps=args.substeps,
                           decision_period=task.decision_period, choppiness=args.choppiness,
                           lidar=dataclasses.asdict(lidar), objects_per_env=len(OBJECTS), rows=rows)


if __name__ == "__main__":
    main()
