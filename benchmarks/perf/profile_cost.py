"""What the physics profile costs: the E-Boat step and an environment's decision, earlier model against new,
interleaved in one run on one device.

    python -m benchmarks.perf.profile_cost --device cuda:0 --boats 4096 16384 --json out/profile_cost.json

"Earlier" is the seed profile's forces on the mesh hull (``EBoatConfig(profile="seed", hydrostatics="mesh")``: Kerner's drag on the
whole flow, the sheet's tables; the simulator's default before issue 19), "physics" the new default
(ITTC friction and the Delft residuary term per boat, lifting-surface fins, the ORC main, topsides
windage). Both run the same code path otherwise; the cases alternate, each timed as a captured graph
(median of batches), so clocks and temperatures are shared. The environment is the BCDACA mission
(``MissionConfig``: decision 1 s, dt 0.05 s, 1 substep, Hs 0.3 m JONSWAP, 10 m/s gusty wind), its
real-time factor = envs x decision period / wall seconds per decision.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import logging

import torch
import warp as wp

from benchmarks.perf.bench_eboat import build, time_step
from benchmarks.perf.bench_envs import seconds_per_call
from benchmarks.perf.timing import device_description, write_results_json
from ocean_warp.eboat import EBoatConfig, Hydrostatics, Profile
from ocean_warp.envs import MissionConfig, SailingEnv


def earlier_boat() -> EBoatConfig:
    """The simulator's default before the physics profile: the seed profile's forces on the mesh hull."""
    return EBoatConfig(profile=Profile.SEED, hydrostatics=Hydrostatics.MESH)


PROFILES = {"earlier (seed forces, mesh hull)": earlier_boat, "physics": EBoatConfig}


def decision_seconds(boat: EBoatConfig, envs: int, device, repeats: int) -> float:
    """Median wall seconds of one mission decision of ``envs`` environments sailing ``boat``."""
    task = MissionConfig()
    task = dataclasses.replace(task, simulator=dataclasses.replace(task.simulator, boat=boat, hydrodynamics=None))
    env = SailingEnv(task, envs, device=device, seed=1)
    actions = torch.tensor([[0.0, 0.2, 0.1]], device=env.torch_device).repeat(envs, 1)
    sync = (lambda: torch.cuda.synchronize(env.torch_device)) if env.torch_device.type == "cuda" else (lambda: None)
    for _ in range(3):
        env.step(actions)
    return seconds_per_call(lambda: env.step(actions), repeats, sync)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--device", default="cuda:0" if wp.get_cuda_device_count() else "cpu")
    parser.add_argument("--boats", type=int, nargs="+", default=[4096, 16384])
    parser.add_argument("--repeats", type=int, default=10, help="timed decisions per case (median)")
    parser.add_argument("--json", help="write the results here")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    wp.init()
    device = wp.get_device(args.device)
    rows = []
    for boats in args.boats:
        row = {"boats": boats}
        for name, boat in PROFILES.items():
            step = time_step(build(device, boats, False, 0.5, boat=boat()))
            row[f"{name}: boat-substeps/s"] = boats * 5 / step
        for name, boat in PROFILES.items():
            seconds = decision_seconds(boat(), boats, device, args.repeats)
            row[f"{name}: decisions/s"] = boats / seconds
            row[f"{name}: RTF"] = boats * MissionConfig().decision_period / seconds
        rows.append(row)
        print(row, flush=True)
    print(device_description(device), datetime.date.today().isoformat())
    if args.json:
        write_results_json(args.json, device, rows=rows)


if __name__ == "__main__":
    main()
