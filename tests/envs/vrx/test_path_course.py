"""VRX's follow-the-path course with buoys: the gates' buoys where the rule puts them (numpy from the gates), the
obstacles clear of every gate's opening and of the start over seeded layouts, a WAM-V driven into a buoy flagged
and its episode ended, and a batch's slice (``first_env``) sailing bit for bit as the batch does."""

import dataclasses

import numpy as np
import pytest
import torch

import ocean_warp as ow
from ocean_warp.contact import ContactConfig
from ocean_warp.envs.protocol import EnvBuffers
from ocean_warp.envs.vrx import PathCourseConfig, VrxEnv, VrxStartConfig, VrxTaskConfig

CALM = VrxStartConfig(wind_speed=(0.0, 0.0))


def path_task(**changes) -> VrxTaskConfig:
    return VrxTaskConfig(**{"kind": "follow_path", "goals": 3, "start": CALM, **changes})


def segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Horizontal distance from points p (..., 2) to the segment a-b (..., 2) [m]."""
    ab, ap = b - a, p - a
    t = np.clip((ap * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-12), 0.0, 1.0)
    return np.linalg.norm(ap - t[..., None] * ab, axis=-1)


def test_gate_buoys_sit_either_side_of_each_gate(device, rng):
    """Gate g's buoys are table rows 2g, 2g + 1: the gate's centre plus and minus the half width along the
    normal to its heading (port, then starboard); the scene's rows stand at the origin plus them."""
    config = PathCourseConfig()
    task = path_task()
    env = VrxEnv(task, 4, device=device, seed=int(rng.integers(1 << 30)))
    route = env.buffers.route.cpu().numpy()  # (N, G, 3): x, y, heading
    table = env.buffers.obstacles.cpu().numpy()
    assert table.shape == (4, 2 * 3 + config.obstacles, 4)
    normal = np.stack([-np.sin(route[..., 2]), np.cos(route[..., 2])], axis=-1)
    np.testing.assert_allclose(table[:, 0:6:2, :2], route[..., :2] + 0.5 * task.gate_width * normal, atol=1e-4)
    np.testing.assert_allclose(table[:, 1:6:2, :2], route[..., :2] - 0.5 * task.gate_width * normal, atol=1e-4)
    np.testing.assert_array_equal(table[:, :6, 2], np.float32(config.gate_buoy_radius))
    np.testing.assert_array_equal(table[:, :6, 3], 1.0)  # buoys
    course = env.obstacles
    anchor = course.scene.anchor.numpy()
    first_row = course.first_row.numpy()
    origin = env.buffers.origin.cpu().numpy()
    for e in range(4):
        np.testing.assert_allclose(anchor[first_row[e]:first_row[e] + 6, :2], origin[e, :2] + table[e, :6, :2],
                                   atol=1e-3)


def test_obstacles_never_block_a_gate_opening(device):
    """Over seeded layouts (5 seeds, 8 environments, several episodes each), every obstacle kept stands with its
    surface at least the opening clearance from every gate's opening (the segment between its buoys' centres),
    the start clearance from the start and the spacing from the other obstacles; most are kept."""
    config = PathCourseConfig(obstacles=4, opening_clearance=3.0, start_clearance=5.0, spacing=2.0)
    env = VrxEnv(path_task(path_course=config), 8, device=device, seed=1)
    kept = tried = 0
    for seed in range(5):
        env.reset(seed=seed)
        table = env.buffers.obstacles.cpu().numpy()
        obstacles = table[:, 6:]
        placed = obstacles[..., 3] > 0
        kept += int(placed.sum())
        tried += placed.size
        for e in range(8):
            centres = obstacles[e, placed[e], :2].astype(np.float64)
            radius = obstacles[e, placed[e], 2].astype(np.float64)
            for g in range(3):
                port, starboard = table[e, 2 * g, :2], table[e, 2 * g + 1, :2]
                gap = segment_distance(centres, port[None], starboard[None]) - radius
                assert np.all(gap >= config.opening_clearance - 1e-3), (seed, e, g, gap)
            assert np.all(np.linalg.norm(centres, axis=1) - radius >= config.start_clearance - 1e-3)
            pairs = np.linalg.norm(centres[:, None] - centres[None], axis=-1) - radius[:, None] - radius[None]
            assert np.all(pairs[~np.eye(len(centres), dtype=bool)] >= config.spacing - 1e-3)
        # Parked rows are zeros in the table and sit far below the sea in the scene.
        assert np.all(obstacles[~placed] == 0.0)
    assert kept > tried // 2, f"only {kept} of {tried} obstacles found a place"


def yaw_of(q: np.ndarray) -> np.ndarray:
    return np.arctan2(2 * (q[..., 3] * q[..., 2] + q[..., 0] * q[..., 1]), 1 - 2 * (q[..., 1] ** 2 + q[..., 2] ** 2))


def capsule_gap(buoy: np.ndarray, position: np.ndarray, q: np.ndarray, shape) -> np.ndarray:
    """Horizontal distance from buoy centres (N, 2) to the boats' capsule axes [m] (numpy)."""
    axis = np.stack([np.cos(yaw_of(q)), np.sin(yaw_of(q))], axis=-1)
    return segment_distance(buoy, position[:, :2] + shape.stern[0] * axis, position[:, :2] + shape.bow[0] * axis)


def test_a_boat_driven_into_a_buoy_is_flagged_and_its_episode_ends(device, rng):
    """A buoy put 3 m ahead of each WAM-V's bow (beyond its capsule), both thrusters full ahead, contact that
    flags without pushing: the boat is flagged COLLIDED in the decision its capsule (numpy, from the poses) comes
    within reach of the buoy (the capsule's radius plus the buoy's) and not before; its episode ends there
    (terminated, the flagged penalty in its reward)."""
    contact = ContactConfig(stiffness=0.0, damping=0.0)
    task = path_task(path_course=PathCourseConfig(obstacles=0, contact=contact))
    n = 2
    env = VrxEnv(task, n, device=device, seed=int(rng.integers(1 << 30)))
    shape = task.vessel.collision_shape()
    b, course = env.buffers, env.obstacles
    position, q = b.position.cpu().numpy(), b.orientation.cpu().numpy()
    ahead = np.stack([np.cos(yaw_of(q)), np.sin(yaw_of(q))], axis=1)
    buoy_radius = task.path_course.gate_buoy_radius
    reach = shape.radius + buoy_radius
    buoy = position[:, :2] + (shape.bow[0] + reach + 3.0) * ahead
    # Move each environment's first gate buoy there (the scene row's anchor: the buoy then rides the sea), and its
    # other buoys 500 m off (a later gate's may lie near the start), so that the planted one is the only one near.
    anchor, rows = course.scene.anchor.numpy(), course.first_row.numpy()
    for k in range(1, 2 * task.goals):
        anchor[rows + k, :2] = position[:, :2] + 500.0
    anchor[rows, :2] = buoy
    course.scene.anchor.assign(anchor)
    course.scene.refresh()  # the rows contact reads follow their anchors now, not at the next decision's end
    full = torch.ones((n, env.num_actions), device=env.torch_device)
    ended = np.zeros(n, dtype=bool)
    for _ in range(40):
        before = capsule_gap(buoy, b.position.cpu().numpy(), b.orientation.cpu().numpy(), shape)
        env.step(full)
        after = capsule_gap(buoy, b.final_position.cpu().numpy(), b.final_orientation.cpu().numpy(), shape)
        done = b.done.cpu().numpy() & ~ended
        for e in np.flatnonzero(done):
            assert b.terminated.cpu().numpy()[e]
            assert b.final_status.cpu().numpy()[e] & ow.BoatStatus.COLLIDED
            assert b.reward.cpu().numpy()[e] < -task.reward.flagged_penalty + 2.0 * task.reward.reach_bonus
            assert before[e] > reach - 0.05 and after[e] < reach + 0.05, (before[e], after[e], reach)
        for e in np.flatnonzero(~done & ~ended):
            assert after[e] > reach - 0.05, "within reach but not flagged"
        ended |= done
        if ended.all():
            break
    assert ended.all(), "every boat reached its buoy"


def test_a_slice_of_the_batch_sails_as_the_batch():
    """VrxEnv(first_env=3) of 2 environments is environments 3 and 4 of a batch of 5, buoys included, through
    episode ends (a 2 s time limit) and a re-seeded reset."""
    task = path_task(episode_time=2.0)
    whole = VrxEnv(task, 5, device="cpu", seed=11)
    tail = VrxEnv(task, 2, device="cpu", seed=11, first_env=3)
    generator = torch.Generator().manual_seed(1)
    ends = 0
    for step in range(9):
        if step == 6:
            whole.reset(seed=4)
            tail.reset(seed=4)
        actions = 2.0 * torch.rand(5, whole.num_actions, generator=generator) - 1.0
        whole.step(actions)
        tail.step(actions[3:])
        ends += int(whole.buffers.done.sum())
        for field in dataclasses.fields(EnvBuffers):
            a, b = getattr(whole.buffers, field.name)[3:], getattr(tail.buffers, field.name)
            assert a.shape == b.shape and torch.equal(torch.nan_to_num(a, nan=0.0), torch.nan_to_num(b, nan=0.0)), \
                (step, field.name)
    assert ends >= 5


def test_a_bad_path_course_is_named():
    with pytest.raises(ValueError, match="PathCourseConfig.obstacle_radius"):
        PathCourseConfig(obstacle_radius=0.0)
    with pytest.raises(ValueError, match="VrxTaskConfig.path_course must be a PathCourseConfig"):
        path_task(path_course=3)
