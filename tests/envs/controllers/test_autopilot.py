"""The classical sailing autopilot (ocean_warp.envs.controllers.sailing_autopilot): its decisions for hand-built states, its
config checks, and physics-checked sailing (a beam reach, a dead-upwind beat, a short mission)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import warp as wp

from benchmarks.studies.autopilot_mission import run_mission
from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig, Hydrostatics, Profile
from ocean_warp.envs.controllers.sailing_autopilot import AutopilotConfig, SailingAutopilot
from ocean_warp.kernels.eboat_actions import apply_eboat_actions
from ocean_warp.envs.tasks.task_configs import MissionConfig, mission_simulator
from ocean_warp.frames import quaternion_from_roll_pitch_yaw, roll_pitch_yaw
from ocean_warp.wind import WindConfig

WIND_FROM = math.pi  # the tests' wind blows towards +x
DEG = math.pi / 180.0
TUNING_BOAT = EBoatConfig(profile=Profile.SEED, hydrostatics=Hydrostatics.MESH)
"""The boat the autopilot's default gains were tuned on: the seed profile's forces on the mesh hull."""


def wrap(angle):
    return (np.asarray(angle) + math.pi) % (2.0 * math.pi) - math.pi


class FakeBoats:
    """Just the arrays the autopilot reads, set by hand for each boat."""

    def __init__(self, device, headings, *, positions=None, surge=0.0, roll=0.0, wind=(10.0, 0.0, 0.0)):
        n = len(headings)
        angles = np.column_stack([np.broadcast_to(roll, n), np.zeros(n), headings])
        velocity = np.zeros((n, 6), dtype=np.float32)
        velocity[:, 0] = surge
        self.position = wp.array(np.zeros((n, 3)) if positions is None else positions, dtype=wp.vec3, device=device)
        self.orientation = wp.array(quaternion_from_roll_pitch_yaw(angles), dtype=wp.quat, device=device)
        self.velocity = wp.array(velocity, dtype=wp.types.vector(6, wp.float32), device=device)
        self.wind_velocity = wp.array(np.tile(wind, (n, 1)), dtype=wp.vec3, device=device)

    def move(self, positions):
        self.position.assign(np.asarray(positions, dtype=np.float32))


def decide(pilot, targets, device):
    actions = wp.zeros((pilot.count, 3), dtype=float, device=device)
    pilot.act(wp.array(np.asarray(targets, dtype=np.float32), dtype=wp.vec3, device=device), actions)
    return actions.numpy(), pilot.course.numpy()


def test_config_validation():
    AutopilotConfig()  # the defaults are valid
    for field, value, text in [
        ("tack_hysteresis", -0.1, "AutopilotConfig.tack_hysteresis"),
        ("tack_hysteresis", math.pi / 2, "AutopilotConfig.tack_hysteresis"),
        ("no_go_angle", 0.5, "AutopilotConfig.no_go_angle"),
        ("close_hauled_angle", 0.0, "AutopilotConfig.close_hauled_angle"),
        ("close_hauled_angle", math.pi / 2, "AutopilotConfig.close_hauled_angle"),
        ("run_angle", math.pi / 2, "AutopilotConfig.run_angle"),
        ("run_angle", 3.5, "AutopilotConfig.run_angle"),
        ("decision_period", 0.0, "AutopilotConfig.decision_period"),
        ("decision_period", float("nan"), "AutopilotConfig.decision_period"),
        ("heading_gain", 0.0, "AutopilotConfig.heading_gain"),
        ("yaw_rate_gain", -1.0, "AutopilotConfig.yaw_rate_gain"),
        ("rudder_limit", 1.2, "AutopilotConfig.rudder_limit"),
        ("lane_half_width", -1.0, "AutopilotConfig.lane_half_width"),
        ("heel_ease", float("inf"), "AutopilotConfig.heel_ease"),
        ("tack_timeout", -1.0, "AutopilotConfig.tack_timeout"),
        ("propeller_level", 6, "AutopilotConfig.propeller_level"),
        ("propeller_level", 1.5, "AutopilotConfig.propeller_level"),
        ("attack_angle", "0.3", "AutopilotConfig.attack_angle"),
    ]:
        with pytest.raises(ValueError, match=text.replace(".", r"\.")):
            AutopilotConfig(**{field: value})
    with pytest.raises(ValueError, match=r"AutopilotConfig\.max_sheet"):
        AutopilotConfig(min_sheet=1.0, max_sheet=0.5)
    with pytest.raises(ValueError, match="SailingAutopilot: config"):
        SailingAutopilot(FakeBoats("cpu", [0.0]), config={"tack_hysteresis": 0.1})


def test_sheet_from_apparent_wind(device):
    """Heading north (+y) at 1 m/s in a 10 m/s wind blowing towards +x: the apparent wind (10, -1) m/s
    comes from 84.29 deg off the port bow, so the sheet is 84.29 - 20 = 64.29 deg, and 15 deg more for
    heel 20 deg (5 deg past the 15 deg limit, eased 3 rad/rad); a1 = sheet / 45 deg - 1."""
    boats = FakeBoats(device, [math.pi / 2, math.pi / 2], surge=1.0, roll=np.array([0.0, 20.0 * DEG]))
    pilot = SailingAutopilot(boats)
    actions, _ = decide(pilot, [[0.0, 100.0, 0.0]] * 2, device)
    awa = math.degrees(math.atan2(10.0, 1.0))  # angle between the bow (+y) and where the air comes from
    assert awa == pytest.approx(84.2894, abs=1e-3)
    expected = np.array([awa - 20.0, awa - 20.0 + 3.0 * 5.0])
    np.testing.assert_allclose((actions[:, 1] + 1.0) * 45.0, expected, atol=0.05)
    assert np.all(actions[:, 0] == 0.0)  # reaching with way on: no motor assist


def test_course_choices(device):
    """Line of sight on a reach; close-hauled on the boat's side for a target dead upwind (never inside
    the no-go zone); broad reaches 150 deg off the wind by default, a dead run with run_angle 180 deg."""
    config = AutopilotConfig()
    ch = config.close_hauled_angle
    # Boat 0: target on a beam reach (north); 1 and 2: dead upwind (west) on either tack;
    # 3: dead downwind (east).
    headings = [math.pi / 2, WIND_FROM + 0.9, WIND_FROM - 0.9, 0.3]
    targets = [[0, 100, 0], [-100, 0, 0], [-100, 0, 0], [100, 0, 0]]
    pilot = SailingAutopilot(FakeBoats(device, headings, surge=1.0))
    _, course = decide(pilot, targets, device)
    np.testing.assert_allclose(wrap(course - np.array([math.pi / 2, WIND_FROM + ch, WIND_FROM - ch, 30.0 * DEG])),
                               0.0, atol=1e-5)
    np.testing.assert_array_equal(pilot.side.numpy()[1:3], [1, -1])
    gybing = SailingAutopilot(FakeBoats(device, [0.3, -0.3], surge=1.0), AutopilotConfig(run_angle=140.0 * DEG))
    _, course = decide(gybing, [[100, 0, 0]] * 2, device)
    np.testing.assert_allclose(wrap(course - np.array([40.0 * DEG, -40.0 * DEG])), 0.0, atol=1e-5)
    running = SailingAutopilot(FakeBoats(device, [0.3], surge=1.0), AutopilotConfig(run_angle=math.pi))
    _, course = decide(running, [[100, 0, 0]], device)
    np.testing.assert_allclose(wrap(course), 0.0, atol=1e-5)


def test_tack_hysteresis(device):
    """A boat beating towards a target 200 m upwind keeps its tack while the target's bearing crosses
    the wind axis, and tacks once it is past by the hysteresis; then the same the other way."""
    config = AutopilotConfig(tack_hysteresis=20.0 * DEG, lane_half_width=0.0)
    boats = FakeBoats(device, [WIND_FROM + config.close_hauled_angle], surge=1.0)
    pilot = SailingAutopilot(boats, config)
    target = [[-200.0, 0.0, 0.0]]
    sides = []
    # Offsets of the target's bearing from the wind's source, as seen from the boat.
    for offset in [0.0, 10.0, -10.0, -19.0, -21.0, -10.0, 10.0, 19.0, 21.0]:
        bearing = WIND_FROM + offset * DEG
        boats.move([[-200.0 - 200.0 * math.cos(bearing), -200.0 * math.sin(bearing), 0.0]])
        _, course = decide(pilot, target, device)
        sides.append(int(pilot.side.numpy()[0]))
        assert abs(wrap(course[0] - WIND_FROM)) == pytest.approx(config.close_hauled_angle, abs=1e-5)
    assert sides == [1, 1, 1, 1, -1, -1, -1, -1, 1]
    assert int(pilot.tacks.numpy()[0]) == 2


def test_reset_mask_and_propeller(device):
    boats = FakeBoats(device, [WIND_FROM + 0.9, WIND_FROM - 0.9, 0.3])
    pilot = SailingAutopilot(boats, AutopilotConfig(propeller_level=-3, assist_level=0))
    actions, _ = decide(pilot, [[-100, 0, 0]] * 3, device)
    np.testing.assert_array_equal(pilot.side.numpy(), [1, -1, -1])
    commands = [wp.zeros(3, dtype=float, device=device), wp.zeros(3, dtype=float, device=device),
                wp.zeros(3, dtype=wp.int32, device=device)]
    wp.launch(apply_eboat_actions, dim=3, device=device,
              inputs=[wp.array(actions, dtype=float, device=device), wp.ones(3, dtype=wp.int32, device=device)],
              outputs=commands)
    np.testing.assert_array_equal(commands[2].numpy(), [-3, -3, -3])
    np.testing.assert_allclose(commands[0].numpy(), actions[:, 2] * 60.0 * DEG, rtol=1e-6)
    pilot.reset(wp.array([0, 1, 0], dtype=wp.int32, device=device))
    np.testing.assert_array_equal(pilot.side.numpy(), [1, 0, -1])
    pilot.reset()
    np.testing.assert_array_equal(pilot.side.numpy(), [0, 0, 0])


def test_act_in_captured_graph(device):
    boats = FakeBoats(device, [0.3, 2.0])
    pilot = SailingAutopilot(boats)
    targets = wp.array(np.array([[0, 100, 0], [-100, 0, 0]], dtype=np.float32), dtype=wp.vec3, device=device)
    actions = wp.zeros((2, 3), dtype=float, device=device)
    mask = wp.array([1, 1], dtype=wp.int32, device=device)
    pilot.act(targets, actions)  # load the modules outside the capture
    pilot.reset(mask)
    expected = actions.numpy().copy()
    actions.zero_()
    with wp.ScopedCapture(device) as capture:
        pilot.reset(mask)
        pilot.act(targets, actions)
    wp.capture_launch(capture.graph)
    np.testing.assert_allclose(actions.numpy(), expected, atol=1e-6)


def sail(device, starts, headings, targets, seconds, *, wind=10.0, config=None, boat=None):
    """Sail boats in still water and a steady wind towards +x with the autopilot; returns per-decision
    (heading, course, position, status) arrays and the pilot. ``boat``: default the boat the autopilot's
    default gains were tuned on (the seed profile's forces on the mesh hull)."""
    sim_config = EBoatSimulatorConfig(boat=boat if boat is not None else TUNING_BOAT,
                                      wind=WindConfig(speed=wind, direction=0.0))
    n = len(starts)
    sim = EBoatSimulator(sim_config, n, device=device)
    config = config if config is not None else AutopilotConfig()
    sim.reset(position=starts, heading=headings, velocity=[1.0, 0, 0, 0, 0, 0], sheet=45.0 * DEG)
    pilot = SailingAutopilot(sim.state, config)
    actions = wp.zeros((n, 3), dtype=float, device=device)
    target_array = wp.array(np.asarray(targets, dtype=np.float32), dtype=wp.vec3, device=device)
    steps = int(round(config.decision_period / sim_config.dt))
    log = {"heading": [], "course": [], "position": [], "status": []}
    for _ in range(int(seconds / config.decision_period)):
        pilot.act(target_array, actions)
        sim.launch_actions(actions)
        for _ in range(steps):
            sim.step()
        log["heading"].append(roll_pitch_yaw(sim.state.orientation.numpy())[:, 2])
        log["course"].append(pilot.course.numpy().copy())
        log["position"].append(sim.state.position.numpy()[:, :2].copy())
        log["status"].append(sim.state.status.numpy().copy())
    return {k: np.array(v) for k, v in log.items()}, pilot


SAIL_ONLY = AutopilotConfig(close_hauled_angle=65.0 * DEG, no_go_angle=75.0 * DEG, heel_limit=25.0 * DEG,
                            heel_ease=2.0, assist_level=0, tack_timeout=0.0, approach_radius=20.0)
"""Under sail alone: no motor assist, and a wear at once instead of a tack."""


def test_beam_reach_and_beat(device):
    """Under sail alone: boat 0 on a beam reach (target 1 km north) holds its course within a few degrees. Boat 1 beats on
    the starboard tack with its target 60 m away, 72 deg off the wind on the far side, past the 70 deg
    tack hysteresis: it never steers into the no-go zone, changes tack once (wearing round) and not
    back, and gains on the target."""
    bearing = WIND_FROM - 72.0 * DEG
    start = np.array([0.0, 100.0])
    target = start + 60.0 * np.array([math.cos(bearing), math.sin(bearing)])
    log, pilot = sail(device, starts=[[0.0, 0.0, 0.0], [*start, 0.0]], headings=[math.pi / 2, WIND_FROM + 65.0 * DEG],
                      targets=[[0.0, 1000.0, 0.0], [*target, 0.0]], seconds=120.0, config=SAIL_ONLY)
    assert np.all(log["status"] == 0)
    error = wrap(log["heading"][30:, 0] - math.pi / 2)
    assert abs(error.mean()) < 3.0 * DEG and np.abs(error).max() < 10.0 * DEG
    config = pilot.config
    off_wind = np.abs(wrap(log["course"][:, 1] - WIND_FROM))
    assert np.all(off_wind >= config.close_hauled_angle - 1e-4)  # the course is never in the no-go zone
    assert int(pilot.tacks.numpy()[1]) == 1
    assert int(pilot.side.numpy()[1]) == -1
    distance = np.hypot(*(log["position"][-1, 1] - target))
    assert distance < 60.0 - 20.0


def test_sail_only_beat_on_the_physics_boat(device):
    """The physics-profile boat under sail alone with ``AutopilotConfig.sail_only()`` in 5 m/s: a target 60 m
    dead upwind is reached by beating, with at least one tack, the boat upright throughout and its course never
    inside the no-go zone."""
    config = AutopilotConfig.sail_only()
    start_heading = WIND_FROM - 60.0 * DEG
    log, pilot = sail(device, starts=[[0.0, 0.0, 0.0]], headings=[start_heading], targets=[[-60.0, 0.0, 0.0]],
                      seconds=240.0, wind=5.0, config=config, boat=EBoatConfig())
    assert np.all(log["status"] == 0)
    assert np.all(np.abs(wrap(log["course"][:, 0] - WIND_FROM)) >= config.close_hauled_angle - 1e-4)
    distance = np.hypot(*(log["position"][:, 0] - np.array([-60.0, 0.0])).T)
    assert distance.min() < 10.0, distance.min()
    assert int(pilot.tacks.numpy()[0]) >= 1


def test_two_full_missions(device):
    """Two seeded runs of the whole BCDACA mission in waves and gusts, with the mesh hull, through the
    mission environment, as ``benchmarks/studies/autopilot_mission.py`` sails its twenty (about 600 s each), on
    the boat the defaults were tuned on (on the physics boat they capsize in 10 m/s: RESULTS)."""
    task = dataclasses.replace(MissionConfig(), simulator=mission_simulator(TUNING_BOAT))
    result = run_mission(2, device=device, seed=3, task=task)
    assert np.all(result["success"] == 1.0), result
    assert np.all(result["waypoints"] == 6) and np.all(result["status"] == 0)
    assert np.all(result["time"] < 1200.0) and np.all(result["tacks"] <= 10)
