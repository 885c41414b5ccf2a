"""The ROS node's clock and episode ends without ROS: its decision loop (``NodeLoop``) on a bus that records
what it is given (no rospy), sailing as fast as possible with a reset in the middle and a boat carried beyond
its lost distance. /clock ticks every 1/--clock-hz s of simulated time and never runs back, the reset moves the
clock on by one decision, the lost boat's episode end says "lost", and the --record log holds the same clock and
episode end; the pacer spreads its ticks over each period; the controller's help names its file."""

from __future__ import annotations

import argparse
import threading
import time

import numpy as np
import pytest

from ocean_warp.fleet import END_REASONS, BoatStatus, episode_end
from ocean_warp.ros import topics
from ocean_warp.ros.node_loop import NodeLoop, Pacer

CLOCK_HZ = 4.0
RESET_AT_S = 3.0
"""The recording bus asks for a reset once the clock has reached this [s]."""
DURATION_S = 7.0


class RecordingBus:
    """The bus interface of ``NodeLoop`` (``Ros1Bus``'s), recording every message and line; when the clock
    first reaches ``reset_at`` it calls the reset service from another thread, as rospy would, and returns once
    the request waits for the loop (so the loop resets before its next decision)."""

    caller_id = "/recording_bus"

    def __init__(self, loop_holder: list, reset_at: float):
        self.published: list = []
        self.lines: list[str] = []
        self.answers: list = []
        self._holder, self._reset_at, self._asked = loop_holder, reset_at, False

    def publish(self, messages, *, latched=()) -> None:
        for message in messages:
            self.published.append(message)
            if message.topic == topics.CLOCK and message.time_ns >= self._reset_at * 1e9 and not self._asked:
                self._asked = True
                loop = self._holder[0]
                threading.Thread(target=lambda: self.answers.append(loop._on_reset(None))).start()
                deadline = time.monotonic() + 60.0
                while not loop._reset_pending() and time.monotonic() < deadline:  # the loop sees it next
                    time.sleep(0.001)

    def subscribe(self, topic, type_name, callback) -> None:
        pass

    def publisher(self, topic, type_name, *, latch=False):
        return None

    def service(self, name, handler) -> None:
        pass

    def resolve_name(self, name: str) -> str:
        return "/ocean_warp/reset"

    def shut_down(self) -> bool:
        return False

    def info(self, text: str) -> None:
        self.lines.append(text)

    warn = info


@pytest.fixture(scope="module")
def sailed(tmp_path_factory):
    """(bus, loop, log path) of two boats of the node's task sailed for DURATION_S with a reset at RESET_AT_S;
    boat 1 is carried 300 m away before the first decision (beyond the seed task's 125 m)."""
    pytest.importorskip("mcap_ros2")
    from ocean_warp.envs.ros.mcap_log import McapRecorder
    from ocean_warp.envs.ros.node import _Simulation

    sim = _Simulation.build(argparse.Namespace(sea_state=None, wind=None, seed=5, hull="auto", lidar=False,
                                               camera=False, boats=2), "EBoatWaypoint-v0", "cpu")
    position = sim.env.simulator.state.position
    moved = position.numpy()
    moved[1, 0] += 300.0
    position.assign(moved)
    args = argparse.Namespace(duration=DURATION_S, lockstep=False, lockstep_timeout=0.0, as_fast_as_possible=True,
                              rate_factor=0.0, clock_hz=CLOCK_HZ)
    holder: list = []
    bus = RecordingBus(holder, RESET_AT_S)
    path = tmp_path_factory.mktemp("node") / "run.mcap"
    recorder = McapRecorder(path)
    loop = NodeLoop(sim, bus, args, recorder)
    holder.append(loop)
    loop.run()
    recorder.close()
    return bus, loop, path


def _reset_time(bus) -> float:
    line = next(line for line in bus.lines if "reset: every boat restarted" in line)
    return float(line.rsplit("t = ", 1)[1].split(" s")[0])


def test_the_clock_ticks_evenly_and_never_runs_back_through_a_reset(sailed):
    bus, loop, _ = sailed
    clock = np.array([m.time_ns for m in bus.published if m.topic == topics.CLOCK]) / 1e9
    assert bus.answers and bus.answers[0][0], bus.answers
    assert np.all(np.diff(clock) > 0), clock
    assert _reset_time(bus) == RESET_AT_S + 1.0  # one decision after the last time published
    # every 1/CLOCK_HZ s from 0 to the duration: the reset took one decision's slot and kept the ticks going
    np.testing.assert_allclose(clock, np.arange(0.0, DURATION_S + 1e-9, 1.0 / CLOCK_HZ), atol=1e-6)
    stamps = sorted({m.time_ns for m in bus.published if m.topic.endswith("/gps/fix")})
    np.testing.assert_allclose(np.array(stamps) / 1e9, np.arange(0.0, DURATION_S + 1e-9), atol=1e-6)
    assert loop.sim.time_s() == pytest.approx(DURATION_S, abs=1e-6)


def test_a_boat_beyond_its_lost_distance_ends_lost(sailed):
    bus, _, _ = sailed
    ends = [m for m in bus.published if m.topic.endswith(topics.EPISODE_TOPIC)]
    assert [m.topic for m in ends] == ["/eboat_1/mission_control/episode"]  # after the first decision
    data = ends[0].fields["data"]
    assert len(data) == len(topics.EPISODE_END) == 8
    assert END_REASONS[int(data[5])] == "lost" and data[0] == 0.0 and data[4] == 0.0
    assert data[6] == 1.0 and data[7] == pytest.approx(1.0) and ends[0].time_ns == 1_000_000_000
    line = next(line for line in bus.lines if "episode ended" in line)
    assert "/eboat_1/mission_control/episode: episode ended at t = 1.0 s: lost," in line


def test_the_record_holds_the_same_clock_and_the_episode_end(sailed):
    pytest.importorskip("rosbags")
    from rosbags.highlevel import AnyReader

    bus, _, path = sailed
    seen: dict[str, list] = {}
    with AnyReader([path]) as reader:
        for connection, log_time, raw in reader.messages():
            seen.setdefault(connection.topic, []).append((log_time, reader.deserialize(raw, connection.msgtype)))
    clock = [message.clock.sec * 10**9 + message.clock.nanosec for _, message in seen["/clock"]]
    assert clock == [m.time_ns for m in bus.published if m.topic == topics.CLOCK]
    observations = [t for t, _ in seen["/eboat_0/mission_control/observations"]]
    assert observations == sorted(observations) and len(set(observations)) == len(observations) == DURATION_S + 1
    (log_time, end), = seen["/eboat_1/mission_control/episode"]
    assert log_time == 1_000_000_000 and END_REASONS[int(end.data[5])] == "lost"


def test_episode_end_reasons_follow_the_status_then_the_time_limit():
    capsized_and_touched = BoatStatus.CAPSIZED | BoatStatus.COLLIDED
    assert episode_end(False, False, capsized_and_touched) == "capsized"
    assert episode_end(False, True, BoatStatus.COLLIDED) == "collided"
    assert episode_end(False, False, BoatStatus.SUNK) == "flagged"
    assert episode_end(True, True, 0) == "time-out"
    assert episode_end(True, False, 0) == "reached"
    assert episode_end(False, False, 0) == "lost"
    messages = topics.episode_messages(9_500_000_000, [True, True, False], [1, 0, 0], [1, 0, 0], [9, 4, 0],
                                       [1.0, -2.0, 0.0], [0, BoatStatus.COLLIDED, 0], [False, False, True])
    assert [topics.episode_end_reason(m) for m in messages] == ["reached", "collided"]
    assert [m.fields["data"][6:] for m in messages] == [[0.0, 9.5], [1.0, 9.5]]


def test_the_pacer_spreads_actions_over_each_period_and_runs_them_at_once_when_unpaced():
    stop, seen = threading.Event(), []
    unpaced = Pacer(0.0)
    unpaced.wait(stop, [(0.5, lambda: seen.append("a")), (0.9, lambda: seen.append("b"))])
    assert seen == ["a", "b"]
    period = 0.4
    pacer = Pacer(period)
    pacer.wait(stop)  # the first decision at once
    start = time.monotonic()
    times: list[float] = []
    pacer.wait(stop, [(fraction, lambda: times.append(time.monotonic() - start)) for fraction in (0.25, 0.5, 0.75)])
    waited = time.monotonic() - start
    # lower bounds only (load makes waits longer, never shorter); 20 ms for the clock's resolution
    assert len(times) == 3 and times == sorted(times)
    for due, at in zip((0.25, 0.5, 0.75), times):
        assert at >= due * period - 0.02
    assert waited >= period - 0.02


def test_the_controllers_help_names_its_file_not_a_missing_job():
    from ocean_warp.ros import controller_node

    text = controller_node._parser().format_help()
    assert text.startswith("usage: controller_node.py ") and "ocean-warp controller" not in text
    assert "python3 ocean_warp/ros/controller_node.py --policy" in text
