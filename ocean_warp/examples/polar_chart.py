"""The E-Boat's speed polar: steady speed over true wind angles 0-180 deg for true wind 4, 7 and 10 m/s.

    python -m ocean_warp.examples.polar_chart --out out/polar          # or: ocean-warp polar --out out/polar

Every (wind speed, wind angle, sheet setting) is one boat of one batched simulation; an autopilot holds
each heading and the sheet setting with the best steady speed wins (see ``ocean_warp.eboat.polar``).
Writes ``polar.png`` and ``polar.csv``. A few minutes on a CPU, seconds on a GPU.
"""

from __future__ import annotations

import csv
import logging
import math
import os
import sys
import time

import numpy as np
import warp as wp

from ocean_warp.atomic_files import atomic_output, save_figure
from ocean_warp.cli_support import (
    check_options,
    checked_device,
    checked_output_folder,
    finite_above,
    finite_at_least,
    plural,
)
from ocean_warp.eboat import EBoat, EBoatConfig
from ocean_warp.examples.polar_chart_options import parser as _parser
from ocean_warp.eboat.polar import PolarResult, speed_polar


def hull_speed(eboat: EBoat) -> float:
    """1.34 sqrt(LWL in feet) knots, in m/s, for the waterline at rest."""
    waterline_ft = eboat.waterline_length(-eboat.rest_height()) / 0.3048
    return 1.34 * math.sqrt(waterline_ft) * 0.514444


def write_csv(path: str, result: PolarResult) -> None:
    with atomic_output(path) as temporary, open(temporary, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["true_wind_speed_mps", "true_wind_angle_deg", "boat_speed_mps", "sheet_deg", "heel_deg"])
        for i, tws in enumerate(result.wind_speeds):
            for j, twa in enumerate(result.wind_angles):
                writer.writerow([f"{tws:.1f}", f"{math.degrees(twa):.1f}", f"{result.speed[i, j]:.3f}",
                                 f"{math.degrees(result.sheet[i, j]):.0f}", f"{math.degrees(result.heel[i, j]):.1f}"])


def plot(path: str, result: PolarResult, limit: float) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(6.4, 6.4))
    ax = fig.add_subplot(projection="polar")
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    ax.set_thetamin(0)
    ax.set_thetamax(180)
    for i, tws in enumerate(result.wind_speeds):
        ax.plot(result.wind_angles, result.speed[i], marker="o", ms=3, label=f"true wind {tws:g} m/s")
    ax.plot(np.linspace(0, math.pi, 100), np.full(100, limit), "k:", lw=0.8, label="hull speed")
    ax.set_title("E-Boat speed polar: boat speed [m/s] over true wind angle")
    ax.legend(loc="lower left", fontsize=8)
    fig.tight_layout()
    save_figure(fig, path, dpi=110)


def main(argv=None) -> int:
    """``ocean-warp polar``: returns 0; bad options exit with status 2 and one line."""
    parser = _parser()
    args = parser.parse_args(argv)
    bad_wind = next((v for v in args.wind_speeds if not finite_above(v, 0.0)), None)
    check_options(parser, (
        ("--wind-speeds", bad_wind, bad_wind is None, "numbers > 0 [m/s]"),
        ("--angle-step", args.angle_step, finite_above(args.angle_step, 0.0) and args.angle_step <= 180.0,
         "in (0, 180] [deg]"),
        ("--sheet-step", args.sheet_step, finite_above(args.sheet_step, 0.0) and args.sheet_step <= 90.0,
         "in (0, 90] [deg]"),
        ("--settle", args.settle, finite_at_least(args.settle, 0.0), "a number >= 0 [s]"),
    ))
    device = checked_device(parser, args.device)
    wp.config.log_level = logging.WARNING
    checked_output_folder(parser, args.out)
    os.makedirs(args.out, exist_ok=True)
    boat = EBoatConfig(seakeeping=True) if args.seakeeping else EBoatConfig()
    eboat = EBoat(boat)
    start = time.perf_counter()
    result = speed_polar(wind_speeds=args.wind_speeds, wind_angles_deg=np.arange(0.0, 180.0 + 1e-9, args.angle_step),
                         sheets_deg=np.arange(0.0, 90.0 + 1e-9, args.sheet_step), settle_time=args.settle,
                         boat=boat, device=device, progress=None)  # a bar where stderr is a terminal
    elapsed = time.perf_counter() - start
    png, table = os.path.join(args.out, "polar.png"), os.path.join(args.out, "polar.csv")
    limit = hull_speed(eboat)
    plot(png, result, limit)
    write_csv(table, result)
    boats = result.all_speeds.size
    held = np.isfinite(result.speed)
    best = f"best speed {np.max(result.speed[held]):.2f} m/s" if held.any() else "no wind angle held"
    print(f"{plural(boats, 'boat')} sailed in {elapsed:.0f} s on {device}; hull speed {limit:.2f} m/s; {best}")
    print("boat speed [m/s] by true wind speed (rows) and angle [deg] (columns; --: not held)")
    labels = [f"  {tws:4.1f} m/s: " for tws in result.wind_speeds]
    print(" " * len(labels[0]) + " ".join(f"{math.degrees(a):4.0f}" for a in result.wind_angles))
    for label, speeds in zip(labels, result.speed):
        print(label + " ".join("  --" if np.isnan(v) else f"{v:4.2f}" for v in speeds))
    print(f"wrote {png}\nwrote {table}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
