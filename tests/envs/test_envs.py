"""The batched sailing environment: buffers, resets, determinism, the seed's reward and observations,
time-outs, flagged boats, graph capture."""

import dataclasses
import math

import numpy as np
import pytest
import torch

import ocean_warp as ow
from ocean_warp.eboat import EBoatConfig
from ocean_warp.envs import MissionConfig, SailingEnv, StartConfig, WaypointConfig, WaypointPlusConfig
from ocean_warp.frames import roll_pitch_yaw
from ocean_warp.sensors import SensorConfig

CALM_START = StartConfig(heading_deg=(0.0, 0.0), heading_step_deg=0.0, wind_speed=(0.0, 0.0),
                         wind_direction_deg=(0.0, 0.0), wind_direction_step_deg=0.0)


def fast(task, **simulator_fields):
    """The task with the four-point buoyancy (much faster on the CPU) and the given simulator fields."""
    simulator = dataclasses.replace(task.simulator, boat=EBoatConfig(hydrostatics="points"), **simulator_fields)
    return dataclasses.replace(task, simulator=simulator)


def flat(task):
    return fast(task, ocean=ow.OceanConfig(tile_size=256.0, resolution=16, significant_wave_height=0.0))


@pytest.mark.parametrize("config", [WaypointConfig, WaypointPlusConfig, MissionConfig])
def test_buffers_are_zero_copy_views_with_the_documented_shapes(device, config):
    env = SailingEnv(fast(config()), 6, device=device)
    b = env.buffers
    # The set's values, then the reef level on every task with a reef rule (all but the seed's waypoint task).
    p = {"seed": 5, "plus": 15}[env.task.observation.value] + (0 if config is WaypointConfig else 1)
    assert b.policy_obs.shape == (6, p) and b.critic_obs.shape == (6, p + 12)
    assert b.actions.shape == (6, 3) and b.reward.shape == (6,) and b.target.shape == (6, 3)
    assert b.done.dtype == torch.bool and b.time_out.dtype == torch.bool and b.episode_length.dtype == torch.int32
    for name, array in (("policy_obs", env.policy_obs), ("critic_obs", env.critic_obs), ("reward", env.reward),
                        ("done", env.done), ("time_out", env.time_out), ("episode_length", env.episode_length)):
        assert getattr(b, name).data_ptr() == array.ptr, name
        assert getattr(b, name).device == env.torch_device
    env.step(torch.zeros(6, 3, device=env.torch_device))
    assert torch.all(torch.isfinite(b.policy_obs)) and torch.all(torch.isfinite(b.critic_obs))


def test_bad_task_configs_name_the_field():
    with pytest.raises(ValueError, match="WaypointConfig.decision_period 0.33 s must be a whole number"):
        WaypointConfig(decision_period=0.33)
    with pytest.raises(ValueError, match="MissionConfig.reach_radius must be > 0"):
        MissionConfig(reach_radius=0.0)
    with pytest.raises(ValueError, match="StartConfig.wind_speed must have low <= high"):
        StartConfig(wind_speed=(8.0, 2.0))
    with pytest.raises(ValueError, match="WaypointConfig.observation must be one of 'seed', 'plus'"):
        WaypointConfig(observation="pixels")
    with pytest.raises(ValueError, match=r"SailingEnv.step: actions must have shape \(2, 3\)"):
        SailingEnv(flat(WaypointConfig()), 2, device="cpu").step(torch.zeros(2, 2))


def test_seed_start_distribution_follows_the_grids(rng):
    env = SailingEnv(fast(WaypointConfig()), 256, device="cpu", seed=int(rng.integers(1 << 30)))
    state = env.simulator.state
    heading = np.degrees(roll_pitch_yaw(state.orientation.numpy())[:, 2])
    np.testing.assert_allclose(np.mod(heading + 1e-3, 20.0), 1e-3, atol=2e-3)  # a 20 deg grid
    direction = np.degrees(state.wind_mean_direction.numpy())
    np.testing.assert_allclose(np.mod(direction + 1e-3, 10.0), 1e-3, atol=2e-3)  # a 10 deg grid
    speed = state.wind_mean_speed.numpy()
    assert speed.min() >= 0.0 and speed.max() <= 12.0 and speed.std() > 2.0  # uniform 0-12: std 3.5
    local = state.position.numpy() - env.buffers.origin.numpy()
    np.testing.assert_allclose(local[:, :2], 0.0, atol=1e-6)  # at the origin
    waypoint = env.buffers.target.numpy() - env.buffers.origin.numpy()
    np.testing.assert_allclose(waypoint, np.tile([100.0, 0.0, 0.0], (256, 1)), atol=1e-4)
    cells, _, _ = np.histogram2d(*env.buffers.origin.numpy()[:, :2].T, bins=4, range=[[0, 256], [0, 256]])
    assert cells.min() >= 12 and cells.max() <= 20, "256 origins spread evenly over the 4 x 4 cells of the tile"


def test_start_draws_are_independent(rng):
    """Each part of a start (heading, wind speed and direction, waypoint distance and bearing, surge,
    sheet, gusts) comes from its own draw: over many environments no two are correlated, and each
    grid is covered."""
    start = StartConfig(heading_step_deg=0.0, wind_speed=(2.0, 12.0), wind_direction_step_deg=0.0,
                        gust_scale=(0.0, 2.0), waypoint_distance=(50.0, 150.0), waypoint_bearing_deg=(-180.0, 180.0),
                        surge_speed=(0.0, 1.0), sheet_deg=(0.0, 90.0))
    env = SailingEnv(flat(dataclasses.replace(WaypointConfig(), start=start)), 1024, device="cpu",
                     seed=int(rng.integers(1 << 30)))
    rows = env.simulator.tensors.start
    waypoint = (env.buffers.target - env.buffers.origin).numpy()
    draws = np.stack([np.cos(np.radians(roll_pitch_yaw(rows.orientation.numpy())[:, 2])),
                      rows.wind_speed.numpy(), np.cos(rows.wind_direction.numpy()), rows.gust_scale.numpy(),
                      np.hypot(waypoint[:, 0], waypoint[:, 1]), np.cos(np.arctan2(waypoint[:, 1], waypoint[:, 0])),
                      rows.velocity.numpy()[:, 0], rows.sheet.numpy()])
    correlation = np.corrcoef(draws)
    off_diagonal = np.abs(correlation[~np.eye(len(draws), dtype=bool)])
    assert off_diagonal.max() < 0.15, np.round(correlation, 2)  # independent: |r| ~ 1/sqrt(1024) = 0.03
    grid = SailingEnv(flat(WaypointConfig()), 1024, device="cpu", seed=int(rng.integers(1 << 30)))
    headings = np.round(roll_pitch_yaw(grid.simulator.state.orientation.numpy())[:, 2] / np.radians(20.0))
    directions = np.round(grid.simulator.state.wind_mean_direction.numpy() / np.radians(10.0))
    assert len(np.unique(np.mod(headings, 18))) == 18 and len(np.unique(np.mod(directions, 36))) == 36
    pairs = len({(a, b) for a, b in zip(np.mod(headings, 18), np.mod(directions, 36))})
    assert pairs > 400, "heading and wind direction grids combine freely (648 pairs)"


def apparent_wind(state):
    """Apparent wind angle (from the bow, + to port) [rad] and speed [m/s] at the masthead, from the
    state alone: the world wind turned into the body frame minus the masthead's velocity."""
    from scipy.spatial.transform import Rotation

    rotation = Rotation.from_quat(state["orientation"])
    wind_body = rotation.inv().apply(state["wind"])
    nu = state["velocity"]
    masthead = state["masthead"]
    apparent = wind_body - (nu[:, :3] + np.cross(nu[:, 3:], masthead))
    return np.arctan2(-apparent[:, 1], -apparent[:, 0]), np.hypot(apparent[:, 0], apparent[:, 1])


def test_seed_reward_and_observations_match_hand_computation(device, rng):
    """Calm sea and air: the boat hardly moves in a decision, so the reward is known from where it was put."""
    task = dataclasses.replace(flat(WaypointConfig(start=CALM_START)), decision_period=0.25)
    env = SailingEnv(task, 4, device=device, seed=int(rng.integers(1 << 30)))
    origin = env.buffers.origin.cpu().numpy()
    # Boat 0 next to the waypoint (reached), 1 beyond 125 m (lost), 2 and 3 somewhere in between.
    local = np.array([[97.0, 2.0, 0.0], [-30.0, 10.0, 0.0], rng.uniform(10, 60, 3) * [1, 1, 0],
                      np.array([rng.uniform(0, 60), rng.uniform(-40, 40), 0.0])])  # closer than 125 m
    env.simulator.reset(position=origin + local, heading=rng.uniform(-math.pi, math.pi, 4))
    levels = np.array([0, 3, 2, -4])
    actions = np.column_stack([levels / 5.0 + 0.1 * np.sign(levels), rng.uniform(-1, 1, 4), np.zeros(4)])
    env.step(torch.tensor(actions, dtype=torch.float32, device=env.torch_device))
    b = env.buffers
    distance = np.hypot(100.0 - local[:, 0], local[:, 1])
    progress = (100.0 - distance) / 125.0
    expected = np.where(progress > 0, progress * (1 - 0.9 * np.abs(levels) / 5), progress - 0.01 * np.abs(levels))
    expected += np.array([1.0, -1.0, 0.0, 0.0])
    np.testing.assert_allclose(b.reward.cpu().numpy(), expected, atol=2e-3)
    np.testing.assert_array_equal(b.terminated.cpu().numpy(), [True, True, False, False])
    np.testing.assert_array_equal(b.final_success.cpu().numpy()[:2], [1.0, 0.0])

    # Observations of the two boats still sailing, from their state.
    sim = env.simulator
    state = {"orientation": sim.state.orientation.numpy()[2:], "velocity": sim.state.velocity.numpy()[2:],
             "wind": sim.state.wind_velocity.numpy()[2:], "masthead": sim.eboat.masthead}
    position = sim.state.position.numpy()[2:] - origin[2:]
    heading = roll_pitch_yaw(state["orientation"])[:, 2]
    to_go = np.array([100.0, 0.0]) - position[:, :2]
    bearing = np.angle(np.exp(1j * (np.arctan2(to_go[:, 1], to_go[:, 0]) - heading)))
    awa, aws = apparent_wind(state)
    expected_obs = np.column_stack([2 * np.hypot(*to_go.T) / 125 - 1, np.degrees(bearing) / 180,
                                    state["velocity"][:, 0] / 5 - 1, aws / 15 - 1, np.degrees(awa) / 180])
    np.testing.assert_allclose(b.policy_obs.cpu().numpy()[2:], np.clip(expected_obs, -1, 1), atol=2e-4)


def test_time_outs_are_not_terminations(device):
    task = dataclasses.replace(flat(WaypointConfig(start=CALM_START)), episode_time=3.0)
    env = SailingEnv(task, 3, device=device)
    b = env.buffers
    zeros = torch.zeros(3, 3, device=env.torch_device)
    for _ in range(2):
        env.step(zeros)
        assert not b.done.any()
    env.step(zeros)
    assert b.time_out.all() and not b.terminated.any() and b.done.all()
    assert torch.all(b.episode_length == 0) and torch.all(b.final_length == 3)


def test_ended_environments_and_only_they_are_reset(device, rng):
    env = SailingEnv(fast(WaypointPlusConfig()), 8, device=device, seed=int(rng.integers(1 << 30)))
    b = env.buffers
    policy = lambda: torch.tensor(rng.uniform(-0.3, 0.3, (8, 3)), dtype=torch.float32, device=env.torch_device)  # noqa: E731
    for _ in range(3):
        env.step(policy())
    chosen = rng.permutation(8)[:3]
    lengths = b.episode_length.clone()
    lengths[chosen] = env.max_episode_length - 1  # these time out on the next decision
    b.episode_length.copy_(lengths)
    before = env.simulator.state.position.numpy().copy()
    env.step(policy())
    after = env.simulator.state.position.numpy()
    done = b.done.cpu().numpy()
    assert set(np.flatnonzero(done)) == set(chosen)
    others = np.setdiff1d(np.arange(8), chosen)
    assert torch.all(b.episode_length[others] == lengths[others] + 1)
    assert torch.all(b.episode_length[chosen] == 0)
    assert np.all(np.linalg.norm(after[others] - before[others], axis=1) < 5.0), "the others sailed on"
    start = env.buffers.origin.cpu().numpy()[chosen]
    assert np.all(np.linalg.norm((after[chosen] - start)[:, :2], axis=1) < 2.0 * math.sqrt(2) + 1e-3)  # jitter 2 m
    np.testing.assert_array_equal(b.final_policy_obs.cpu().numpy()[others], b.policy_obs.cpu().numpy()[others])


def run_episode_trace(device, seed, actions):
    env = SailingEnv(fast(WaypointPlusConfig(), sensors=SensorConfig()), 4, device=device, seed=seed)
    observations, rewards = [], []
    for a in actions:
        env.step(torch.tensor(a, device=env.torch_device))
        observations.append(env.buffers.policy_obs.cpu().numpy().copy())
        rewards.append(env.buffers.reward.cpu().numpy().copy())
    return np.array(observations), np.array(rewards)


def test_same_seed_same_actions_same_trajectory(rng):
    seed = int(rng.integers(1 << 30))
    actions = rng.uniform(-1, 1, (200, 4, 3)).astype(np.float32)
    first = run_episode_trace("cpu", seed, actions)
    second = run_episode_trace("cpu", seed, actions)
    np.testing.assert_array_equal(first[0], second[0])
    np.testing.assert_array_equal(first[1], second[1])
    other = run_episode_trace("cpu", seed + 1, actions[:5])
    assert not np.array_equal(other[0], first[0][:5]), "another seed, other starts and noise"


def test_a_frozen_boat_ends_its_episode_and_comes_back_healthy(device):
    env = SailingEnv(flat(WaypointConfig(start=CALM_START)), 3, device=device)
    actions = torch.zeros(3, 3, device=env.torch_device)
    env.step(actions)
    actions[1, 2] = math.nan  # a diverged policy
    env.step(actions)
    b = env.buffers
    np.testing.assert_array_equal(b.terminated.cpu().numpy(), [False, True, False])
    assert b.reward[1].item() == pytest.approx(-1.0)
    assert b.final_status[1].item() & ow.BoatStatus.BAD_INPUT
    assert env.simulator.state.status.numpy()[1] == 0
    assert torch.all(torch.isfinite(b.policy_obs))
    log = env.episode_log()
    assert log["/episode/bad_input_rate"].tolist() == [1.0] and log["/episode/ended"].item() == 1
    actions[1, 2] = 0.0
    env.step(actions)
    assert not b.done.any() and np.all(env.simulator.state.status.numpy() == 0)


def test_mission_advances_through_its_waypoints(device):
    """Put the boat on each waypoint in turn: the target moves along B, C, D, A, C, A with +1 each time,
    and the sixth ends the episode with success."""
    task = flat(MissionConfig(start=CALM_START))
    env = SailingEnv(dataclasses.replace(task, decision_period=0.25), 1, device=device)
    origin = env.buffers.origin.cpu().numpy()[0]
    route = np.array(task.route)
    for leg, waypoint in enumerate(route):
        np.testing.assert_allclose(env.buffers.target.cpu().numpy()[0, :2], origin[:2] + waypoint, atol=1e-4)
        env.simulator.reset(position=origin + [waypoint[0] + 1.0, waypoint[1], 0.0])
        env.step(torch.zeros(1, 3, device=env.torch_device))
        assert env.buffers.reward[0].item() > 0.5
        assert env.buffers.done[0].item() == (leg == 5)
    assert env.buffers.final_success[0].item() == 1.0 and env.buffers.final_waypoints[0].item() == 6


def test_captured_and_eager_decisions_agree(device, rng):
    """A decision replayed from its capture (a CUDA graph, or Warp's recorded CPU launches) equals the same
    decision launched anew."""
    actions = torch.tensor(rng.uniform(-1, 1, (6, 16, 3)), dtype=torch.float32)
    results = []
    for capture in (True, False):
        task = WaypointPlusConfig()
        task = dataclasses.replace(task, simulator=dataclasses.replace(task.simulator, capture_graph=capture))
        env = SailingEnv(task, 16, device=device, seed=7)
        trace = []
        for a in actions:
            env.step(a)
            trace.append(torch.cat([env.buffers.policy_obs, env.buffers.reward[:, None]], dim=1).cpu().numpy())
        results.append(np.array(trace))
    np.testing.assert_allclose(results[0], results[1], atol=1e-5)


def test_a_seeded_reset_restarts_waves_gusts_and_noise():
    """With the default sea, gusts and noisy sensors: reset(seed) twice, the same actions, the same
    observations (the waves' clock and the noise streams restart too)."""
    env = SailingEnv(WaypointPlusConfig(), 2, device="cpu")
    traces = []
    for _ in range(2):
        env.reset(seed=11)
        trace = [env.buffers.policy_obs.clone()]
        for k in range(3):
            env.step(torch.full((2, 3), 0.2 * k - 0.1))
            trace.append(env.buffers.policy_obs.clone())
        traces.append(torch.stack(trace))
    assert torch.equal(traces[0], traces[1])
