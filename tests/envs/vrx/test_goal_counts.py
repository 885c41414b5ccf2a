"""Each VRX episode's own count of goals or gates (``VrxTaskConfig.goals`` a range): the counts drawn within it and
covering it, an episode ended after its own last goal with the last one observed past it, VRX's score over the
episode's own goals (numpy), and the path's buoys kept clear of the start over many seeded draws."""

import numpy as np
import pytest
import torch

from ocean_warp.eboat import EBoatVessel
from ocean_warp.envs.registration import make_task_config
from ocean_warp.envs.vrx import PathCourseConfig, VrxEnv, VrxStartConfig, VrxTaskConfig
from tests.envs.vrx.vrx_poses import StepPoses, pose_error, yaw_of


@pytest.fixture(scope="module")
def vessel():
    return EBoatVessel()


def test_counts_are_drawn_in_the_range_and_cover_it(vessel, device):
    """Over 4 seeds of 64 environments, ``goals=(2, 5)`` draws every count from 2 to 5, each about a quarter of the
    time (256 draws: each count between 15 % and 35 %); the route's columns from the count on repeat the last
    goal, and the first goals are those of the fixed count 5 on the same seed (the count is drawn last)."""
    n = 64
    ranged = VrxEnv(VrxTaskConfig(kind="wayfinding", goals=(2, 5), vessel=vessel), n, device=device, seed=0)
    fixed = VrxEnv(VrxTaskConfig(kind="wayfinding", goals=5, vessel=vessel), n, device=device, seed=0)
    counts = []
    for seed in range(4):
        ranged.reset(seed=seed)
        fixed.reset(seed=seed)
        count = ranged.goal_count.numpy()
        assert count.min() >= 2 and count.max() <= 5
        np.testing.assert_array_equal(fixed.goal_count.numpy(), 5)
        route, full = ranged.buffers.route.cpu().numpy(), fixed.buffers.route.cpu().numpy()
        for e in range(n):
            c = count[e]
            np.testing.assert_array_equal(route[e, :c], full[e, :c])
            np.testing.assert_array_equal(route[e, c:], np.broadcast_to(route[e, c - 1], (5 - c, 3)))
        counts.append(count)
    share = np.bincount(np.concatenate(counts), minlength=6)[2:] / (4 * n)
    assert np.all((share > 0.15) & (share < 0.35)), share


def test_an_episode_ends_after_its_own_last_goal(vessel, device, rng):
    """With a reach error no pose misses, each decision reaches one goal: an episode of c goals ends, a success,
    after exactly c decisions with c goals reached, whatever the others' counts; until then the policy sees the
    next goal, or the current one again at the last (route column min(index + 1, c - 1), from numpy)."""
    n = 32
    task = VrxTaskConfig(kind="wayfinding", goals=(1, 6), vessel=vessel, reach_error=1e4, lost_distance=1e4,
                         episode_time=20.0)
    env = VrxEnv(task, n, device=device, seed=int(rng.integers(1 << 30)))
    b = env.buffers
    count = env.goal_count.numpy().copy()
    assert len(np.unique(count)) >= 4
    zeros = torch.zeros((n, 3), device=env.torch_device)
    first = np.ones(n, bool)  # still in its first episode
    for decision in range(1, 7):
        route = b.route.cpu().numpy().copy()
        env.step(zeros)
        ended = b.done.cpu().numpy() & first
        np.testing.assert_array_equal(ended, first & (count == decision))
        np.testing.assert_array_equal(b.terminated.cpu().numpy()[ended], True)
        np.testing.assert_array_equal(b.final_length.cpu().numpy()[ended], decision)
        np.testing.assert_array_equal(b.final_waypoints.cpu().numpy()[ended], decision)
        np.testing.assert_array_equal(b.final_success.cpu().numpy()[ended], 1.0)
        first &= ~ended
        index = b.waypoint_index.cpu().numpy()
        np.testing.assert_array_equal(index[first], decision)
        following = route[np.arange(n), np.minimum(index + 1, count - 1)]
        local = b.position.cpu().numpy() - b.origin.cpu().numpy()
        yaw = yaw_of(b.orientation.cpu().numpy())
        ahead = np.cos(yaw) * (following[:, 0] - local[:, 0]) + np.sin(yaw) * (following[:, 1] - local[:, 1])
        np.testing.assert_allclose(b.policy_obs.cpu().numpy()[first, 8], np.clip(ahead / 10, -5, 5)[first],
                                   atol=2e-4)
    assert not first.any()


def test_wayfinding_score_is_the_mean_over_the_episodes_own_goals(vessel, device, rng):
    """Goals 30-40 m apart (none reached): every episode runs to the time limit, and ``final_score`` equals the
    mean over its own c goals of the least pose error to each (numpy, from every physics step's pose), c differing
    from one environment of the batch to the next."""
    task = VrxTaskConfig(kind="wayfinding", goals=(1, 4), vessel=vessel, episode_time=3.0,
                         start=VrxStartConfig(goal_distance=(30.0, 40.0), goal_spacing=(30.0, 40.0)))
    n = 12
    env = VrxEnv(task, n, device=device, seed=int(rng.integers(1 << 30)))
    b = env.buffers
    route = b.route.cpu().numpy().copy()
    count = env.goal_count.numpy().copy()
    assert len(np.unique(count)) >= 3
    poses = StepPoses(env)
    env.attach(poses)
    least = np.full((n, 4), np.inf)
    for _ in range(task.max_episode_length):
        env.step(torch.as_tensor(rng.uniform(-1, 1, (n, 3)), dtype=torch.float32, device=env.torch_device))
        local, yaw = poses.local(b.origin.cpu().numpy())
        errors = np.stack([pose_error(local, yaw, route[:, g]) for g in range(4)], axis=-1)  # (steps, N, 4)
        least = np.minimum(least, errors.min(axis=0))
    assert b.done.cpu().numpy().all()
    expected = [least[e, :count[e]].mean() for e in range(n)]
    np.testing.assert_allclose(b.final_score.cpu().numpy(), expected, rtol=2e-4, atol=2e-4)


def test_every_buoy_of_the_path_is_clear_of_the_start(device):
    """Short legs turning any way bring later gates back past the start: over 12 seeds of 64 environments (768
    episodes of 2 to 8 gates), every buoy's surface, gate's or obstacle's, lies at least ``start_clearance`` from
    the start, and every leg keeps its drawn length (the gates are drawn again or turned, never moved nearer)."""
    course = PathCourseConfig(obstacles=3, start_clearance=4.0)
    start = VrxStartConfig(goal_distance=(6.0, 8.0), goal_spacing=(8.0, 10.0), leg_turn_deg=(-180.0, 180.0),
                           wind_speed=(0.0, 0.0))
    task = VrxTaskConfig(kind="follow_path", goals=(2, 8), gate_width=10.0, start=start, path_course=course)
    env = VrxEnv(task, 64, device=device, seed=0)
    nearest = np.inf
    for seed in range(12):
        env.reset(seed=seed)
        table = env.buffers.obstacles.cpu().numpy()
        count = env.goal_count.numpy()
        buoys = table[..., 3] != 0
        assert np.all(buoys.sum(axis=1) >= 2 * count)
        gap = np.linalg.norm(table[..., :2], axis=-1) - table[..., 2]
        nearest = min(nearest, gap[buoys].min())
        route = env.buffers.route.cpu().numpy()
        legs = np.linalg.norm(np.diff(route[..., :2], axis=1), axis=-1)
        for e in range(64):
            assert np.all((legs[e, :count[e] - 1] >= 8.0 - 1e-3) & (legs[e, :count[e] - 1] <= 10.0 + 1e-3))
    assert nearest >= course.start_clearance - 1e-3, nearest


def test_the_registered_tasks_draw_vrxs_counts():
    assert make_task_config("WamvWayfinding-v0").goals == (3, 5)
    assert make_task_config("WamvFollowPath-v0").goals == (3, 9)
    assert make_task_config("WamvStationKeeping-v0").goal_range == (1, 1)


@pytest.mark.parametrize("changes, words", [
    ({"goals": (4, 2)}, "goals must have low <= high"), ({"goals": (0, 3)}, "goals must be an integer in"),
    ({"goals": (1, 2, 3)}, "goals must be a count or a"), ({"goals": 2.5}, "goals must be an integer in"),
    ({"kind": "station_keeping", "goals": (1, 2)}, "goals must be 1 for station keeping"),
    ({"gate_width": 8.0}, "must leave its buoys' surfaces at least path_course.start_clearance")])
def test_bad_counts_and_clearances_name_what_is_wrong(vessel, changes, words):
    fields = {"kind": "follow_path", "vessel": vessel, **changes}
    with pytest.raises(ValueError, match=words) as error:
        VrxTaskConfig(**fields)
    assert "\n" not in str(error.value)
