"""The E-Boat's speed polar: steady speed over true wind angles 0-180 deg for true wind 4, 7 and 10 m/s.

    python -m ocean_warp.examples.polar --out out/polar          # or: ocean-warp polar --out out/polar

Every (wind speed, wind angle, sheet setting) is one boat of one batched simulation; an autopilot holds
each heading and the sheet setting with the best steady speed wins (see ``ocean_warp.eboat.polar``).
Writes ``polar.png`` and ``polar.csv``. A few minutes on a CPU, seconds on a GPU.
"""

from __future__ import annotations

import argparse
import csv
import logging
import math
import os
import time

import numpy as np
import warp as wp

from ocean_warp.atomic_files import atomic_output
from ocean_warp.eboat import EBoat
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
    with atomic_output(path) as temporary:
        fig.savefig(temporary, dpi=110)
    plt.close(fig)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description="The E-Boat's speed polar (PNG and CSV).")
    parser.add_argument("--out", default="out/polar", help="folder for polar.png and polar.csv")
    parser.add_argument("--device", default=None, help='Warp device, e.g. "cpu" or "cuda:0"')
    parser.add_argument("--wind-speeds", type=float, nargs="+", default=[4.0, 7.0, 10.0], help="[m/s]")
    parser.add_argument("--angle-step", type=float, default=15.0, help="true wind angle step [deg]")
    parser.add_argument("--sheet-step", type=float, default=15.0, help="sheet search step [deg]")
    parser.add_argument("--settle", type=float, default=60.0, help="settling time [s]")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    eboat = EBoat()
    start = time.perf_counter()
    result = speed_polar(wind_speeds=args.wind_speeds, wind_angles_deg=np.arange(0.0, 180.0 + 1e-9, args.angle_step),
                         sheets_deg=np.arange(0.0, 90.0 + 1e-9, args.sheet_step), settle_time=args.settle,
                         device=args.device)
    elapsed = time.perf_counter() - start
    os.makedirs(args.out, exist_ok=True)
    png, table = os.path.join(args.out, "polar.png"), os.path.join(args.out, "polar.csv")
    limit = hull_speed(eboat)
    plot(png, result, limit)
    write_csv(table, result)
    boats = result.all_speeds.size
    print(f"{boats} boats sailed in {elapsed:.0f} s; hull speed {limit:.2f} m/s; best speed "
          f"{np.nanmax(result.speed):.2f} m/s")
    for i, tws in enumerate(result.wind_speeds):
        row = " ".join("  --" if np.isnan(v) else f"{v:4.2f}" for v in result.speed[i])
        print(f"  {tws:4.1f} m/s: {row}")
    print(f"wrote {png}\nwrote {table}")


if __name__ == "__main__":
    main()
