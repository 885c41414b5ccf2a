"""Benchmark: the hull-force pass and the full substep of ocean_warp against a vectorised torch
implementation of the same per-triangle model (benchmarks/references/hull_references.py).

    python -m benchmarks.perf.bench_hull --device cuda:0 --boats 1024 4096 16384 65536 --triangles 500 2000 8000
    python -m benchmarks.perf.bench_hull --device cpu --boats 256 1024 --triangles 500 2000

Hull pass = sampling the ocean at every hull vertex + clipping and integrating every triangle (pressure,
drag, suction, friction; slamming off) + the per-boat reduction. Full substep = ocean update (512 x 512,
choppy) + hull pass + rigid-body integration. On CUDA both sides run as captured graphs. torch runs
are skipped where their intermediates would not fit in memory (--torch-limit).
"""

from __future__ import annotations

import argparse
import datetime
import logging

import numpy as np
import warp as wp


from benchmarks.references.hull_references import TorchHullReference
from benchmarks.perf.timing import (
    device_description,
    median_seconds_host,
    median_seconds_torch_graph,
    median_seconds_warp_graph,
    write_results_json,
)
import ocean_warp as ow


def boat_hull(target_triangles: int) -> ow.Hull:
    """A 2.5 x 1.0 x 0.6 m ellipsoidal hull with about ``target_triangles`` triangles."""
    import trimesh

    best = min(range(4, 200), key=lambda k: abs(len(trimesh.creation.uv_sphere(count=(k, k)).faces) - target_triangles))
    mesh = trimesh.creation.uv_sphere(count=(best, best), radius=1.0)
    mesh.apply_scale([1.25, 0.5, 0.3])
    return ow.Hull.from_trimesh(mesh, name=f"ellipsoid{len(mesh.faces)}")


def build(device, boats: int, hull: ow.Hull, seed: int = 0, choppiness: float = 1.0, block_dim: int | None = None):
    rng = np.random.default_rng(seed)
    boat = ow.BoatType.floating_solid(hull, draft_fraction=0.4, linear_damping=[50, 100, 500, 100, 100, 50])
    fleet = ow.Fleet(boat, boats, device=device)
    ocean = ow.Ocean(ow.OceanConfig(tile_size=512.0, resolution=512, significant_wave_height=1.5, peak_period=6.0,
                                    choppiness=choppiness), device=device)
    ocean.update(10.0)
    angles = rng.uniform(-0.1, 0.1, size=(boats, 3))
    half = np.linalg.norm(angles, axis=1, keepdims=True) / 2
    axes = angles / np.maximum(np.linalg.norm(angles, axis=1, keepdims=True), 1e-12)
    fleet.reset(position=np.column_stack([rng.uniform(0, 512, size=(boats, 2)), rng.uniform(-0.2, 0.1, size=boats)]),
                orientation=np.concatenate([axes * np.sin(half), np.cos(half)], axis=1),
                velocity=np.concatenate([rng.uniform(-2, 2, (boats, 3)), rng.uniform(-0.3, 0.3, (boats, 3))], axis=1))
    simulator = ow.Simulator(ocean, fleet, ow.SimulatorConfig(dt=0.0025, substeps=1, block_dim=block_dim))
    return simulator


def time_warp(simulator, work) -> float:
    device = simulator.device
    if device.is_cuda:
        work()
        with wp.ScopedCapture(device=device) as capture:
            work()
        return median_seconds_warp_graph(capture.graph, device, batches=9, per_batch=10)
    return median_seconds_host(work, batches=3, per_batch=1, sync=lambda: wp.synchronize_device(device))


def time_torch(work, on_cuda: bool) -> float:
    import torch

    if on_cuda:
        stream = torch.cuda.Stream()
        stream.wait_stream(torch.cuda.current_stream())
        with torch.cuda.stream(stream):
            work()
        torch.cuda.current_stream().wait_stream(stream)
        graph = torch.cuda.CUDAGraph()
        with torch.cuda.graph(graph):
            work()
        return median_seconds_torch_graph(graph, batches=9, per_batch=10)
    return median_seconds_host(work, batches=3, per_batch=1)


def benchmark(device, boats: int, hull: ow.Hull, torch_limit: int, choppiness: float, block_dim=None) -> dict:
    import torch

    simulator = build(device, boats, hull, choppiness=choppiness, block_dim=block_dim)
    triangles = hull.triangle_count
    row = {"boats": boats, "triangles": triangles}
    row["warp_hull_us"] = time_warp(simulator, simulator.compute_hull_wrenches) * 1e6
    row["warp_substep_us"] = time_warp(simulator, simulator.substep) * 1e6
    if boats * triangles <= torch_limit:
        fresh = build(device, boats, hull, choppiness=choppiness)  # the boats before the timed runs moved them
        fresh.compute_hull_wrenches()
        reference = TorchHullReference(fresh)
        reference.hull_wrenches()
        warp_wrench = wp.to_torch(fresh.fleet.forces.hydro_wrench).double()
        row["relative_difference"] = float(torch.linalg.norm(reference.wrench.double() - warp_wrench)
                                           / torch.linalg.norm(warp_wrench))
        on_cuda = device.is_cuda
        row["torch_hull_us"] = time_torch(reference.hull_wrenches, on_cuda) * 1e6
        reference.with_torch_ocean(fresh.ocean.wave_grid.cells, 10.0)
        row["torch_substep_us"] = time_torch(lambda: reference.substep(fresh.config.substep_dt), on_cuda) * 1e6
        del reference
        if on_cuda:
            torch.cuda.empty_cache()
    return row


def print_row(row: dict) -> None:
    tri_per_s = row["boats"] * row["triangles"] / (row["warp_hull_us"] * 1e-6)
    boat_substeps = row["boats"] / (row["warp_substep_us"] * 1e-6)
    line = (f"| {row['boats']:6d} | {row['triangles']:5d} | {row['warp_hull_us']:10.1f} | {tri_per_s / 1e9:7.2f} |"
            f" {row['warp_substep_us']:10.1f} | {boat_substeps / 1e6:8.2f} |")
    if "torch_hull_us" in row:
        line += (f" {row['torch_hull_us']:10.1f} | {row['torch_hull_us'] / row['warp_hull_us']:6.1f}x |"
                 f" {row['torch_substep_us']:10.1f} | {row['torch_substep_us'] / row['warp_substep_us']:6.1f}x |"
                 f" {row['relative_difference']:.1e} |")
    else:
        line += "          – |      – |          – |      – |       – |"
    print(line, flush=True)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--device", default="cuda:0" if wp.get_cuda_device_count() else "cpu")
    parser.add_argument("--boats", type=int, nargs="+", default=[1024, 4096, 16384, 65536])
    parser.add_argument("--triangles", type=int, nargs="+", default=[500, 2000, 8000])
    parser.add_argument("--torch-limit", type=float, default=None,
                        help="largest boats x triangles for torch (default: 4e7 on CUDA, 2e6 on the CPU)")
    parser.add_argument("--choppiness", type=float, default=1.0,
                        help="of the ocean (0: no fixed-point inversion when sampling)")
    parser.add_argument("--block-dim", type=int, nargs="*", default=[],
                        help="instead of the table: time the hull pass with these threads per boat")
    parser.add_argument("--json", help="write the results here")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    device = wp.get_device(args.device)
    torch_limit = int(args.torch_limit or (4e7 if device.is_cuda else 2e6))
    if args.block_dim:
        for triangles in args.triangles:
            hull = boat_hull(triangles)
            for boats in args.boats:
                for block_dim in args.block_dim:
                    simulator = build(device, boats, hull, choppiness=args.choppiness, block_dim=block_dim)
                    us = time_warp(simulator, simulator.compute_hull_wrenches) * 1e6
                    print(f"boats {boats} triangles {hull.triangle_count} block_dim {block_dim}: hull pass {us:.1f} us",
                          flush=True)
        return
    print(f"hull pass and full substep, ocean choppiness {args.choppiness}; {device_description(device)}; "
          f"{datetime.date.today()}")
    print("|  boats | tris  | Warp hull [us] | G tri/s | Warp substep [us] | M boat-substeps/s |"
          " torch hull [us] | ratio | torch substep [us] | ratio | Warp vs torch |")
    rows = []
    for triangles in args.triangles:
        hull = boat_hull(triangles)
        for boats in args.boats:
            row = benchmark(device, boats, hull, torch_limit, args.choppiness)
            rows.append(row)
            print_row(row)
    if args.json:
        write_results_json(args.json, device, choppiness=args.choppiness, rows=rows)


if __name__ == "__main__":
    main()
