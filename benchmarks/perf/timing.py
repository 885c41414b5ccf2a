"""Helpers shared by the benchmarks: medians of repeated batches, device events on CUDA, results as JSON."""

from __future__ import annotations

import datetime
import json
import platform
import statistics
import time
from collections.abc import Callable

import warp as wp

from ocean_warp.atomic_files import atomic_output


def median_seconds_host(fn: Callable[[], None], *, batches: int = 7, per_batch: int = 3, sync=None) -> float:
    """Median wall time [s] of one call, over ``batches`` batches of ``per_batch`` calls (after one warm-up)."""
    fn()
    if sync:
        sync()
    samples = []
    for _ in range(batches):
        start = time.perf_counter()
        for _ in range(per_batch):
            fn()
        if sync:
            sync()
        samples.append((time.perf_counter() - start) / per_batch)
    return statistics.median(samples)


def median_seconds_warp_graph(graph, device, *, batches: int = 15, per_batch: int = 50) -> float:
    """Median time [s] of one replay of a captured Warp graph, measured with CUDA events."""
    wp.capture_launch(graph)
    wp.synchronize_device(device)
    samples = []
    for _ in range(batches):
        start, end = wp.Event(device, enable_timing=True), wp.Event(device, enable_timing=True)
        wp.record_event(start)
        for _ in range(per_batch):
            wp.capture_launch(graph)
        wp.record_event(end)
        wp.synchronize_event(end)
        samples.append(wp.get_event_elapsed_time(start, end) * 1e-3 / per_batch)
    return statistics.median(samples)


def median_seconds_torch_graph(graph, *, batches: int = 15, per_batch: int = 50) -> float:
    """Median time [s] of one replay of a captured torch CUDA graph, measured with CUDA events."""
    import torch

    graph.replay()
    torch.cuda.synchronize()
    samples = []
    for _ in range(batches):
        start, end = torch.cuda.Event(enable_timing=True), torch.cuda.Event(enable_timing=True)
        start.record()
        for _ in range(per_batch):
            graph.replay()
        end.record()
        end.synchronize()
        samples.append(start.elapsed_time(end) * 1e-3 / per_batch)
    return statistics.median(samples)


def device_description(device) -> str:
    """Human-readable name of a Warp device, with the CPU model for "cpu"."""
    device = wp.get_device(device)
    if device.is_cuda:
        return f"{device.name} ({device.alias})"
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as info:
            for line in info:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"CPU: {cpu}"


def write_results_json(path: str, device, **results) -> None:
    """Write ``results`` with the device's description and today's date to ``path``, atomically."""
    record = {"device": device_description(device), "date": str(datetime.date.today()), **results}
    with atomic_output(path) as temporary, open(temporary, "w") as handle:
        json.dump(record, handle, indent=2)
