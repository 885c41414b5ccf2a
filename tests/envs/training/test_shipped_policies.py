"""The policies shipped in the package do what the README says they do, on the CPU.

The yardsticks come from the tasks, not from the policies: the seed task's success (the boat came within
5 m of its waypoint), and the mission's six waypoints reached before the time limit, checked against the
recorded path. An untrained network of the same shape fails the same checks, so they can fail.
"""

from __future__ import annotations

import numpy as np
import pytest
import torch

from ocean_warp.envs import WaypointConfig
from ocean_warp.envs.evaluation import evaluate_mission
from ocean_warp.envs.training.policies import shipped_policy_path
from ocean_warp.envs.training.policy_io import Policy, build_actor, load_policy, read_checkpoint
from ocean_warp.envs.apps.success_rate import evaluate_task


def _untrained_like(path) -> Policy:
    data = read_checkpoint(path)
    torch.manual_seed(7)
    actor = build_actor(int(data["num_obs"]), int(data["num_actions"]), data["actor_config"])
    return Policy(actor, task=data["task"], observation=data["observation"], num_obs=int(data["num_obs"])).eval()


@pytest.mark.parametrize("task_id", ["EBoatWaypoint-v0", "EBoatMission-v0"])
def test_shipped_policies_are_small_and_load(task_id):
    path = shipped_policy_path(task_id)
    assert path.stat().st_size < 64 * 1024  # kilobytes, as the README promises
    policy = load_policy(path, task=task_id)
    assert policy.task.removeprefix("ocean_warp/") == task_id


def test_shipped_waypoint_policy_reaches_the_seed_waypoint():
    """On starts it never trained on (seed 1000 + 64 environments), at least 90 % success, as the
    issue's CPU target asks of it; an untrained network of the same shape does far worse."""
    path = shipped_policy_path("EBoatWaypoint-v0")
    trained = evaluate_task(load_policy(path), WaypointConfig(), episodes=64, seed=1234)
    untrained = evaluate_task(_untrained_like(path), WaypointConfig(), episodes=64, seed=1234)
    assert trained.success_rate >= 0.9, trained.success_rate
    assert untrained.success_rate < 0.5, untrained.success_rate
    # a successful seed episode needs at least 100 m - 5 m at no more than ~5 m/s: 19 s
    assert trained.length_s[trained.success].min() >= 19.0


def test_shipped_mission_policy_sails_bcdaca_on_the_cpu():
    """Two seeded runs of the full mission in waves (Hs 0.3 m, gusty 10 m/s): both completed, every
    waypoint of BCDACA within 5 m on the recorded path, well inside the 1800 s limit."""
    evaluation = evaluate_mission(shipped_policy_path("EBoatMission-v0"), runs=2, seed=3, autopilot=False,
                                  progress=False, device="cpu")
    result = evaluation.results["policy"]
    assert result.success.all(), result.status
    assert (result.waypoints == len(result.route)).all()
    assert (result.time_s < 1200.0).all()
    for path in result.paths:  # independent of the env's own bookkeeping: the path passes each waypoint
        closest = np.nanmin(np.linalg.norm(path.xy[:, None, :] - result.route[None, :, :], axis=-1), axis=0)
        assert (closest <= 5.0 + 2.5).all(), closest  # 5 m reach + at most one decision's travel at 2.5 m/s
