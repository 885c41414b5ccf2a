"""A knockdown in strong wind and what turns the boat: the yaw-moment budget of one trace.

    python -m benchmarks.studies.knockdown --wind-speed 10 --device cpu

The E-Boat starts close-hauled on starboard (true wind angle ``--twa``) at ``--speed`` with the sheet hauled in
(``--sheet``) in flat water and a steady wind; the rudder stays centred and the propeller off, so nothing
steers it: the sail heels it hard and the boat rounds up as the forces on it say. Every step the yaw moment
about the body z axis is split into its sources (body frame, about the origin, [N m]):

  sail, keel, rudder, windage   the rig's parts (the rig's force model run again on a copy of the boat's
                                 state with all but that part's coefficients zeroed)
  hull                          the hull pass: pressure, cross-flow drag, friction, residuary resistance
  munk                          -(C_A(nu_r) nu_r)_z, the added-mass Coriolis (Munk) moment; for a hull with a
                                 database the added-mass velocity terms of the heading frame
                                 (``kernels.seakeeping_frame``)
  radiation                     -mu_z, the radiation memory (0 for a hull without a database)
  rigid_body                    -(c_RB(nu))_z, the rigid body's own velocity terms
and the yaw acceleration those imply about z alone (the mass matrix's couplings left out), beside the one
the trace shows. A heeled boat turns about the vertical, and the mass matrix couples forces into turning, so
each source's whole wrench (with gravity, the appendages' buoyancy and the diagonal damping beside them) is
also taken through the mass matrix, M^-1 tau, to the world-vertical angular acceleration it gives
(``<source>_yaw_accel`` [deg/s^2]); these sum to the observed one but for the integrator's implicit terms.
Reported: the largest yaw rate and heel, and the budgets at the moment of the largest yaw acceleration toward
the wind and averaged over the round-up (the first ``--window`` seconds). Written atomically:
``benchmarks/data/knockdown_budget.csv``.
"""

from __future__ import annotations

import argparse
import csv
import math
import os

import numpy as np
import warp as wp

from ocean_warp.atomic_files import atomic_output
from ocean_warp.device_structs import struct_from
from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.frames import roll_pitch_yaw
from ocean_warp.kernels.sailing_rig import RigState, sailing_rig
from ocean_warp.wind import WindConfig
from benchmarks import DATA

BODY_TERMS = ("sail", "keel", "rudder", "windage", "hull", "munk", "radiation", "rigid_body")
"""The sources of the body-z budget."""
WORLD_TERMS = BODY_TERMS + ("gravity", "appendage_buoyancy", "damping")
"""The sources of the world-yaw acceleration budget (every wrench the equations of motion see in flat water)."""
PARTS = {"sail": (1.0, 0.0, 0.0), "keel": (0.0, 1.0, 0.0), "rudder": (0.0, 0.0, 1.0), "windage": (0.0, 0.0, 0.0)}
"""Foil factors that leave one part of the rig (windage: none of the foils, so windage and propeller)."""


def rig_part_wrenches(sim: EBoatSimulator) -> dict[str, np.ndarray]:
    """{part: (N, 6)} the rig's wrench from each part at the boats' current state (the rig's state is copied,
    so the simulation is not disturbed)."""
    rig, device = sim.rig, sim.device
    around = rig._around
    parts = {}
    for name, factors in PARTS.items():
        state = struct_from(RigState, rudder_angle=wp.clone(rig.state.rudder_angle),
                            sheet_limit=wp.clone(rig.state.sheet_limit), boom_angle=wp.clone(rig.state.boom_angle),
                            boom_rate=wp.clone(rig.state.boom_rate),
                            foil_scale=wp.full(sim.count, wp.vec3(*factors), dtype=wp.vec3, device=device),
                            reef_level=wp.clone(rig.state.reef_level))
        out = wp.zeros(sim.count, dtype=wp.types.vector(6, float), device=device)
        status = wp.zeros(sim.count, dtype=int, device=device)
        wp.launch(sailing_rig, dim=sim.count, device=device,
                  inputs=[rig.parameters, rig.tables, rig.wind.gusts, 0.0, around, rig.control, state],
                  outputs=[out, status])
        parts[name] = out.numpy().astype(np.float64)
    windage = parts["windage"]
    for name in ("sail", "keel", "rudder"):
        parts[name] = parts[name] - windage
    return parts


def heading_tilt(orientation: np.ndarray) -> np.ndarray:
    """R_t = R_z(psi)^T R: body -> heading frame of a body -> world quaternion (x, y, z, w)."""
    rotation = rotation_matrix(orientation)
    psi = math.atan2(rotation[1, 0], rotation[0, 0])
    c, s = math.cos(psi), math.sin(psi)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]) @ rotation


def rotation_matrix(q: np.ndarray) -> np.ndarray:
    """Body -> world rotation of a quaternion (x, y, z, w)."""
    x, y, z, w = np.asarray(q, dtype=np.float64) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def heading_frame_terms(tilt: np.ndarray, nu_r: np.ndarray, added: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(T^T A T, c_A): the body-frame added mass and added-mass velocity terms of A applied in the heading frame
    (``kernels.seakeeping_frame``'s formula, in numpy)."""
    t = np.kron(np.eye(2), tilt)
    nu_h = t @ nu_r
    v, w = nu_h[:3], nu_h[3:]
    bow = tilt[:, 0]
    frame_rate = np.array([0.0, 0.0, (-bow[2] / max(bow[0], 0.1)) * w[0] + w[2]])
    tilt_rate = w - frame_rate
    a = added @ nu_h
    terms = added @ np.concatenate([np.cross(tilt_rate, v), np.cross(tilt_rate, w)])
    terms += np.concatenate([np.cross(frame_rate, a[:3]), np.cross(frame_rate, a[3:]) + np.cross(v, a[:3])])
    return t.T @ added @ t, t.T @ terms


def velocity_term_wrenches(sim: EBoatSimulator) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """({"munk", "rigid_body", "radiation", "damping"}: (6,) body-frame wrenches [N, N m] of boat 0's velocity
    terms and memory, on the right-hand side), and the mass matrix (6, 6) its acceleration meets."""
    boat_type = sim.fleet.model.boat_types[0]
    state = sim.fleet.numpy()
    nu = state["velocity"][0].astype(np.float64)
    nu_r = nu.copy()
    nu_r[:3] -= sim.fleet.state.water_velocity.numpy()[0].astype(np.float64)
    mass, r_g, inertia = boat_type.mass, boat_type.center_of_mass, boat_type.inertia_about_origin
    database = boat_type.seakeeping
    radiation = np.zeros(6)
    if database is None:
        a = boat_type.added_mass @ nu_r
        munk = -np.concatenate([np.cross(nu_r[3:], a[:3]), np.cross(nu_r[:3], a[:3]) + np.cross(nu_r[3:], a[3:])])
        mass_matrix = boat_type.mass_matrix
    else:
        tilt = heading_tilt(state["orientation"][0])
        added, terms = heading_frame_terms(tilt, nu_r, np.asarray(database.added_mass_infinite, dtype=np.float64))
        munk = -terms
        mass_matrix = boat_type.rigid_body_mass_matrix + added
        outputs = sim.fleet.state.radiation_output.numpy().astype(np.float64)
        for index, term in enumerate(database.radiation):
            radiation[term.row] -= outputs[index * sim.count]
        radiation = np.kron(np.eye(2), tilt).T @ radiation
    v, w = nu[:3], nu[3:]
    w_cross_v = np.cross(w, v)
    rigid = -np.concatenate([mass * (w_cross_v + np.cross(w, np.cross(w, r_g))),
                             np.cross(w, inertia @ w) + mass * np.cross(r_g, w_cross_v)])
    linear, quadratic = np.asarray(boat_type.linear_damping), np.asarray(boat_type.quadratic_damping)
    damping = -(linear * nu_r + quadratic * np.abs(nu_r) * nu_r)
    return {"munk": munk, "rigid_body": rigid, "radiation": radiation, "damping": damping}, mass_matrix


def knockdown(wind_speed: float, twa: float, speed: float, sheet: float, duration: float, dt: float,
              config: EBoatConfig, device) -> tuple[dict, list[dict]]:
    """One boat's trace: the summary and a budget row per step."""
    sim = EBoatSimulator(EBoatSimulatorConfig(boat=config, wind=WindConfig(speed=wind_speed, direction=math.pi),
                                              dt=dt), 1, device=device)
    # The wind blows toward -x; yaw +twa puts it over the starboard bow.
    sim.reset(heading=twa, velocity=[speed, 0, 0, 0, 0, 0], wind_speed=wind_speed, wind_direction=math.pi,
              sheet=sheet)
    boat_type = sim.fleet.model.boat_types[0]
    rows, previous_rate, previous_world_rate = [], 0.0, 0.0
    for step in range(int(round(duration / dt))):
        sim.step()
        state = sim.fleet.numpy()
        rate = float(state["velocity"][0, 5])
        rotation = rotation_matrix(state["orientation"][0])
        world_rate = float(rotation[2] @ state["velocity"][0, 3:].astype(np.float64))
        roll, _, yaw = roll_pitch_yaw(state["orientation"][:1])[0]
        row = {"time_s": (step + 1) * dt, "heel_deg": math.degrees(roll), "yaw_rate_degps": math.degrees(rate),
               "world_yaw_rate_degps": math.degrees(world_rate), "twa_deg": math.degrees(yaw),
               "speed_mps": float(state["velocity"][0, 0])}
        wrenches = {name: wrench[0] for name, wrench in rig_part_wrenches(sim).items()}
        rig = sum(wrenches.values())
        wrenches["hull"] = state["hydro_wrench"][0].astype(np.float64)
        terms, mass_matrix = velocity_term_wrenches(sim)
        wrenches.update(terms)
        weight = rotation[2] * (-boat_type.mass * sim.ocean.config.water.gravity)
        wrenches["gravity"] = np.concatenate([weight, np.cross(boat_type.center_of_mass, weight)])
        wrenches["appendage_buoyancy"] = sim.fleet.forces.model_wrench.numpy()[0].astype(np.float64) - rig
        for name in BODY_TERMS:
            row[name] = float(wrenches[name][5])
        row["sum"] = sum(row[k] for k in BODY_TERMS)
        row["implied_yaw_accel_degps2"] = math.degrees(row["sum"] / mass_matrix[5, 5])
        row["observed_yaw_accel_degps2"] = math.degrees((rate - previous_rate) / dt)
        for name in WORLD_TERMS:
            angular = np.linalg.solve(mass_matrix, wrenches[name])[3:]
            row[f"{name}_yaw_accel"] = math.degrees(float(rotation[2] @ angular))
        row["sum_yaw_accel"] = sum(row[f"{k}_yaw_accel"] for k in WORLD_TERMS)
        row["observed_world_yaw_accel"] = math.degrees((world_rate - previous_world_rate) / dt)
        previous_rate, previous_world_rate = rate, world_rate
        rows.append(row)
    rates = np.array([r["yaw_rate_degps"] for r in rows])
    summary = {"wind_speed_mps": wind_speed, "max_yaw_rate_degps": float(np.max(np.abs(rates))),
               "max_world_yaw_rate_degps": float(np.max(np.abs([r["world_yaw_rate_degps"] for r in rows]))),
               "max_heel_deg": float(np.max(np.abs([r["heel_deg"] for r in rows])))}
    return summary, rows


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--wind-speed", type=float, default=10.0, help="true wind [m/s]")
    parser.add_argument("--twa", type=float, default=50.0, help="true wind angle at the start [deg]")
    parser.add_argument("--speed", type=float, default=1.5, help="boat speed at the start [m/s]")
    parser.add_argument("--sheet", type=float, default=15.0, help="sheet (boom limit) [deg]")
    parser.add_argument("--duration", type=float, default=15.0, help="[s]")
    parser.add_argument("--window", type=float, default=5.0, help="the round-up the average covers [s]")
    parser.add_argument("--dt", type=float, default=0.01)
    parser.add_argument("--hull", default="real", help="EBoatConfig.hull")
    parser.add_argument("--seakeeping", action="store_true", help="EBoatConfig.seakeeping (the real hull's database)")
    parser.add_argument("--device", default=None)
    parser.add_argument("--out", default=os.path.join(DATA, "knockdown_budget.csv"))
    args = parser.parse_args(argv)
    config = EBoatConfig(hull=args.hull, seakeeping=args.seakeeping)
    summary, rows = knockdown(args.wind_speed, math.radians(args.twa), args.speed, math.radians(args.sheet),
                              args.duration, args.dt, config, args.device)
    with atomic_output(args.out) as temporary, open(temporary, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows({k: f"{v:.5g}" for k, v in row.items()} for row in rows)
    print(", ".join(f"{k} {v:.3g}" for k, v in summary.items()))
    toward_wind = [r for r in rows if r["time_s"] <= args.window]
    # Rounding up turns the bow toward the wind: heading toward 0, against the sign of the true wind angle.
    toward = -math.copysign(1.0, args.twa)
    peak = max(toward_wind, key=lambda r: toward * r["observed_yaw_accel_degps2"])
    terms = BODY_TERMS + ("sum",)
    print("yaw moments [N m] at the largest yaw acceleration toward the wind (t = "
          f"{peak['time_s']:.2f} s, heel {peak['heel_deg']:.1f} deg, yaw rate {peak['yaw_rate_degps']:.1f} deg/s):")
    print("  " + ", ".join(f"{k} {peak[k]:+.1f}" for k in terms))
    mean = {k: float(np.mean([r[k] for r in toward_wind])) for k in terms}
    print(f"mean over the first {args.window:g} s: " + ", ".join(f"{k} {mean[k]:+.1f}" for k in terms))
    print(f"implied yaw acceleration {peak['implied_yaw_accel_degps2']:+.1f} deg/s^2, observed "
          f"{peak['observed_yaw_accel_degps2']:+.1f}")
    world = [f"{k}_yaw_accel" for k in WORLD_TERMS] + ["sum_yaw_accel", "observed_world_yaw_accel"]
    for start, stop in ((0.0, args.window / 2), (0.0, args.window)):
        span = [r for r in rows if start < r["time_s"] <= stop]
        mean = {k: float(np.mean([r[k] for r in span])) for k in world}
        print(f"world-yaw acceleration through M^-1 [deg/s^2], mean over {start:g}-{stop:g} s: "
              + ", ".join(f"{k.removesuffix('_yaw_accel')} {mean[k]:+.1f}" for k in world))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
