"""USD recording: wall time, file sizes and memory of :class:`ocean_warp.usd.StageRecorder`.

Each case records ``--frames`` frames of a fleet with random poses (seeded) on a JONSWAP ocean, either
a mesh per frame or one seamless loop, with one prim per boat or point instancers. Printed per case:
seconds per frame, the stage's and the loop's sizes [MiB], and the process's resident memory after a
quarter of the frames and at the end (flat memory means samples leave for the file as they come).

    python -m benchmarks.perf.bench_usd --device cpu --frames 400
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time

import numpy as np

import ocean_warp as ow
from ocean_warp.eboat import EBoatVessel
from ocean_warp.usd import FleetDrawing, OceanDrawing, StageRecorder, loop_path_for

MIB = 1024.0 * 1024.0


def resident_mib() -> float:
    """This process's resident memory [MiB] (Linux /proc; NaN elsewhere)."""
    try:
        with open("/proc/self/statm") as statm:
            return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / MIB
    except (OSError, ValueError):
        return float("nan")


def record_case(folder: str, *, boats: int, frames: int, instanced: bool, loop: bool, resolution: int,
                device: str, seed: int = 0) -> dict:
    """Record one case into ``folder``; returns its figures."""
    config = ow.OceanConfig(spectrum="jonswap", significant_wave_height=0.3, peak_period=3.0, resolution=128,
                            tile_size=100.0, loop_period=30.0 if loop else None, seed=seed)
    ocean = ow.Ocean(config, device=device)
    rng = np.random.default_rng(seed)
    fps = 2.0
    path = os.path.join(folder, f"b{boats}_{'inst' if instanced else 'prims'}_{'loop' if loop else 'mesh'}.usdc")
    side = 10.0 * np.sqrt(boats)
    positions = np.zeros((boats, 3))
    positions[:, :2] = rng.uniform(0.0, side, (boats, 2))
    quarter_memory = float("nan")
    start = time.perf_counter()
    drawing = OceanDrawing(ocean, resolution=resolution, extent=(0.0, side, 0.0, side), loop=loop)
    fleet = FleetDrawing(boats, instanced=instanced, vessel=EBoatVessel())
    with StageRecorder(path, fps=fps, ocean=drawing, fleet=fleet) as recorder:
        for frame in range(frames):
            positions[:, :2] += rng.normal(0.0, 0.5, (boats, 2))
            yaw = rng.uniform(-np.pi, np.pi, boats)
            orientations = np.stack([np.zeros(boats), np.zeros(boats), np.sin(yaw / 2), np.cos(yaw / 2)], axis=1)
            joints = {"boom_angle": rng.uniform(-1.2, 1.2, boats), "rudder_angle": rng.uniform(-0.5, 0.5, boats)}
            recorder.record(frame / fps, positions, orientations, joints=joints)
            if frame == frames // 4:
                quarter_memory = resident_mib()
    seconds = time.perf_counter() - start
    loop_path = loop_path_for(path)
    return dict(boats=boats, layout="instancers" if instanced else "prims", ocean="loop" if loop else "per frame",
                resolution=resolution, seconds_per_frame=seconds / frames,
                stage_mib=os.path.getsize(path) / MIB,
                loop_mib=os.path.getsize(loop_path) / MIB if os.path.exists(loop_path) else 0.0,
                memory_quarter_mib=quarter_memory, memory_end_mib=resident_mib())


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--device", default="cpu", help="Warp device for the ocean (default cpu)")
    parser.add_argument("--frames", type=int, default=400, help="frames per case (default 400, 2 per second)")
    parser.add_argument("--resolution", type=int, default=64, help="ocean mesh vertices per side (default 64)")
    args = parser.parse_args(argv)
    cases = [(16, False, False), (16, False, True), (256, False, True), (256, True, True), (4096, True, True)]
    print(f"{args.frames} frames at 2 fps, ocean mesh {args.resolution} per side, device {args.device}")
    print(f"{'boats':>6} {'layout':>10} {'ocean':>9} {'ms/frame':>9} {'stage MiB':>9} {'loop MiB':>8} "
          f"{'RSS 1/4 MiB':>11} {'RSS end MiB':>11}")
    with tempfile.TemporaryDirectory() as folder:
        for boats, instanced, loop in cases:
            r = record_case(folder, boats=boats, frames=args.frames, instanced=instanced, loop=loop,
                            resolution=args.resolution, device=args.device)
            print(f"{r['boats']:>6} {r['layout']:>10} {r['ocean']:>9} {1e3 * r['seconds_per_frame']:>9.2f} "
                  f"{r['stage_mib']:>9.1f} {r['loop_mib']:>8.1f} {r['memory_quarter_mib']:>11.0f} "
                  f"{r['memory_end_mib']:>11.0f}", flush=True)
            for name in os.listdir(folder):
                os.remove(os.path.join(folder, name))


if __name__ == "__main__":
    main()
