"""Benchmark: the full E-Boat step (ocean, hull pressure, wind, sail/keel/rudder/propeller, sensors,
integration) in boat-substeps per second.

    python -m benchmarks.perf.bench_eboat --device cuda:0 --boats 1024 4096 16384 65536
    python -m benchmarks.perf.bench_eboat --device cpu --boats 1024 4096 16384 65536

Boats sail in a JONSWAP sea (512 x 512 grid over 512 m, Hs 1 m, Tp 5 s, choppiness 0.5 or --choppiness) and gusty
wind, with random headings and sheet, rudder and propeller commands; the E-Boat's hull has 2 024
triangles, or at most N with --hull-triangles N (benchmarks/studies/hull_fidelity.py measures what that costs in
fidelity). A step is 5 substeps of 0.01 s. On CUDA the step is a captured graph.
"""

from __future__ import annotations

import argparse
import datetime
import logging

import numpy as np
import warp as wp


from benchmarks.perf.timing import (
    device_description,
    median_seconds_host,
    median_seconds_warp_graph,
    write_results_json,
)
import ocean_warp as ow
from ocean_warp.eboat import EBoat, EBoatConfig, EBoatSimulator, EBoatSimulatorConfig

SUBSTEPS = 5


def build(device, boats: int, ocean_every_substep: bool, choppiness: float, seed: int = 0,
          hull_triangles: int | None = None, boat: EBoatConfig | None = None) -> EBoatSimulator:
    """``boat`` (default: the physics profile with ``hull_triangles``) replaces the boat's config."""
    rng = np.random.default_rng(seed)
    config = EBoatSimulatorConfig(
        boat=boat if boat is not None else EBoatConfig(hull_triangles=hull_triangles),
        ocean=ow.OceanConfig(tile_size=512.0, resolution=512, significant_wave_height=1.0, peak_period=5.0,
                             choppiness=choppiness, seed=seed),
        wind=ow.WindConfig(speed=7.0, gust_speed_std=1.0, gust_direction_std=0.1),
        dt=SUBSTEPS * 0.01, substeps=SUBSTEPS, ocean_every_substep=ocean_every_substep)
    sim = EBoatSimulator(config, boats, device=device)
    sim.reset(position=np.column_stack([rng.uniform(0, 512, (boats, 2)), np.full(boats, 0.05)]),
              heading=rng.uniform(-np.pi, np.pi, boats), velocity=[1.0, 0, 0, 0, 0, 0],
              sheet=rng.uniform(0.2, 1.2, boats))
    control = sim.tensors.control
    control.rudder[:] = control.rudder.new_tensor(rng.uniform(-0.2, 0.2, boats))
    control.propeller[:] = control.propeller.new_tensor(rng.integers(-1, 3, boats))
    return sim


def time_step(sim: EBoatSimulator) -> float:
    device = sim.device
    if device.is_cuda:
        for _ in range(3):
            sim.step()
        wp.synchronize_device(device)
        return median_seconds_warp_graph(sim.simulator.step_graph, device, batches=7, per_batch=10)
    sim.step()  # compiles the kernels; a CPU step of 64k boats takes about a minute, so time single steps
    return median_seconds_host(sim.step, batches=3, per_batch=1, sync=lambda: wp.synchronize_device(device))


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--device", default="cuda:0" if wp.get_cuda_device_count() else "cpu")
    parser.add_argument("--boats", type=int, nargs="+", default=[1024, 4096, 16384, 65536])
    parser.add_argument("--choppiness", type=float, default=0.5, help="of the sea (0: linear Airy waves)")
    parser.add_argument("--hull-triangles", type=int, default=None, metavar="N",
                        help="triangle budget of the hull (default: the full hull, 2 024 triangles)")
    parser.add_argument("--seakeeping", action=argparse.BooleanOptionalAction, default=None,
                        help="radiation memory and diffraction from the hull's database (default: the boat's default)")
    parser.add_argument("--json", help="write the results here")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    device = wp.get_device(args.device)
    options = {} if args.seakeeping is None else {"seakeeping": args.seakeeping}
    boat = EBoatConfig(hull_triangles=args.hull_triangles, **options)
    triangles = EBoat(boat).hull.triangle_count
    print(f"E-Boat step ({SUBSTEPS} substeps), choppiness {args.choppiness}, hull of {triangles} triangles, "
          f"seakeeping {'on' if boat.seakeeping else 'off'}; "
          f"{device_description(device)}; {datetime.date.today()}")
    print("|  boats | ocean every substep: step [ms] | M boat-substeps/s | ocean once a step: step [ms] | "
          "M boat-substeps/s |")
    rows = []
    for boats in args.boats:
        row = {"boats": boats}
        for every, key in ((True, "every"), (False, "once")):
            sim = build(device, boats, every, args.choppiness, boat=boat)
            seconds = time_step(sim)
            assert np.all(np.isfinite(sim.fleet.numpy()["position"])), "the benchmark boats must stay finite"
            row[f"{key}_step_ms"] = seconds * 1e3
            row[f"{key}_boat_substeps_per_s"] = boats * SUBSTEPS / seconds
            del sim
        rows.append(row)
        print(f"| {boats:6d} | {row['every_step_ms']:10.3f} | {row['every_boat_substeps_per_s'] / 1e6:8.3g} | "
              f"{row['once_step_ms']:10.3f} | {row['once_boat_substeps_per_s'] / 1e6:8.3g} |", flush=True)
    if args.json:
        write_results_json(args.json, device, choppiness=args.choppiness, hull_triangles=triangles,
                           seakeeping=boat.seakeeping, rows=rows)


if __name__ == "__main__":
    main()
