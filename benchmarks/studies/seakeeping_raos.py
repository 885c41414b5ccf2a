"""The E-Boat's hull in regular waves against potential flow: response amplitude operators beside capytaine's.

    pip install -e ".[bem]" && python -m benchmarks.studies.seakeeping_raos --device cpu

For each wave period (default 0.8-6 s) and heading (head seas: heave and pitch; beam seas: roll) the bare
hull of the E-Boat (its mass properties, no rig: the BEM solver knows no keel or sail either) floats at rest
in a regular Airy wave of steepness H / lambda = ``--steepness``, built with the simulator's physics profile
(per-triangle pressure decaying with depth, the radiation memory and diffraction load of the shipped
hydrodynamic database, the viscous cross-flow drag). After ``--settle`` wave periods the motions are fitted
with a sinusoid at the wave's frequency over ``--periods`` more; the RAO is the amplitude over the wave
amplitude a (heave [m/m]) or over the wave slope k a (pitch, roll [rad/rad]). A soft yaw restraint holds the
heading (``YAW_STIFFNESS``), as a basin's soft mooring does: the waves' mean yaw moment on a hull whose ends
differ would turn it, which linear theory (and the reference) leaves out.

The reference is capytaine's linear RAO of the same hull mesh at the same rest pose with the same mass
matrix and the hydrostatic stiffness of that mesh (``ocean_warp.seakeeping.bem``), solved here at each period. A second
steepness (``--check-steepness``) shows whether the simulated RAOs depend on the wave amplitude. Natural
periods come from free decays in still water (heave and pitch from 2 cm / 2 deg, roll from 10 deg).
Written atomically: ``benchmarks/data/seakeeping_raos.csv`` and ``benchmarks/figures/seakeeping_raos.png``.
"""

from __future__ import annotations

import argparse
import csv
import math
import os

import numpy as np

import ocean_warp as ow
from ocean_warp.atomic_files import atomic_output
from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.frames import quaternion_from_roll_pitch_yaw, roll_pitch_yaw
from ocean_warp.wind import WindConfig
from benchmarks import DATA, FIGURES

GRAVITY = 9.81
HEADINGS = {"head": math.pi, "beam": -math.pi / 2}
"""Wave directions of travel [rad] for a boat heading +x: head seas come from ahead, beam seas from port."""
MOTIONS = {"head": ("heave", "pitch"), "beam": ("roll",)}


def deep_water_wavelength(period: float) -> float:
    return GRAVITY * period**2 / (2.0 * math.pi)


def regular_sea(period: float, amplitude: float, direction: float) -> ow.OceanConfig:
    """A regular wave that fits its tile exactly along x or y, with at least 16 grid cells per wavelength."""
    wavelength = deep_water_wavelength(period)
    tile = wavelength * max(1, math.ceil(8.0 / wavelength))
    resolution = 64
    while resolution < 256 and tile / resolution > wavelength / 16.0:
        resolution *= 2
    return ow.OceanConfig(spectrum="regular", tile_size=tile, resolution=resolution, amplitude=amplitude,
                          period=period, direction=direction)


def _simulator(ocean_config: ow.OceanConfig, device, *, foils: bool = False, attitude=(0.0, 0.0, 0.0),
               heave: float = 0.0, dt: float = 0.01) -> EBoatSimulator:
    """One E-Boat at rest in ``ocean_config``'s sea, no wind: its hull, appendage buoyancy and radiation, with the
    keel's and rudder's forces (``foils``) or without them (the BEM reference knows no lifting surfaces)."""
    sim = EBoatSimulator(EBoatSimulatorConfig(boat=EBoatConfig(seakeeping=True), ocean=ocean_config,
                                              wind=WindConfig(speed=0.0), dt=dt), 1, device=device)
    rest = sim.eboat.rest_height(device=device)
    sim.reset(position=[0.0, 0.0, rest + heave], wind_speed=0.0, foil_scale=[0.0, float(foils), float(foils)])
    if any(attitude):
        state = sim.fleet.numpy()
        sim.fleet.reset(position=state["position"],
                        orientation=quaternion_from_roll_pitch_yaw(np.array([attitude], dtype=float)))
    sim.rest_height = rest
    return sim


def _motions(sim: EBoatSimulator) -> tuple[float, float, float]:
    state = sim.fleet.numpy()
    roll, pitch, _ = roll_pitch_yaw(state["orientation"][:1])[0]
    return float(state["position"][0, 2] - sim.rest_height), float(roll), float(pitch)


YAW_STIFFNESS = 1000.0
"""[N m/rad] of the soft restraint that holds the heading in waves (as a model basin's soft mooring does): a
free hull whose ends differ turns slowly under the waves' mean yaw moment, which linear theory leaves out."""
YAW_DAMPING = 400.0
"""[N m s/rad]."""
DRIFT_STIFFNESS = 20.0
"""[N/m] of the soft horizontal mooring that keeps the hull on its spot (a natural period near 20 s, far from the
waves'): the waves' mean drift force would otherwise carry it downwave, and the frequency it meets the waves at
would then differ from theirs."""
DRIFT_DAMPING = 100.0
"""[N s/m]."""


def _hold_heading(sim: EBoatSimulator) -> None:
    """Set the soft mooring's force and moment (world frame) for the coming step: it holds the heading and the
    spot, not the motions at the waves' frequency."""
    state = sim.fleet.numpy()
    yaw = roll_pitch_yaw(state["orientation"][:1])[0][2]
    rate = state["velocity"][0, 5]
    x, y, z, w = (float(c) for c in state["orientation"][0])
    body_to_world = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                              [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                              [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    horizontal = (body_to_world @ state["velocity"][0, :3])[:2]
    wrench = np.zeros((1, 6), dtype=np.float32)
    wrench[0, :2] = -DRIFT_STIFFNESS * state["position"][0, :2] - DRIFT_DAMPING * horizontal
    wrench[0, 5] = -YAW_STIFFNESS * yaw - YAW_DAMPING * rate
    sim.fleet.control.wrench_world.assign(wrench)


def simulated_response(period, heading, steepness, settle, periods, device):
    """{motion: complex amplitude} of heave [m], roll and pitch [rad] at the wave's frequency, over the wave
    amplitude (heave) or slope (roll, pitch)."""
    amplitude = steepness * deep_water_wavelength(period) / 2.0
    sim = _simulator(regular_sea(period, amplitude, HEADINGS[heading]), device)
    wave = sim.ocean.regular_wave
    omega, k = wave.omega, wave.wavenumber
    dt = sim.config.dt
    settle_steps = int(round(settle * period / dt))
    measure_steps = int(round(periods * period / dt))
    times, motions = [], []
    for step in range(settle_steps + measure_steps):
        _hold_heading(sim)
        sim.step()
        if step >= settle_steps:
            times.append((step + 1) * dt)
            motions.append(_motions(sim))
    times, motions = np.array(times), np.array(motions, dtype=np.float64)
    basis = np.column_stack([np.ones_like(times), np.cos(omega * times), np.sin(omega * times)])
    coefficients, *_ = np.linalg.lstsq(basis, motions, rcond=None)
    complex_amplitude = coefficients[1] - 1j * coefficients[2]
    scale = {"heave": amplitude, "roll": k * amplitude, "pitch": k * amplitude}
    index = {"heave": 0, "roll": 1, "pitch": 2}
    upright = bool(np.all(sim.fleet.numpy()["status"] == 0))
    return {m: complex_amplitude[index[m]] / scale[m] if upright else complex(math.nan) for m in MOTIONS[heading]}


def free_decay(motion: str, device, *, foils: bool, duration: float = 12.0) -> tuple[float, np.ndarray]:
    """(period [s] of the first zero crossings, the decaying signal) of a free decay in still water."""
    calm = ow.OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.0)
    start = {"heave": dict(heave=0.02), "pitch": dict(attitude=(0.0, math.radians(2.0), 0.0)),
             "roll": dict(attitude=(math.radians(10.0), 0.0, 0.0))}[motion]
    sim = _simulator(calm, device, foils=foils, **start)
    dt = sim.config.dt
    signal = []
    for _ in range(int(round(duration / dt))):
        sim.step()
        signal.append(_motions(sim)[{"heave": 0, "roll": 1, "pitch": 2}[motion]])
    signal = np.array(signal)
    centred = signal - np.mean(signal[-int(2.0 / dt):])
    crossings = np.flatnonzero(np.sign(centred[1:]) != np.sign(centred[:-1]))
    times = [(i + centred[i] / (centred[i] - centred[i + 1])) * dt for i in crossings]
    period = float(2.0 * np.mean(np.diff(times[:6]))) if len(times) >= 3 else math.nan
    return period, signal


def capytaine_reference(periods) -> tuple[dict, dict]:
    """({heading: {motion: |RAO| at each period}}, {motion: natural period [s]}) of the shipped database's
    hull with the E-Boat's mass matrix and its hull's and appendages' hydrostatic stiffness (linear potential
    flow). capytaine solves the radiation and diffraction problems at each period itself: interpolating the
    database's 50 frequencies instead misses the RAOs by up to 19 % below 1.25 s (pitch at 1.0 s) and by 57 % at
    roll's resonance."""
    import capytaine as cpt

    from ocean_warp.eboat import EBoat
    from ocean_warp.seakeeping import bem
    from ocean_warp.seakeeping.response import hydrostatic_stiffness, natural_period, rigid_body_mass_matrix

    eboat = EBoat(EBoatConfig(seakeeping=True))
    database, mp, geometry = eboat.seakeeping, eboat.mass_properties, eboat.geometry
    mass_matrix = rigid_body_mass_matrix(mp.mass, mp.center_of_mass, mp.inertia)
    stiffness = hydrostatic_stiffness(eboat.hull, database.rest_height, mp.mass, mp.center_of_mass,
                                      appendage_volume=geometry.appendage_volume,
                                      appendage_center=geometry.appendage_center)
    headings = {"head": 180.0, "beam": math.degrees(HEADINGS["beam"]) % 360.0}
    raos = {heading: {motion: [] for motion in MOTIONS[heading]} for heading in HEADINGS}
    with bem._quiet_capytaine():
        body = bem._immersed_body(cpt, eboat.hull, database.rest_height, True, float(database.frequencies.max()),
                                  database.gravity)
        solver = cpt.BEMSolver()
        for period in periods:
            omega = 2.0 * math.pi / period
            added, damping = bem._radiation_matrices(cpt, solver, body, omega, database.water_density,
                                                     database.gravity)
            forces = bem._excitation(cpt, solver, body, omega, np.radians(list(headings.values())),
                                     database.water_density, database.gravity)
            impedance = -omega**2 * (mass_matrix + added) + 1j * omega * damping + stiffness
            for index, heading in enumerate(headings):
                response = np.linalg.solve(impedance, forces[index])  # per metre of wave amplitude
                for motion in MOTIONS[heading]:
                    dof = {"heave": 2, "roll": 3, "pitch": 4}[motion]
                    slope = 1.0 if motion == "heave" else omega**2 / GRAVITY  # per wave slope k a
                    raos[heading][motion].append(abs(response[dof]) / slope)
    naturals = {m: natural_period(database, mass_matrix[d, d], stiffness[d, d], d)
                for m, d in (("heave", 2), ("roll", 3), ("pitch", 4))}
    return {h: {m: np.array(v) for m, v in r.items()} for h, r in raos.items()}, naturals


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--periods-s", type=float, nargs="+",
                        default=[0.8, 0.9, 1.0, 1.1, 1.25, 1.4, 1.6, 1.8, 2.0, 2.25, 2.5, 3.0, 4.0, 5.0, 6.0])
    parser.add_argument("--steepness", type=float, default=1.0 / 60.0, help="H / lambda")
    parser.add_argument("--check-steepness", type=float, default=1.0 / 120.0, help="a second steepness; 0: none")
    parser.add_argument("--settle", type=float, default=15.0, help="wave periods before the fit (at least 10 s)")
    parser.add_argument("--periods", type=float, default=10.0, help="wave periods fitted")
    parser.add_argument("--no-decays", action="store_true", help="skip the free decays (natural periods)")
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--out", default=os.path.join(DATA, "seakeeping_raos.csv"))
    parser.add_argument("--figure", default=os.path.join(FIGURES, "seakeeping_raos.png"))
    args = parser.parse_args(argv)

    reference, reference_periods = capytaine_reference(args.periods_s)
    rows = []
    for index, period in enumerate(args.periods_s):
        for heading in HEADINGS:
            settle = max(args.settle, 10.0 / period)
            response = simulated_response(period, heading, args.steepness, settle, args.periods, args.device)
            check = {}
            if args.check_steepness > 0:
                check = simulated_response(period, heading, args.check_steepness, settle, args.periods, args.device)
            for motion, value in response.items():
                expected = float(reference[heading][motion][index])
                row = {"period_s": period, "heading": heading, "motion": motion, "simulated": abs(value),
                       "capytaine": expected, "ratio": abs(value) / expected,
                       "simulated_check_steepness": abs(check.get(motion, math.nan))}
                rows.append(row)
                print(", ".join(f"{k} {v:.4g}" if isinstance(v, float) else f"{k} {v}" for k, v in row.items()),
                      flush=True)
    for motion in () if args.no_decays else ("heave", "pitch", "roll"):
        period, _ = free_decay(motion, args.device, foils=False)
        print(f"natural period of {motion}: free decay {period:.3f} s, capytaine {reference_periods[motion]:.3f} s")
    if not args.no_decays:
        period, roll = free_decay("roll", args.device, foils=True, duration=20.0)
        peaks = np.degrees(np.abs(roll))
        print(f"roll decay from 10 deg with keel and rudder: period {period:.3f} s, |roll| after 2/5/10 s "
              f"{peaks[199]:.2f}/{peaks[499]:.2f}/{peaks[999]:.2f} deg")
    with atomic_output(args.out) as temporary, open(temporary, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows({k: (f"{v:.5g}" if isinstance(v, float) else v) for k, v in row.items()} for row in rows)
    _figure(rows, args.figure)
    print(f"wrote {args.out} and {args.figure}")


def _figure(rows, path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    for axis, motion in zip(axes, ("heave", "pitch", "roll")):
        chosen = [r for r in rows if r["motion"] == motion]
        periods = [r["period_s"] for r in chosen]
        axis.plot(periods, [r["capytaine"] for r in chosen], "k-", label="capytaine (potential flow)")
        axis.plot(periods, [r["simulated"] for r in chosen], "o-", label="ocean_warp")
        if any(math.isfinite(r["simulated_check_steepness"]) for r in chosen):
            axis.plot(periods, [r["simulated_check_steepness"] for r in chosen], "x--", label="ocean_warp, half steepness")
        axis.set_title(f"{motion} ({'head' if motion != 'roll' else 'beam'} seas)")
        axis.set_xlabel("wave period [s]")
        axis.set_ylabel("RAO [m/m]" if motion == "heave" else "RAO [rad/rad]")
        axis.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    with atomic_output(path) as temporary:
        fig.savefig(temporary, dpi=110, format="png")
    plt.close(fig)


if __name__ == "__main__":
    main()
