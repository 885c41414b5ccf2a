"""The PID station keeper (envs/controllers/station_keeping.py) on an independent 3-DOF WAM-V (wamv_plant.py):
fixed and azimuth thrusters reach and hold seeded random goal poses, with and without a steady push."""

import math

import numpy as np
import pytest
import torch

from ocean_warp.envs.controllers.station_keeping import StationKeepingConfig, StationKeepingController
from ocean_warp.envs.controllers.thrust_allocation import ThrusterLayout, azimuth_thrust, differential_thrust

from .wamv_plant import Plant, fake_env, run

HOLD_FROM, END = 60.0, 90.0
"""The pose must be held from 60 s on; the runs end at 90 s."""


def _sail(start, goal, num_actions, disturbance=None):
    """Errors (T, N) in position [m] and heading [rad] at each decision, and the plant at the end."""
    plant = Plant(start, disturbance=disturbance)
    env = fake_env(plant, num_actions, goal)
    controller = StationKeepingController()
    controller.reset(env)
    distance, heading = [], []

    def record(env, plant):
        distance.append(np.hypot(*(plant.eta[:, :2] - goal[:, :2]).T))
        heading.append(np.abs(np.remainder(plant.eta[:, 2] - goal[:, 2] + math.pi, 2 * math.pi) - math.pi))

    run(env, plant, controller, END, on_decision=record)
    return np.array(distance), np.array(heading), env.decision_period, plant


def _held(distance, heading, period):
    after = int(round(HOLD_FROM / period))
    return distance[after:].max(), np.degrees(heading[after:].max())


def _goals_away(rng, n, low=6.0, high=12.0):
    start = np.column_stack([rng.uniform(-5, 5, (n, 2)), rng.uniform(-math.pi, math.pi, n)])
    bearing, distance = rng.uniform(-math.pi, math.pi, n), rng.uniform(low, high, n)
    goal = np.column_stack([start[:, 0] + distance * np.cos(bearing), start[:, 1] + distance * np.sin(bearing),
                            rng.uniform(-math.pi, math.pi, n)])
    return start, goal


@pytest.mark.parametrize("num_actions", [2, 4])
def test_reaches_and_holds_a_random_goal_pose(rng, num_actions):
    start, goal = _goals_away(rng, 16)
    distance, heading, period, plant = _sail(start, goal, num_actions)
    worst_distance, worst_heading = _held(distance, heading, period)
    assert worst_distance < 1.0 and worst_heading < 10.0, (worst_distance, worst_heading)


def test_fixed_thrusters_hold_against_a_push_along_the_goal_heading(rng):
    # Fixed thrusters have no sideways force: the push is along the goal's heading, ahead or astern, and the
    # boats start on their goal poses. (Pushed while they come in from elsewhere, some drift up to about 1.3 m
    # off the goal's axis as they turn onto it, which they cannot take back: see the controller's module.)
    n = 16
    goal = np.column_stack([rng.uniform(-20, 20, (n, 2)), rng.uniform(-math.pi, math.pi, n)])
    start = goal.copy()
    push = 20.0 * rng.choice([-1.0, 1.0], n)[:, None] * np.column_stack([np.cos(goal[:, 2]), np.sin(goal[:, 2])])
    distance, heading, period, plant = _sail(start, goal, 2, push)
    worst_distance, worst_heading = _held(distance, heading, period)
    assert worst_distance < 1.0 and worst_heading < 10.0, (worst_distance, worst_heading)
    # The surge integral takes the push: without it, 20 N against the 100 N/m surge gain would leave the boats
    # 0.2 m off along the goal's heading.
    along = np.sum((plant.eta[:, :2] - goal[:, :2]) * np.column_stack([np.cos(goal[:, 2]), np.sin(goal[:, 2])]), 1)
    assert np.abs(along).max() < 0.05


def test_azimuth_thrusters_hold_against_a_push_from_anywhere(rng):
    n = 16
    start, goal = _goals_away(rng, n)
    direction = rng.uniform(-math.pi, math.pi, n)
    push = 20.0 * np.column_stack([np.cos(direction), np.sin(direction)])
    distance, heading, period, plant = _sail(start, goal, 4, push)
    worst_distance, worst_heading = _held(distance, heading, period)
    assert worst_distance < 1.0 and worst_heading < 10.0, (worst_distance, worst_heading)
    # the integrals take the push: 20 N against the 100 N/m gains alone would leave 0.2 m
    assert distance[-1].max() < 0.05


def test_plant_signs():
    # Left thrust alone: the boat turns to starboard (yaw rate < 0) and moves ahead.
    plant = Plant([[0.0, 0.0, 0.0]])
    for _ in range(50):
        plant.step(np.array([[1.0, 0.0]]), 0.02)
    assert plant.nu[0, 2] < 0.0 and plant.nu[0, 0] > 0.0
    # Both thrust angles to port (azimuth): the stern is pushed to port, the bow turns to starboard.
    plant = Plant([[0.0, 0.0, 0.0]])
    for _ in range(50):
        plant.step(np.array([[1.0, 1.0, 0.5, 0.5]]), 0.02)
    assert plant.nu[0, 2] < 0.0 and plant.nu[0, 1] > 0.0


@pytest.mark.parametrize("num_actions", [2, 4])
def test_turns_toward_the_goal_heading(num_actions):
    # On the goal, heading 0.5 rad to port of the goal's: the controller turns to starboard (left thrust above
    # the right; with azimuth thrusters, their net moment negative in the plant).
    plant = Plant([[0.0, 0.0, 0.5]])
    env = fake_env(plant, num_actions, [[0.0, 0.0, 0.0]])
    controller = StationKeepingController()
    controller.reset(env)
    controller.act(env)
    actions = env.buffers.actions.numpy()
    assert plant.forces(actions)[0, 2] < 0.0
    if num_actions == 2:
        assert actions[0, 0] > actions[0, 1]


def test_allocation_gives_what_was_asked():
    # Within the thrusters' limits, the allocations give the asked force and moment back in the plant.
    layout = ThrusterLayout(x=-2.37, half_spacing=1.03, azimuth_limit=math.pi / 2)
    plant = Plant([[0.0, 0.0, 0.0]] * 3)
    surge, sway, moment = torch.tensor([80.0, -40.0, 0.0]), torch.tensor([30.0, -20.0, 0.0]), torch.tensor(
        [50.0, -60.0, 100.0])
    np.testing.assert_allclose(plant.forces(azimuth_thrust(surge, sway, moment, layout).numpy()),
                               np.column_stack([surge, sway, moment]), atol=1e-3)
    got = plant.forces(differential_thrust(surge, moment, layout).numpy())
    np.testing.assert_allclose(got[:, [0, 2]], np.column_stack([surge, moment]), atol=1e-3)
    # A moment beyond the reserve with full surge asked: the moment is kept, the surge cut.
    got = plant.forces(differential_thrust(torch.tensor([500.0]), torch.tensor([150.0]), layout).numpy())
    assert got[0, 2] == pytest.approx(150.0, abs=1e-3) and got[0, 0] < 500.0


def test_config_validation():
    with pytest.raises(ValueError, match="StationKeepingConfig.release_radius must be >= arrive_radius"):
        StationKeepingConfig(arrive_radius=5.0, release_radius=4.0)
    with pytest.raises(ValueError, match="StationKeepingConfig.heading_p"):
        StationKeepingConfig(heading_p=float("nan"))
    with pytest.raises(ValueError, match="ThrusterLayout.azimuth_limit"):
        ThrusterLayout(azimuth_limit=4.0)


def test_rejects_a_task_of_other_actions():
    plant = Plant([[0.0, 0.0, 0.0]])
    env = fake_env(plant, 3, [[1.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="must be 2 .* or 4"):
        StationKeepingController().reset(env)
