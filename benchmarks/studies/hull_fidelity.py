"""Fidelity of the E-Boat's hull at a triangle budget, against the full hull (2 024 triangles).

    python -m benchmarks.studies.hull_fidelity --budgets 256 512 1024 2048 --out scratch/hull_fidelity.md
    python -m benchmarks.studies.hull_fidelity --no-polar          # the hydrostatics and periods only (seconds)

Each budget's hull (``EBoatConfig(hull_triangles=budget)``: the same procedure, fewer stations and section
points) and the full hull are measured on the CPU with the simulator:

- rest height and draft: ``EBoat.rest_height`` (bisection on the hull pass's vertical force, upright);
- GM: the hull pass's righting moment about the centre of mass at +-2 deg of heel about the rest waterline,
  GM = -dM_x / (2 F sin 2 deg); beside it, an independent numpy value (the submerged volume clipped at the
  re-found waterline, its centre of buoyancy by the divergence theorem, GZ / sin 2 deg);
- heave and roll periods: free decay in still water, calm air, from 3 cm up and from 4 deg of heel; the
  period is twice the mean time between the zero crossings of the motion about where it settles;
- resistance at 1 m/s: the hull pass's surge force on the boat held upright at rest height at 1 m/s;
- the speed polar in 7 m/s of true wind (``speed_polar``) at a few angles, best of a few sheet settings.

Relative errors are against the full hull. The tolerances the tests hold every budget to are in the table.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import logging
import math

import numpy as np
import warp as wp


import ocean_warp as ow
from ocean_warp.atomic_files import atomic_output
from ocean_warp.eboat import EBoat, EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.eboat.polar import speed_polar
from ocean_warp.frames import quaternion_from_roll_pitch_yaw, roll_pitch_yaw

HEEL = math.radians(2.0)
"""Heel of the GM measurements [rad]: small, so GZ / sin(heel) is GM to within (BM / 2) tan^2 = 0.1 %."""
POLAR_ANGLES_DEG = (45.0, 60.0, 90.0, 120.0, 150.0)
POLAR_SHEETS_DEG = (0.0, 15.0, 30.0, 45.0, 60.0, 75.0)
TOLERANCES = ((1000, 0.015, 0.01), (500, 0.04, 0.015), (250, 0.10, 0.07))
"""(smallest budget, rest draft, GM): the relative errors against the full hull that tests/ocean_warp/test_coarse_hulls.py
allows a hull of at least that many triangles; this benchmark measured (2026-11-23) 0.6 and 0.1 % at 1 024,
2.2 and 0.3 % at 512, 7.1 and 4.4 % at 256 (2 048 gives the full hull)."""


def tolerances(budget: int) -> tuple[float, float]:
    """(rest draft, GM) relative tolerances [-] for a hull of ``budget`` >= 250 triangles (see TOLERANCES)."""
    for smallest, draft, gm in TOLERANCES:
        if budget >= smallest:
            return draft, gm
    raise ValueError(f"tolerances: budget must be >= {TOLERANCES[-1][0]}, got {budget!r}")


# --- an independent hydrostatics of the mesh, in numpy (float64) ---------------------------------

def _heel_matrix(heel: float) -> np.ndarray:
    """Rotation [-] about the body x axis by ``heel`` [rad] (positive: port side up)."""
    c, s = math.cos(heel), math.sin(heel)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _cut(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(T, 3) points where the edges a-b cross z = 0."""
    t = a[:, 2] / (a[:, 2] - b[:, 2])
    return a + t[:, None] * (b - a)


def submerged_triangles(corners: np.ndarray) -> np.ndarray:
    """(S, 3, 3) the parts below z = 0 of triangles ``corners`` (T, 3, 3) [m], world frame, each split into
    triangles with the orientation of the one it came from."""
    wet = corners[:, :, 2] < 0.0
    count = wet.sum(axis=1)
    pieces = [corners[count == 3]]
    for wet_count in (1, 2):
        chosen = corners[count == wet_count]
        odd = wet[count == wet_count] if wet_count == 1 else ~wet[count == wet_count]
        # Roll each triangle's corners (keeping their cyclic order) so that the odd one out comes first.
        first = np.argmax(odd, axis=1)
        order = (first[:, None] + np.arange(3)) % 3
        a, b, c = (np.take_along_axis(chosen, order[:, k, None, None], axis=1)[:, 0] for k in range(3))
        if wet_count == 1:
            pieces.append(np.stack([a, _cut(a, b), _cut(a, c)], axis=1))
        else:
            ab, ca = _cut(a, b), _cut(c, a)
            pieces += [np.stack([ab, b, c], axis=1), np.stack([ab, c, ca], axis=1)]
    return np.concatenate(pieces)


def displacement(vertices: np.ndarray, triangles: np.ndarray, height: float, turn: np.ndarray | None = None):
    """Volume [m^3] and centre of buoyancy (3,) [m, world frame] of the closed mesh (body frame, outward
    triangles) turned by the rotation matrix ``turn`` (default upright) with its origin ``height`` [m]
    above still water.

    Divergence theorem over the submerged part: V = sum of z n_z dA, and the first moments of x, y, z are
    sums of x z n_z, y z n_z, z^2/2 n_z dA; the waterplane cap adds nothing to either (z = 0 on it). The
    integrands are linear and quadratic on each triangle: the centroid rule and the edge-midpoint rule
    are exact for them."""
    world = vertices @ (np.eye(3) if turn is None else turn).T + np.array([0.0, 0.0, height])
    pieces = submerged_triangles(world[triangles])
    if len(pieces) == 0:
        return 0.0, np.zeros(3)
    area_z = 0.5 * np.cross(pieces[:, 1] - pieces[:, 0], pieces[:, 2] - pieces[:, 0])[:, 2]
    volume = float(np.sum(area_z * pieces[:, :, 2].mean(axis=1)))
    middles = 0.5 * (pieces + np.roll(pieces, -1, axis=1))  # (S, 3 edges, 3)
    z = middles[:, :, 2]
    moments = np.stack([middles[:, :, 0] * z, middles[:, :, 1] * z, 0.5 * z * z], axis=2).mean(axis=1)
    return volume, (area_z[:, None] * moments).sum(axis=0) / volume


def equilibrium_height(vertices, triangles, volume: float, turn: np.ndarray | None = None) -> float:
    """Height [m] of the origin above still water at which the mesh turned by the rotation matrix ``turn``
    (default upright) displaces ``volume`` [m^3] (bisection)."""
    low, high = -1.0, 1.0
    for _ in range(50):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if displacement(vertices, triangles, middle, turn)[0] > volume else (low, middle)
    return 0.5 * (low + high)


def numpy_hydrostatics(eboat: EBoat, water_density: float) -> tuple[float, float]:
    """(rest height [m], GM [m]) of ``eboat``'s hull and mass from the numpy hydrostatics above: the upright
    waterline carrying its weight, and GZ / sin(HEEL) with the waterline re-found at HEEL. The appendages the
    mesh leaves out (the real boat's keel, bulb and rudder: ``eboat.geometry.appendage_volume``) stay under
    water and carry their share at their centroid."""
    vertices, triangles = np.asarray(eboat.hull.vertices, np.float64), np.asarray(eboat.hull.triangles)
    appendages = eboat.geometry.appendage_volume
    volume = eboat.boat_type.mass / water_density - appendages
    height = equilibrium_height(vertices, triangles, volume)
    heeled = equilibrium_height(vertices, triangles, volume, _heel_matrix(HEEL))
    _, buoyancy_centre = displacement(vertices, triangles, heeled, _heel_matrix(HEEL))
    appendage_centre = _heel_matrix(HEEL) @ np.asarray(eboat.geometry.appendage_center, np.float64)
    buoyancy_centre = (volume * buoyancy_centre + appendages * appendage_centre) / (volume + appendages)
    gravity_centre = _heel_matrix(HEEL) @ np.asarray(eboat.boat_type.center_of_mass, np.float64)
    return height, float((gravity_centre[1] - buoyancy_centre[1]) / math.sin(HEEL))


# --- the simulator's measurements ----------------------------------------------------------------

def _held(eboat: EBoat, positions, orientations, velocities, *, drag: bool) -> np.ndarray:
    """(N, 6) the hull pass's wrench [N, N m about the origin, body frame] on boats held at these poses and
    Fossen velocities in still water, with or without the water model's drag."""
    water = eboat.hydrodynamics if drag else eboat.hydrodynamics.without_drag()
    fleet = ow.Fleet(eboat.boat_type, len(positions), device="cpu")
    ocean = ow.Ocean(ow.OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.0), device="cpu")
    simulator = ow.Simulator(ocean, fleet, ow.SimulatorConfig(hydrodynamics=water))
    fleet.reset(position=positions, orientation=orientations, velocity=velocities)
    simulator.compute_hull_wrenches()
    return fleet.forces.hydro_wrench.numpy().astype(np.float64)


def simulator_gm(eboat: EBoat, rest_height: float) -> float:
    """GM [m] from the hull pass: the righting moment about the centre of mass at +-HEEL about the rest
    waterline's centre line, GM = -(M_x(+) - M_x(-)) / (2 |F| sin HEEL)."""
    pivot = np.array([0.0, 0.0, -rest_height])  # body point on the still-water surface at rest
    heels = np.array([HEEL, -HEEL])
    orientations = quaternion_from_roll_pitch_yaw(np.column_stack([heels, np.zeros(2), np.zeros(2)]))
    positions = np.array([-_heel_matrix(h) @ pivot for h in heels])
    wrench = _held(eboat, positions, orientations, np.zeros((2, 6)), drag=False)
    # The appendages the mesh leaves out (the real boat's), under water: rho g V up at their centroid.
    water = ow.WaterConfig()
    lift = water.density * water.gravity * eboat.geometry.appendage_volume
    wrench[:, :3] += np.array([lift * _heel_matrix(h).T @ np.array([0.0, 0.0, 1.0]) for h in heels])
    wrench[:, 3:] += np.cross(np.asarray(eboat.geometry.appendage_center),
                              [lift * _heel_matrix(h).T @ np.array([0.0, 0.0, 1.0]) for h in heels])
    about_centre = wrench[:, 3:] - np.cross(np.asarray(eboat.boat_type.center_of_mass), wrench[:, :3])
    force = np.linalg.norm(wrench[:, :3], axis=1).mean()
    return float(-(about_centre[0, 0] - about_centre[1, 0]) / (2.0 * force * math.sin(HEEL)))


def resistance(eboat: EBoat, rest_height: float, speed: float = 1.0) -> float:
    """The hull's resistance [N] at ``speed`` [m/s]: minus the hull pass's surge force on the boat held
    upright at its rest height, moving ahead at ``speed`` in still water."""
    wrench = _held(eboat, [[0.0, 0.0, rest_height]], [[0.0, 0.0, 0.0, 1.0]], [[speed, 0, 0, 0, 0, 0]], drag=True)
    return float(-wrench[0, 0])


def mean_period(times: np.ndarray, signal: np.ndarray, crossings: int = 6) -> float:
    """Period [s] of a decaying oscillation ``signal`` sampled at ``times`` [s]: twice the mean spacing of
    its first ``crossings`` zero crossings (linearly interpolated); NaN if it crosses fewer than 3 times."""
    sign_change = np.nonzero(np.signbit(signal[:-1]) != np.signbit(signal[1:]))[0][:crossings]
    if len(sign_change) < 3:
        return math.nan
    t0, t1, s0, s1 = times[sign_change], times[sign_change + 1], signal[sign_change], signal[sign_change + 1]
    at = t0 - s0 * (t1 - t0) / (s1 - s0)
    return float(2.0 * np.mean(np.diff(at)))


def decay_periods(config: EBoatConfig, rest_height: float, seconds: float = 20.0) -> tuple[float, float]:
    """(heave, roll) natural periods [s]: two boats in still water and calm air, one let go 3 cm above its
    rest height, one upright at rest height heeled 4 deg; each motion is measured about its mean over the
    last quarter of ``seconds``."""
    sim = EBoatSimulator(EBoatSimulatorConfig(boat=config, wind=ow.WindConfig(speed=0.0)), 2, device="cpu")
    start = np.array([[0.0, 0.0, rest_height + 0.03], [20.0, 0.0, rest_height]])
    sim.reset(position=start)
    heeled = quaternion_from_roll_pitch_yaw([[math.radians(4.0), 0.0, 0.0]])
    sim.fleet.reset([1], position=start[1:], orientation=heeled)
    steps = int(round(seconds / sim.config.dt))
    heave, roll = np.empty(steps), np.empty(steps)
    for step in range(steps):
        sim.step()
        state = sim.fleet.numpy()
        heave[step] = state["position"][0, 2]
        roll[step] = roll_pitch_yaw(state["orientation"][1])[0, 0]
    times = sim.config.dt * np.arange(1, steps + 1)
    settled = slice(3 * steps // 4, None)
    return (mean_period(times, heave - heave[settled].mean()), mean_period(times, roll - roll[settled].mean()))


def polar_speeds(config: EBoatConfig) -> np.ndarray:
    """(A,) best steady speed [m/s] at POLAR_ANGLES_DEG in 7 m/s of true wind (NaN: could not hold it)."""
    result = speed_polar(wind_speeds=[7.0], wind_angles_deg=POLAR_ANGLES_DEG, sheets_deg=POLAR_SHEETS_DEG,
                         settle_time=40.0, average_time=15.0, boat=config, device="cpu")
    return result.speed[0]


@dataclasses.dataclass
class Fidelity:
    """What one hull measured; lengths [m], periods [s], force [N], speeds [m/s]."""

    label: str
    triangles: int
    rest_height: float
    draft: float
    numpy_rest_height: float
    gm: float
    numpy_gm: float
    heave_period: float
    roll_period: float
    resistance: float
    polar: np.ndarray | None


def measure(budget: int | None, with_polar: bool) -> Fidelity:
    """Measure the hull of ``budget`` triangles (None: the full hull)."""
    config = EBoatConfig(hull_triangles=budget)
    eboat = EBoat(config)
    height = eboat.rest_height()
    numpy_height, numpy_gm = numpy_hydrostatics(eboat, ow.WaterConfig().density)
    heave, roll = decay_periods(config, height)
    label = "full" if budget is None else str(budget)
    return Fidelity(label, eboat.hull.triangle_count, height, -(height + eboat.hull.vertices[:, 2].min()),
                    numpy_height, simulator_gm(eboat, height), numpy_gm, heave, roll, resistance(eboat, height),
                    polar_speeds(config) if with_polar else None)


# --- the table -----------------------------------------------------------------------------------

def _cell(value: float, full: float, digits: int, absolute: bool = False) -> str:
    """``value`` and its relative error against ``full`` [%] (``absolute``: its difference [mm])."""
    if not math.isfinite(value):
        return "n/a"
    if not math.isfinite(full) or full == 0.0:
        return f"{value:.{digits}f}"
    if absolute:
        return f"{value:.{digits}f} ({1e3 * (value - full):+.1f} mm)"
    return f"{value:.{digits}f} ({100.0 * (value - full) / abs(full):+.1f} %)"


def table(rows: list[Fidelity], full: Fidelity) -> str:
    """The markdown table: each hull's values, with the relative error against the full hull."""
    absolute = {"rest_height", "numpy_rest_height"}  # near zero: relative errors would mislead
    columns = [("rest height [m]", "rest_height", 4), ("numpy rest height [m]", "numpy_rest_height", 4),
               ("draft [m]", "draft", 4), ("GM [m]", "gm", 4), ("numpy GM [m]", "numpy_gm", 4),
               ("heave T [s]", "heave_period", 3), ("roll T [s]", "roll_period", 3),
               ("R(1 m/s) [N]", "resistance", 2)]
    header = ["hull", "triangles"] + [name for name, _, _ in columns]
    if full.polar is not None:
        header += [f"V {angle:.0f} deg [m/s]" for angle in POLAR_ANGLES_DEG]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for row in rows:
        cells = [row.label, str(row.triangles)]
        cells += [_cell(getattr(row, key), getattr(full, key), digits, key in absolute) if row is not full
                  else f"{getattr(row, key):.{digits}f}" for _, key, digits in columns]
        if full.polar is not None and row.polar is not None:
            cells += [_cell(v, f, 3) if row is not full else f"{v:.3f}" for v, f in zip(row.polar, full.polar)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def report(rows: list[Fidelity], full: Fidelity, seconds: float) -> str:
    """The whole markdown report: what was measured, the table, the tests' tolerances."""
    polar = (f"polar: 7 m/s true wind, best of sheets {', '.join(f'{s:.0f}' for s in POLAR_SHEETS_DEG)} deg, "
             "40 s settling + 15 s average" if full.polar is not None else "no polar (--no-polar)")
    return "\n".join([
        f"# E-Boat hull fidelity per triangle budget (CPU, {datetime.date.today()}, {seconds:.0f} s)", "",
        "Values, and in brackets the relative error against the full hull (2 024 triangles; for the rest heights,",
        "near zero, the difference in mm). Rest height: of the base frame above still water, upright (bisection on",
        "the hull pass); draft: keel below water; numpy: an independent numpy computation of the mesh (divergence",
        f"theorem on the clipped submerged part). GM at {math.degrees(HEEL):.0f} deg of heel; periods from free decay",
        "(3 cm heave, 4 deg heel); R: the hull pass at 1 m/s, upright at rest height; " + polar + ".", "",
        table(rows, full), "",
        "Tolerances held by tests/ocean_warp/test_coarse_hulls.py (relative error against the full hull, both from the numpy "
        "hydrostatics): " + "; ".join(f"budget >= {smallest}: rest draft {100 * draft:.1f} %, GM {100 * gm:.1f} %"
                                        for smallest, draft, gm in TOLERANCES) + ".", ""])


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--budgets", type=int, nargs="+", default=[256, 512, 1024, 2048],
                        help="triangle budgets to compare with the full hull")
    parser.add_argument("--no-polar", action="store_true", help="skip the speed polar (the costly part)")
    parser.add_argument("--out", help="also write the markdown report here (atomically)")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    wp.config.quiet = True
    started = datetime.datetime.now()
    full = measure(None, not args.no_polar)
    rows = [measure(budget, not args.no_polar) for budget in args.budgets] + [full]
    text = report(rows, full, (datetime.datetime.now() - started).total_seconds())
    print(text)
    if args.out:
        with atomic_output(args.out) as temporary, open(temporary, "w") as handle:
            handle.write(text)


if __name__ == "__main__":
    main()
