"""VRX's scoring rules (envs/tasks/vrx_scoring.py): hand-computed episodes for the numpy rules, and the device
kernels against the numpy rules on seeded random trajectories."""

import math

import numpy as np
import pytest
import warp as wp

from ocean_warp.envs.tasks.vrx_scoring import (
    FollowPathRules,
    FollowPathScore,
    StationKeepingScore,
    WayfindingScore,
    follow_path_score,
    station_keeping_score,
    wayfinding_score,
)

# --- hand-computed episodes ---


def test_station_keeping_mean_of_pose_errors():
    # goal (0, 0, yaw 0). Sample 1: 3 m off, 0.5 rad heading error: 3 + 0.75^3 * 0.5 = 3 + 0.421875 * 0.5
    # = 3.2109375. Sample 2: on the goal, heading 0.2 rad off: 0 + 1 * 0.2 = 0.2. Mean: 1.70546875.
    positions = np.array([[3.0, 0.0], [0.0, 0.0]])
    assert station_keeping_score(positions, [0.5, -0.2], [0.0, 0.0, 0.0]) == pytest.approx(1.70546875, abs=1e-12)


def test_station_keeping_heading_error_wraps():
    # goal yaw 3.0, boat yaw -3.0 on the goal: the heading error is 2 pi - 6 = 0.28319, not 6.
    assert station_keeping_score([[5.0, 5.0]], [-3.0], [5.0, 5.0, 3.0]) == pytest.approx(2 * math.pi - 6.0)


def test_wayfinding_mean_of_least_errors():
    # waypoints A (0, 0, 0) and B (10, 0, pi/2). Sample 1 on A heading 0: e_A = 0. Sample 2 at (10, 2)
    # heading pi/2: e_B = 2 + 0.75^2 * 0 = 2; e_B at sample 1 was 10 + 0.75^10 * pi/2 = 10.09, e_A at sample 2
    # sqrt(104) + ... > 10. Least errors 0 and 2: score 1.
    positions = np.array([[0.0, 0.0], [10.0, 2.0]])
    assert wayfinding_score(positions, [0.0, math.pi / 2], [[0, 0, 0], [10, 0, math.pi / 2]]) == pytest.approx(1.0)


def _gates_along_x(xs, half_width=5.0):
    # Forward is +x: z x (red - green) = +x needs red - green along -y, so the red buoy lies at -y, to the
    # starboard of a boat heading +x.
    return np.array([[x, -half_width, x, half_width] for x in xs], dtype=float)


def _line(points, step=0.5):
    """Straight segments through ``points`` sampled every ``step`` metres."""
    out = [np.asarray(points[0], float)]
    for a, b in zip(points[:-1], points[1:]):
        a, b = np.asarray(a, float), np.asarray(b, float)
        n = max(1, int(round(np.linalg.norm(b - a) / step)))
        out += [a + (b - a) * (i / n) for i in range(1, n + 1)]
    return np.array(out)


def test_follow_path_in_order():
    # Gates at x = 10, 20, 30; the boat runs along y = 0. Gate 0: 10; gate 1: 10 + 1 (consecutive);
    # gate 2: 10 + 1 (consecutive) + 1 (the last gate): 33.
    assert follow_path_score(_line([(0, 0), (40, 0)]), _gates_along_x([10, 20, 30])) == pytest.approx(33.0)


def test_follow_path_backwards_does_not_count():
    # The same run through gates facing -x: gate 0 is crossed backwards (not scored, not invalidated), and no
    # later gate is watched before gate 0 is crossed forward: 0 points.
    gates = _gates_along_x([10, 20, 30])[:, [2, 3, 0, 1]]
    assert follow_path_score(_line([(0, 0), (40, 0)]), gates) == 0.0


def test_follow_path_skipped_gate_is_lost():
    # Gates at x = 10, 20, 30, 40. Gate 0 (10); around gate 1 outside its buoys (y = 20); gate 2 (10, not
    # consecutive); back around to x = 15 and through gate 1 forward (not watched any more: 0) and gate 2
    # again (already passed: 0); gate 3 (10 + 1 consecutive to gate 2 + 1 last): 32. In order it would be 44.
    path = _line([(0, 0), (15, 0), (15, 20), (25, 20), (25, 0), (35, 0), (35, 20), (15, 20), (15, 0), (45, 0)])
    assert follow_path_score(path, _gates_along_x([10, 20, 30, 40])) == pytest.approx(32.0)


def test_follow_path_gate_crossed_backwards_is_invalid():
    # Gates at x = 10, 20, 30. Gate 0 (10); around gate 1 to x = 25, back through it heading -x: invalid, and
    # the consecutive run broken; around again and through gate 2: 10, no consecutive bonus, 1 for the last
    # gate: 21.
    path = _line([(0, 0), (15, 0), (15, 20), (25, 20), (25, 0), (15, 0), (15, 20), (25, 20), (25, 0), (35, 0)])
    assert follow_path_score(path, _gates_along_x([10, 20, 30])) == pytest.approx(21.0)


def test_follow_path_collisions():
    # One gate at x = 10, samples 1 s apart along y = 0 from x = 0: gate 0 (10 + 1 last gate) at t = 10 s, which
    # ends the course. Contacts at t = 2 s (counted: 0 - 3 floored at 0), t = 5 s (within 10 s of the last
    # counted one: not counted) and t = 9 s (7 s after: not counted): 11 points.
    path = np.array([[x, 0.0] for x in range(0, 12)], float)
    contacts = np.zeros(len(path), bool)
    contacts[[2, 5, 9]] = True
    assert follow_path_score(path, _gates_along_x([10]), contacts, dt=1.0) == pytest.approx(11.0)
    # Two gates (10, 30): gate 0 at t = 10 s (10); contacts at t = 12 s (counted: 7), t = 23 s (11 s later:
    # counted: 4) and t = 30 s (7 s later: not counted); gate 1 at t = 30 s (10 + 1 consecutive + 1 last): 16.
    path = np.array([[x, 0.0] for x in range(0, 32)], float)
    contacts = np.zeros(len(path), bool)
    contacts[[12, 23, 30]] = True
    assert follow_path_score(path, _gates_along_x([10, 30]), contacts, dt=1.0) == pytest.approx(16.0)


def test_follow_path_rules_validation():
    with pytest.raises(ValueError, match="FollowPathRules.obstacle_penalty"):
        FollowPathRules(obstacle_penalty=float("nan"))
    with pytest.raises(ValueError, match="FollowPathRules.collision_buffer"):
        FollowPathRules(collision_buffer=-1.0)


# --- the kernels against the numpy rules ---


def _quats(yaws):
    q = np.zeros(yaws.shape + (4,), np.float32)
    q[..., 2] = np.sin(yaws / 2)
    q[..., 3] = np.cos(yaws / 2)
    return q


def _vec3(a, device):
    return wp.array(np.asarray(a, np.float32), dtype=wp.vec3, device=device)


def test_station_keeping_kernel_matches_numpy(device, rng):
    n, steps = 32, 60
    goals = np.column_stack([rng.uniform(-20, 20, (n, 2)), rng.uniform(-math.pi, math.pi, n)])
    xy = goals[:, None, :2] + np.cumsum(rng.normal(0, 0.5, (n, steps, 2)), axis=1)
    yaws = rng.uniform(-math.pi, math.pi, n)[:, None] + np.cumsum(rng.normal(0, 0.3, (n, steps)), axis=1)
    yaws = np.remainder(yaws + math.pi, 2 * math.pi) - math.pi
    score = StationKeepingScore(n, device)
    target = _vec3(goals, device)
    for t in range(steps):
        position = _vec3(np.column_stack([xy[:, t], np.zeros(n)]), device)
        score.update(position, wp.array(_quats(yaws[:, t]), dtype=wp.quat, device=device), target)
    final = wp.full(n, -1.0, dtype=float, device=device)
    done = np.zeros(n, bool)
    done[: n // 2] = True
    score.finish(wp.array(done, dtype=wp.bool, device=device), final)
    got = final.numpy()
    expected = [station_keeping_score(xy[i], yaws[i], goals[i]) for i in range(n // 2)]
    np.testing.assert_allclose(got[: n // 2], expected, rtol=1e-5)
    assert np.all(got[n // 2:] == -1.0)  # not ended: untouched
    np.testing.assert_array_equal(score.samples.numpy(), np.where(done, 0, steps))


def test_wayfinding_kernel_matches_numpy(device, rng):
    n, steps, r = 24, 80, 4
    origin = np.column_stack([rng.uniform(-100, 100, (n, 2)), np.zeros(n)])
    route = np.concatenate([rng.uniform(-30, 30, (n, r, 2)), rng.uniform(-math.pi, math.pi, (n, r, 1))], axis=2)
    xy = np.cumsum(rng.normal(0, 1.5, (n, steps, 2)), axis=1)
    yaws = np.remainder(np.cumsum(rng.normal(0, 0.4, (n, steps)), axis=1) + math.pi, 2 * math.pi) - math.pi
    counts = rng.integers(1, r + 1, n)
    score = WayfindingScore(n, r, device)
    score.count.assign(counts.astype(np.int32))
    route_wp = wp.array(route.astype(np.float32), dtype=wp.vec3, device=device)
    for t in range(steps):
        position = _vec3(origin + np.column_stack([xy[:, t], np.zeros(n)]), device)
        score.update(position, wp.array(_quats(yaws[:, t]), dtype=wp.quat, device=device), _vec3(origin, device),
                     route_wp)
    final = wp.zeros(n, dtype=float, device=device)
    score.finish(wp.array(np.ones(n, bool), dtype=wp.bool, device=device), final)
    expected = [wayfinding_score(xy[i], yaws[i], route[i, : counts[i]]) for i in range(n)]
    np.testing.assert_allclose(final.numpy(), expected, rtol=1e-5, atol=1e-5)


def _clear_of_gate_edges(xy, gates, margin=1e-3):
    """``xy`` (n, T, 2) with each sample moved off the lines where a gate's side changes (its own line and the
    two through its buoys) by more than ``margin`` [m]: float32 and float64 then agree on every side."""
    xy = xy.copy()
    for _ in range(3):
        red, green = gates[:, None, :, :2], gates[:, None, :, 2:]
        width = np.linalg.norm(red - green, axis=-1)
        u = (red - green) / width[..., None]
        rel = xy[:, :, None, :] - 0.5 * (red + green)
        along = rel[..., 0] * -u[..., 1] + rel[..., 1] * u[..., 0]
        across = np.abs(np.sum(rel * u, axis=-1)) - 0.5 * width
        near = ((np.abs(along) < margin) | (np.abs(across) < margin)).any(axis=2)
        if not near.any():
            return xy
        xy[near] += 5 * margin
    raise AssertionError("could not move the samples off the gates' edges")


def test_follow_path_kernel_matches_numpy(device, rng):
    n, steps, g, dt = 48, 400, 5, 0.5
    origin = np.column_stack([rng.uniform(-100, 100, (n, 2)), np.zeros(n)])
    # Gates every ~15 m along +x with a jittered centre, width and angle; their red buoys to starboard.
    centres = np.stack([10 + 15 * np.arange(g) + rng.uniform(-2, 2, (n, g)), rng.uniform(-3, 3, (n, g))], axis=2)
    half = rng.uniform(3, 6, (n, g, 1))
    angle = rng.uniform(-0.4, 0.4, (n, g))
    across = np.stack([np.sin(angle), -np.cos(angle)], axis=2)  # red - green direction, near -y
    gates = np.concatenate([centres + half * across, centres - half * across], axis=2)
    # Walks drifting +x at 0.6 m/s on average, their surge and sway swinging with random phases (backwards at
    # times, sideways by up to 1.2 m/s): crossings forward, backwards and skipped gates, and courses that differ.
    vx = 0.6 + 0.9 * np.sin(np.cumsum(rng.normal(0, 0.3, (n, steps)), axis=1) + rng.uniform(0, 2 * np.pi, (n, 1)))
    vy = 1.2 * np.sin(np.cumsum(rng.normal(0, 0.3, (n, steps)), axis=1) + rng.uniform(0, 2 * np.pi, (n, 1)))
    xy = _clear_of_gate_edges(np.cumsum(np.stack([vx, vy], axis=2) * dt, axis=1), gates)
    contact = rng.random((n, steps)) < 0.004  # a contact or two a run: the floor at 0 points seldom hides the gates
    rules = FollowPathRules(collision_buffer=4.0)
    score = FollowPathScore(n, g, device, rules)
    gates_wp = wp.array(gates.astype(np.float32), dtype=wp.vec4, device=device)
    for t in range(steps):
        position = _vec3(origin + np.column_stack([xy[:, t], np.zeros(n)]), device)
        score.update(position, _vec3(origin, device), gates_wp, wp.array(contact[:, t], dtype=wp.bool, device=device),
                     dt)
    final = wp.zeros(n, dtype=float, device=device)
    score.finish(wp.array(np.ones(n, bool), dtype=wp.bool, device=device), final)
    expected = np.array([follow_path_score(xy[i], gates[i], contact[i], dt, rules) for i in range(n)])
    np.testing.assert_allclose(final.numpy(), expected, atol=1e-4)
    assert len(np.unique(expected)) > 3  # the walks took different courses through the gates
    # reset_masked: a new course, nothing written
    score.reset_masked(wp.array(np.ones(n, bool), dtype=wp.bool, device=device))
    assert np.all(score.score.numpy() == 0.0) and np.all(score.last_crossed.numpy() == -1)


def test_follow_path_scores_each_course_over_its_own_gates(device):
    """One batch of four courses on the same four gates (x = 10, 20, 30, 40; 5 m half width) with 2, 3, 4 and 4
    gates that count (the caller's ``count`` array): every boat runs along y = 0 from x = 0 to 50, except the last,
    which stops at x = 25. Hand-computed: a course of c gates all crossed in order scores 10 c + (c - 1) bonuses
    for the consecutive gates + 1 for the last = 11 c (22, 33, 44), the gates after its last ignored; the boat
    that stops after two of four scores 10 + 11 = 21 and has not finished."""
    n, dt = 4, 0.5
    gates = np.broadcast_to(_gates_along_x([10, 20, 30, 40]), (n, 4, 4))
    count = wp.array(np.array([2, 3, 4, 4], np.int32), dtype=wp.int32, device=device)
    score = FollowPathScore(n, 4, device, count=count)
    assert score.count is count
    origin = _vec3(np.zeros((n, 3)), device)
    gates_wp = wp.array(np.ascontiguousarray(gates, dtype=np.float32), dtype=wp.vec4, device=device)
    no_contact = wp.zeros(n, dtype=wp.bool, device=device)
    for x in np.arange(0.25, 50.0, 0.5):  # off the gates' lines: each sample lies clearly before or after
        xs = np.array([x, x, x, min(x, 25.25)])
        score.update(_vec3(np.column_stack([xs, np.zeros((n, 2))]), device), origin, gates_wp, no_contact, dt)
    np.testing.assert_array_equal(score.finished.numpy(), [1, 1, 1, 0])
    final = wp.zeros(n, dtype=float, device=device)
    score.finish(wp.array(np.ones(n, bool), dtype=wp.bool, device=device), final)
    np.testing.assert_allclose(final.numpy(), [22.0, 33.0, 44.0, 21.0])


def test_a_count_array_that_does_not_fit_is_named(device):
    with pytest.raises(ValueError, match=r"count must be a \(3,\) int32 array"):
        WayfindingScore(3, 4, device, count=wp.zeros(3, dtype=float, device=device))
    with pytest.raises(ValueError, match=r"count must be a \(3,\) int32 array"):
        FollowPathScore(3, 4, device, count=wp.zeros(2, dtype=wp.int32, device=device))
