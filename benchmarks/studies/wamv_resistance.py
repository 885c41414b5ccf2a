"""The WAM-V physics profile's resistance ahead, before and after its pontoons' wave-making resistance, beside
VRX's lumped fit.

    python -m benchmarks.studies.wamv_resistance                 # CPU, about 10 s

1. Steady speeds: WAM-Vs of the physics profile (default config: seakeeping database, fixed thrusters) in still
   water and calm air, both thrusters at one command each, run ``--seconds`` and averaged over the last
   ``--average``; once without wave resistance (``WamvConfig(wave_resistance=False)``, the profile as it was)
   and once with it (the default). At a steady speed the thrust (VRX's curve) is the resistance, so the runs
   give the simulator's R(U) points too.
2. The resistance curve R(U) ahead, in parts: friction as the physics profile applies it to the hull at rest
   (ITTC-1957 C_F at Re = U L / nu times (1 + k), on the mesh's wetted area at rest: the hull pass applies it per
   wetted triangle, so this is its upright, level value), the pair's wave resistance (Michell's integral at
   each speed; the table the hull kernel interpolates is written beside, r at Fn 0, 0.05, ..., 0.75), and
   VRX's fit Xu u + Xuu u |u| (``figures.VRX_LINEAR_DAMPING``, ``VRX_QUADRATIC_DAMPING``).

Writes ``<data>/wamv/wamv_resistance.json`` in one rename (``ocean_warp.atomic_files``) and prints both tables.
"""

from __future__ import annotations

import argparse
import json
import math

import numpy as np

from ocean_warp.atomic_files import atomic_output
from ocean_warp.hull_form import floating_waterline, measure_hull_form
from ocean_warp.resistance import FROUDE_SAMPLES, FROUDE_STEP, ittc_1957
from ocean_warp.sensors import SensorConfig
from ocean_warp.thin_ship import michell_resistance
from ocean_warp.wamv import WamvConfig, WamvSimulator, WamvSimulatorConfig, figures, wamv_hull_mesh
from ocean_warp.wamv import wamv_hydrodynamics
from ocean_warp.wamv.wave_resistance import pontoon_offsets, wamv_wave_resistance
from ocean_warp.water_config import WaterConfig
from benchmarks import DATA

COMMANDS = (0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)
"""Both thrusters' command in each run; 0.4 and 1.0 are the ones reported."""
SPEEDS = np.round(np.arange(0.25, 8.01, 0.25), 2)
"""Speeds [m/s] of the resistance curve."""


def steady_speeds(config: WamvConfig, commands, seconds: float, average: float, device: str):
    """(speeds [m/s], thrusts [N]) of one boat per command after ``seconds``, the speed averaged over the last
    ``average`` seconds."""
    sim = WamvSimulator(WamvSimulatorConfig(boat=config, sensors=SensorConfig.noise_free()), len(commands),
                        device=device)
    sim.reset(position=(0.0, 0.0, sim.rest_height()))
    sim.control.thrust_command.assign(np.repeat(np.asarray(commands, dtype=np.float32)[:, None], 2, axis=1))
    steps, tail = int(round(seconds / sim.config.dt)), int(round(average / sim.config.dt))
    speeds = []
    for step in range(steps):
        sim.step()
        if step >= steps - tail:
            speeds.append(sim.fleet.numpy()["velocity"][:, 0])
    return np.mean(speeds, axis=0), sim.state.thrust.numpy().sum(axis=1)


def resistance_curve(water: WaterConfig) -> dict:
    """R(U) [N] ahead in parts at ``SPEEDS``: friction, Michell's wave resistance, their sum, VRX's fit; and the
    table r(Fn) the hull kernel reads."""
    config = WamvConfig()
    hull = wamv_hull_mesh(config)
    form = measure_hull_form(hull, floating_waterline(hull, config.mass, water.density))
    form_factor = wamv_hydrodynamics(config).form_factor
    reynolds = SPEEDS * config.pontoon_length / water.kinematic_viscosity
    friction = 0.5 * water.density * SPEEDS**2 * form.wetted_area * (1.0 + form_factor) * ittc_1957(reynolds)
    wave = michell_resistance(pontoon_offsets(config), SPEEDS, separation=config.pontoon_spacing,
                              density=water.density, gravity=water.gravity)
    table = wamv_wave_resistance(config)
    froude = SPEEDS / math.sqrt(water.gravity * table.waterline_length)
    x_u, x_uu = figures.VRX_LINEAR_DAMPING[0], figures.VRX_QUADRATIC_DAMPING[0]
    return {"speed": SPEEDS.tolist(), "froude": froude.tolist(), "friction": friction.tolist(),
            "wave_michell": wave.tolist(), "physics_total": (friction + wave).tolist(),
            "vrx": (x_u * SPEEDS + x_uu * SPEEDS**2).tolist(),
            "wetted_area": form.wetted_area, "form_factor": form_factor, "displaced_volume": form.displaced_volume,
            "table_froude": (FROUDE_STEP * np.arange(FROUDE_SAMPLES)).tolist(),
            "table_upright": list(table.upright)}


def vrx_steady_speed(thrust: float) -> float:
    """Speed [m/s] at which VRX's Xu u + Xuu u^2 takes ``thrust`` [N]."""
    x_u, x_uu = figures.VRX_LINEAR_DAMPING[0], figures.VRX_QUADRATIC_DAMPING[0]
    return (-x_u + math.sqrt(x_u**2 + 4.0 * x_uu * thrust)) / (2.0 * x_uu)


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="simulated seconds per run")
    parser.add_argument("--average", type=float, default=10.0, help="seconds averaged at the end")
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--out", default=str(DATA / "wamv" / "wamv_resistance.json"))
    args = parser.parse_args(argv)
    water = WaterConfig()
    runs = {}
    for label, wave_resistance in (("before", False), ("after", True)):
        speeds, thrusts = steady_speeds(WamvConfig(wave_resistance=wave_resistance), COMMANDS, args.seconds,
                                        args.average, args.device)
        runs[label] = {"speed": speeds.tolist(), "thrust": thrusts.tolist()}
    thrusts = np.asarray(runs["after"]["thrust"])
    result = {
        "what": "WAM-V physics profile: steady speed [m/s] under both thrusters at each command (thrust [N], "
                "VRX's curve) without ('before') and with ('after') the pontoons' Michell wave resistance, VRX's "
                "lumped fit's speed at the same thrust, and the resistance curve R(U) [N] in parts",
        "device": args.device, "seconds": args.seconds, "average": args.average, "commands": list(COMMANDS),
        "steady": dict(runs, vrx={"speed": [vrx_steady_speed(t) for t in thrusts]}),
        "curve": resistance_curve(water),
    }
    with atomic_output(args.out) as temporary, open(temporary, "w") as handle:
        json.dump(result, handle, indent=1)
    before, after, vrx = runs["before"]["speed"], runs["after"]["speed"], result["steady"]["vrx"]["speed"]
    print(f"{'command':>8} {'thrust N':>9} {'before m/s':>11} {'after m/s':>10} {'VRX m/s':>8}")
    for i, command in enumerate(COMMANDS):
        print(f"{command:8.1f} {thrusts[i]:9.1f} {before[i]:11.3f} {after[i]:10.3f} {vrx[i]:8.3f}")
    curve = result["curve"]
    print(f"\n{'U m/s':>6} {'Fn':>5} {'friction N':>10} {'wave N':>7} {'total N':>8} {'VRX N':>7}")
    for i in range(0, len(SPEEDS), 2):
        print(f"{SPEEDS[i]:6.2f} {curve['froude'][i]:5.2f} {curve['friction'][i]:10.1f} "
              f"{curve['wave_michell'][i]:7.1f} {curve['physics_total'][i]:8.1f} {curve['vrx'][i]:7.1f}")
    print(f"\nwrote {args.out}")
    return result


if __name__ == "__main__":
    main()
