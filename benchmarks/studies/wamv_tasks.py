"""VRX's tasks on the WAM-V: a policy (or none) sailed over seeded runs, scored by VRX's rules from the poses of
every decision.

    python -m benchmarks.studies.wamv_tasks --task WamvStationKeeping-v0 --policy policy.pt --runs 100 \
        --wind 5 --sea 0.3 --device cuda:0 --json sk.json

Scores (computed here in torch from ``buffers``, once per decision, over each run's first episode): station
keeping, the mean over the run of the pose error d + 0.75^d |heading error| [m]; wayfinding, the mean over the
goals of each goal's least pose error [m]; following the path, the gates passed in order.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math

import torch

from ocean_warp.atomic_files import atomic_output
from ocean_warp.envs.env_factory import make_env
from ocean_warp.envs.registration import make_task_config
from ocean_warp.envs.training.policy_io import load_policy
from ocean_warp.envs.vrx import VrxTask, wamv_vessel


def yaw_of(q: torch.Tensor) -> torch.Tensor:
    x, y, z, w = q.unbind(-1)
    return torch.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def pose_errors(position, orientation, origin, goals) -> torch.Tensor:
    """(N, G) VRX's pose error of every boat to every goal pose (x, y from the origin, heading) [m]."""
    local = (position - origin)[:, None, :2]
    d = torch.linalg.norm(goals[:, :, :2] - local, dim=-1)
    heading = torch.remainder(goals[:, :, 2] - yaw_of(orientation)[:, None] + math.pi, 2 * math.pi) - math.pi
    return d + 0.75**d * heading.abs()


def sail(task_id: str, policy_path: str | None, runs: int, wind: float, sea: float, seed: int, device: str,
         duration: float | None = None) -> dict:
    task = make_task_config(task_id)
    if duration is not None:
        task = make_task_config(task, max_episode_steps=int(round(duration / task.decision_period)))
    task = dataclasses.replace(task, vessel=wamv_vessel(sea),
                               start=dataclasses.replace(task.start, wind_speed=(wind, wind)))
    env = make_env(task, runs, device=device, seed=seed)
    b = env.buffers
    policy = load_policy(policy_path, device=env.torch_device) if policy_path else None
    running = torch.zeros(runs, device=env.torch_device)
    best = torch.full((runs, task.goals), float("inf"), device=env.torch_device)
    active = torch.ones(runs, dtype=torch.bool, device=env.torch_device)
    decisions = torch.zeros(runs, device=env.torch_device)
    route = b.route.clone()
    outcome = {"success": torch.zeros(runs, device=env.torch_device),
               "gates": torch.zeros(runs, device=env.torch_device)}
    for _ in range(task.max_episode_length):
        with torch.inference_mode():
            actions = policy(b.policy_obs) if policy is not None else torch.zeros_like(b.actions)
        env.step(actions)
        errors = pose_errors(b.final_position, b.final_orientation, b.origin, route)
        current = errors.gather(1, b.waypoint_index.long().clamp(max=task.goals - 1)[:, None])[:, 0]
        running += torch.where(active, current, torch.zeros_like(current))
        decisions += active.float()
        best = torch.where(active[:, None], torch.minimum(best, errors), best)
        ended = active & b.done
        outcome["success"] = torch.where(ended, b.final_success, outcome["success"])
        outcome["gates"] = torch.where(ended, b.final_waypoints.float(), outcome["gates"])
        active &= ~b.done
        if not active.any():
            break
    if task.kind is VrxTask.STATION_KEEPING:
        score = running / decisions.clamp(min=1)
    elif task.kind is VrxTask.WAYFINDING:
        score = best.mean(dim=1)
    else:
        score = outcome["gates"]
    return {"task": task_id, "policy": policy_path or "none (zero thrust)", "runs": runs, "wind_m_s": wind,
            "duration_s": task.episode_time,
            "sea_hs_m": sea, "seed": seed, "device": str(env.device), "vrx_score_mean": float(score.mean()),
            "vrx_score_median": float(score.median()), "success_rate": float(outcome["success"].mean()),
            "scores": [round(float(v), 4) for v in score.cpu()]}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--task", default="WamvStationKeeping-v0")
    parser.add_argument("--policy", help="a checkpoint (exported policy); none: zero thrust")
    parser.add_argument("--runs", type=int, default=100)
    parser.add_argument("--wind", type=float, default=5.0, help="mean true wind [m/s]")
    parser.add_argument("--sea", type=float, default=0.3, help="significant wave height [m]")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--duration", type=float, help="a run's time limit [s] (default: the task's; VRX runs 300 s)")
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--json", help="write the result here")
    args = parser.parse_args(argv)
    result = sail(args.task, args.policy, args.runs, args.wind, args.sea, args.seed, args.device, args.duration)
    print(f"{result['task']}: {result['policy']}: VRX score mean {result['vrx_score_mean']:.3f}, median "
          f"{result['vrx_score_median']:.3f}, success {result['success_rate']:.2f} over {result['runs']} runs")
    if args.json:
        with atomic_output(args.json) as path:
            with open(path, "w") as handle:
                json.dump(result, handle, indent=1)


if __name__ == "__main__":
    main()
