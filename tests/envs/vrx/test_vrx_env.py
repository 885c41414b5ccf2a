"""VRX's tasks on a vessel, checked against numpy: the observation of the goal, the reward of a decision worked
out from the poses before and after it, the start draws within their ranges, gate crossings, bad configs.

The E-Boat serves as the vessel here (any vessel does: the env reads only the protocol's common state); the
WAM-V's own tests sail the same env with the WAM-V."""

import math

import numpy as np
import pytest
import torch
import warp as wp

from ocean_warp.eboat import EBoatVessel
from ocean_warp.envs.vrx import VrxEnv, VrxRewardConfig, VrxStartConfig, VrxTaskConfig
from ocean_warp.envs.vrx.vrx_kernels import crossed_gate
from tests.envs.vrx.vrx_poses import StepPoses, pose_error, yaw_of


def wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


@pytest.fixture(scope="module")
def vessel():
    return EBoatVessel()


def test_observation_is_the_goal_in_the_boats_frame(vessel, device, rng):
    env = VrxEnv(VrxTaskConfig(kind="wayfinding", goals=3, vessel=vessel), 6, device=device,
                 seed=int(rng.integers(1 << 30)))
    for _ in range(3):
        env.step(torch.as_tensor(rng.uniform(-1, 1, (6, 3)), dtype=torch.float32, device=env.torch_device))
    b = env.buffers
    pos, q = b.position.cpu().numpy(), b.orientation.cpu().numpy()
    local = pos - b.origin.cpu().numpy()
    route = b.route.cpu().numpy()
    index = b.waypoint_index.cpu().numpy()
    goal = route[np.arange(6), index]
    yaw = yaw_of(q)
    dx, dy = goal[:, 0] - local[:, 0], goal[:, 1] - local[:, 1]
    along = np.cos(yaw) * dx + np.sin(yaw) * dy
    across = -np.sin(yaw) * dx + np.cos(yaw) * dy
    obs = b.policy_obs.cpu().numpy()
    np.testing.assert_allclose(obs[:, 0], np.clip(along / 10, -5, 5), atol=2e-4)
    np.testing.assert_allclose(obs[:, 1], np.clip(across / 10, -5, 5), atol=2e-4)
    np.testing.assert_allclose(obs[:, 2], np.sin(wrap(goal[:, 2] - yaw)), atol=2e-4)
    np.testing.assert_allclose(obs[:, 3], np.cos(wrap(goal[:, 2] - yaw)), atol=2e-4)
    np.testing.assert_allclose(obs[:, 4], np.clip(np.hypot(dx, dy) / 10, -5, 5), atol=2e-4)
    np.testing.assert_allclose(obs[:, 5:8], b.velocity.cpu().numpy()[:, [0, 1, 5]], atol=1e-5)
    # The target buffer is the goal in the world, its heading in column 2.
    np.testing.assert_allclose(b.target.cpu().numpy()[:, :2], goal[:, :2] + b.origin.cpu().numpy()[:, :2], atol=1e-4)
    np.testing.assert_allclose(b.target.cpu().numpy()[:, 2], goal[:, 2], atol=1e-6)


def test_reward_is_progress_in_pose_error_less_its_costs(vessel, device, rng):
    reward = VrxRewardConfig(progress_scale=1.5, error_cost=0.2, action_cost=0.3, reach_bonus=0.0)
    task = VrxTaskConfig(kind="station_keeping", vessel=vessel, reward=reward)
    n = 5
    env = VrxEnv(task, n, device=device, seed=int(rng.integers(1 << 30)))
    b = env.buffers
    goal = b.route.cpu().numpy()[:, 0]
    for _ in range(2):
        before = pose_error(b.position.cpu().numpy() - b.origin.cpu().numpy(), yaw_of(b.orientation.cpu().numpy()),
                            goal)
        actions = rng.uniform(-1.2, 1.2, (n, 3)).astype(np.float32)
        env.step(torch.as_tensor(actions, device=env.torch_device))
        after = pose_error(b.final_position.cpu().numpy() - b.origin.cpu().numpy(),
                           yaw_of(b.final_orientation.cpu().numpy()), goal)
        clipped = np.clip(actions, -1, 1)
        expected = 1.5 * (before - after) - 0.2 * after * task.decision_period - 0.3 * (clipped**2).mean(axis=1)
        np.testing.assert_allclose(b.reward.cpu().numpy(), expected, rtol=1e-4, atol=1e-4)
        assert not b.done.cpu().numpy().any()


def test_starts_are_drawn_within_their_ranges(vessel, device, rng):
    start = VrxStartConfig(goal_distance=(4.0, 6.0), goal_spacing=(8.0, 9.0), wind_speed=(2.0, 3.0),
                           current_speed=(0.1, 0.2))
    env = VrxEnv(VrxTaskConfig(kind="wayfinding", goals=4, vessel=vessel, start=start), 64, device=device,
                 seed=int(rng.integers(1 << 30)))
    route = env.buffers.route.cpu().numpy()
    first = np.hypot(route[:, 0, 0], route[:, 0, 1])
    spacing = np.hypot(*np.moveaxis(np.diff(route[:, :, :2], axis=1), -1, 0))
    assert first.min() >= 4.0 - 1e-4 and first.max() <= 6.0 + 1e-4
    assert spacing.min() >= 8.0 - 1e-4 and spacing.max() <= 9.0 + 1e-4
    assert np.ptp(first) > 1.0  # drawn, not fixed
    wind = env.simulator.state.wind_mean_speed.numpy()
    assert wind.min() >= 2.0 - 1e-5 and wind.max() <= 3.0 + 1e-5 and np.ptp(wind) > 0.5
    current = env.simulator.state.current_speed.numpy()
    assert current.min() >= 0.1 - 1e-5 and current.max() <= 0.2 + 1e-5
    # One seed, one sequence of episodes; another seed, other goals.
    env.reset(seed=7)
    again = env.buffers.route.cpu().numpy().copy()
    env.reset(seed=7)
    np.testing.assert_array_equal(env.buffers.route.cpu().numpy(), again)
    env.reset(seed=8)
    assert not np.allclose(env.buffers.route.cpu().numpy(), again)


@wp.kernel
def _crossings(gates: wp.array(dtype=wp.vec3), before: wp.array(dtype=wp.vec3), after: wp.array(dtype=wp.vec3),
               half_width: float, out: wp.array(dtype=int)):
    i = wp.tid()
    out[i] = int(crossed_gate(gates[i], half_width, before[i], after[i]))


def test_a_gate_counts_only_forward_and_between_its_buoys(device, rng):
    centre = rng.uniform(-20, 20, 2)
    heading = rng.uniform(-math.pi, math.pi)
    ahead = np.array([math.cos(heading), math.sin(heading)])
    side = np.array([-ahead[1], ahead[0]])
    cases = [  # (lateral offset [m], from along, to along, crossed?)
        (1.0, -1.0, 1.0, 1), (-4.5, -0.5, 0.5, 1), (6.0, -1.0, 1.0, 0), (1.0, 1.0, -1.0, 0), (0.0, -2.0, -1.0, 0),
        (0.0, 1.0, 2.0, 0)]
    gates = [(centre[0], centre[1], heading)] * len(cases)
    before = [(*(centre + lat * side + a * ahead), 0.0) for lat, a, _, _ in cases]
    after = [(*(centre + lat * side + b * ahead), 0.0) for lat, _, b, _ in cases]
    out = wp.zeros(len(cases), dtype=int, device=device)
    arrays = [wp.array(np.array(v, dtype=np.float32), dtype=wp.vec3, device=device) for v in (gates, before, after)]
    wp.launch(_crossings, dim=len(cases), device=device, inputs=[*arrays, 5.0], outputs=[out])
    assert out.numpy().tolist() == [c[3] for c in cases]


@pytest.mark.parametrize("field, value, words", [
    ("vessel", "wamv", "expected a vessel"), ("goals", 3, "goals must be 1 for station keeping"),
    ("actions", ("left_thrust",), "has no action 'left_thrust'"), ("decision_period", 0.013, "whole number"),
    ("kind", "docking", "kind must be one of")])
def test_bad_configs_name_what_is_wrong(vessel, field, value, words):
    fields = {"kind": "station_keeping", "vessel": vessel, field: value}
    with pytest.raises(ValueError, match=words) as error:
        VrxTaskConfig(**fields)
    assert "\n" not in str(error.value)


def test_a_task_can_switch_a_vessels_action_off(vessel, device, rng):
    env = VrxEnv(VrxTaskConfig(kind="station_keeping", vessel=vessel, actions=("sheet", "rudder")), 3, device=device,
                 seed=int(rng.integers(1 << 30)))
    env.step(torch.full((3, 3), 1.0, device=env.torch_device))
    assert (env.simulator.control.propeller.numpy() == 0).all()
    assert np.allclose(env.simulator.control.rudder.numpy(), math.radians(60.0))


def test_shipped_wayfinding_policy_reaches_its_first_goal_on_the_cpu():
    """The shipped WAM-V wayfinding policy, on 4 seeded runs in 2 m/s of wind on a 0.3 m sea, brings every boat's
    pose error to its first goal (10-20 m away at the start) under 1 m within 40 s (VRX's scoring rule, computed
    here in numpy from the buffers)."""
    import dataclasses

    from ocean_warp.envs.registration import make_task_config
    from ocean_warp.envs.training.policies import shipped_policy_path
    from ocean_warp.envs.training.policy_io import load_policy

    task = make_task_config("WamvWayfinding-v0")
    task = dataclasses.replace(task, start=dataclasses.replace(task.start, wind_speed=(2.0, 2.0)))
    env = VrxEnv(task, 4, device="cpu", seed=11)
    policy = load_policy(shipped_policy_path("WamvWayfinding-v0"))
    b = env.buffers
    first = b.route.cpu().numpy()[:, 0].copy()
    best = np.full(4, np.inf)
    for _ in range(80):
        with torch.inference_mode():
            env.step(policy(b.policy_obs))
        error = pose_error(b.final_position.numpy() - b.origin.numpy(), yaw_of(b.final_orientation.numpy()), first)
        best = np.minimum(best, error)
    assert np.all(best < 1.0), best


@pytest.mark.parametrize("kind, goals", [("station_keeping", 1), ("wayfinding", 3)])
def test_final_score_is_vrx_rule_over_the_episode(vessel, device, rng, kind, goals):
    """``final_score`` at an episode's end equals VRX's rule computed here in numpy from every physics step's pose
    (VRX samples every update): station keeping, the mean pose error to the goal; wayfinding, the mean over the
    goals of the least error. For station keeping the decisions' last poses alone give another score (the test can
    tell)."""
    task = VrxTaskConfig(kind=kind, goals=goals, vessel=vessel, episode_time=3.0,
                         start=VrxStartConfig(goal_distance=(30.0, 40.0), goal_spacing=(30.0, 40.0)))
    n = 4
    env = VrxEnv(task, n, device=device, seed=int(rng.integers(1 << 30)))
    b = env.buffers
    poses = StepPoses(env)
    env.attach(poses)
    route = b.route.cpu().numpy().copy()
    errors = []
    for step in range(task.max_episode_length):
        env.step(torch.as_tensor(rng.uniform(-1, 1, (n, 3)), dtype=torch.float32, device=env.torch_device))
        local, yaw = poses.local(b.origin.cpu().numpy())
        errors.extend(np.stack([pose_error(local, yaw, route[:, g]) for g in range(goals)], axis=-1))
        done = b.done.cpu().numpy()
        assert done.all() == (step == task.max_episode_length - 1) and (done.all() or not done.any())
    errors = np.array(errors)  # (physics steps, N, goals)
    assert len(errors) == task.max_episode_length * env.steps_per_decision
    rule = (lambda e: e[:, :, 0].mean(axis=0)) if kind == "station_keeping" else (lambda e: e.min(axis=0).mean(axis=1))
    np.testing.assert_allclose(b.final_score.cpu().numpy(), rule(errors), rtol=2e-4, atol=2e-4)
    if kind == "station_keeping":  # a mean: once a decision misses the steps between (a minimum may not)
        once_a_decision = rule(errors[env.steps_per_decision - 1::env.steps_per_decision])
        assert np.abs(once_a_decision - rule(errors)).max() > 1e-2


@pytest.mark.parametrize("task_id, autopilot, baseline", [
    ("WamvStationKeeping-v0", "line", "pivot-station-keeping"), ("WamvWayfinding-v0", "line", "pivot-station-keeping"),
    ("WamvFollowPath-v0", "line", "gate-guidance"), ("WamvStationKeeping-v0", "legacy", "pid-station-keeping"),
    ("WamvFollowPath-v0", "legacy", "los-guidance")])
def test_eval_of_a_vrx_task_writes_vrx_scores(task_id, autopilot, baseline, tmp_path):
    """``ocean-warp eval --task <VRX task>``: the shipped policy and the task's classical baseline (the new one by
    default, the earlier with ``--autopilot legacy``), each run's VRX score in runs.csv and their mean per controller
    in results.csv."""
    import csv

    from ocean_warp.envs.apps.evaluation import main

    assert main(["--task", task_id, "--runs", "2", "--time-limit", "3", "--out", str(tmp_path), "--no-progress",
                 "--device", "cpu", "--autopilot", autopilot]) == 0
    with open(tmp_path / "results.csv") as handle:
        table = {row["controller"]: row for row in csv.DictReader(handle)}
    with open(tmp_path / "runs.csv") as handle:
        runs = list(csv.DictReader(handle))
    assert set(table) == {"policy", baseline}
    for name, row in table.items():
        scores = [float(run["vrx_score"]) for run in runs if run["controller"] == name]
        assert len(scores) == 2 and all(math.isfinite(v) and v >= 0.0 for v in scores)
        assert float(row["vrx_score"]) == pytest.approx(np.mean(scores), rel=1e-4)


def test_a_reward_without_costs_is_the_progress_alone_and_kernels_are_shared(vessel, device, rng):
    """With zero error and action costs the reward kernel holds the progress alone (its key says so): the reward is
    1.5 x the pose error removed, worked out from the poses before and after; two envs of one selection share it."""
    from ocean_warp.envs.vrx.reward_terms import vrx_reward_terms
    from ocean_warp.envs.vrx.vrx_kernels import vrx_evaluate_kernel

    reward = VrxRewardConfig(progress_scale=1.5, error_cost=0.0, action_cost=0.0, reach_bonus=0.0)
    task = VrxTaskConfig(kind="station_keeping", vessel=vessel, reward=reward)
    assert vrx_reward_terms(task) == ("flagged",)
    assert vrx_evaluate_kernel(vrx_reward_terms(task)).key == "vrx_evaluate_progress_flagged"
    env = VrxEnv(task, 3, device=device, seed=int(rng.integers(1 << 30)))
    b = env.buffers
    goal = b.route.cpu().numpy()[:, 0]
    before = pose_error(b.position.cpu().numpy() - b.origin.cpu().numpy(), yaw_of(b.orientation.cpu().numpy()), goal)
    env.step(torch.as_tensor(rng.uniform(-1, 1, (3, 3)), dtype=torch.float32, device=env.torch_device))
    after = pose_error(b.final_position.cpu().numpy() - b.origin.cpu().numpy(),
                       yaw_of(b.final_orientation.cpu().numpy()), goal)
    np.testing.assert_allclose(b.reward.cpu().numpy(), 1.5 * (before - after), rtol=1e-4, atol=1e-4)
    assert vrx_evaluate_kernel(("flagged",)) is vrx_evaluate_kernel(vrx_reward_terms(task))
    with pytest.raises(ValueError, match="unknown reward terms"):
        vrx_evaluate_kernel(("bonus",))
