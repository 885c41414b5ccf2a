"""Where an E-Boat step spends its time: each stage of the step timed alone, as its own CUDA graph.

    python -m benchmarks.perf.eboat_breakdown --boats 4096 16384 [--choppiness 0]

Same scene as ``bench_eboat.py``. Per substep: ocean update, hull pass (vertex sampling, triangle
clipping and pressure, per-boat sum), sailing rig (foils, sail swing, actuators, propeller), wind
(gust update and masthead sample) and integration; per step: sensors.
"""

from __future__ import annotations

import argparse
import datetime
import logging

import warp as wp


from benchmarks.perf.bench_eboat import SUBSTEPS, build
from benchmarks.perf.timing import device_description, median_seconds_warp_graph


def graph_microseconds(launch, device) -> float:
    """Median time [µs] of one replay of ``launch`` captured as a graph (after an uncaptured warm-up)."""
    launch()
    with wp.ScopedCapture(device=device) as capture:
        launch()
    return median_seconds_warp_graph(capture.graph, device, batches=9, per_batch=20) * 1e6


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--device", default="cuda:0")
    parser.add_argument("--boats", type=int, nargs="+", default=[4096, 16384])
    parser.add_argument("--choppiness", type=float, default=0.0)
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    device = wp.get_device(args.device)
    if not device.is_cuda:
        parser.error("the breakdown times CUDA graphs; pass a CUDA --device")
    print(f"E-Boat step breakdown, choppiness {args.choppiness}; {device_description(device)}; "
          f"{datetime.date.today()}")
    print("|  boats | ocean [µs] | hull pass [µs] | rig [µs] | wind [µs] | integrate [µs] | sensors, per step [µs] |"
          " sum per step [µs] | whole step [µs] |")
    for boats in args.boats:
        sim = build(device, boats, True, args.choppiness)
        simulator = sim.simulator
        for _ in range(3):  # the whole step first, while the boats sail as in bench_eboat.py
            sim.step()
        wp.synchronize_device(device)
        whole = median_seconds_warp_graph(simulator.step_graph, device, batches=7, per_batch=10) * 1e6
        stages = {
            "ocean": simulator.ocean.update,
            "hull": simulator.compute_hull_wrenches,
            "rig": lambda: sim.rig.substep(simulator),
            "wind": lambda: sim.wind.substep(simulator),
            "integrate": simulator.integrate,
            "sensors": lambda: sim.sensors.step(simulator),
        }
        micro = {name: graph_microseconds(launch, device) for name, launch in stages.items()}
        per_step = SUBSTEPS * sum(v for k, v in micro.items() if k != "sensors") + micro["sensors"]
        print(f"| {boats:6d} | {micro['ocean']:10.1f} | {micro['hull']:14.1f} | {micro['rig']:8.1f} | "
              f"{micro['wind']:9.1f} | {micro['integrate']:14.1f} | {micro['sensors']:22.1f} | {per_step:17.0f} | "
              f"{whole:15.0f} |", flush=True)
        del sim


if __name__ == "__main__":
    main()
