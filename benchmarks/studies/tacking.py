"""Tacking under sail alone: from close-hauled on one tack, through the wind, to close-hauled on the other.

    python -m benchmarks.studies.tacking --polar out/polar/polar.csv --device cuda:0
    python -m benchmarks.studies.tacking --wind-speeds 10 --reef 2 --close-hauled 50 20 --out tacking_reef.csv

For each true wind speed (default 5 and 10 m/s) the boat starts close-hauled on starboard (the wind over
its starboard bow) at the true wind angle of its best upwind VMG in the polar, with that polar point's
sheet, in flat water and a steady wind; the propeller stays off. After ``--settle`` seconds the heading
autopilot (``ocean_warp.eboat.heading_autopilot.HeadingAutopilot``, PID on the rudder) is told to hold the same
angle on port. Reported per wind speed, with ``--boats`` copies of the run started at slightly different
sheets (the polar's setting and +-5 deg) so that one lucky setting does not decide it:
  through      the heading crossed the wind and reached within 10 deg of the new course, upright
  time_s       from the order to within 10 deg of the new course [s]
  speed_before mean speed over the 10 s before the order [m/s]
  speed_min    lowest speed ahead through the tack [m/s]
  speed_after  mean speed 20-30 s after the order [m/s] (way kept: as a fraction of speed_before)
Written atomically: ``benchmarks/data/tacking.csv``.
"""

from __future__ import annotations

import argparse
import csv
import math
import os

import numpy as np

from ocean_warp.atomic_files import atomic_output
from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.eboat.heading_autopilot import HeadingAutopilot
from ocean_warp.frames import roll_pitch_yaw
from ocean_warp.wind import WindConfig
from benchmarks import DATA

SETTLED_DEG = 10.0
"""Within this of the new course the tack is done [deg]."""


def close_hauled_points(polar_csv: str, wind_speeds) -> dict[float, tuple[float, float]]:
    """{true wind speed: (true wind angle [rad], sheet [rad]) of the best upwind VMG} from ``ocean-warp polar``'s CSV."""
    best: dict[float, tuple[float, float, float]] = {}
    with open(polar_csv) as handle:
        for row in csv.DictReader(handle):
            tws, twa, speed = float(row["true_wind_speed_mps"]), float(row["true_wind_angle_deg"]), float(row["boat_speed_mps"])
            if twa >= 90.0 or not math.isfinite(speed):
                continue
            vmg = speed * math.cos(math.radians(twa))
            if vmg > best.get(tws, (-1.0, 0.0, 0.0))[0]:
                best[tws] = (vmg, math.radians(twa), math.radians(float(row["sheet_deg"])))
    missing = [w for w in wind_speeds if w not in best]
    if missing:
        raise SystemExit(f"tacking: {polar_csv} has no upwind point at {missing} m/s")
    return {w: best[w][1:] for w in wind_speeds}


def tack(tws: float, twa: float, sheet: float, *, boats: int, settle: float, after: float, dt: float,
         device, seakeeping: bool = False, reef: int = 0) -> dict:
    """Sail ``boats`` copies (sheets spread +-5 deg) through one tack in ``tws`` [m/s] with the rig at reef level
    ``reef`` (0: the full sail); the summary row."""
    sheets = np.clip(sheet + np.radians(np.linspace(-5.0, 5.0, boats)), 0.0, math.radians(90.0))
    # The wind comes from +x (blows towards -x): yaw +twa points the bow twa to the left of the wind's source,
    # so the wind comes over the starboard bow (starboard tack); yaw -twa is the port tack.
    config = EBoatSimulatorConfig(boat=EBoatConfig(seakeeping=seakeeping),
                                  wind=WindConfig(speed=tws, direction=math.pi), dt=dt)
    sim = EBoatSimulator(config, boats, device=device)
    sim.reset(position=np.column_stack([np.arange(boats) * 30.0, np.zeros(boats), np.zeros(boats)]), heading=twa,
              velocity=[1.0, 0, 0, 0, 0, 0], wind_speed=tws, wind_direction=math.pi, sheet=sheets,
              reef_level=np.full(boats, reef))
    autopilot = HeadingAutopilot(sim)
    autopilot.set_target(np.full(boats, twa))
    settle_steps, after_steps = int(round(settle / dt)), int(round(after / dt))
    speeds, headings = [], []
    for step in range(settle_steps + after_steps):
        if step == settle_steps:
            autopilot.set_target(np.full(boats, -twa))
        autopilot.steer()
        sim.step()
        state = sim.fleet.numpy()
        speeds.append(state["velocity"][:, 0].copy())
        headings.append(roll_pitch_yaw(state["orientation"])[..., 2].copy())
    speeds, headings = np.array(speeds), np.array(headings)
    upright = sim.fleet.numpy()["status"] == 0
    time = np.arange(1, after_steps + 1) * dt
    new_course = np.abs(np.angle(np.exp(1j * (headings[settle_steps:] + twa)))) < math.radians(SETTLED_DEG)
    through = new_course.any(axis=0) & upright
    first = np.where(through, new_course.argmax(axis=0), -1)
    before = speeds[settle_steps - int(10.0 / dt):settle_steps].mean(axis=0)
    late = (time >= 20.0) & (time <= 30.0)
    rows = {"true_wind_speed_mps": tws, "reef_level": reef, "true_wind_angle_deg": math.degrees(twa),
            "sheet_deg": math.degrees(sheet), "boats": boats,
            "through": int(through.sum()), "time_s": float(np.mean(time[first[through]])) if through.any() else math.nan,
            "speed_before_mps": float(before.mean()), "speed_min_mps": float(speeds[settle_steps:].min(axis=0).mean()),
            "speed_after_mps": float(speeds[settle_steps:][late].mean()) if late.any() else math.nan}
    rows["way_kept"] = rows["speed_after_mps"] / rows["speed_before_mps"]
    return rows


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--polar", default=None, help="ocean-warp polar's polar.csv (the close-hauled points)")
    parser.add_argument("--close-hauled", type=float, nargs=2, default=None, metavar=("TWA_DEG", "SHEET_DEG"),
                        help="the close-hauled point for every wind speed, in place of --polar's")
    parser.add_argument("--reef", type=int, default=0, help="reef level of every boat's rig (0: the full sail)")
    parser.add_argument("--wind-speeds", type=float, nargs="+", default=[5.0, 10.0], help="[m/s]")
    parser.add_argument("--boats", type=int, default=5, help="copies per wind speed, sheets spread +-5 deg")
    parser.add_argument("--settle", type=float, default=40.0, help="close-hauled before the tack [s]")
    parser.add_argument("--after", type=float, default=40.0, help="sailed after the order [s]")
    parser.add_argument("--dt", type=float, default=0.05)
    parser.add_argument("--device", default=None)
    parser.add_argument("--seakeeping", action="store_true", help="EBoatConfig.seakeeping (the hull's database)")
    parser.add_argument("--out", default=os.path.join(DATA, "tacking.csv"))
    args = parser.parse_args(argv)
    if (args.polar is None) == (args.close_hauled is None):
        parser.error("give either --polar or --close-hauled")
    if args.close_hauled is not None:
        point = tuple(math.radians(v) for v in args.close_hauled)
        points = {w: point for w in args.wind_speeds}
    else:
        points = close_hauled_points(args.polar, args.wind_speeds)
    rows = [tack(w, *points[w], boats=args.boats, settle=args.settle, after=args.after, dt=args.dt, device=args.device,
                 seakeeping=args.seakeeping, reef=args.reef) for w in args.wind_speeds]
    with atomic_output(args.out) as temporary, open(temporary, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in row.items()} for row in rows)
    for row in rows:
        print(", ".join(f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in row.items()))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
