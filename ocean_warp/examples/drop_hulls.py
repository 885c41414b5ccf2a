"""Example: a few dozen hulls of different shapes dropped into a JONSWAP sea; heave and roll over time.

    ocean-warp drop-hulls --out out/drop-hulls    # or: python -m ocean_warp.examples.drop_hulls ...

Writes ``hull_motions.png`` (heave and roll of every boat, coloured by shape) and ``hull_motions.csv``.
"""

from __future__ import annotations

import csv
import logging
import os
import sys

import numpy as np
import warp as wp
from tqdm import tqdm

import ocean_warp as ow
from ocean_warp.atomic_files import atomic_output, save_figure
from ocean_warp.cli_support import (
    check_options,
    checked_device,
    checked_output_folder,
    finite_at_least,
    plural,
)
from ocean_warp.examples.drop_hulls_options import MAX_BOATS_PER_SHAPE, parser as _parser
from ocean_warp.frames import quaternion_from_roll_pitch_yaw, roll_pitch_yaw

SHAPES = {
    "box": lambda: ow.Hull.box(3.0, 1.2, 0.8, subdivisions=2),
    "ellipsoid": lambda: ow.Hull.ellipsoid(1.5, 0.6, 0.4, subdivisions=3),
    "sphere": lambda: ow.Hull.sphere(0.6, subdivisions=3),
    "cylinder": lambda: ow.Hull.cylinder(0.4, 3.0, sections=24),
}


DT = 0.02
"""Time step of the simulation [s]."""


def boat_types() -> list[ow.BoatType]:
    """Each shape floating with 40 % of its volume submerged, lightly damped."""
    types = []
    for name, make in SHAPES.items():
        hull = make()
        types.append(ow.BoatType.floating_solid(hull, draft_fraction=0.4, name=name,
                                                linear_damping=[20, 20, 200, 20, 20, 20]))
    return types


def run(out_dir: str, *, device=None, boats_per_shape: int = 8, seconds: float = 40.0, seed: int = 3,
        progress: bool | None = False) -> dict:
    """Drop ``boats_per_shape`` hulls of each shape at random places, heights (1-2.5 m) and tilts (seeded by
    ``seed``), simulate ``seconds`` [s] on ``device`` and write the PNG and CSV into ``out_dir``; returns the
    device, the number of boats, how many ended flagged (``Fleet.status`` not 0) and the files.
    ``progress``: a progress bar of the time steps on stderr (None: only where stderr is a terminal)."""
    rng = np.random.default_rng(seed)
    types = boat_types()
    type_of_boat = np.repeat(np.arange(len(types)), boats_per_shape)
    fleet = ow.Fleet(types, types=type_of_boat, device=device)
    ocean = ow.Ocean(ow.OceanConfig(tile_size=200.0, resolution=128, significant_wave_height=1.2, peak_period=5.0,
                                    spreading=8.0, choppiness=0.6, seed=seed), device=fleet.device)
    count = len(type_of_boat)
    start = np.column_stack([rng.uniform(0, 200, size=(count, 2)), rng.uniform(1.0, 2.5, size=count)])
    tilt = np.column_stack([rng.uniform(-0.4, 0.4, size=(count, 2)), rng.uniform(-np.pi, np.pi, size=count)])
    fleet.reset(position=start, orientation=quaternion_from_roll_pitch_yaw(tilt))
    config = ow.SimulatorConfig(dt=DT, substeps=4)
    simulator = ow.Simulator(ocean, fleet, config)
    steps = int(round(seconds / config.dt))
    times, heave, roll = np.arange(1, steps + 1) * config.dt, np.empty((steps, count)), np.empty((steps, count))
    for step in tqdm(range(steps), desc="drop-hulls", unit="step", file=sys.stderr, dynamic_ncols=True,
                     disable=None if progress is None else not progress):
        simulator.step()
        heave[step] = fleet.state.position.numpy()[:, 2]
        roll[step] = roll_pitch_yaw(fleet.state.orientation.numpy())[:, 0]
    status = fleet.state.status.numpy()
    names = [types[t].name for t in type_of_boat]
    png = os.path.join(out_dir, "hull_motions.png")
    table = os.path.join(out_dir, "hull_motions.csv")
    _plot(png, times, heave, roll, names)
    _write_csv(table, times, heave, roll, names)
    return {"device": str(fleet.device), "boats": count, "flagged": int(np.count_nonzero(status)),
            "files": [png, table], "final_heave_std": float(heave[-steps // 4:].std())}


def _plot(path, times, heave, roll, names) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    colours = {name: f"C{i}" for i, name in enumerate(SHAPES)}
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for boat, name in enumerate(names):
        label = name if names.index(name) == boat else None
        top.plot(times, heave[:, boat], color=colours[name], lw=0.7, alpha=0.8, label=label)
        bottom.plot(times, np.degrees(roll[:, boat]), color=colours[name], lw=0.7, alpha=0.8)
    top.set_ylabel("heave: origin height [m]")
    bottom.set_ylabel("roll [deg]")
    bottom.set_xlabel("time [s]")
    top.legend(loc="upper right", ncol=len(colours))
    top.set_title("hulls dropped into a JONSWAP sea (Hs 1.2 m, Tp 5 s)")
    fig.tight_layout()
    save_figure(fig, path, dpi=110)


def _write_csv(path, times, heave, roll, names) -> None:
    with atomic_output(path) as temporary, open(temporary, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["time_s"] + [f"heave_m_{i}_{n}" for i, n in enumerate(names)]
                        + [f"roll_rad_{i}_{n}" for i, n in enumerate(names)])
        for row in range(len(times)):
            writer.writerow([f"{times[row]:.3f}"] + [f"{v:.5f}" for v in heave[row]] + [f"{v:.5f}" for v in roll[row]])


def main(argv=None) -> int:
    """``ocean-warp drop-hulls``: returns 0; bad options exit with status 2 and one line."""
    parser = _parser()
    args = parser.parse_args(argv)
    check_options(parser, (
        ("--boats-per-shape", args.boats_per_shape, 1 <= args.boats_per_shape <= MAX_BOATS_PER_SHAPE,
         f"a whole number from 1 to {MAX_BOATS_PER_SHAPE} (the heave and roll of every hull are kept at every step)"),
        ("--seconds", args.seconds, finite_at_least(args.seconds, DT), f"a number of seconds >= one step ({DT} s)"),
    ))
    device = checked_device(parser, args.device)
    wp.config.log_level = logging.WARNING
    checked_output_folder(parser, args.out)
    os.makedirs(args.out, exist_ok=True)
    report = run(args.out, device=device, boats_per_shape=args.boats_per_shape, seconds=args.seconds,
                 progress=None)  # a bar where stderr is a terminal
    print(f"{plural(report['boats'], 'hull')} on {report['device']} for {args.seconds:g} s, "
          f"{report['flagged']} flagged (capsized, sunk, flying or non-finite)")
    for path in report["files"]:
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
