"""VRX's tasks on the GPU: WAM-Vs per second, beside VRX's own real-time factor.

    python -m benchmarks.perf.bench_wamv --envs 4096 16384 --json benchmarks/data/wamv_rtf_h100.json

For each batch size it times, after a few decisions under way: the physics of a decision alone, the env step
(actions, physics, task kernels, resets) and the env with an rsl-rl policy (128, 128) in the loop. It reports
decisions per second, boat-substeps per second and the aggregate real-time factor (simulated boat-seconds per
wall second), with the task, decision period, dt, substeps, hull and sea stated.
"""

from __future__ import annotations

import argparse
import datetime
import json

import torch
import warp as wp

from ocean_warp.atomic_files import atomic_output
from ocean_warp.envs.interfaces.rsl_rl_env import RslRlVecEnv
from ocean_warp.envs.vrx import VrxEnv, VrxTaskConfig, wamv_vessel

from .bench_envs import policy_network, seconds_per_call


def measure(task: VrxTaskConfig, envs: int, device, repeats: int) -> dict:
    env = VrxEnv(task, envs, device=device, seed=1)
    torch_device = env.torch_device
    sync = (lambda: torch.cuda.synchronize(torch_device)) if torch_device.type == "cuda" else (lambda: None)
    policy = policy_network(env.num_policy_obs, [128, 128], torch_device, outputs=env.num_actions)
    fixed = torch.full((envs, env.num_actions), 0.3, device=torch_device)
    for _ in range(3):
        env.step(fixed)
    sim = env.simulator

    def physics():
        for _ in range(env.steps_per_decision):
            sim.step()

    row = {"envs": envs, "physics_s": seconds_per_call(physics, repeats, sync),
           "env_s": seconds_per_call(lambda: env.step(fixed), repeats, sync)}
    rsl = RslRlVecEnv(env)
    observations = [rsl.get_observations()]

    @torch.inference_mode()
    def rsl_step():
        observations[0] = rsl.step(policy(observations[0]["policy"]))[0]

    row["rsl_rl_s"] = seconds_per_call(rsl_step, repeats, sync)
    if not torch.all(torch.isfinite(env.buffers.policy_obs)):
        raise RuntimeError("observations must stay finite")
    substeps = env.steps_per_decision * task.simulator.substeps
    for key in ("physics", "env", "rsl_rl"):
        seconds = row[f"{key}_s"]
        row[f"{key}_decisions_per_s"] = envs / seconds
        row[f"{key}_boat_substeps_per_s"] = envs * substeps / seconds
        row[f"{key}_rtf"] = envs * task.decision_period / seconds
    return row


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--device", default="cuda:0" if wp.get_cuda_device_count() else "cpu")
    parser.add_argument("--envs", type=int, nargs="+", default=[4096, 16384])
    parser.add_argument("--kind", default="station_keeping")
    parser.add_argument("--profile", default="vrx", choices=["vrx", "physics"])
    parser.add_argument("--sea", type=float, default=0.3, help="significant wave height [m]")
    parser.add_argument("--decisions", type=int, default=10, help="timed decisions per case (median)")
    parser.add_argument("--json", help="write the results here")
    args = parser.parse_args(argv)
    task = VrxTaskConfig(kind=args.kind, vessel=wamv_vessel(args.sea, profile=args.profile))
    sim = task.simulator
    triangles = len(task.vessel.simulator(1, device="cpu").boat_type.hull.triangles)
    meta = {"device": wp.get_device(args.device).name if args.device != "cpu" else "cpu",
            "date": datetime.date.today().isoformat(), "task": args.kind, "vessel": "WAM-V",
            "profile": args.profile, "decision_period_s": task.decision_period, "dt_s": sim.dt,
            "substeps": sim.substeps, "hull_triangles": int(triangles),
            "sea": f"JONSWAP Hs {args.sea} m, Tp 3 s", "rows": []}
    for envs in args.envs:
        row = measure(task, envs, args.device, args.decisions)
        meta["rows"].append(row)
        print(f"{envs:6d} envs: physics {row['physics_boat_substeps_per_s'] / 1e6:.2f} M boat-substeps/s, env "
              f"{row['env_decisions_per_s'] / 1e3:.0f} k decisions/s (RTF {row['env_rtf'] / 1e3:.0f} k), rsl-rl+policy "
              f"{row['rsl_rl_decisions_per_s'] / 1e3:.0f} k decisions/s (RTF {row['rsl_rl_rtf'] / 1e3:.0f} k)")
    if args.json:
        with atomic_output(args.json) as path:
            with open(path, "w") as handle:
                json.dump(meta, handle, indent=1)


if __name__ == "__main__":
    main()
