"""Tasks built from terms (``envs/tasks/reward_terms.py``, ``observation_blocks.py``, ``task_kernels.py``): each
reward term alone gives its hand-computed value on a hand-made state, a task selects the terms with weights and
leaves out the rest, the observation kernel holds the reef column only where the task has a reef rule, and the
environments of one task share one built kernel."""

import dataclasses
import math

import numpy as np
import pytest
import torch
import warp as wp

import ocean_warp as ow
from ocean_warp.device_structs import struct_from
from ocean_warp.eboat import EBoatConfig
from ocean_warp.kernels.spatial import vec6
from ocean_warp.envs import (AvoidSailConfig, MissionConfig, MissionSailConfig, ReefRule, RewardConfig, SailingEnv,
                             WaypointConfig, WaypointPlusConfig)
from ocean_warp.envs.tasks.observation_blocks import PRIVILEGED_BLOCK
from ocean_warp.envs.tasks.reward_terms import reward_terms
from ocean_warp.envs.tasks.task_kernels import (PRIVILEGED_OBS, BoatView, Course, EpisodeEnds, TaskParameters,
                                                evaluate_kernel, evaluate_kernel_for, observe_kernel,
                                                observe_kernel_for, policy_observation_count)

ZERO_WEIGHTS = dict(propeller_gain=0.0, propeller_cost=0.0, reach_bonus=0.0, lost_penalty=0.0, flagged_penalty=0.0,
                    collision_penalty=0.0, proximity_cost=0.0, smoothness=0.0, time_cost=0.0, energy_cost=0.0)
"""Every optional term's weight at 0: the reward is the progress alone (``RewardConfig`` with these and one
weight set tests that term alone)."""
ROUTE = ((100.0, 0.0, 0.0), (100.0, 100.0, 0.0))
"""Two waypoints from the origin [m]; each leg starts at the origin."""
LAST_ACTION = (0.2, -0.4, 0.5)
COLLIDED, CAPSIZED = 32, 2
"""``BoatStatus`` flags."""


def _task(propeller=True, **weights):
    return WaypointConfig(reward=RewardConfig(**{**ZERO_WEIGHTS, **weights}), propeller=propeller)


def _parameters(task) -> TaskParameters:
    parameters = struct_from(TaskParameters, task, task.reward, reef_levels=3)
    parameters.route_length = len(ROUTE)
    return parameters


def _evaluate(task, device, positions, previous_distance, actions=None, status=None, clearance=None):
    """The built evaluation kernel of ``task`` on one row per position (world = from the origin [m]), each on the
    route's first leg: (reward, terminated, target index, last actions) as numpy."""
    n = len(positions)
    array = lambda values, dtype=float: wp.array(np.asarray(values), dtype=dtype, device=device)  # noqa: E731
    course = Course()
    course.origin = array(np.zeros((n, 3), np.float32), wp.vec3)
    course.route = wp.array(np.tile(np.array(ROUTE, np.float32), (n, 1, 1)), dtype=wp.vec3, device=device)
    course.target_index = array(np.zeros(n, np.int32), int)
    course.leg_start = array(np.zeros((n, 3), np.float32), wp.vec3)
    course.previous_distance = array(np.array(previous_distance, np.float32))
    course.last_action = array(np.tile(np.array(LAST_ACTION, np.float32), (n, 1)))
    course.episode_length = array(np.zeros(n, np.int32), wp.int32)
    course.episode_return = array(np.zeros(n, np.float32))
    course.episode_count = array(np.zeros(n, np.int32), int)
    course.target_world = array(np.zeros((n, 3), np.float32), wp.vec3)
    ends = EpisodeEnds()
    for name, dtype in (("reward", float), ("terminated", wp.bool), ("time_out", wp.bool), ("done", wp.bool),
                        ("reset_mask", wp.int32), ("final_return", float), ("final_length", wp.int32),
                        ("final_success", float), ("final_status", int), ("final_waypoints", int)):
        setattr(ends, name, wp.zeros(n, dtype=dtype, device=device))
    actions = np.zeros((n, 3), np.float32) if actions is None else np.array(actions, np.float32)
    status = np.zeros(n, np.int32) if status is None else np.array(status, np.int32)
    clearance = np.full(n, 100.0, np.float32) if clearance is None else np.array(clearance, np.float32)
    wp.launch(evaluate_kernel_for(task), dim=n, device=device,
              inputs=[_parameters(task), array(actions), array(status, int),
                      array(np.array(positions, np.float32), wp.vec3), array(clearance), course, ends])
    return (ends.reward.numpy(), ends.terminated.numpy(), course.target_index.numpy(), course.last_action.numpy())


def test_the_progress_alone(device):
    # 50 m -> 40 m from the waypoint at (100, 0): 10 m of the 125 m scale; 30 -> 40 m: -10 m.
    reward, terminated, _, _ = _evaluate(_task(), device, [(60.0, 0.0, 0.0), (60.0, 0.0, 0.0)], [50.0, 30.0])
    np.testing.assert_allclose(reward, [10.0 / 125.0, -10.0 / 125.0], rtol=1e-6)
    assert not terminated.any()


def test_the_propeller_term_alone_scales_a_gain_and_adds_to_a_loss(device):
    # a0 = 0.5: level int(5 * 0.5) = 2; a0 = -0.9: level -4, |4|.
    task = _task(propeller_gain=0.9, propeller_cost=0.01)
    reward, _, _, _ = _evaluate(task, device, [(60.0, 0.0, 0.0)] * 2, [50.0, 30.0],
                                actions=[(0.5, 0.0, 0.0), (-0.9, 0.0, 0.0)])
    np.testing.assert_allclose(reward, [0.08 * (1.0 - 0.9 * 2.0 / 5.0), -0.08 - 0.01 * 4.0], rtol=1e-6)


def test_the_reach_bonus_alone_and_the_next_leg(device):
    # 5 m from the first waypoint (3-4-5) with a 5 m radius, no progress: the bonus, and the second waypoint.
    reward, terminated, index, _ = _evaluate(_task(reach_bonus=1.5), device, [(97.0, 4.0, 0.0)], [5.0])
    np.testing.assert_allclose(reward, [1.5], rtol=1e-6)
    assert index[0] == 1 and not terminated[0]


def test_the_lost_penalty_alone(device):
    # 130 m from the waypoint on a 100 m leg with the 25 m margin: lost, no progress.
    reward, terminated, _, _ = _evaluate(_task(lost_penalty=0.7), device, [(-30.0, 0.0, 0.0)], [130.0])
    np.testing.assert_allclose(reward, [-0.7], rtol=1e-6)
    assert terminated[0]


def test_the_flagged_and_collision_penalties_each_alone(device):
    positions, previous = [(60.0, 0.0, 0.0)] * 2, [50.0, 50.0]
    flagged, terminated, _, _ = _evaluate(_task(flagged_penalty=0.7), device, positions, previous,
                                          status=[CAPSIZED, COLLIDED])
    np.testing.assert_allclose(flagged, [-0.7, 0.0], rtol=1e-6)
    assert terminated.all()
    collided, _, _, _ = _evaluate(_task(collision_penalty=2.0), device, positions, previous,
                                  status=[CAPSIZED, COLLIDED])
    np.testing.assert_allclose(collided, [0.0, -2.0], rtol=1e-6)


def test_the_proximity_cost_alone(device):
    # A 1 m gap of the 5 m range costs 0.3 (1 - 1/5); 7 m, none.
    reward, _, _, _ = _evaluate(_task(proximity_cost=0.3), device, [(60.0, 0.0, 0.0)] * 2, [40.0, 40.0],
                                clearance=[1.0, 7.0])
    np.testing.assert_allclose(reward, [-0.3 * 0.8, 0.0], atol=1e-7)


def test_the_smoothness_cost_alone_on_clipped_and_non_finite_actions(device):
    # (0.5, 1.7 -> 1, nan -> 0) after (0.2, -0.4, 0.5): changes 0.3, 1.4, -0.5.
    reward, _, _, last = _evaluate(_task(smoothness=0.05), device, [(60.0, 0.0, 0.0)], [40.0],
                                   actions=[(0.5, 1.7, float("nan"))])
    np.testing.assert_allclose(reward, [-0.05 * (0.09 + 1.96 + 0.25)], rtol=1e-6)
    np.testing.assert_allclose(last[0], [0.5, 1.0, 0.0])


def test_the_time_cost_alone(device):
    reward, _, _, _ = _evaluate(_task(time_cost=0.01), device, [(60.0, 0.0, 0.0)], [40.0])
    np.testing.assert_allclose(reward, [-0.01], rtol=1e-6)


def test_the_motor_energy_alone(device):
    # Level -4 of 5 over a 1 s decision at 0.02 per second of full thrust.
    reward, _, _, _ = _evaluate(_task(energy_cost=0.02), device, [(60.0, 0.0, 0.0)], [40.0],
                                actions=[(-0.8, 0.0, 0.0)])
    np.testing.assert_allclose(reward, [-0.02 * 1.0 * 0.8**1.5], rtol=1e-6)


def test_a_sail_only_task_leaves_the_propeller_terms_out(device):
    task = _task(propeller=False, propeller_gain=0.9, propeller_cost=0.01, energy_cost=0.02)
    assert reward_terms(task) == ()
    reward, _, _, _ = _evaluate(task, device, [(60.0, 0.0, 0.0)] * 2, [50.0, 30.0], actions=[(1.0, 0.0, 0.0)] * 2)
    np.testing.assert_allclose(reward, [0.08, -0.08], rtol=1e-6)


def test_tasks_select_the_terms_with_weights():
    assert reward_terms(WaypointConfig()) == ("propeller", "reach", "lost", "flagged", "collision")
    assert reward_terms(WaypointPlusConfig()) == ("propeller", "reach", "lost", "flagged", "collision",
                                                  "smoothness")
    assert reward_terms(MissionSailConfig()) == ("reach", "lost", "flagged", "collision")
    assert reward_terms(AvoidSailConfig()) == ("reach", "lost", "flagged", "collision", "proximity")
    assert evaluate_kernel_for(WaypointConfig()).key == "evaluate_progress_propeller_reach_lost_flagged_collision"


def test_unknown_selections_are_refused():
    with pytest.raises(ValueError, match="evaluate_kernel: unknown reward terms \\['wind'\\]"):
        evaluate_kernel(("wind",))
    with pytest.raises(ValueError, match="observe_kernel: unknown observation set 'full'"):
        observe_kernel("full", False)


def _boats(device, n, reef_level):
    """One boat 40 m short of (100, 0) heading east, level, at 2 m/s, reef level ``reef_level``; sensor readings
    that tell their channels apart (heel 30 deg, yaw rate 0.25 rad/s, apparent wind 3 m/s, log 1 m/s)."""
    boats = BoatView()
    boats.position = wp.array(np.tile([60.0, 0.0, 0.0], (n, 1)).astype(np.float32), dtype=wp.vec3, device=device)
    boats.orientation = wp.array(np.tile([0.0, 0.0, 0.0, 1.0], (n, 1)).astype(np.float32), dtype=wp.quat,
                                 device=device)
    boats.velocity = wp.array(np.tile([2.0, 0, 0, 0, 0, 0], (n, 1)).astype(np.float32), dtype=vec6, device=device)
    boats.wind_velocity = wp.array(np.tile([0.0, 5.0, 0.0], (n, 1)).astype(np.float32), dtype=wp.vec3, device=device)
    readings = np.zeros((n, 16), np.float32)
    readings[:, 0] = 60.0
    readings[:, 7], readings[:, 8] = 9.81 * 0.5, 9.81 * math.sqrt(0.75)  # specific force, body y and z: 30 deg heel
    readings[:, 9], readings[:, 11] = 0.1, 0.25  # roll and yaw rates [rad/s]
    readings[:, 14], readings[:, 15] = 3.0, 1.0  # apparent wind speed and the log [m/s]
    boats.truth = wp.array(readings, dtype=float, device=device)
    boats.readings = wp.array(readings, dtype=float, device=device)
    for name in ("rudder_angle", "boom_angle", "sheet_limit"):
        setattr(boats, name, wp.zeros(n, dtype=float, device=device))
    boats.reef_level = wp.array(np.full(n, reef_level, np.int32), dtype=int, device=device)
    return boats


def _observe(task, device, width):
    """The built observation kernel of ``task`` on :func:`_boats`, into NaN-filled rows ``width`` values wide."""
    n = 1
    course = Course()
    course.origin = wp.zeros(n, dtype=wp.vec3, device=device)
    course.leg_start = wp.zeros(n, dtype=wp.vec3, device=device)
    course.target_world = wp.array([(100.0, 0.0, 0.0)], dtype=wp.vec3, device=device)
    course.target_index = wp.zeros(n, dtype=int, device=device)
    course.last_action = wp.array(np.array([LAST_ACTION], np.float32), dtype=float, device=device)
    for name, dtype in (("previous_distance", float), ("episode_length", wp.int32), ("episode_return", float),
                        ("episode_count", int)):
        setattr(course, name, wp.zeros(n, dtype=dtype, device=device))
    course.route = wp.zeros((n, 2), dtype=wp.vec3, device=device)
    policy = wp.array(np.full((n, width), np.nan, np.float32), dtype=float, device=device)
    critic = wp.array(np.full((n, width + 12), np.nan, np.float32), dtype=float, device=device)
    wp.launch(observe_kernel_for(task), dim=n, device=device,
              inputs=[_parameters(task), _boats(device, n, reef_level=2), course], outputs=[policy, critic])
    return policy.numpy()[0], critic.numpy()[0]


def test_a_task_without_the_reef_rule_builds_a_kernel_without_the_reef_column(device):
    plain = WaypointConfig()
    reefed = dataclasses.replace(plain, reef=ReefRule())
    assert (policy_observation_count(plain), policy_observation_count(reefed)) == (5, 6)
    assert observe_kernel_for(plain).key != observe_kernel_for(reefed).key
    # 40 m from the waypoint on a 100 m leg with the 25 m margin (d_lost 125 m), dead ahead.
    policy, critic = _observe(plain, device, 6)
    seed = [2.0 * 40.0 / 125.0 - 1.0, 0.0, 2.0 / 5.0 - 1.0, 3.0 / 15.0 - 1.0, 0.0]  # apparent wind 3 m/s dead ahead
    np.testing.assert_allclose(policy[:5], seed, atol=1e-6)
    assert np.isnan(policy[5]), "the plain task's kernel wrote a sixth column"
    np.testing.assert_allclose(critic[:5], policy[:5])
    np.testing.assert_allclose(critic[5:8], [40.0 / 125.0, 0.0, 1.0], atol=1e-6)
    assert np.isfinite(critic[:5 + PRIVILEGED_OBS]).all() and np.isnan(critic[5 + PRIVILEGED_OBS:]).all()
    policy, critic = _observe(reefed, device, 6)
    np.testing.assert_allclose(policy[5], 2.0 / (3 - 1))
    np.testing.assert_allclose(critic[6:9], [40.0 / 125.0, 0.0, 1.0], atol=1e-6)
    assert np.isfinite(critic).all()
    assert len(PRIVILEGED_BLOCK) == PRIVILEGED_OBS


def test_the_plus_block_reads_the_sensor_channels_it_names(device):
    policy, _ = _observe(WaypointPlusConfig(reef=None), device, 15)
    columns = dict(zip(("distance", "sin", "cos", "water_speed"), policy[:4]))
    np.testing.assert_allclose(columns["distance"], 40.0 / 125.0, rtol=1e-6)
    np.testing.assert_allclose(columns["water_speed"], 1.0 / 2.0)
    np.testing.assert_allclose([columns["sin"], columns["cos"]], [0.0, 1.0], atol=1e-6)
    np.testing.assert_allclose(policy[6], 3.0 / 10.0, rtol=1e-6)  # apparent wind speed
    np.testing.assert_allclose(policy[7], math.pi / 6.0, rtol=1e-6)  # heel
    np.testing.assert_allclose(policy[8], 0.25 / 0.5)  # yaw rate
    np.testing.assert_allclose(policy[12:15], LAST_ACTION)


def _tiny(task):
    ocean = ow.OceanConfig(tile_size=256.0, resolution=16, significant_wave_height=0.0)
    simulator = dataclasses.replace(task.simulator, boat=EBoatConfig(hydrostatics="points"), ocean=ocean)
    return dataclasses.replace(task, simulator=simulator)


def test_environments_of_one_task_share_one_built_kernel():
    first = SailingEnv(_tiny(MissionConfig()), 2, device="cpu", seed=1)
    first.step(torch.zeros((2, 3)))
    built = evaluate_kernel.cache_info().misses, observe_kernel.cache_info().misses
    # Another batch of the same task, with other numbers (weights, length): the same terms, the same kernels.
    other = dataclasses.replace(MissionConfig(), episode_time=60.0,
                                reward=RewardConfig(progress_scale=100.0, reach_bonus=2.0))
    second = SailingEnv(_tiny(other), 3, device="cpu", seed=2)
    second.step(torch.zeros((3, 3)))
    assert (evaluate_kernel.cache_info().misses, observe_kernel.cache_info().misses) == built
    assert evaluate_kernel_for(first.task) is evaluate_kernel_for(second.task)
    assert observe_kernel_for(first.task) is observe_kernel_for(second.task)
