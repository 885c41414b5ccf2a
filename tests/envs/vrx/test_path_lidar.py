"""The follow-the-path policy sees the buoys through a lidar: its observation's sectors against the buoys'
table in numpy (calm water: a buoy well inside a sector and in range shows there at its distance, a sector with
no buoy near its span reads 1), the layout naming every column, and a bad sector count named."""

import math

import numpy as np
import pytest
import torch

from ocean_warp.envs.vrx import PathCourseConfig, VrxEnv, VrxStartConfig, VrxTaskConfig
from ocean_warp.envs.vrx.observation_blocks import vrx_policy_layout
from ocean_warp.envs.vrx.task_config import wamv_vessel
from ocean_warp.envs.vrx.tasks import follow_path_task, path_lidar
from ocean_warp.envs.vrx.vrx_kernels import POLICY_BASE, PRIVILEGED

SECTORS = 24


def lidar_task() -> VrxTaskConfig:
    course = PathCourseConfig(obstacles=6, lidar=path_lidar(), lidar_sectors=SECTORS, contact=None)
    return VrxTaskConfig(kind="follow_path", goals=3, vessel=wamv_vessel(0.0),
                         start=VrxStartConfig(wind_speed=(0.0, 0.0)), path_course=course)


def buoys_seen_from(table: np.ndarray, sensor_xy: np.ndarray, yaw: float):
    """The buoy rows of ``table`` (K, 4: x, y, radius, kind) seen from ``sensor_xy`` [m] with the boat at ``yaw``
    [rad]: each centre's bearing from the bow [rad, + to port, in -pi .. pi], its angular half width [rad], the
    horizontal distance to it [m] and the radius [m]."""
    rows = table[table[:, 3] > 0]
    offset = rows[:, :2] - sensor_xy
    distance = np.hypot(offset[:, 0], offset[:, 1])
    bearing = (np.arctan2(offset[:, 1], offset[:, 0]) - yaw + math.pi) % (2 * math.pi) - math.pi
    half = np.arcsin(np.clip(rows[:, 2] / np.maximum(distance, 1e-6), 0.0, 1.0))
    return bearing, half, distance, rows[:, 2]


def test_sectors_show_the_buoys_of_the_table(device, rng):
    """Calm water, no wind: after each of a few decisions, a sector (k spans azimuths -pi + k 15 deg to 15 deg
    more) holding a buoy within 25 m a degree and its angular size inside its span reads no more than that buoy's
    distance + 0.3 m and no less than the nearest surface of any buoy reaching into the span, / 30 m; a sector
    that no buoy within 31 m reaches reads exactly 1. The critic holds the same values after its privileged
    ones."""
    env = VrxEnv(lidar_task(), 6, device=device, seed=int(rng.integers(1 << 30)))
    actions = torch.zeros((6, env.num_actions), device=env.torch_device)
    actions[:, :2] = 0.3
    mount = np.array(path_lidar().mount[:2])
    width = 2 * math.pi / SECTORS
    checked = empty = 0
    for _ in range(3):
        env.step(actions)
        policy = env.buffers.policy_obs.cpu().numpy()
        critic = env.buffers.critic_obs.cpu().numpy()
        first = POLICY_BASE + env.num_actions
        sectors = policy[:, first:first + SECTORS]
        np.testing.assert_array_equal(critic[:, first + PRIVILEGED:first + PRIVILEGED + SECTORS], sectors)
        state = env.simulator.state
        position = state.position.numpy() - env.origin.numpy()
        q = state.orientation.numpy()  # x y z w
        table = env.obstacles.table.numpy()
        for e in range(6):
            yaw = math.atan2(2 * (q[e, 3] * q[e, 2] + q[e, 0] * q[e, 1]), 1 - 2 * (q[e, 1] ** 2 + q[e, 2] ** 2))
            c, s = math.cos(yaw), math.sin(yaw)
            sensor = position[e, :2] + np.array([c * mount[0] - s * mount[1], s * mount[0] + c * mount[1]])
            bearing, half, distance, radius = buoys_seen_from(table[e], sensor, yaw)
            for k in range(SECTORS):
                centre = -math.pi + (k + 0.5) * width
                off_centre = np.abs((bearing - centre + math.pi) % (2 * math.pi) - math.pi)
                reaches = (off_centre < 0.5 * width + half + math.radians(1.0)) & (distance - radius < 31.0)
                inside = (off_centre < 0.5 * width - half - math.radians(1.0)) & (distance < 25.0)
                if inside.any():
                    lowest = (distance[reaches] - radius[reaches]).min()
                    assert (lowest - 0.05) / 30.0 <= sectors[e, k] <= (distance[inside].min() + 0.3) / 30.0
                    checked += 1
                if not reaches.any():
                    assert sectors[e, k] == 1.0
                    empty += 1
    assert checked >= 6 and empty >= 100


def test_the_layout_names_every_column(device):
    """With the lidar: the task's values, the last actions, then 24 sectors, as many columns as the env observes;
    without (the registered task): no sector."""
    task = lidar_task()
    layout = vrx_policy_layout(task)
    observed = VrxEnv(task, 1, device=device).num_policy_obs
    assert len(layout) == POLICY_BASE + len(task.vessel.actions) + SECTORS == observed
    assert [column.name for column in layout[-SECTORS:]] == [f"lidar_sector_{k}" for k in range(SECTORS)]
    assert "/ 30 m" in layout[-1].unit
    plain = follow_path_task()
    assert len(vrx_policy_layout(plain)) == POLICY_BASE + len(plain.vessel.actions)


@pytest.mark.parametrize("sectors", [7, 0, 361])
def test_a_sector_count_that_does_not_divide_the_beams_is_named(sectors):
    with pytest.raises(ValueError, match="PathCourseConfig.lidar_sectors must be a whole divisor"):
        PathCourseConfig(lidar=path_lidar(), lidar_sectors=sectors)
