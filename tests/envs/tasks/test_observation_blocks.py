"""The observation blocks (``envs/tasks/observation_blocks.py``) against the kernels that write the observation:
every registered task's declared layout has the kernels' count of values, under unique names, and named columns
hold what their names say, computed here in numpy from an environment's state."""

import dataclasses
import math

import numpy as np
import pytest
import torch

import ocean_warp as ow
from ocean_warp.eboat import EBoatConfig
from ocean_warp.envs import SailingEnv, StartConfig, WaypointConfig, WaypointPlusConfig
from ocean_warp.envs.registration import TASK_IDS, make_task_config
from ocean_warp.envs.tasks.observation_blocks import ObservationBlock, policy_blocks, policy_layout
from ocean_warp.envs.tasks.task_kernels import policy_observation_count

CALM_START = StartConfig(heading_deg=(-40.0, 40.0), heading_step_deg=0.0, wind_speed=(5.0, 5.0),
                         wind_direction_deg=(90.0, 90.0), wind_direction_step_deg=0.0)
"""Starts that leave every boat sailing for a few decisions (a beam reach, headings around the waypoint's)."""


def tiny(task):
    """``task`` on a small flat sea with the four-point buoyancy (quick on the CPU) and calm starts."""
    ocean = ow.OceanConfig(tile_size=256.0, resolution=16, significant_wave_height=0.0)
    simulator = dataclasses.replace(task.simulator, boat=EBoatConfig(hydrostatics="points"), ocean=ocean)
    return dataclasses.replace(task, simulator=simulator, start=CALM_START)


@pytest.mark.parametrize("task_id", [name for name in TASK_IDS if name.startswith("EBoat")])
def test_every_task_declares_each_value_of_its_observation_once(task_id):
    task = make_task_config(task_id)
    layout = policy_layout(task)
    assert len(layout) == policy_observation_count(task)
    names = [column.name for column in layout]
    assert len(set(names)) == len(names), f"{task_id}: repeated column names"
    assert all(column.name.isidentifier() and column.unit for column in layout)
    blocks = [block.name for block in policy_blocks(task)]
    assert blocks == [task.observation.value] + (["reef"] if task.reef is not None else []) \
        + (["lidar"] if task.lidar is not None else [])


def test_the_avoid_task_appends_the_reef_level_then_sectors_around_the_bow():
    task = make_task_config("EBoatAvoid-v0")
    names = [column.name for column in policy_layout(task)]
    first = len(policy_blocks(task)[0])
    assert names[first] == "reef_level"
    assert names[first + 1:] == [f"lidar_sector_{k}" for k in range(task.lidar_sectors)]


def test_a_block_refuses_repeated_names():
    with pytest.raises(ValueError, match="ObservationBlock 'x': column names must be unique"):
        ObservationBlock("x", (("a", "[m]"), ("a", "[s]")))


def _heading(orientation: np.ndarray) -> np.ndarray:
    """Yaw [rad] of body -> world quaternions (x, y, z, w): the angle of the body's x axis in the world."""
    x, y, z, w = orientation.T.astype(np.float64)
    forward_x = 1.0 - 2.0 * (y * y + z * z)
    forward_y = 2.0 * (x * y + w * z)
    return np.arctan2(forward_y, forward_x)


def _columns(env) -> dict[str, np.ndarray]:
    names = [column.name for column in policy_layout(env.task)]
    observation = env.buffers.policy_obs.cpu().numpy()
    return {name: observation[:, k] for k, name in enumerate(names)}


def test_seed_columns_hold_the_distance_bearing_and_speed_of_the_state(rng):
    env = SailingEnv(tiny(WaypointConfig()), 6, device="cpu", seed=int(rng.integers(1 << 30)))
    b = env.buffers
    # A boat starts its leg where it is after the reset: the leg's length is the distance then.
    leg = np.linalg.norm((b.target - b.position).cpu().numpy()[:, :2], axis=1)
    for _ in range(3):
        env.step(torch.from_numpy(rng.uniform(-1.0, 1.0, (6, 3)).astype(np.float32)))
        assert not b.done.any() and not b.waypoint_index.any(), "the check needs every boat on its first leg"
    to_target = (b.target - b.position).cpu().numpy()[:, :2].astype(np.float64)
    distance = np.linalg.norm(to_target, axis=1)
    bearing = np.angle(np.exp(1j * (np.arctan2(to_target[:, 1], to_target[:, 0])
                                    - _heading(b.orientation.cpu().numpy()))))
    columns = _columns(env)
    lost = leg + env.task.lost_margin
    np.testing.assert_allclose(columns["distance_to_waypoint"], np.clip(2.0 * distance / lost - 1.0, -1, 1),
                               atol=1e-5)
    np.testing.assert_allclose(columns["bearing_to_waypoint"], np.clip(np.degrees(bearing) / 180.0, -1, 1),
                               atol=1e-5)
    speed = b.velocity.cpu().numpy()[:, 0]
    np.testing.assert_allclose(columns["speed_ahead"], np.clip(speed / 5.0 - 1.0, -1, 1), atol=1e-5)
    assert np.ptp(distance) > 0.1 and np.ptp(bearing) > math.radians(10.0), "the boats must differ to tell apart"


def test_plus_columns_hold_the_last_actions_clipped(rng):
    env = SailingEnv(tiny(WaypointPlusConfig()), 4, device="cpu", seed=int(rng.integers(1 << 30)))
    actions = rng.uniform(-1.5, 1.5, (4, 3)).astype(np.float32)
    env.step(torch.from_numpy(actions))
    assert not env.buffers.done.any()
    columns = _columns(env)
    for k, name in enumerate(("last_action_propeller", "last_action_sheet", "last_action_rudder")):
        np.testing.assert_array_equal(columns[name], np.clip(actions[:, k], -1.0, 1.0))
