"""The ROS node's pieces that need no ROS: the commands held between decisions and their actions (checked
against the task's own actions kernel), the controller's observation and commands (checked against the
simulator's own observation), remapping names and the master check (ocean_warp.ros.ros1's standard-library
part), the episode topic's messages. CPU, a second or two."""

from __future__ import annotations

import dataclasses
import math
import socket
import time

import numpy as np
import pytest
import torch
import warp as wp

from ocean_warp.envs import SailingEnv
from ocean_warp.eboat import EBoatConfig
from ocean_warp.envs.tasks.task_configs import MissionConfig, WaypointConfig
from ocean_warp.kernels.eboat_actions import apply_eboat_actions
from ocean_warp.ros import ros1, topics
from ocean_warp.ros.commands import (DEFAULT_SAIL_DEG, PROPULSION_TOPIC, RUDDER_TOPIC, SAIL_TOPIC, CommandInbox,
                                     actions_from_commands)
from ocean_warp.ros.controller_node import commands_from_actions, policy_observation


def _task_commands(actions: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The task's actions kernel on the CPU: (sheet [deg], rudder [deg], level) of (N, 3) actions."""
    n = actions.shape[0]
    rudder, sheet = (wp.zeros(n, dtype=float, device="cpu") for _ in range(2))
    level = wp.zeros(n, dtype=int, device="cpu")
    wp.launch(apply_eboat_actions, dim=n, device="cpu",
              inputs=[wp.array(actions, dtype=float, device="cpu"), wp.ones(3, dtype=wp.int32, device="cpu")],
              outputs=[rudder, sheet, level])
    return np.degrees(sheet.numpy()), np.degrees(rudder.numpy()), level.numpy()


def test_commands_become_the_actions_the_task_turns_back_into_them():
    levels = np.arange(-5, 6)
    sails = np.linspace(0.0, 90.0, levels.size)
    rudders = np.linspace(-60.0, 60.0, levels.size)
    actions = actions_from_commands(sails, rudders, levels)
    assert actions.dtype == np.float32 and np.all(np.abs(actions) <= 1.0)
    sheet, rudder, level = _task_commands(actions)
    np.testing.assert_array_equal(level, levels)
    np.testing.assert_allclose(sheet, sails, atol=1e-4)
    np.testing.assert_allclose(rudder, rudders, atol=1e-4)


def test_the_controllers_commands_are_the_tasks_mapping_of_its_actions():
    rng = np.random.default_rng(4)
    actions = rng.uniform(-1.3, 1.3, (64, 3)).astype(np.float32)  # beyond [-1, 1] too: clipped
    sheet, rudder, level = _task_commands(actions)
    for k, row in enumerate(actions):
        sail_deg, rudder_deg, commanded = commands_from_actions(row)
        assert commanded == level[k]
        assert sail_deg == pytest.approx(sheet[k], abs=1e-4) and rudder_deg == pytest.approx(rudder[k], abs=1e-4)
        assert commands_from_actions(row, propeller=False)[2] == 0
    # and what it sends comes back as the same actions (the level up to int(5 a0)'s truncation)
    back = actions_from_commands(*zip(*(commands_from_actions(row) for row in actions)))
    np.testing.assert_allclose(back[:, 1:], np.clip(actions[:, 1:], -1.0, 1.0), atol=1e-6)
    np.testing.assert_array_equal(_task_commands(back)[2], level)


def test_inbox_holds_valid_commands_and_refuses_the_rest_in_one_line():
    inbox = CommandInbox(2)
    np.testing.assert_allclose(inbox.take(), actions_from_commands([DEFAULT_SAIL_DEG] * 2, [0, 0], [0, 0]))
    assert inbox.take()[0].tolist() == [0.0, 0.0, 0.0]
    assert inbox.put(1, RUDDER_TOPIC, 30.0) is None
    for topic, bad in ((RUDDER_TOPIC, math.nan), (RUDDER_TOPIC, math.inf), (RUDDER_TOPIC, 60.5), (SAIL_TOPIC, -1.0),
                       (SAIL_TOPIC, 91.0), (SAIL_TOPIC, "x"), (PROPULSION_TOPIC, 6), (PROPULSION_TOPIC, 2.5)):
        reason = inbox.put(1, topic, bad)
        assert reason is not None and "\n" not in reason and reason.startswith("ignored")
    actions = inbox.take()
    assert actions[1, 2] == pytest.approx(0.5) and actions[0, 2] == 0.0  # the held 30 deg survived the bad ones
    with pytest.raises(ValueError, match="unknown command topic"):
        inbox.put(0, "control_interface/anchor", 1.0)


def test_inbox_waits_for_every_boats_three_commands_or_its_timeout():
    inbox = CommandInbox(2)
    start = time.monotonic()
    assert not inbox.wait_for_commands(0.2)
    assert time.monotonic() - start >= 0.15  # it waited (a lower bound only: load makes waits longer, never shorter)
    assert not inbox.wait_for_commands(math.inf, wake=lambda: True)  # woken at once
    for boat in range(2):
        for topic in (SAIL_TOPIC, RUDDER_TOPIC):
            inbox.put(boat, topic, 10.0)
    assert inbox.missing() == [(0, PROPULSION_TOPIC), (1, PROPULSION_TOPIC)]
    inbox.put(0, PROPULSION_TOPIC, 3)
    inbox.put(1, PROPULSION_TOPIC, -2)
    assert inbox.wait_for_commands(0.1) and inbox.complete()
    actions = inbox.take()
    assert not inbox.complete()
    assert _task_commands(actions)[2].tolist() == [3, -2]


def test_inbox_wind_commands():
    inbox = CommandInbox(1)
    assert inbox.put_wind(0, 3.0, 4.0, 0.0) is None
    assert inbox.held_wind(0) == pytest.approx((5.0, math.atan2(4.0, 3.0)))
    assert inbox.take_wind() == {0: pytest.approx((5.0, math.atan2(4.0, 3.0)))}
    assert inbox.take_wind() == {}
    assert inbox.put_wind(0, math.nan, 0.0, 0.0) is not None and inbox.put_wind(0, 50.0, 0.0, 0.0) is not None
    inbox.clear()
    assert inbox.held_wind(0) is None


def test_the_controller_rebuilds_the_simulators_seed_observation_from_the_topic():
    env = SailingEnv(WaypointConfig(), 3, device="cpu", seed=2)
    rng = np.random.default_rng(0)
    for _ in range(6):
        raw = topics.seed_observation_values(topics.snapshot(env)).astype(np.float32)  # as the topic carries it
        rebuilt = np.stack([policy_observation(row) for row in raw])
        np.testing.assert_allclose(rebuilt, env.buffers.policy_obs.numpy(), atol=2e-5)
        env.step(torch.from_numpy(rng.uniform(-1, 1, (3, 3)).astype(np.float32)))
    with pytest.raises(ValueError, match="9 finite numbers"):
        policy_observation([0.0] * 8)
    # The mission's policy also sees its reef level (level / 2), after the seed's five values: the same rows
    # as the simulator's, whose level comes from the wind by the task's rule (16 runs, 4-11 m/s).
    mission = dataclasses.replace(MissionConfig(), start=dataclasses.replace(
        MissionConfig().start, wind_speed=(4.0, 11.0)), simulator=dataclasses.replace(
        MissionConfig().simulator, boat=EBoatConfig(hydrostatics="points")))
    env = SailingEnv(mission, 16, device="cpu", seed=int(rng.integers(1000)))
    raw = topics.seed_observation_values(topics.snapshot(env)).astype(np.float32)
    levels = env.simulator.state.reef_level.numpy()
    assert len(set(levels.tolist())) == 3, levels  # every rig among the runs
    rebuilt = np.stack([policy_observation(row, reef_level=int(level)) for row, level in zip(raw, levels)])
    # (the distance's scale, the leg from each jittered start plus 25 m, is checked on the seed task above)
    np.testing.assert_allclose(rebuilt[:, 1:], env.buffers.policy_obs.numpy()[:, 1:], atol=2e-5)
    with pytest.raises(ValueError, match="reef_level"):
        policy_observation(raw[0], reef_level=3)
    with pytest.raises(ValueError, match="1 not finite"):
        policy_observation([math.nan] + [0.0] * 8)


def test_episode_messages_only_for_the_boats_whose_episode_ended():
    messages = topics.episode_messages(7_000_000_000, [False, True, True], [0, 1, 0], [0, 1, 0], [5, 28, 9],
                                       [0.1, 1.8, -1.2], [0, 0, 4])
    assert [m.topic for m in messages] == ["/eboat_1/mission_control/episode", "/eboat_2/mission_control/episode"]
    # success, waypoints, decisions, return, flags, end reason (0: reached; 5: lost), boat, time [s]
    assert messages[0].fields["data"] == pytest.approx([1.0, 1.0, 28.0, 1.8, 0.0, 0.0, 1.0, 7.0])
    assert messages[1].fields["data"] == pytest.approx([0.0, 0.0, 9.0, -1.2, 4.0, 3.0, 2.0, 7.0])  # 4: flagged
    assert messages[1].fields["layout"]["dim"][0]["label"] == "episode_end"
    assert topics.episode_messages(0, [True], [1], [1], [3], [1.0], [0])[0].topic == "/eboat/mission_control/episode"


def test_remapping_names_resolve_as_rospy_does():
    assert ros1.split_remaps(["--boats", "2", "a:=b", "__ns:=/x"]) == (["a:=b", "__ns:=/x"], ["--boats", "2"])
    assert ros1.namespace_of([], {}) == "/" and ros1.namespace_of(["__ns:=sim"], {}) == "/sim/"
    assert ros1.namespace_of([], {"ROS_NAMESPACE": "/fleet/"}) == "/fleet/"
    assert ros1.resolve("eboat/gps/fix", "/sim/", "/sim/ocean_warp") == "/sim/eboat/gps/fix"
    assert ros1.resolve("/tf", "/sim/", "/sim/ocean_warp") == "/tf"
    assert ros1.resolve("~reset", "/", "/ocean_warp") == "/ocean_warp/reset"
    known = {"/eboat/gps/fix", "/ocean_warp/reset", "/tf"}
    assert ros1.unknown_remap(["eboat/gps/fix:=/fix", "~reset:=/r", "__name:=sim", "_private:=1", "/tf:=/tf2"],
                              known, "/", "/ocean_warp") is None
    problem = ros1.unknown_remap(["/eboat/gsp/fix:=/fix"], known, "/", "/ocean_warp")
    assert "/eboat/gsp/fix is none of this node's topics" in problem and "\n" not in problem
    assert "must be name:=new_name" in ros1.unknown_remap(["/tf:="], known, "/", "/ocean_warp")


def test_master_check_says_no_at_once_where_nothing_listens():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        port = s.getsockname()[1]
    assert not ros1.master_online(f"http://localhost:{port}")
    assert not ros1.master_online("not a uri")
    assert ros1.master_uri(["__master:=http://h:1"], {}) == "http://h:1"
    assert ros1.master_uri([], {"ROS_MASTER_URI": "http://m:2"}) == "http://m:2"
    assert ros1.master_uri([], {}) == "http://localhost:11311"
    assert ros1.ros1_type("sensor_msgs/msg/Imu") == "sensor_msgs/Imu"
    with pytest.raises(ValueError):
        ros1.ros1_type("Imu")
