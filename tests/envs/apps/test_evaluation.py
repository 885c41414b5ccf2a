"""``ocean-warp eval`` (ocean_warp.envs.apps.evaluation): the path metrics on hand-made paths, a tiny evaluation of
a random policy and the autopilot on the CPU, the command line, and the runner's decision against
``SailingEnv.step``."""

from __future__ import annotations

import argparse
import csv
import dataclasses
import datetime
import math
import warnings

import numpy as np
import pytest
import torch

from ocean_warp import cli
from ocean_warp.eboat import EBoatConfig, Hydrostatics
from ocean_warp.envs import TASK_IDS, MissionConfig, SailingEnv
from ocean_warp.envs.training import policies
from ocean_warp.envs.apps.evaluation import _policy_for, main
from ocean_warp.envs.evaluation import (
    AutopilotController,
    FleetController,
    PolicyController,
    RecordedDecision,
    evaluate_mission,
    evaluation_task,
    mission_task,
    sail_mission,
)
from ocean_warp.envs.evaluation.mission_metrics import (
    cross_track_profile,
    cross_track_spread,
    leg_indices,
    motor_use,
    path_length,
    wind_crossings,
)
from ocean_warp.envs.training.policy_io import build_actor, load_policy, save_checkpoint
from ocean_warp.ocean_config import OceanConfig
from tests.env_buffers import assert_same_buffers

DEG = math.pi / 180.0
COLUMNS = ["controller", "runs", "completed", "completion_rate", "time_mean_s", "time_std_s", "time_min_s",
           "time_max_s", "distance_mean_m", "tacks_mean", "gybes_mean", "cross_track_spread_m", "capsizes",
           "collisions", "lost", "time_outs", "motor_use", "vrx_score"]


def tiny_mission(**changes) -> MissionConfig:
    """The mission on the four-point hydrostatics and a 16 x 16 sea: cheap enough for a test on the CPU."""
    task = MissionConfig()
    simulator = dataclasses.replace(
        task.simulator, boat=EBoatConfig(hydrostatics=Hydrostatics.POINTS), ocean_every_substep=False,
        ocean=OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.3, peak_period=3.0))
    return dataclasses.replace(task, simulator=simulator, **changes)


def random_policy_file(path, *, constant_actions=None, task="EBoatMission-v0", observation="seed",
                       num_obs=6) -> None:
    """A seed-observation policy for the mission with random weights (or for ``task``, reading
    ``observation``, ``num_obs`` values); with ``constant_actions`` (3,), one whose output layer ignores the
    observation and always gives these actions."""
    config = {"class_name": "MLPModel", "hidden_dims": [32, 32], "activation": "relu", "obs_normalization": False,
              "distribution_cfg": {"class_name": "GaussianDistribution", "init_std": 1.0}}
    torch.manual_seed(0)
    actor = build_actor(num_obs, 3, config)
    if constant_actions is not None:
        last = [module for module in actor.modules() if isinstance(module, torch.nn.Linear)][-1]
        with torch.no_grad():
            last.weight.zero_()
            last.bias.copy_(torch.tensor(constant_actions))
    save_checkpoint(path, {"task": task, "observation": observation, "num_obs": num_obs, "num_actions": 3,
                           "actor_config": config, "actor_state_dict": actor.state_dict()})


# --- metrics on hand-made paths ----------------------------------------------------------------------

def zigzag(headings_deg, block: int):
    """Positions and per-sample headings of a path of ``block`` unit-speed steps per heading."""
    headings = np.repeat(np.radians(headings_deg), block)
    steps = np.column_stack([np.cos(headings), np.sin(headings)])
    xy = np.vstack([[0.0, 0.0], np.cumsum(steps, axis=0)])
    return xy, np.append(headings, headings[-1])


def test_straight_path():
    xy = np.column_stack([np.linspace(0.0, 30.0, 31), np.linspace(0.0, 40.0, 31)])
    assert path_length(xy) == pytest.approx(50.0)
    assert wind_crossings(np.full(31, 53.13 * DEG), 0.0) == (0, 0)
    assert path_length(np.array([[0.0, 0.0], [3.0, 0.0], [3.0, 4.0]])) == pytest.approx(7.0)
    assert path_length(np.zeros((1, 2))) == 0.0


def test_zigzag_upwind_tacks_and_downwind_gybes():
    """Wind toward +x (from -x). Beating west: four boards 45 deg either side of the wind's source (heading 135
    and -135 deg), 3 steps each: 3 tacks, no gybe, 12 m sailed. Running east with gybes: headings +-30 deg,
    four boards: 3 gybes, no tack."""
    xy, heading = zigzag([135.0, -135.0, 135.0, -135.0], block=3)
    assert path_length(xy) == pytest.approx(12.0)
    assert np.allclose(xy[-1], [-12.0 / math.sqrt(2.0), 0.0])
    assert wind_crossings(heading, 0.0) == (3, 0)
    assert wind_crossings(heading, 0.0, margin=0.0) == (3, 0)
    _, heading = zigzag([30.0, -30.0, 30.0, -30.0], block=5)
    assert wind_crossings(heading, 0.0) == (0, 3)
    # The same beat, sampled through each turn: still one tack per turn.
    turn = np.radians([135.0, 150.0, 170.0, 190.0, 210.0, 225.0, 225.0, 200.0, 175.0, 150.0, 135.0])
    assert wind_crossings(turn, 0.0) == (2, 0)


def test_crossings_yawing_failed_tack_and_full_circle():
    """Yawing +-5 deg about head to wind: nothing with the 10 deg margin, every sign flip without one. A tack
    that goes 5 deg through the wind and falls back: nothing (2 flips without margin). A full turn to port
    from a reach: the wind crosses the bow once and the stern once. A wind that veers across the stern of a
    boat holding its course: one gybe (wind direction given per sample)."""
    yaw = np.radians(180.0 + 5.0 * (-1.0) ** np.arange(20))
    assert wind_crossings(yaw, 0.0) == (0, 0)
    assert wind_crossings(yaw, 0.0, margin=0.0) == (19, 0)
    failed = np.radians([135.0, 160.0, 175.0, 185.0, 160.0, 135.0])
    assert wind_crossings(failed, 0.0) == (0, 0)
    assert wind_crossings(failed, 0.0, margin=0.0) == (2, 0)
    circle = np.radians(np.arange(10.0, 391.0, 10.0))  # 10 ... 390 deg
    assert wind_crossings(circle, 0.0) == (1, 1)
    assert wind_crossings(np.zeros(7), np.radians(np.linspace(30.0, -30.0, 7))) == (0, 1)
    with pytest.raises(ValueError, match="margin"):
        wind_crossings(circle, 0.0, margin=math.pi / 2)


def test_motor_use():
    assert motor_use([0, 1, -2, 0]) == 0.5
    assert motor_use(np.zeros(10, dtype=int)) == 0.0
    assert math.isnan(motor_use([]))


def test_cross_track_profile_by_hand():
    """A path that doubles back along the leg (0, 0) -> (20, 0): the offset where it first reaches each
    along-track distance 0, 5, 10, 15, 20 m."""
    path = np.array([[0.0, 0.0], [10.0, 10.0], [5.0, 10.0], [20.0, -10.0]])
    np.testing.assert_allclose(cross_track_profile(path, (0.0, 0.0), (20.0, 0.0), points=5),
                               [0.0, 5.0, 10.0, 10.0 - 20.0 * 10.0 / 15.0, -10.0])
    # Short of the end: the last point's offset; starting beyond 0: the first point's.
    np.testing.assert_allclose(cross_track_profile([[0.0, 1.0], [8.0, 2.0]], (0.0, 0.0), (10.0, 0.0), points=3),
                               [1.0, 1.625, 2.0])
    np.testing.assert_allclose(cross_track_profile([[2.0, 3.0], [10.0, 3.0]], (0.0, 0.0), (10.0, 0.0), points=3),
                               [3.0, 3.0, 3.0])
    # Left of the leg is positive: a leg toward +y, a path at x = -2.
    np.testing.assert_allclose(cross_track_profile([[-2.0, 0.0], [-2.0, 10.0]], (0.0, 0.0), (0.0, 10.0)), 2.0)


def test_cross_track_spread_by_hand():
    """Route (100, 0) then (100, 100) from (0, 0). Runs 1 and 2 sail both legs offset by +d and -d from the
    straight legs (spread d: population std); run 3 sails leg 0 on the line and stops there (leg 0:
    std of (d, -d, 0) = d sqrt(2/3)); run 4 never finishes leg 0 and counts nowhere."""
    d = 3.0
    route, start = [(100.0, 0.0), (100.0, 100.0)], (0.0, 0.0)
    run1 = np.array([[0.0, d], [50.0, d], [100.0 + d, d], [100.0 + d, 50.0], [100.0 + d, 100.0 + d]])
    run2 = np.array([[0.0, -d], [50.0, -d], [100.0 - d, -d], [100.0 - d, 50.0], [100.0 - d, 100.0 - d]])
    run3 = np.array([[0.0, 0.0], [50.0, 0.0], [100.0, 0.0], [100.0, 0.0]])
    run4 = np.array([[0.0, 20.0], [60.0, 20.0]])
    reached = [np.array([0, 0, 1, 1, 2]), np.array([0, 0, 1, 1, 2]), np.array([0, 0, 1, 1]), np.array([0, 0])]
    np.testing.assert_array_equal(leg_indices(reached[0], 0), [0, 1, 2])
    np.testing.assert_array_equal(leg_indices(reached[0], 1), [2, 3, 4])
    per_leg, mean = cross_track_spread([run1, run2], reached[:2], route, start)
    np.testing.assert_allclose(per_leg, [d, d])
    assert mean == pytest.approx(d)
    per_leg, mean = cross_track_spread([run1, run2, run3, run4], reached, route, start)
    np.testing.assert_allclose(per_leg, [d * math.sqrt(2.0 / 3.0), d])
    assert mean == pytest.approx((d * math.sqrt(2.0 / 3.0) + d) / 2.0)
    per_leg, mean = cross_track_spread([run1, run4], [reached[0], reached[3]], route, start)
    assert np.all(np.isnan(per_leg)) and math.isnan(mean)  # a leg needs two runs that completed it
    # a first waypoint where the runs start: that leg has no track (no spread), the next one counts as before
    per_leg, mean = cross_track_spread([run1, run2], [r + 1 for r in reached[:2]], [start] + route, start)
    assert math.isnan(per_leg[0]) and mean == pytest.approx(d)
    np.testing.assert_allclose(per_leg[1:], [d, d])


# --- a tiny evaluation: 2 runs of 20 s, a random policy and the autopilot, on the CPU ----------------

@pytest.fixture(scope="module")
def tiny_evaluation(tmp_path_factory):
    folder = tmp_path_factory.mktemp("eval")
    random_policy_file(folder / "random.pt")
    policy = load_policy(folder / "random.pt")
    evaluation = evaluate_mission(policy, runs=2, time_limit=20.0, device="cpu", progress=False, task=tiny_mission())
    paths = evaluation.write(folder / "out")
    return evaluation, paths


def read_csv(path):
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    return rows[0], [dict(zip(rows[0], row)) for row in rows[1:]]


def test_tiny_evaluation_files(tiny_evaluation):
    evaluation, paths = tiny_evaluation
    with open(paths["trajectories.png"], "rb") as handle:
        png = handle.read()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 20_000
    header, rows = read_csv(paths["results.csv"])
    assert header == COLUMNS
    assert [row["controller"] for row in rows] == ["policy", "autopilot"]
    for row in rows:
        assert int(row["runs"]) == 2
        assert int(row["completed"]) == 0 and float(row["completion_rate"]) == 0.0  # 20 s: no mission done
        assert math.isnan(float(row["time_mean_s"])) and math.isnan(float(row["cross_track_spread_m"]))
        assert float(row["distance_mean_m"]) >= 0.0
        assert float(row["tacks_mean"]) >= 0.0 and float(row["gybes_mean"]) >= 0.0
        assert int(row["lost"]) == 0 and int(row["capsizes"]) + int(row["time_outs"]) == 2
        assert 0.0 <= float(row["motor_use"]) <= 1.0
        assert row["vrx_score"] == ""  # an E-Boat task has no VRX score
    autopilot = rows[1]
    assert 10.0 < float(autopilot["distance_mean_m"]) < 20.0 * 5.0  # under way, slower than 5 m/s
    assert int(autopilot["time_outs"]) == 2
    header, runs = read_csv(paths["runs.csv"])
    assert len(runs) == 4 and [r["controller"] for r in runs] == ["policy"] * 2 + ["autopilot"] * 2
    assert all(float(r["time_s"]) <= 20.0 and float(r["distance_m"]) > 0.0 for r in runs)
    assert [r["own_tacks"] for r in runs[:2]] == ["", ""] and all(r["own_tacks"].isdigit() for r in runs[2:])
    assert header[-1] == "vrx_score" and [r["vrx_score"] for r in runs] == [""] * 4
    arrays = np.load(paths["trajectories.npz"])
    assert list(arrays["controllers"]) == ["policy", "autopilot"]
    assert arrays["autopilot_x"].shape == (2, 21) and arrays["autopilot_propeller"].shape == (2, 20)
    np.testing.assert_array_equal(arrays["autopilot_length"], [20, 20])
    # Printed table: a line per column, a column per controller.
    table = evaluation.format_table().splitlines()
    assert [line.split()[0] for line in table] == COLUMNS


def test_fingerprint_reads_runs_csv_without_the_empty_score(tiny_evaluation):
    """The behaviour fingerprint hashes runs.csv as it was before vrx_score (empty on an E-Boat task): the same
    bytes as the file rewritten without its last column."""
    import io

    from benchmarks.studies.behaviour_fingerprint import _without_empty_score

    _, paths = tiny_evaluation
    with open(paths["runs.csv"], "rb") as handle:
        data = handle.read()
    rows = list(csv.reader(io.StringIO(data.decode(), newline="")))
    assert rows[0][-1] == "vrx_score"
    before = io.StringIO(newline="")
    csv.writer(before).writerows(row[:-1] for row in rows)
    assert _without_empty_score(data) == before.getvalue().encode()


def test_tiny_evaluation_paths(tiny_evaluation):
    """Both controllers sail the same runs: identical starts (position, heading, wind); every path runs from
    its start to the end of its first episode, one sample per decision."""
    evaluation, _ = tiny_evaluation
    policy, autopilot = evaluation.results["policy"], evaluation.results["autopilot"]
    for a, b in zip(policy.paths, autopilot.paths):
        np.testing.assert_array_equal(a.xy[0], b.xy[0])
        assert a.heading[0] == b.heading[0]
        assert len(a.xy) == len(b.xy) == 21 and len(a.propeller) == 20
        assert np.all(np.isfinite(a.xy)) and np.all(a.reached == 0)
    np.testing.assert_array_equal(policy.wind_direction, autopilot.wind_direction)
    starts = np.array([p.xy[0] for p in policy.paths])
    assert np.all(np.abs(starts) <= 1.0 + 1e-6)  # the task's 1 m jitter around A
    assert not np.array_equal(starts[0], starts[1])  # each run its own start
    assert np.all(autopilot.distance_m > 10.0)


def test_recorded_decision_is_env_step(device):
    """The recorder's decision launches what ``SailingEnv.step`` launches (every buffer and state equal,
    decision after decision, through a time-out and the reset it causes); the buffers keep the pose and
    the propeller level from before that reset, and the recorder's one frame is that pose."""
    task = tiny_mission(episode_time=3.0)
    stepped = SailingEnv(task, 3, device=device, seed=5)
    recorded = SailingEnv(task, 3, device=device, seed=5)
    decision = RecordedDecision(recorded)
    generator = torch.Generator().manual_seed(1)
    for k in range(5):
        actions = (2.0 * torch.rand(3, 3, generator=generator) - 1.0).to(stepped.torch_device)
        stepped.step(actions)
        recorded.buffers.actions.copy_(actions)
        decision()
        assert_same_buffers(recorded.buffers, stepped.buffers, f"after decision {k}")
        for name in ("position", "orientation", "velocity"):
            np.testing.assert_array_equal(getattr(recorded.simulator.state, name).numpy(),
                                          getattr(stepped.simulator.state, name).numpy())
        before_reset = stepped.buffers.final_position.cpu().numpy()
        np.testing.assert_array_equal(decision.frames()["position"][0], before_reset)
        now = stepped.simulator.state.position.numpy()
        commanded = np.trunc(5.0 * np.clip(actions[:, 0].cpu().numpy(), -1.0, 1.0))  # the task's a0 -> level map
        np.testing.assert_array_equal(stepped.buffers.propeller_level.cpu().numpy(), commanded)
        if k == 2:  # every run timed out (3 s) and restarted near A: the recorded pose is from before
            assert stepped.buffers.time_out.all()
            assert np.all(np.linalg.norm(before_reset - now, axis=1) > 1.0)
            assert np.all(stepped.simulator.control.propeller.numpy() == 0)  # the reset stopped the motor
        else:
            np.testing.assert_array_equal(before_reset, now)
            np.testing.assert_array_equal(stepped.buffers.position.cpu().numpy(), now)


def test_recorded_decision_frames_inside_the_decision(device):
    """Four frames of a 20-step decision are the states after physics steps 5, 10, 15 and 20, read here
    step by step from a twin environment; the last frame is the decision's recorded pose."""
    task = tiny_mission()
    recorded = SailingEnv(task, 3, device=device, seed=2)
    twin = SailingEnv(task, 3, device=device, seed=2)
    decision = RecordedDecision(recorded, frames_per_decision=4)
    actions = torch.tensor([[0.6, -0.2, 0.4], [0.2, 0.5, -0.7], [1.0, 0.0, 0.1]], device=recorded.torch_device)
    recorded.buffers.actions.copy_(actions)
    decision()
    twin.buffers.actions.copy_(actions)
    twin.launch_actions()
    expected = []
    for step in range(twin.steps_per_decision):
        twin.simulator.launch_step()
        if (step + 1) % (twin.steps_per_decision // 4) == 0:
            state = twin.simulator.state
            expected.append((state.position.numpy().copy(), state.orientation.numpy().copy(),
                             state.boom_angle.numpy().copy(), state.rudder_angle.numpy().copy()))
    frames = decision.frames()
    assert frames["position"].shape == (4, 3, 3) and frames["boom_angle"].shape == (4, 3)
    for f, (position, orientation, boom, rudder) in enumerate(expected):
        np.testing.assert_array_equal(frames["position"][f], position)
        np.testing.assert_array_equal(frames["orientation"][f], orientation)
        np.testing.assert_array_equal(frames["boom_angle"][f], boom)
        np.testing.assert_array_equal(frames["rudder_angle"][f], rudder)
    np.testing.assert_array_equal(frames["position"][-1], recorded.buffers.final_position.cpu().numpy())
    assert np.abs(np.diff(frames["rudder_angle"], axis=0)).max() > 0  # the rudder moves during the decision
    with pytest.raises(ValueError, match="frames_per_decision"):
        RecordedDecision(recorded, frames_per_decision=3)  # does not divide 20 steps


def test_vrx_score_is_read_where_each_first_episode_ends(tmp_path):
    """A task that scores its episodes (here a hook standing in for its kernel: after decision k it writes
    100 k + run + 0.25 into ``env.buffers.final_score``, and NaN for run 2): each run's vrx_score is the value
    at the decision where its first episode ended (the 4th of a 4 s mission at 1 s a decision, every run
    timing out), the controller's is their mean, empty where one run has none."""
    from ocean_warp.envs.evaluation import FixedController, MissionEvaluation

    env = SailingEnv(tiny_mission(episode_time=4.0), 3, device="cpu", seed=0)

    def score(k, decision):
        env.buffers.final_score.copy_(torch.tensor([100.0 * k + 0.25, 100.0 * k + 1.25, math.nan]))

    result = sail_mission(env, FixedController((0.0, 0.0, 0.0)), on_decision=score)
    assert result.time_out.all() and list(result.time_s) == [4.0, 4.0, 4.0]
    np.testing.assert_array_equal(result.vrx_score, [300.25, 301.25, np.nan])
    assert result.summary()["vrx_score"] == ""
    assert [row["vrx_score"] for row in result.run_rows()] == [300.25, 301.25, ""]
    both = result.subset(np.array([True, True, False]), "scored")
    assert both.summary()["vrx_score"] == (300.25 + 301.25) / 2
    paths = MissionEvaluation(task=env.task, settings={"runs": 2, "seed": 0}, results={"scored": both}).write(tmp_path)
    _, rows = read_csv(paths["results.csv"])
    assert float(rows[0]["vrx_score"]) == 300.75
    _, runs = read_csv(paths["runs.csv"])
    assert [float(row["vrx_score"]) for row in runs] == [300.25, 301.25]
    with pytest.raises(ValueError, match=r"vrx_score must be \(3,\)"):
        dataclasses.replace(result, vrx_score=np.zeros(2))


def test_fleet_controller_gives_each_run_its_controllers_actions(tmp_path):
    """Runs 0 and 2 sail with the policy, 1 and 3 with the autopilot: each run's actions equal what its
    controller alone computes in a twin environment; the split results match separate evaluations."""
    random_policy_file(tmp_path / "random.pt")
    policy = load_policy(tmp_path / "random.pt")
    task = tiny_mission(episode_time=30.0)
    mask = np.array([True, False, True, False])
    fleet = FleetController([(PolicyController(policy), mask), (AutopilotController(), ~mask)])
    env = SailingEnv(task, 4, device="cpu", seed=3)
    alone = {name: SailingEnv(task, 4, device="cpu", seed=3) for name in ("policy", "autopilot")}
    controllers = {"policy": PolicyController(policy), "autopilot": AutopilotController()}
    fleet.reset(env)
    for name, controller in controllers.items():
        controller.reset(alone[name])
    fleet.act(env)
    for name, rows in (("policy", mask), ("autopilot", ~mask)):
        controllers[name].act(alone[name])
        np.testing.assert_array_equal(env.buffers.actions.numpy()[rows], alone[name].buffers.actions.numpy()[rows])
    # sailed whole: the policy's runs of the fleet are the policy's runs of a policy-only evaluation
    result = sail_mission(SailingEnv(task, 4, device="cpu", seed=3), fleet)
    reference = sail_mission(SailingEnv(task, 4, device="cpu", seed=3), PolicyController(policy))
    mine, theirs = result.subset(mask, "policy"), reference.subset(mask, "policy")
    assert mine.name == "policy" and mine.runs == 2
    for a, b in zip(mine.paths, theirs.paths):
        np.testing.assert_allclose(a.xy, b.xy, rtol=0, atol=1e-4)
    np.testing.assert_array_equal(mine.time_s, theirs.time_s)
    # the autopilot's own tack and gybe counters reach its runs' rows, and only those (the policy keeps none)
    autopilot = sail_mission(SailingEnv(task, 4, device="cpu", seed=3), AutopilotController()).subset(~mask, "a")
    assert mine.own_tacks is None and mine.run_rows()[0]["own_tacks"] == ""
    theirs = result.subset(~mask, "autopilot")
    for key in ("own_tacks", "own_gybes"):
        np.testing.assert_array_equal(getattr(theirs, key), getattr(autopilot, key))
    assert [row["own_tacks"] for row in theirs.run_rows()] == [int(v) for v in autopilot.own_tacks]
    with pytest.raises(ValueError, match="exactly one controller"):
        FleetController([(PolicyController(policy), mask), (AutopilotController(), mask)])


def test_evaluation_over_a_sharded_env_is_the_same(tmp_path):
    """Evaluation reads only the batched-env protocol: the policy and the autopilot sail 5 runs on a
    ShardedSailingEnv of 2 workers exactly as on one SailingEnv (paths, propeller levels, outcomes and the
    autopilot's own counters bit for bit), and a frame recorder, which looks inside a decision, asks for a
    SailingEnv by name."""
    from ocean_warp.envs.parallel.sharded import ShardedSailingEnv

    random_policy_file(tmp_path / "random.pt")
    task = tiny_mission(episode_time=40.0)
    for controller in (PolicyController(load_policy(tmp_path / "random.pt")), AutopilotController()):
        alone = sail_mission(SailingEnv(task, 5, device="cpu", seed=4), controller)
        with ShardedSailingEnv(task, 5, workers=2, seed=4) as env:
            sharded = sail_mission(env, controller)
            with pytest.raises(ValueError, match="RecordedDecision: env must be a SailingEnv"):
                sail_mission(env, controller, on_decision=lambda k, decision: None)
        for mine, theirs in zip(sharded.paths, alone.paths):
            for field in ("xy", "heading", "propeller", "reached"):
                np.testing.assert_array_equal(getattr(mine, field), getattr(theirs, field), err_msg=field)
        for field in ("success", "time_s", "waypoints", "status", "time_out", "wind_direction", "routes",
                      "own_tacks", "own_gybes"):
            np.testing.assert_array_equal(getattr(sharded, field), getattr(alone, field), err_msg=field)
        assert max(len(path.xy) for path in alone.paths) > 10


def test_progress_bar_ends_full_when_every_run_ends_early(capsys):
    """Every run reaches its one waypoint (where it starts) long before the 20-decision limit: the bar ends at
    100 % of the decisions sailed, not part-way (the demo's stopped at 42 % when every boat was done)."""
    task = tiny_mission(route=((3.0, 0.0),), reach_radius=10.0, episode_time=20.0)
    result = sail_mission(SailingEnv(task, 2, device="cpu", seed=1), AutopilotController(), progress=True)
    sailed = max(len(path.propeller) for path in result.paths)
    assert result.success.all() and sailed < 20
    renders = capsys.readouterr().err.replace("\n", "\r").split("\r")
    last = [text for text in renders if "decision" in text][-1]
    assert "100%" in last and f"{sailed}/{sailed}" in last and "ended 2/2" in last, last


# --- the command line --------------------------------------------------------------------------------

def test_cli_help(capsys):
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["eval", "--help"])
    assert exit_info.value.code == 0
    text = capsys.readouterr().out
    assert "ocean-warp eval" in text
    for option in ("--task", "--runs", "--sea-state", "--wind", "--seed", "--out", "--device", "--policy",
                   "--no-autopilot", "--no-policy", "--time-limit"):
        assert option in text


@pytest.mark.parametrize("argv, message", [
    (["--runs", "0"], "--runs must be a whole number >= 1, got 0"),
    (["--sea-state", "-0.1"], "--sea-state must be"),
    (["--wind", "-1"], "--wind must be"),
    (["--wind", "nan"], "--wind must be"),
    (["--time-limit", "0"], "--time-limit must be"),
    (["--no-policy", "--no-autopilot"], "nothing to run"),
    (["--device", "tpu"], "tpu"),
])
def test_cli_bad_options(argv, message, capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("ocean-warp eval: error: ") and message in err[0], err


def unusable_checkpoints(folder) -> dict[str, str]:
    """Files that are not ocean_warp policies, each with what its one-line error must say: a text file, random
    bytes, a zip with random contents, a truncated policy, a pickled object of another kind, a foreign torch
    file, a folder, and a missing file (random contents seeded)."""
    rng = np.random.default_rng(20)
    (folder / "notes.txt").write_text("policy: the shipped one, please\nnot a checkpoint\n")
    (folder / "random.pt").write_bytes(rng.bytes(4096))
    (folder / "zip_garbage.pt").write_bytes(b"PK\x03\x04" + rng.bytes(4096))
    random_policy_file(folder / "good.pt")
    data = (folder / "good.pt").read_bytes()
    (folder / "truncated.pt").write_bytes(data[: len(data) // 2])
    torch.save({"format": "ocean_warp.policy/1", "when": datetime.date(2026, 11, 23)}, folder / "code.pt")
    torch.save({"weights": torch.zeros(3)}, folder / "foreign.pt")
    (folder / "a_folder.pt").mkdir()
    with warnings.catch_warnings():  # torch.jit is deprecated, yet it is what export-policy writes for libtorch
        warnings.simplefilter("ignore", DeprecationWarning)
        torch.jit.save(torch.jit.script(torch.nn.Linear(5, 3)), str(folder / "scripted.pt"))
    not_ours = "is not an ocean_warp policy checkpoint"
    return {"notes.txt": f"{not_ours}: not a file written by torch.save",
            "random.pt": f"{not_ours}: not a file written by torch.save",
            "zip_garbage.pt": f"{not_ours}: it could not be read as a torch file",
            "truncated.pt": f"{not_ours}: it could not be read as a torch file",
            "code.pt": f"{not_ours}: it holds datetime.date, not only tensors and plain data",
            "foreign.pt": f"{not_ours} (no 'format' key",
            "a_folder.pt": "is a folder, not an ocean_warp policy checkpoint file",
            "missing.pt": "no such file",
            "scripted.pt": "is a TorchScript export (for libtorch, made by ocean-warp export-policy), not a policy "
                           "checkpoint: pass the checkpoint ocean-warp train writes (policy.pt or model_<it>.pt in "
                           "its run folder)"}


def test_cli_unusable_policy(tmp_path, capsys):
    """Anything but an ocean_warp policy: one line naming the file and saying so, exit status 2, no traceback,
    never torch's advice to load unsafely (weights_only=False), nothing written."""
    for name, message in unusable_checkpoints(tmp_path).items():
        with pytest.raises(SystemExit) as exit_info:
            main(["--policy", str(tmp_path / name), "--out", str(tmp_path / "out")])
        assert exit_info.value.code == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1, (name, err)
        assert err[0].startswith(f"ocean-warp eval: error: checkpoint {str(tmp_path / name)!r}"), (name, err)
        assert message in err[0], (name, err)
        assert "weights_only" not in err[0] and "safe_globals" not in err[0]
    assert not (tmp_path / "out").exists()


def test_a_policy_trained_on_another_task_gets_a_one_line_warning(tmp_path, capsys):
    """A waypoint policy reads the mission's observation (the 'seed' set, 5 values), so it sails; eval says in
    one line that it was trained elsewhere. A mission policy on the mission: no warning."""
    parser = argparse.ArgumentParser(prog="ocean-warp eval")
    for task in ("EBoatWaypoint-v0", "EBoatMission-v0"):
        path = tmp_path / f"{task}.pt"
        random_policy_file(path, task=task)
        policy = _policy_for(parser, argparse.Namespace(policy=str(path), no_autopilot=False), "EBoatMission-v0")
        assert policy.task == task
        err = capsys.readouterr().err.strip().splitlines()
        if task == "EBoatMission-v0":
            assert err == []
        else:
            assert err == ["ocean-warp eval: warning: the policy was trained on EBoatWaypoint-v0, not on "
                           "EBoatMission-v0; its results here show how it transfers, not what training on "
                           "EBoatMission-v0 gives"]


@pytest.mark.parametrize("task, observation, num_obs, reads", [
    ("EBoatAvoid-v0", "seed", 5 + 24, "29 values (the 'seed' set's 5 and 24 the task appends: reef level, lidar "
                                      "sectors)"),
    ("EBoatWaypointPlus-v0", "plus", 15, "15 values (the 'plus' set)"),
])
def test_an_observation_mismatch_names_both_sets_and_sizes(task, observation, num_obs, reads, tmp_path):
    random_policy_file(tmp_path / "policy.pt", task=task, observation=observation, num_obs=num_obs)
    env = SailingEnv(tiny_mission(), 1, device="cpu", seed=0)
    with pytest.raises(ValueError) as raised:
        PolicyController(load_policy(tmp_path / "policy.pt")).reset(env)
    assert str(raised.value) == (f"PolicyController: the policy (trained on {task}) reads {reads}, the task gives "
                                 "6 values (the 'seed' set's 5 and 1 the task appends: reef level, lidar sectors): "
                                 f"sail it on {task}, or pass a policy trained for this task")


def test_cli_runs_the_mission(tmp_path, capsys):
    """The command end to end on the real mission (mesh hull), briefly: 1 run of 2 s per controller."""
    random_policy_file(tmp_path / "random.pt")
    code = main(["--policy", str(tmp_path / "random.pt"), "--runs", "1", "--time-limit", "2", "--out",
                 str(tmp_path / "out"), "--no-progress", "--sea-state", "0.2", "--wind", "8", "--seed", "3"])
    assert code == 0
    out = capsys.readouterr().out
    assert "completion_rate" in out and "wrote" in out
    assert "1 run per controller" in out and "1 runs" not in out
    for name in ("results.csv", "runs.csv", "trajectories.npz", "trajectories.png"):
        assert (tmp_path / "out" / name).is_file()
    _, rows = read_csv(tmp_path / "out" / "runs.csv")
    assert len(rows) == 2 and all(float(row["time_s"]) == 2.0 for row in rows)


def test_mission_task_settings():
    task = mission_task(sea_state=0.5, wind=7.0, seed=4, time_limit=60.0, observation="plus")
    assert task.simulator.ocean.significant_wave_height == 0.5 and task.simulator.ocean.seed == 4
    assert task.simulator.wind.speed == 7.0 and task.start.wind_speed == (7.0, 7.0)
    assert task.episode_time == 60.0 and task.observation.value == "plus"
    assert task.route == MissionConfig().route
    with pytest.raises(ValueError, match="runs"):
        evaluate_mission(None, runs=0)
    with pytest.raises(ValueError, match="nothing to evaluate"):
        evaluate_mission(None, runs=1, autopilot=False)


def test_shipped_policy_path(monkeypatch):
    """The shipped policies include these three (more may be added: the sail-only avoidance task's later); every
    shipped one is a registered task's."""
    assert policies.SHIPPED_POLICIES.items() >= {"EBoatMission-v0": "eboat_mission.pt",
                                                 "EBoatWaypoint-v0": "eboat_waypoint.pt",
                                                 "EBoatMissionSail-v0": "eboat_mission_sail.pt"}.items()
    assert set(policies.SHIPPED_POLICIES) <= set(TASK_IDS)
    with pytest.raises(ValueError, match="no policy is shipped"):
        policies.shipped_policy_path("EBoatAvoidSail-v0")
    monkeypatch.setitem(policies.SHIPPED_POLICIES, "EBoatMission-v0", "not_there_yet.pt")
    with pytest.raises(FileNotFoundError, match="not_there_yet.pt"):
        policies.shipped_policy_path("ocean_warp/EBoatMission-v0")


def test_apps_do_not_import_the_eval_command():
    """render, demo, export-usd, the fleet scenario and the success rate take what they sail from
    ocean_warp.envs.evaluation; the eval command's module (its options and main) stays out of them."""
    import subprocess
    import sys

    apps = ("render", "demo", "usd_export", "fleet_scenario", "success_rate")
    code = ("import sys\n" + "".join(f"import ocean_warp.envs.apps.{name}\n" for name in apps)
            + "print('ocean_warp.envs.apps.evaluation' in sys.modules, 'ocean_warp.envs.evaluation' in sys.modules)")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["False", "True"]


def test_benchmark_uses_the_runner(monkeypatch):
    """benchmarks/studies/autopilot_mission.py sails through ocean_warp.envs.evaluation (no loop of its own)."""
    from benchmarks.studies import autopilot_mission

    calls = []

    def spy(*args, **kwargs):
        calls.append(kwargs)
        return evaluate_mission(*args, **kwargs)

    monkeypatch.setattr(autopilot_mission, "evaluate_mission", spy)
    result = autopilot_mission.run_mission(2, time_limit=5.0, task=tiny_mission())
    assert len(calls) == 1 and calls[0]["autopilot"] == "legacy"  # the study of the legacy autopilot
    assert set(result) == {"success", "time", "waypoints", "tacks", "status", "time_out"}
    np.testing.assert_array_equal(result["time"], [5.0, 5.0])
    np.testing.assert_array_equal(result["time_out"], [1.0, 1.0])


# --- every task: ``--task`` ------------------------------------------------------------------------

SHIPPED = set(policies.SHIPPED_POLICIES)
"""Tasks with a shipped policy (the others sail the autopilot alone)."""


EBOAT_TASK_IDS = [name for name in TASK_IDS if name.startswith("EBoat")]
"""The E-Boat's sailing tasks (VRX's, with their own baselines and scores: ``tests/envs/vrx/test_vrx_env.py``)."""


@pytest.mark.parametrize("task_id", [f"ocean_warp/{name}" if k % 2 else name for k, name in enumerate(EBOAT_TASK_IDS)])
def test_cli_runs_every_task(task_id, tmp_path, capsys):
    """``eval --task ID`` for every registered E-Boat id (with and without the prefix): 1 run of 2 s per controller,
    the task's shipped policy where it has one, else the autopilot alone, said in one line."""
    name = task_id.removeprefix("ocean_warp/")
    assert main(["--task", task_id, "--runs", "1", "--time-limit", "2", "--out", str(tmp_path), "--no-progress",
                 "--device", "cpu"]) == 0  # compared below with a CPU environment
    out = capsys.readouterr().out
    assert (f"no policy is shipped for {name}" in out) == (name not in SHIPPED)
    header, rows = read_csv(tmp_path / "results.csv")
    assert header == COLUMNS
    assert [row["controller"] for row in rows] == (["policy", "autopilot"] if name in SHIPPED else ["autopilot"])
    assert all(int(row["runs"]) == 1 and int(row["time_outs"]) + int(row["capsizes"]) == 1 for row in rows)
    if name == "EBoatMissionSail-v0":
        assert float(rows[0]["motor_use"]) == 0.0
    _, runs = read_csv(tmp_path / "runs.csv")
    assert all(float(row["time_s"]) == 2.0 for row in runs)
    # Obstacles: counted in every table (none in 2 s), kept per controller in the NPZ where the task has them,
    # as the environment drew them at its reset (the same task and seed: the same layout).
    assert all(int(row["collisions"]) == 0 for row in rows)
    arrays = np.load(tmp_path / "trajectories.npz")
    task = evaluation_task(name, time_limit=2.0)
    for row in rows:
        if task.obstacles is None:
            assert f"{row['controller']}_obstacles" not in arrays
        else:
            env = SailingEnv(task, 1, device="cpu", seed=0)
            env.reset(seed=0)
            obstacles = arrays[f"{row['controller']}_obstacles"]
            np.testing.assert_array_equal(obstacles, env.buffers.obstacles.cpu().numpy())
            assert obstacles.shape == (1, task.obstacle_slots, 4) and np.any(obstacles[0, :, 3] != 0)


def test_cli_sail_task_ignores_the_policys_propeller(tmp_path, capsys):
    """A policy that always asks for full propeller (a0 = 1): motor use 1 on the mission, 0 on the mission
    under sail alone, for the policy and the autopilot alike (the autopilot without motor assist)."""
    random_policy_file(tmp_path / "full_ahead.pt", constant_actions=[1.0, 0.0, 0.0])
    for task, motor in (("EBoatMission-v0", 1.0), ("EBoatMissionSail-v0", 0.0)):
        out = tmp_path / task
        assert main(["--task", task, "--policy", str(tmp_path / "full_ahead.pt"), "--runs", "1", "--time-limit", "3",
                     "--out", str(out), "--no-progress"]) == 0
        _, rows = read_csv(out / "results.csv")
        assert float(rows[0]["motor_use"]) == motor
        arrays = np.load(out / "trajectories.npz")
        assert np.all(arrays["policy_propeller"] == 5 * motor)
        if task == "EBoatMissionSail-v0":
            assert float(rows[1]["motor_use"]) == 0.0 and np.all(arrays["autopilot_propeller"] == 0)
    capsys.readouterr()


@pytest.mark.parametrize("argv, message", [
    (["--task", "EBoatNowhere-v0"], "unknown task id 'EBoatNowhere-v0'; known: " + ", ".join(TASK_IDS)),
    (["--task", "EBoatAvoidSail-v0", "--no-autopilot"], "no policy is shipped for EBoatAvoidSail-v0 and "
                                                            "--no-autopilot leaves nothing to run"),
])
def test_cli_task_errors_are_one_line(argv, message, tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(argv + ["--out", str(tmp_path / "out")])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "out").exists()


def test_evaluation_task_settings():
    """--sea-state and --wind replace the task's only when given; --wind fixes a drawn wind speed."""
    plus = evaluation_task("ocean_warp/EBoatWaypointPlus-v0", seed=2)
    assert plus.start.wind_speed == (2.0, 12.0) and plus.simulator.ocean.significant_wave_height == 0.5
    assert plus.simulator.ocean.seed == 2 and plus.episode_time == 300.0
    fixed = evaluation_task("EBoatWaypointPlus-v0", wind=6.0, sea_state=0.2, time_limit=50.0, observation="seed")
    assert fixed.start.wind_speed == (6.0, 6.0) and fixed.simulator.wind.speed == 6.0
    assert fixed.simulator.ocean.significant_wave_height == 0.2 and fixed.episode_time == 50.0
    assert fixed.observation.value == "seed" and fixed.start.wind_direction_deg == plus.start.wind_direction_deg
    assert evaluation_task() == mission_task()  # the default: the mission as before
    with pytest.raises(ValueError, match="known: EBoatWaypoint-v0"):
        evaluation_task("EBoatNowhere-v0")


def test_waypoint_task_runs_sail_to_their_own_waypoints(tmp_path):
    """EBoatWaypointPlus-v0 with waypoints drawn 15-25 m away (any bearing), 3 runs of 60 s: each run sails to
    the waypoint it drew, the same for both controllers; "completed" is reaching it, and a completed path
    ends within the reach radius of its own waypoint (plus a decision's travel). The files carry the
    per-run waypoints."""
    random_policy_file(tmp_path / "random.pt")
    plus = evaluation_task("EBoatWaypointPlus-v0", observation="seed")
    simulator = dataclasses.replace(
        plus.simulator, boat=dataclasses.replace(plus.simulator.boat, hydrostatics=Hydrostatics.POINTS),
        ocean_every_substep=False,
        ocean=OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.3, peak_period=3.0))
    task = dataclasses.replace(plus, simulator=simulator,
                               start=dataclasses.replace(plus.start, waypoint_distance=(15.0, 25.0)))
    evaluation = evaluate_mission(load_policy(tmp_path / "random.pt"), runs=3, time_limit=60.0, wind=6.0,
                                  progress=False, task=task)
    policy, autopilot = evaluation.results["policy"], evaluation.results["autopilot"]
    np.testing.assert_array_equal(policy.routes, autopilot.routes)
    assert policy.routes.shape == (3, 1, 2) and not autopilot.shared_route
    reach = np.linalg.norm(autopilot.routes[:, 0], axis=1)
    assert np.all((reach > 15.0 - 1e-3) & (reach < 25.0 + 1e-3)) and len(np.unique(reach)) == 3
    with pytest.raises(ValueError, match="drew their own waypoints"):
        autopilot.route
    assert autopilot.success.any(), autopilot.waypoints  # the autopilot, motor assisting, reaches 25 m in 60 s
    for result in (policy, autopilot):
        np.testing.assert_array_equal(result.waypoints, result.success.astype(int))
        for path, own, done in zip(result.paths, result.routes, result.success):
            if done:
                assert np.linalg.norm(path.xy[-1] - own[0]) <= task.reach_radius + 3.0
    paths = evaluation.write(tmp_path / "out")
    arrays = np.load(paths["trajectories.npz"])
    np.testing.assert_array_equal(arrays["autopilot_routes"], autopilot.routes)
    np.testing.assert_array_equal(arrays["policy_routes"], policy.routes)
    assert "route" not in arrays


# --- obstacles: the collisions column, the "collided" end, the layouts in the files -----------------

def tiny_avoid(**changes):
    """EBoatAvoid-v0 on the four-point hull and a 16 x 16 sea, without the lidar (cheap on the CPU), with a
    hand-made course: a waypoint 40 m due east (bearing 0), the boat heading straight at it from the start
    (no jitter), nearly no wind (0.5 m/s), and one pile of radius 2 m at the middle of the leg, on it."""
    from ocean_warp.envs.tasks.task_configs import AvoidConfig, ObstacleLayoutConfig

    task = evaluation_task(AvoidConfig(), wind=0.5, seed=0)
    simulator = dataclasses.replace(
        task.simulator, boat=dataclasses.replace(task.simulator.boat, hydrostatics=Hydrostatics.POINTS),
        ocean_every_substep=False,
        ocean=OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.2, peak_period=3.0))
    start = dataclasses.replace(task.start, heading_deg=(0.0, 0.0), waypoint_distance=(40.0, 40.0),
                                waypoint_bearing_deg=(0.0, 0.0), position_jitter=0.0)
    layout = ObstacleLayoutConfig(count=(1, 1), pile_fraction=1.0, pile_radius=(2.0, 2.0), along_track=(0.5, 0.5),
                                  cross_track=0.0)
    return dataclasses.replace(task, **({"simulator": simulator, "start": start, "obstacles": layout, "lidar": None,
                                         "episode_time": 30.0} | changes))


def test_collisions_are_counted_against_a_run_that_hits_a_pile(tmp_path):
    """Two runs of the hand-made course, a pile of radius 2 m on the leg 20 m ahead: run 0 goes full ahead
    with the rudder amidships (straight into the pile), run 1 full astern (away from it). Run 0 ends with
    BoatStatus.COLLIDED where its bow meets the pile, long before the time limit; run 1 does not. The
    collisions column counts 1, runs.csv ends run 0 "collided", and the files keep the layout the reset drew
    (the pile where the task puts it), equal to ``buffers.obstacles`` after a reset."""
    from ocean_warp.envs.evaluation import FixedController, MissionEvaluation
    from ocean_warp.fleet import BoatStatus

    task = tiny_avoid()
    fresh = SailingEnv(task, 2, device="cpu", seed=4)
    fresh.reset(seed=4)
    table = fresh.buffers.obstacles.cpu().numpy()
    start = fresh.buffers.position.cpu().numpy()[:, :2] - fresh.buffers.origin.cpu().numpy()[:, :2]
    waypoint = fresh.buffers.route.cpu().numpy()[:, 0, :2]
    np.testing.assert_allclose(start, 0.0, atol=1e-5)
    np.testing.assert_allclose(waypoint, [[40.0, 0.0], [40.0, 0.0]], atol=1e-4)
    assert table.shape == (2, 1, 4)
    np.testing.assert_allclose(table[:, 0], [[20.0, 0.0, 2.0, 2.0]] * 2, atol=1e-4)  # the pile, mid-leg

    env = SailingEnv(task, 2, device="cpu", seed=4)
    ahead, astern = np.array([True, False]), np.array([False, True])
    fleet = FleetController([(FixedController((1.0, 0.0, 0.0)), ahead), (FixedController((-1.0, 0.0, 0.0)), astern)])
    result = sail_mission(env, fleet)
    np.testing.assert_array_equal(result.obstacles, table)
    np.testing.assert_array_equal(result.collided, [True, False])
    assert result.status[0] & BoatStatus.COLLIDED and not result.success.any()
    assert result.end(0) == "collided" and result.end(1) != "collided"
    assert result.time_s[0] < 20.0  # 16 m at a few m/s
    # Where it ended: on the leg, short of the pile's surface (2 m from its centre) by less than a hull length
    # (the bow is 1.3 m ahead of the origin; the contact force stops the boat there and pushes it back a little).
    final = result.paths[0].xy[-1]
    assert 2.0 < np.linalg.norm(final - [20.0, 0.0]) < 2.0 + 2.5 and final[0] < 20.0 and abs(final[1]) < 1.0
    summary = result.summary()
    assert summary["collisions"] == 1 and summary["capsizes"] == 0
    assert result.subset(np.array([0]), "ahead").summary()["collisions"] == 1

    evaluation = MissionEvaluation(task=task, settings={"runs": 2, "seed": 4}, results={"fleet": result})
    paths = evaluation.write(tmp_path)
    _, rows = read_csv(paths["results.csv"])
    assert rows[0]["collisions"] == "1" and rows[0]["capsizes"] == "0"
    _, runs = read_csv(paths["runs.csv"])
    assert runs[0]["end"] == "collided" and runs[1]["end"] != "collided"
    arrays = np.load(paths["trajectories.npz"])
    np.testing.assert_array_equal(arrays["fleet_obstacles"], table)
    assert "collisions 1" in " ".join(evaluation.format_table().split())


def test_a_task_without_obstacles_keeps_its_files():
    """On the mission every run has an empty obstacle table (N, 0, 4): collisions 0, no obstacles key."""
    result = sail_mission(SailingEnv(tiny_mission(episode_time=2.0), 2, device="cpu", seed=1), AutopilotController())
    assert result.obstacles.shape == (2, 0, 4) and not result.has_obstacles
    assert result.summary()["collisions"] == 0 and not result.collided.any()


def test_recorded_decision_keeps_the_obstacle_rows_without_touching_the_env(device):
    """On a task with obstacles the recorder's decision is still ``env.step()`` (every buffer equal, the
    obstacle scene's rows too), and its object frames are the scene's rows as ``scene.refresh()`` gives them:
    at the decision's last frame, those of the stepped env (which refreshes the scene after the physics)."""
    task = tiny_avoid(episode_time=10.0, obstacles=dataclasses.replace(tiny_avoid().obstacles, count=(3, 5),
                                                                      pile_fraction=0.5, cross_track=10.0))
    stepped, recorded = (SailingEnv(task, 2, device=device, seed=3) for _ in range(2))
    decision = RecordedDecision(recorded, frames_per_decision=2)
    actions = torch.tensor([[0.6, 0.1, 0.2], [0.3, -0.4, -0.1]], device=stepped.torch_device)
    for k in range(3):
        stepped.step(actions)
        recorded.buffers.actions.copy_(actions)
        decision()
        assert_same_buffers(recorded.buffers, stepped.buffers, f"after decision {k}")
        frames = decision.frames()
        view = stepped.obstacles.scene.view
        np.testing.assert_array_equal(recorded.obstacles.scene.view.object_position.numpy(),
                                      view.object_position.numpy())
        assert frames["object_position"].shape == (2, 2 * 5, 3)
        np.testing.assert_array_equal(frames["object_position"][-1], view.object_position.numpy())
        np.testing.assert_array_equal(frames["object_orientation"][-1], view.object_orientation.numpy())
    floating = recorded.obstacles.scene.floats.numpy() == 1
    assert floating.any() and not np.array_equal(frames["object_position"][0][floating, 2],
                                                 frames["object_position"][1][floating, 2])  # riding the waves
