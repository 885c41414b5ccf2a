"""Benchmark: collection throughput of the batched sailing environment, with policy inference, per interface.

    python -m benchmarks.perf.bench_envs --device cuda:0 --envs 1024 4096 16384 65536
    python -m benchmarks.perf.bench_envs --device cpu --envs 64 256 1024 --decisions 3

For each number of environments it times, one decision at a time:
- ``physics``: the bare simulator, ``steps_per_decision`` steps (a CUDA graph each) and nothing else;
- ``env``: ``SailingEnv.step`` with fixed actions (actions, physics, task kernels, resets; one graph);
- the environment layer alone: actions to commands, task kernels and the masked reset, captured;
- ``core+policy``, ``rsl_rl``, ``gymnasium``, ``sb3``: a decision through each interface with an MLP
  policy (``--hidden``, ELU) choosing the actions from the observations, as a rollout does.
It reports environment decisions per second and the aggregate real-time factor (simulated boat-seconds
per wall-second), and the environment layer's cost beside the bare physics it wraps. The layer's work
does not depend on how many envs end, because every kernel runs over all of them with a mask.

The task is Waypoint+ (mesh hull, 2 024 triangles; JONSWAP Hs 0.5 m, Tp 3.5 s, choppiness 0.5, 64 x 64
grid over 256 m; gusty wind; noisy sensors), with ``--dt``, ``--substeps`` and ``--decision-period``.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import logging
import time

import numpy as np
import torch
import warp as wp


from benchmarks.perf.timing import device_description, write_results_json
from ocean_warp.envs import SailingEnv, WaypointPlusConfig
from ocean_warp.envs.interfaces.gym_env import SailingVectorEnv
from ocean_warp.envs.interfaces.rsl_rl_env import RslRlVecEnv


def policy_network(inputs: int, hidden: list[int], device, outputs: int = 3) -> torch.nn.Module:
    layers, width = [], inputs
    for size in hidden:
        layers += [torch.nn.Linear(width, size), torch.nn.ELU()]
        width = size
    layers += [torch.nn.Linear(width, outputs), torch.nn.Tanh()]
    return torch.nn.Sequential(*layers).to(device).eval()


def seconds_per_call(call, repeats: int, sync) -> float:
    """Median wall time of ``call`` over ``repeats`` runs, after one warm-up run."""
    call()
    sync()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        sync()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def _captured(env: SailingEnv):
    """The environment layer alone (actions -> commands, task kernels, masked resets), as one graph on
    CUDA; the same launches eagerly on the CPU."""
    def launch():
        env.launch_actions()
        env.launch_task()

    if not env.device.is_cuda:
        return launch
    launch()
    with wp.ScopedCapture(device=env.device) as capture:
        launch()
    return lambda: wp.capture_launch(capture.graph)


def measure(task, envs: int, device, hidden: list[int], repeats: int, interfaces: list[str]) -> dict:
    env = SailingEnv(task, envs, device=device, seed=1)
    torch_device = env.torch_device
    sync = (lambda: torch.cuda.synchronize(torch_device)) if torch_device.type == "cuda" else (lambda: None)
    policy = policy_network(env.num_policy_obs, hidden, torch_device)
    fixed = torch.tensor([[0.0, 0.2, 0.1]], device=torch_device).repeat(envs, 1)
    for _ in range(3):  # sail away from the start first
        env.step(fixed)
    row = {"envs": envs}
    sim = env.simulator

    def physics():
        for _ in range(env.steps_per_decision):
            sim.step()

    row["physics_s"] = seconds_per_call(physics, repeats, sync)
    row["env_s"] = seconds_per_call(lambda: env.step(fixed), repeats, sync)
    row["layer_s"] = seconds_per_call(_captured(env), repeats, sync)

    @torch.inference_mode()
    def core_with_policy():
        env.step(policy(env.buffers.policy_obs))

    if "core" in interfaces:
        row["core+policy_s"] = seconds_per_call(core_with_policy, repeats, sync)
    if "rsl_rl" in interfaces:
        rsl = RslRlVecEnv(env)
        observations = [rsl.get_observations()]

        @torch.inference_mode()
        def rsl_step():
            obs, rewards, dones, extras = rsl.step(policy(observations[0]["policy"]))
            observations[0] = obs

        row["rsl_rl_s"] = seconds_per_call(rsl_step, repeats, sync)
    if "gymnasium" in interfaces:
        vector = SailingVectorEnv.from_env(env)
        numpy_obs = [vector.reset(seed=2)[0]]

        @torch.inference_mode()
        def gym_step():
            actions = policy(torch.as_tensor(numpy_obs[0], device=torch_device)).cpu().numpy()
            numpy_obs[0] = vector.step(actions)[0]

        row["gymnasium_s"] = seconds_per_call(gym_step, repeats, sync)
    if "sb3" in interfaces:
        try:
            from ocean_warp.envs.interfaces.sb3_env import Sb3VecEnv
        except ImportError:
            print("  (sb3 skipped: stable-baselines3 is not installed)")
        else:
            vec = Sb3VecEnv(env)
            sb3_obs = [vec.reset()]

            @torch.inference_mode()
            def sb3_step():
                actions = policy(torch.as_tensor(sb3_obs[0], device=torch_device)).cpu().numpy()
                vec.step_async(actions)
                sb3_obs[0] = vec.step_wait()[0]

            row["sb3_s"] = seconds_per_call(sb3_step, repeats, sync)
    assert torch.all(torch.isfinite(env.buffers.policy_obs)), "observations must stay finite"
    del env
    return row


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--device", default="cuda:0" if wp.get_cuda_device_count() else "cpu")
    parser.add_argument("--envs", type=int, nargs="+", default=[1024, 4096, 16384, 65536])
    parser.add_argument("--dt", type=float, default=0.05, help="simulator step [s]")
    parser.add_argument("--substeps", type=int, default=5)
    parser.add_argument("--decision-period", type=float, default=1.0, help="[s]")
    parser.add_argument("--choppiness", type=float, default=0.5)
    parser.add_argument("--hidden", type=int, nargs="+", default=[128, 128], help="policy MLP widths")
    parser.add_argument("--decisions", type=int, default=10, help="timed decisions per case (median)")
    parser.add_argument("--interfaces", nargs="+", default=["core", "rsl_rl", "gymnasium", "sb3"])
    parser.add_argument("--seakeeping", action="store_true",
                        help="the boat with its hull's radiation memory and diffraction (EBoatConfig.seakeeping)")
    parser.add_argument("--json", help="write the results here")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    device = wp.get_device(args.device)
    task = WaypointPlusConfig()
    ocean = dataclasses.replace(task.simulator.ocean, choppiness=args.choppiness)
    boat = dataclasses.replace(task.simulator.boat, seakeeping=True) if args.seakeeping else task.simulator.boat
    simulator = dataclasses.replace(task.simulator, ocean=ocean, dt=args.dt, substeps=args.substeps, boat=boat)
    task = dataclasses.replace(task, simulator=simulator, decision_period=args.decision_period)
    print(f"Waypoint+ decisions: period {task.decision_period} s = {task.steps_per_decision} steps of dt {args.dt} s "
          f"x {args.substeps} substeps; mesh hull, seakeeping {'on' if boat.seakeeping else 'off'}; "
          f"JONSWAP Hs {ocean.significant_wave_height} m, Tp {ocean.peak_period} s, "
          f"choppiness {ocean.choppiness}; policy MLP {args.hidden}; {device_description(device)}; "
          f"{datetime.date.today()}")
    columns = ["physics", "env"] + [{"core": "core+policy"}.get(i, i) for i in args.interfaces]
    print("| envs | " + " | ".join(f"{c}: ms, k dec/s, RTF" for c in columns) + " | env layer alone [ms] | "
          "layer / physics | (env - physics) / physics |")
    rows = []
    for envs in args.envs:
        row = measure(task, envs, device, args.hidden, args.decisions, args.interfaces)
        cells = []
        for c in columns:
            seconds = row.get(f"{c}_s")
            if seconds is None:
                cells.append("--")
                continue
            row[f"{c}_decisions_per_s"] = envs / seconds
            row[f"{c}_real_time_factor"] = envs * task.decision_period / seconds
            cells.append(f"{seconds * 1e3:.1f}, {envs / seconds / 1e3:.1f}, {envs * task.decision_period / seconds:,.0f}")
        row["env_layer_fraction"] = row["layer_s"] / row["physics_s"]
        row["env_minus_physics_fraction"] = (row["env_s"] - row["physics_s"]) / row["physics_s"]
        rows.append(row)
        print(f"| {envs} | " + " | ".join(cells) + f" | {row['layer_s'] * 1e3:.3f} | "
              f"{100 * row['env_layer_fraction']:.2f} % | {100 * row['env_minus_physics_fraction']:.1f} % |", flush=True)
    if args.json:
        write_results_json(args.json, device, task="Waypoint+", dt=args.dt, substeps=args.substeps,
                           decision_period=task.decision_period, choppiness=args.choppiness, hidden=args.hidden,
                           rows=rows)


if __name__ == "__main__":
    main()
