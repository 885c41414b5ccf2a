"""Line-of-sight guidance (envs/controllers/los_guidance.py) on an independent 3-DOF WAM-V (wamv_plant.py):
convergence onto a straight leg, seeded random routes sailed to their end, and the commands' signs."""

import math

import numpy as np
import pytest
import torch

from ocean_warp.envs.controllers.los_guidance import LosGuidanceConfig, LosGuidanceController

from .wamv_plant import Plant, fake_env, run


def _cross_track(positions, a, b):
    """Signed distance [m] of (N, 2) ``positions`` from the lines a -> b (positive to port)."""
    d = (b - a) / np.linalg.norm(b - a, axis=1, keepdims=True)
    rel = positions - a
    return d[:, 0] * rel[:, 1] - d[:, 1] * rel[:, 0]


@pytest.mark.parametrize("num_actions", [2, 4])
def test_converges_onto_a_straight_leg(rng, num_actions):
    # The boats sail the second leg of a route (waypoint_index 1): from route[0] = (0, 0) to route[1], 300 m
    # away in a random direction; they start 5 to 15 m off the line on either side, heading up to 60 deg off it.
    n = 16
    direction = rng.uniform(-math.pi, math.pi, n)
    route = np.zeros((n, 2, 3))
    route[:, 1, :2] = 300.0 * np.column_stack([np.cos(direction), np.sin(direction)])
    offset = rng.uniform(5, 15, n) * rng.choice([-1.0, 1.0], n)
    along = rng.uniform(0, 20, n)
    start = np.column_stack([along * np.cos(direction) - offset * np.sin(direction),
                             along * np.sin(direction) + offset * np.cos(direction),
                             direction + rng.uniform(-math.pi / 3, math.pi / 3, n)])
    plant = Plant(start)
    env = fake_env(plant, num_actions, route[:, 1], route=route)
    env.buffers.waypoint_index.fill_(1)
    controller = LosGuidanceController()
    controller.reset(env)
    errors = []
    run(env, plant, controller, 120.0, on_decision=lambda env, plant: errors.append(
        _cross_track(plant.eta[:, :2], route[:, 0, :2], route[:, 1, :2])))
    errors = np.abs(np.array(errors))
    after = int(round(60.0 / env.decision_period))
    assert errors[after:].max() < 0.5, errors[after:].max()
    assert errors[0].min() > 4.0  # they did start off the line


@pytest.mark.parametrize("num_actions", [2, 4])
def test_reaches_every_waypoint_of_a_random_route(rng, num_actions):
    # Routes of 4 waypoints from the env's origin, legs 20 to 40 m turning up to 120 deg; a waypoint counts
    # within 3 m, then the next is the target (as the env does).
    n, count, radius = 12, 4, 3.0
    heading = rng.uniform(-math.pi, math.pi, n)
    points, here = [], np.zeros((n, 2))
    for _ in range(count):
        heading = heading + rng.uniform(-2 * math.pi / 3, 2 * math.pi / 3, n)
        here = here + rng.uniform(20, 40, n)[:, None] * np.column_stack([np.cos(heading), np.sin(heading)])
        points.append(here)
    route = np.concatenate([np.stack(points, axis=1), np.zeros((n, count, 1))], axis=2)
    origin = rng.uniform(-50, 50, (n, 2))
    start = np.column_stack([origin, rng.uniform(-math.pi, math.pi, n)])
    plant = Plant(start)
    env = fake_env(plant, num_actions, route[:, 0] + np.column_stack([origin, np.zeros(n)]), route=route)
    env.buffers.origin[:, :2] = torch.tensor(origin, dtype=torch.float32)
    controller = LosGuidanceController()
    controller.reset(env)
    reached = np.zeros(n, int)
    closest = np.full((n, count), np.inf)

    def advance(env, plant):
        here = plant.eta[:, :2] - origin
        for i in range(n):
            if reached[i] < count:
                closest[i, reached[i]] = min(closest[i, reached[i]], np.linalg.norm(here[i] - route[i, reached[i], :2]))
                if closest[i, reached[i]] < radius:
                    reached[i] += 1
        index = np.minimum(reached, count - 1)
        env.buffers.waypoint_index.copy_(torch.tensor(index, dtype=torch.int32))
        env.buffers.target[:, :2] = torch.tensor(route[np.arange(n), index, :2] + origin, dtype=torch.float32)

    run(env, plant, controller, 300.0, on_decision=advance)
    assert np.all(reached == count), (reached, closest)


def test_steers_toward_a_leg_to_starboard():
    # A boat heading +x, its leg running along y = -10 (to starboard): it turns to starboard, the left
    # thruster above the right, and the plant's yaw moment of those actions is negative.
    route = np.array([[[0.0, -10.0, 0.0], [200.0, -10.0, 0.0]]])
    plant = Plant([[0.0, 0.0, 0.0]])
    env = fake_env(plant, 2, route[:, 1], route=route)
    env.buffers.waypoint_index.fill_(1)
    controller = LosGuidanceController()
    controller.reset(env)
    controller.act(env)
    actions = env.buffers.actions.numpy()
    assert actions[0, 0] > actions[0, 1]
    assert plant.forces(actions)[0, 2] < 0.0


def test_config_validation():
    with pytest.raises(ValueError, match="LosGuidanceConfig.lookahead"):
        LosGuidanceConfig(lookahead=0.0)
    with pytest.raises(ValueError, match="LosGuidanceConfig.speed_i"):
        LosGuidanceConfig(speed_i=-1.0)
