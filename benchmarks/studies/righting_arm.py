"""The E-Boat's righting-arm (GZ) curve from its hull mesh, against the VPP input's and the simulator's heel.

    python -m benchmarks.studies.righting_arm                      # CPU, about 10 s
    python -m benchmarks.studies.righting_arm --seconds 90 --moments 10 40 80 120

1. GZ of the canoe-body mesh (``EBoat().hull``) at 0-90 deg of heel in 5 deg steps, free in heave and
   trim (``ocean_warp.stability``): exact clipping at the still-water plane, the centre of buoyancy by the
   divergence theorem, sea water 1025 kg/m^3, the centre of gravity of the composite mass properties
   (keel ballast included; the real boat's keel fin, bulb and rudder, outside the mesh, add their
   displacement's buoyancy at its centroid, as in the simulator). Beside it the same
   with the trim held at 0, and the GZ column of ``shared/eboat/vpp_inputs.json`` (a different,
   parametric hull with its own centre of gravity: compared, not required to agree).
2. The simulator's steady heel under a known heeling couple: one E-Boat per moment in still water and
   calm air (Warp, CPU; the sails and foils make no force at rest), a pure couple about the body x axis
   written each step to the fleet's external body-frame wrench (``EBoatSimulator.control.wrench_body``,
   Mx), ramped in smoothly over ``--ramp`` seconds and held; the heel averaged over the last
   ``--average`` seconds, against the heel at which m g GZ(heel) equals the moment on the mesh curve.

Writes ``<data>/righting_arm.csv`` (long form; ``series`` is mesh, mesh_heave_only, vpp_input or
simulator; simulator rows hold the steady heel, the arm M / (m g) the moment asks for, the moment, the
trim and the predicted heel) and ``<out>/righting_arm.png``, each in one rename
(``ocean_warp.atomic_files``), and prints both tables.
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import warp as wp

from ocean_warp.atomic_files import atomic_output, save_figure
from ocean_warp.eboat import EBoat, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.frames import roll_pitch_yaw
from ocean_warp.hull_form import floating_waterline
from ocean_warp.stability import RightingArmCurve, equilibrium_heel, righting_arm_curve
from ocean_warp.wind import WindConfig
from benchmarks import REPO, DATA, FIGURES

DEFAULT_VPP_INPUTS = REPO.parent / "shared" / "eboat" / "vpp_inputs.json"
HEELS_DEG = np.arange(0.0, 90.0 + 1e-9, 5.0)
MOMENTS = (20.0, 50.0, 100.0, 130.0, 150.0)
"""Heeling couples [N m]; 150 exceeds the mesh curve's largest righting moment (about 137 N m)."""
SMALL_HEEL = math.radians(1.0)
"""Heel [rad] of the initial slope GM = GZ / sin(heel) (the wall-sided term (BM / 2) tan^2 is 0.005 %)."""


@dataclasses.dataclass(frozen=True)
class SteadyHeel:
    """What the simulator settled to under each heeling couple."""

    moment: np.ndarray
    """(N,) heeling couple about body x [N m]."""
    heel: np.ndarray
    """(N,) mean heel over the averaging window [rad] (port side up positive)."""
    spread: np.ndarray
    """(N,) peak-to-peak heel over the window [rad]: what is left of the roll oscillation."""
    trim: np.ndarray
    """(N,) mean trim (pitch, bow down positive) over the window [rad]."""
    capsized: np.ndarray
    """(N,) bool: the heel passed 90 deg at some time."""


def appendages(eboat: EBoat) -> dict:
    """The keyword arguments of ``ocean_warp.stability`` for ``eboat``'s appendages outside its mesh."""
    return dict(appendages=eboat.appendages)


def eboat_curves(eboat: EBoat, heels_deg=HEELS_DEG) -> tuple[RightingArmCurve, RightingArmCurve]:
    """(free in heave and trim, free in heave only) GZ curves of ``eboat``'s mesh at ``heels_deg`` [deg]."""
    mp = eboat.mass_properties
    heels = np.radians(np.asarray(heels_deg, dtype=np.float64))
    return (righting_arm_curve(eboat.hull, mp.mass, mp.center_of_mass, heels, **appendages(eboat)),
            righting_arm_curve(eboat.hull, mp.mass, mp.center_of_mass, heels, free_trim=False, **appendages(eboat)))


def initial_metacentric_height(eboat: EBoat) -> float:
    """GM [m]: the mesh curve's initial slope, (GZ(SMALL_HEEL) - GZ(0) cos(SMALL_HEEL)) / sin(SMALL_HEEL), free
    in heave and trim (GZ(0): the arm of a centre of gravity off the centre line, as the real boat's 0.17 mm)."""
    mp = eboat.mass_properties
    curve = righting_arm_curve(eboat.hull, mp.mass, mp.center_of_mass, [0.0, SMALL_HEEL], **appendages(eboat))
    upright, heeled = curve.righting_arm
    return float((heeled - upright * math.cos(SMALL_HEEL)) / math.sin(SMALL_HEEL))


def vpp_righting_arm(path: Path) -> tuple[np.ndarray, np.ndarray, float]:
    """(heel [deg], GZ [m], mass [kg]) of the VPP inputs' parametric hull."""
    data = json.loads(Path(path).read_text())
    return np.asarray(data["GZ"]["heel"], float), np.asarray(data["GZ"]["gz_m"], float), float(data["inputs"]["Mass"])


def _ramp(time: float, ramp: float) -> float:
    """Smooth 0 -> 1 over ``ramp`` [s] (half a cosine), then 1: a step would roll the boat past the peak."""
    return 1.0 if time >= ramp else 0.5 * (1.0 - math.cos(math.pi * time / ramp))


def steady_heels(moments, *, seconds: float = 60.0, ramp: float = 10.0, average: float = 10.0, dt: float = 0.05,
                 substeps: int = 5, device="cpu") -> SteadyHeel:
    """One E-Boat per heeling couple in ``moments`` [N m] (about body x, positive heels port side up), in
    still water and calm air, let go upright at its rest height; the couple ramps in over ``ramp`` [s] and
    holds for the rest of ``seconds`` [s]; the heel and trim are averaged over the last ``average`` [s]."""
    moments = np.asarray(moments, dtype=np.float64).reshape(-1)
    if moments.size == 0 or not np.all(np.isfinite(moments)):
        raise ValueError(f"steady_heels.moments must be finite numbers [N m], got {moments!r}")
    if not 0.0 < average <= seconds - ramp:
        raise ValueError(f"steady_heels.average must be in (0, seconds - ramp] [s], got {average!r}")
    config = EBoatSimulatorConfig(wind=WindConfig(speed=0.0), dt=dt, substeps=substeps)
    sim = EBoatSimulator(config, len(moments), device=device)
    rest = -floating_waterline(sim.eboat.hull, sim.eboat.hull_load(config.water.density), config.water.density)
    sim.reset(position=(0.0, 0.0, rest))
    steps, window = int(round(seconds / dt)), int(round(average / dt))
    wrench = np.zeros((len(moments), 6), dtype=np.float32)
    angles = np.empty((steps, len(moments), 3))
    for step in range(steps):
        wrench[:, 3] = moments * _ramp(step * dt, ramp)
        sim.control.wrench_body.assign(wrench)
        sim.step()
        angles[step] = roll_pitch_yaw(sim.fleet.numpy()["orientation"])
    held = angles[-window:]
    return SteadyHeel(moment=moments, heel=held[:, :, 0].mean(axis=0), spread=np.ptp(held[:, :, 0], axis=0),
                      trim=held[:, :, 1].mean(axis=0), capsized=np.any(np.abs(angles[:, :, 0]) > math.pi / 2, axis=0))


def predicted_heels(eboat: EBoat, curve: RightingArmCurve, moments, gravity: float = 9.81) -> np.ndarray:
    """(N,) heels [rad] where m g GZ of the mesh equals each of ``moments`` [N m] (NaN: beyond the curve's peak)."""
    return np.array([equilibrium_heel(eboat.hull, curve, float(m), gravity) for m in moments])


def vanishing_heel(curve: RightingArmCurve) -> float:
    """Heel [rad] past the peak where GZ turns negative (linear between the curve's heels); NaN if it stays positive."""
    peak = int(np.argmax(curve.righting_arm))
    negative = np.flatnonzero(curve.righting_arm[peak:] < 0.0)
    if len(negative) == 0:
        return math.nan
    i = peak + int(negative[0])
    gz, heel = curve.righting_arm[i - 1:i + 1], curve.heel[i - 1:i + 1]
    return float(heel[0] + gz[0] / (gz[0] - gz[1]) * (heel[1] - heel[0]))


def _format(value) -> str:
    if isinstance(value, (float, np.floating)):
        return "nan" if math.isnan(value) else f"{value:.6g}"
    return str(value)


def csv_rows(curve, heave_only, vpp, steady, predicted, gravity: float) -> list[list]:
    """Rows of the long-form csv (see the module docstring)."""
    weight = curve.mass * gravity
    rows = []
    for name, c in (("mesh", curve), ("mesh_heave_only", heave_only)):
        rows += [[name, math.degrees(h), gz, weight * gz, math.degrees(t), math.nan, ""]
                 for h, gz, t in zip(c.heel, c.righting_arm, c.trim)]
    vpp_heel, vpp_gz, vpp_mass = vpp
    rows += [["vpp_input", h, gz, vpp_mass * gravity * gz, math.nan, math.nan, ""] for h, gz in zip(vpp_heel, vpp_gz)]
    for m, h, t, capsized, p in zip(steady.moment, steady.heel, steady.trim, steady.capsized, predicted):
        rows.append(["simulator", math.nan if capsized else math.degrees(h), m / weight, m,
                     math.nan if capsized else math.degrees(t), math.degrees(p), "capsized" if capsized else ""])
    return rows


def write_csv(path: Path, rows: list[list]) -> None:
    header = ["series", "heel_deg", "gz_m", "righting_moment_n_m", "trim_deg", "predicted_heel_deg", "note"]
    with atomic_output(path) as temporary, open(temporary, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        writer.writerows([[_format(v) for v in row] for row in rows])


def write_figure(path: Path, curve, heave_only, vpp, steady, gravity: float) -> None:
    """GZ against heel: the mesh's (free trim, heave only), the VPP input's, the simulator's steady heels."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    weight = curve.mass * gravity
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.plot(np.degrees(curve.heel), curve.righting_arm, "-o", ms=3, label="E-Boat mesh, free in heave and trim")
    ax.plot(np.degrees(heave_only.heel), heave_only.righting_arm, ":", label="E-Boat mesh, trim held at 0")
    ax.plot(vpp[0], vpp[1], "--s", ms=3, label="VPP input (parametric hull, zG -0.16 m)")
    settled = ~steady.capsized
    ax.plot(np.degrees(steady.heel[settled]), steady.moment[settled] / weight, "kx", ms=9, mew=2,
            label="simulator: steady heel under M, at M / (m g)")
    for m in steady.moment[~settled]:
        ax.axhline(m / weight, color="r", lw=0.8, ls="-.", label=f"M = {m:g} N m: simulator capsized")
    ax.axhline(0.0, color="grey", lw=0.5)
    ax.set_xlabel("heel [deg]")
    ax.set_ylabel("righting arm GZ [m]")
    right = ax.secondary_yaxis("right", functions=(lambda gz: gz * weight, lambda rm: rm / weight))
    right.set_ylabel(f"E-Boat righting moment m g GZ [N m] (m = {curve.mass:.1f} kg)")
    ax.set_xlim(0.0, 90.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    ax.set_title("E-Boat righting arm: mesh hydrostatics, VPP input, simulator", fontsize=10)
    fig.tight_layout()
    save_figure(fig, path, dpi=120)


def print_tables(curve, heave_only, vpp, gm: float, steady, predicted) -> None:
    vpp_at = dict(zip(np.round(vpp[0]).astype(int), vpp[1]))
    peak = int(np.argmax(curve.righting_arm))
    print(f"GM (initial slope of the mesh curve) = {gm:.4f} m; centre of gravity "
          f"{curve.center_of_mass[2] - curve.water_level[0]:.3f} m above the upright waterline; largest righting "
          f"moment {curve.righting_moment()[peak]:.1f} N m at {math.degrees(curve.heel[peak]):.0f} deg; "
          f"stability vanishes at {math.degrees(vanishing_heel(curve)):.1f} deg")
    print(f"{'heel deg':>8} {'GZ mesh m':>10} {'GZ heave-only m':>16} {'trim deg':>9} {'GZ VPP input m':>15}")
    for h, gz, gz0, t in zip(curve.heel, curve.righting_arm, heave_only.righting_arm, curve.trim):
        deg = int(round(math.degrees(h)))
        print(f"{deg:8d} {gz:10.4f} {gz0:16.4f} {math.degrees(t):9.2f} {vpp_at.get(deg, math.nan):15.4f}")
    print(f"\n{'moment N m':>10} {'predicted deg':>14} {'simulated deg':>14} {'difference deg':>15} {'spread deg':>11}")
    for m, p, h, s, capsized in zip(steady.moment, predicted, steady.heel, steady.spread, steady.capsized):
        simulated = "capsized" if capsized else f"{math.degrees(h):.3f}"
        difference = math.degrees(h - p) if not capsized else math.nan
        print(f"{m:10g} {math.degrees(p):14.3f} {simulated:>14} {difference:15.3f} {math.degrees(s):11.3f}")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--out", type=Path, default=FIGURES, help="folder of the figure")
    parser.add_argument("--data", type=Path, default=DATA, help="folder of the csv")
    parser.add_argument("--vpp-inputs", type=Path, default=DEFAULT_VPP_INPUTS, help="json with the VPP's GZ column")
    parser.add_argument("--moments", type=float, nargs="+", default=list(MOMENTS), help="heeling couples [N m]")
    parser.add_argument("--seconds", type=float, default=60.0, help="simulated time per boat [s]")
    parser.add_argument("--ramp", type=float, default=10.0, help="time to ramp the couple in [s]")
    parser.add_argument("--average", type=float, default=10.0, help="window of the steady heel [s]")
    parser.add_argument("--dt", type=float, default=0.05, help="simulator step [s]")
    parser.add_argument("--substeps", type=int, default=5)
    parser.add_argument("--device", default="cpu")
    args = parser.parse_args(argv)

    wp.config.quiet = True
    eboat = EBoat()
    gravity = EBoatSimulatorConfig().water.gravity
    curve, heave_only = eboat_curves(eboat)
    vpp = vpp_righting_arm(args.vpp_inputs)
    gm = initial_metacentric_height(eboat)
    predicted = predicted_heels(eboat, curve, args.moments, gravity)
    steady = steady_heels(args.moments, seconds=args.seconds, ramp=args.ramp, average=args.average, dt=args.dt,
                          substeps=args.substeps, device=args.device)
    print_tables(curve, heave_only, vpp, gm, steady, predicted)
    write_csv(args.data / "righting_arm.csv", csv_rows(curve, heave_only, vpp, steady, predicted, gravity))
    write_figure(args.out / "righting_arm.png", curve, heave_only, vpp, steady, gravity)
    print(f"\nwrote {args.data / 'righting_arm.csv'} and {args.out / 'righting_arm.png'}")


if __name__ == "__main__":
    main()
