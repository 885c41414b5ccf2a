"""The topics read a vessel's common state and its joints named by its parts: the E-Boat's boom and rudder, a
WAM-V's two thruster angles, compared with the simulator's own state arrays."""

from __future__ import annotations

import numpy as np
import torch

from ocean_warp.envs import SailingEnv, WaypointConfig
from ocean_warp.envs.vrx import VrxEnv, VrxTaskConfig
from ocean_warp.ros import topics
from ocean_warp.wamv import Wamv, WamvConfig, WamvSimulatorConfig
from ocean_warp.wamv.config import ThrusterLayout


def sail(env, rng, decisions: int = 3) -> None:
    for _ in range(decisions):
        env.step(torch.as_tensor(rng.uniform(-1, 1, (env.num_envs, env.num_actions)), dtype=torch.float32,
                                 device=env.torch_device))


def test_an_eboat_snapshot_names_its_boom_and_rudder(rng):
    env = SailingEnv(WaypointConfig(), 2, device="cpu", seed=int(rng.integers(1 << 30)))
    sail(env, rng)
    state = topics.snapshot(env)
    assert state.joint_names == ("boom_angle", "rudder_angle")
    boom, rudder = env.simulator.state.boom_angle.numpy(), env.simulator.state.rudder_angle.numpy()
    assert np.any(boom != 0.0)
    np.testing.assert_array_equal(state.joint_angles, np.column_stack([boom, rudder]).astype(np.float64))
    seed = topics.seed_observation_values(state)
    np.testing.assert_allclose(seed[:, 5], np.degrees(boom.astype(np.float64)), rtol=1e-12)
    np.testing.assert_allclose(seed[:, 6], np.degrees(rudder.astype(np.float64)), rtol=1e-12)


def test_a_wamv_snapshot_names_its_thrusters_and_has_no_boom(rng):
    """Azimuth thrusters: the joints are the two columns of ``thruster_angle``; the seed's boom and rudder
    columns are NaN (the WAM-V has neither); the common state (pose, wind) is the simulator's."""
    config = WamvSimulatorConfig(boat=WamvConfig(thrusters=ThrusterLayout.AZIMUTH))
    vessel = Wamv(config)
    env = VrxEnv(VrxTaskConfig(kind="wayfinding", goals=2, vessel=vessel), 3, device="cpu",
                 seed=int(rng.integers(1 << 30)))
    sail(env, rng)
    state = topics.snapshot(env)
    assert state.joint_names == ("thruster_angle_0", "thruster_angle_1")
    angles = env.simulator.state.thruster_angle.numpy().astype(np.float64)
    assert angles.shape == (3, 2) and np.any(angles != 0.0)
    np.testing.assert_array_equal(state.joint_angles, angles)
    np.testing.assert_array_equal(state.position, env.simulator.state.position.numpy().astype(np.float64))
    np.testing.assert_array_equal(state.wind_velocity, env.simulator.state.wind_velocity.numpy().astype(np.float64))
    seed = topics.seed_observation_values(state)
    assert np.all(np.isnan(seed[:, 5:7])) and np.all(np.isfinite(seed[:, [0, 1, 2, 7]]))
    names = {message.topic for message in topics.state_messages(state)}
    assert {"/eboat_0/gps/fix", "/eboat_2/imu/data", "/tf"} <= names


def test_joints_given_by_name_join_the_list():
    n = 2
    common = dict(time_ns=0, position=np.zeros((n, 3)), orientation=np.tile([0.0, 0.0, 0.0, 1.0], (n, 1)),
                  velocity=np.zeros((n, 6)), target=np.zeros((n, 3)), wind_velocity=np.zeros((n, 3)),
                  current_velocity=np.zeros((n, 3)), truth=np.zeros((n, 16)), readings=np.zeros((n, 16)),
                  propeller_level=np.zeros(n), noise_scale=np.ones(n), sensor_std=np.ones(16))
    state = topics.BoatSnapshot(**common, boom_angle=[0.1, 0.2], rudder_angle=[-0.3, 0.4])
    assert state.joint_names == ("boom_angle", "rudder_angle")
    np.testing.assert_array_equal(state.joint("rudder_angle"), [-0.3, 0.4])
    other = topics.BoatSnapshot(**common, joint_names=("thruster_angle_0",), joint_angles=[[0.5], [0.6]])
    assert np.all(np.isnan(other.joint("boom_angle")))
