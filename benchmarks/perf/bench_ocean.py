"""Benchmark: one ocean update (all eight fields) by ocean_warp's Warp kernels against torch.fft and,
on the CPU, numpy.fft doing the same work. On CUDA both Warp and torch run as captured graphs.

    python -m benchmarks.perf.bench_ocean --device cuda:0 --sizes 256 512 1024
    python -m benchmarks.perf.bench_ocean --device cpu --sizes 256 512
    python -m benchmarks.perf.bench_ocean --device cuda:0 --sweep 512     # launch configurations

Prints a table; ``--json PATH`` also writes the numbers.
"""

from __future__ import annotations

import argparse
import datetime
import logging

import numpy as np
import warp as wp


from benchmarks.references.ocean_references import NumpyOceanReference, TorchOceanReference
from benchmarks.perf.timing import (
    device_description,
    median_seconds_host,
    median_seconds_torch_graph,
    median_seconds_warp_graph,
    write_results_json,
)
from ocean_warp import FftPlan, Ocean, OceanConfig


def sea(n: int) -> OceanConfig:
    """A JONSWAP sea with 1 m grid spacing, the sea of every row of the table."""
    return OceanConfig(tile_size=float(n), resolution=n, significant_wave_height=2.0, peak_period=8.0, choppiness=1.0)


def time_warp(ocean: Ocean) -> float:
    device = ocean.device
    if device.is_cuda:
        with wp.ScopedCapture(device=device) as capture:
            ocean.update()
        return median_seconds_warp_graph(capture.graph, device)
    return median_seconds_host(ocean.update, sync=lambda: wp.synchronize_device(device))


def time_torch(reference: TorchOceanReference, device) -> float:
    import torch

    if device.is_cuda:
        stream = torch.cuda.Stream()
        stream.wait_stream(torch.cuda.current_stream())
        with torch.cuda.stream(stream):
            for _ in range(3):  # warm up cuFFT plans outside the capture
                reference.update()
        torch.cuda.current_stream().wait_stream(stream)
        graph = torch.cuda.CUDAGraph()
        with torch.cuda.graph(graph):
            reference.update()
        return median_seconds_torch_graph(graph)
    return median_seconds_host(reference.update)


def fields_agree(ocean: Ocean, torch_fields) -> float:
    """Relative difference between the Warp fields and torch's, all eight together."""
    warp_fields = ocean.fields.numpy().astype(np.float64)
    reference = torch_fields.cpu().numpy()
    reference = np.stack([reference.real, reference.imag], axis=-1)
    return float(np.linalg.norm(warp_fields - reference) / np.linalg.norm(reference))


def benchmark_sizes(device, sizes) -> list[dict]:
    import torch

    torch_device = "cuda" if device.is_cuda else "cpu"
    rows = []
    for n in sizes:
        ocean = Ocean(sea(n), device=device)
        t = 123.4
        ocean.update(t)
        reference = TorchOceanReference(ocean.wave_grid.cells, torch_device)
        reference.time.fill_(t)
        reference.update()
        if device.is_cuda:
            torch.cuda.synchronize()
        row = {"n": n, "max_relative_difference": fields_agree(ocean, reference.fields)}
        row["warp_us"] = time_warp(ocean) * 1e6
        row["torch_us"] = time_torch(reference, device) * 1e6
        if device.is_cpu:
            numpy_reference = NumpyOceanReference(ocean.wave_grid.cells)
            numpy_reference.time = t
            row["numpy_us"] = median_seconds_host(numpy_reference.update) * 1e6
            row["warp_ffts_alone_us"], row["numpy_ffts_alone_us"] = time_ffts_alone(device, n)
        rows.append(row)
        print_row(row)
    return rows


def sweep_plans(device, n: int) -> list[dict]:
    """Time the Warp update with 2, 4 and 8 grid points per thread (GPU tuning)."""
    rows = []
    for points_per_thread in (2, 4, 8):
        plan = FftPlan(block_dim=n // points_per_thread)
        try:
            us = time_warp(Ocean(sea(n), device=device, fft_plan=plan)) * 1e6
        except Exception as error:  # a configuration cuFFTDx or the shared memory cannot take
            print(f"  {plan}: failed: {str(error).splitlines()[0][:120]}")
            continue
        rows.append({"n": n, "block_dim": plan.block_dim, "warp_us": us})
        print(f"  n={n} block_dim={plan.block_dim:4d}: {us:9.1f} us", flush=True)
    return rows


def time_ffts_alone(device, n: int) -> tuple[float, float]:
    """The 2-D inverse FFTs of an update alone (four complex n x n transforms, no spectrum work):
    Warp's tile_ifft row kernel twice, against numpy.fft.ifft2 on the same data [us]."""
    from ocean_warp.kernels.fft import ifft_rows_kernel

    rng = np.random.default_rng(0)
    data = (rng.standard_normal((4 * n, n)) + 1j * rng.standard_normal((4 * n, n))).astype(np.complex64)
    src = wp.array(data.view(np.float32).reshape(4 * n, n, 2), dtype=wp.vec2f, device=device)
    middle, dst = wp.empty_like(src), wp.empty_like(src)
    kernel = ifft_rows_kernel(n)
    block_dim = FftPlan.for_device(n, device).block_dim
    by_column = [middle[f * n:(f + 1) * n].transpose() for f in range(4)]

    def warp_ffts():
        wp.launch_tiled(kernel, dim=[4 * n], inputs=[src], outputs=[middle], block_dim=block_dim, device=device)
        for f, view in enumerate(by_column):
            wp.launch_tiled(kernel, dim=[n], inputs=[view], outputs=[dst[f * n:(f + 1) * n]], block_dim=block_dim,
                            device=device)

    stacked = data.reshape(4, n, n)
    warp_us = median_seconds_host(warp_ffts, sync=lambda: wp.synchronize_device(device)) * 1e6
    numpy_us = median_seconds_host(lambda: np.fft.ifft2(stacked)) * 1e6
    return warp_us, numpy_us


def print_row(row: dict) -> None:
    line = (f"| {row['n']:>5}² | {row['warp_us']:10.1f} | {row['torch_us']:10.1f} | "
            f"{row['torch_us'] / row['warp_us']:6.2f}x |")
    if "numpy_us" in row:
        line += f" {row['numpy_us']:10.1f} | {row['warp_us'] / row['numpy_us']:6.2f}x |"
    line += f" {row['max_relative_difference']:.1e} |"
    if "warp_ffts_alone_us" in row:
        line += (f"  FFTs alone: Warp {row['warp_ffts_alone_us']:.0f} us, numpy {row['numpy_ffts_alone_us']:.0f} us "
                 f"({row['warp_ffts_alone_us'] / row['numpy_ffts_alone_us']:.1f}x)")
    print(line, flush=True)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--device", default="cuda:0" if wp.get_cuda_device_count() else "cpu")
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024])
    parser.add_argument("--sweep", type=int, nargs="*", default=[], help="grid sizes to sweep launch configurations at")
    parser.add_argument("--json", help="write the results here")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    device = wp.get_device(args.device)
    print(f"ocean update, all 8 fields; {device_description(device)}; {datetime.date.today()}")
    header = "|  grid  | Warp [us]  | torch [us] | torch/Warp |"
    if device.is_cpu:
        header += " numpy [us] | Warp/numpy |"
    print(header + " Warp vs torch |")
    results = {"sizes": benchmark_sizes(device, args.sizes)}
    if args.sweep:
        results["sweep"] = [row for n in args.sweep for row in sweep_plans(device, n)]
    if args.json:
        write_results_json(args.json, device, **results)


if __name__ == "__main__":
    main()
