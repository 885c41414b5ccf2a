"""The autopilot's obstacle avoidance (ocean_warp.envs.controllers: ``steer_clear``, ``LidarSectors``): the
collision-cone law against numbers worked by hand, the target left alone where nothing blocks the course,
the lidar's sector geometry, the config checks, and a boat sailed at a pile that hits it without the
avoidance and clears it with it."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import warp as wp

from ocean_warp.envs.controllers.sailing_autopilot import AutopilotConfig, LidarSectors, SailingAutopilot
from ocean_warp.envs.sailing_env import SailingEnv
from ocean_warp.envs.tasks.obstacle_layout import ObstacleLayoutConfig
from ocean_warp.envs.tasks.task_configs import AvoidConfig, StartConfig, avoid_lidar
from ocean_warp.fleet import BoatStatus
from ocean_warp.frames import quaternion_from_roll_pitch_yaw

DEG = math.pi / 180.0
SECTORS = 24
MAX_RANGE = 50.0
MOUNT = (1.1, 0.0, 0.8)


class FakeBoats:
    """The arrays the autopilot reads, set by hand: level boats at rest at ``positions`` with ``headings``,
    in a true wind of 8 m/s from ``wind_from`` [rad]."""

    def __init__(self, device, positions, headings, wind_from):
        n = len(headings)
        angles = np.column_stack([np.zeros(n), np.zeros(n), headings])
        self.position = wp.array(np.asarray(positions, dtype=np.float32), dtype=wp.vec3, device=device)
        self.orientation = wp.array(quaternion_from_roll_pitch_yaw(angles), dtype=wp.quat, device=device)
        self.velocity = wp.zeros(n, dtype=wp.types.vector(6, wp.float32), device=device)
        wind = -8.0 * np.column_stack([np.cos(wind_from), np.sin(wind_from), np.zeros(n)])
        self.wind_velocity = wp.array(wind.astype(np.float32), dtype=wp.vec3, device=device)


def observation(device, readings, columns=5):
    """(N, columns + 24) observations: zeros, then the sectors' values, 1 (nothing) but where ``readings``
    (one {sector: range [m]} per boat) says."""
    values = np.zeros((len(readings), columns + SECTORS), dtype=np.float32)
    values[:, columns:] = 1.0
    for boat, seen in enumerate(readings):
        for sector, distance in seen.items():
            values[boat, columns + sector] = distance / MAX_RANGE
    return wp.array(values, dtype=float, device=device)


def task_sectors(values, first=5):
    return LidarSectors.from_lidar(values, first, avoid_lidar(), SECTORS)


def decide(pilot, targets, device):
    actions = wp.zeros((pilot.count, 3), dtype=float, device=device)
    pilot.act(wp.array(np.asarray(targets, dtype=np.float32), dtype=wp.vec3, device=device), actions)
    return actions.numpy()


def test_sector_geometry():
    """The task's lidar: beam b at -180 + b deg, 15 beams a sector: sector s's beams span -180 + 15 s ...
    -180 + 15 s + 14 deg, so its centre is -180 + 15 s + 7 deg, and it is 15 deg wide (7.5 deg each side)."""
    sectors = task_sectors(observation("cpu", [{}]))
    expected = np.radians(-180.0 + 15.0 * np.arange(SECTORS) + 7.0)
    np.testing.assert_allclose(sectors.azimuth, expected, atol=1e-12)
    assert sectors.half_width == pytest.approx(7.5 * DEG)
    assert sectors.max_range == 50.0 and sectors.mount == MOUNT and sectors.first == 5
    # A sensor yawed 90 deg to port: every centre turns with it.
    yawed = LidarSectors.from_lidar(observation("cpu", [{}]), 5, avoid_lidar(mount_rpy=(0.0, 0.0, 0.5 * math.pi)),
                                    SECTORS)
    np.testing.assert_allclose(yawed.azimuth, expected + 0.5 * math.pi, atol=1e-12)
    with pytest.raises(ValueError, match="sectors must be a whole divisor"):
        LidarSectors.from_lidar(observation("cpu", [{}]), 5, avoid_lidar(), 7)
    with pytest.raises(ValueError, match=r"LidarSectors\.first"):
        task_sectors(observation("cpu", [{}]), first=6)  # 6 + 24 columns > 29


def test_config_validation():
    for field, value in [("avoidance", 1), ("avoidance_range", 0.0), ("avoidance_range", float("inf")),
                         ("avoidance_clearance", -1.0), ("avoidance_clearance", 0.0),
                         ("avoidance_lookahead", float("nan")), ("avoidance_memory", -0.5),
                         ("avoidance_turn_cost", -1.0), ("avoidance_cone", 0.0), ("avoidance_cone", 1.6)]:
        with pytest.raises(ValueError, match=rf"AutopilotConfig\.{field}"):
            AutopilotConfig(**{field: value})
    with pytest.raises(ValueError, match="SailingAutopilot: lidar"):
        SailingAutopilot(FakeBoats("cpu", [[0, 0, 0]], [0.0], [0.0]), lidar=object())


def test_nothing_near_leaves_the_target(device):
    """With no return within the range (none at all, or one at 30 m > 20 m, or one beside the course), the
    steering target is the target itself, and the actions are bit-equal to those of the autopilot without a
    lidar."""
    n = 3
    positions = [[3.0, -2.0, 0.0], [0.0, 0.0, 0.0], [10.0, 5.0, 0.0]]
    headings = [0.4, 0.0, -2.0]
    targets = np.array([[80.0, 10.0, 0.0], [100.0, 0.0, 0.0], [-50.0, -60.0, 0.0]], dtype=np.float32)
    wind_from = np.full(n, 90.0 * DEG)  # the targets lie on reaches
    readings = [{}, {12: 30.0}, {3: 8.0, 20: 12.0}]  # boat 2: returns on either quarter, well off its course
    pilot = SailingAutopilot(FakeBoats(device, positions, headings, wind_from),
                             lidar=task_sectors(observation(device, readings)))
    plain = SailingAutopilot(FakeBoats(device, positions, headings, wind_from))
    actions = decide(pilot, targets, device)
    np.testing.assert_array_equal(pilot.steering.numpy(), targets)
    np.testing.assert_array_equal(pilot.deflection.numpy(), 0.0)
    np.testing.assert_array_equal(actions, decide(plain, targets, device))
    np.testing.assert_array_equal(pilot.course.numpy(), plain.course.numpy())


def test_collision_cone_by_hand(device):
    """A return 15 m from the lidar blocks the courses within 7.5 deg (half a sector) + asin(3 / 15) =
    19.04 deg of its sector's centre; the boat steers to the point 20 m away on the clear bearing whose
    course (as the course logic steers it) is cheapest. All head east (0 deg) to a target 100 m east.
    Boat 0, a beam reach (wind from north): the return in sector 12 (centre +7 deg) blocks -12.04 ... +26.04
    deg; it steers to -12.04 deg (off the course by 12.04 deg, turning 12.04: cheaper than +26.04).
    Boat 1, wind from 55 deg (no-go zone -5 ... 115 deg): its course is close-hauled at 5 deg; the return in
    sector 11 (centre -8 deg) blocks -27.04 ... +11.04 deg. The bearing +11.04 deg lies in the no-go zone,
    where the boat would sail close-hauled at 5 deg, inside the cone: it takes -27.04 deg.
    Boat 2, the same return in a wind from 70 deg (no-go 10 ... 130 deg; course 0 deg, a close reach): for
    the bearing +11.04 deg it sails close-hauled at 20 deg, clear of the cone and cheaper (20 + 20 deg) than
    -27.04 deg (27.04 + 27.04): it steers to the bearing +11.04 deg and sails 20 deg.
    Boat 3: the return in sector 13 (centre +22 deg) blocks +2.96 ... +41.04 deg: the course 0 is clear.
    (The kernel puts the edges 1e-4 rad outside the cones.)"""
    positions = np.array([[2.0, -1.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    headings = np.zeros(4)
    wind_from = np.radians([90.0, 55.0, 70.0, 90.0])
    targets = positions + np.array([100.0, 0.0, 0.0])
    readings = [{12: 15.0}, {11: 15.0}, {11: 15.0}, {13: 15.0}]
    pilot = SailingAutopilot(FakeBoats(device, positions, headings, wind_from),
                             lidar=task_sectors(observation(device, readings)))
    decide(pilot, targets, device)
    cone = 7.5 + math.degrees(math.asin(3.0 / 15.0))
    assert cone == pytest.approx(19.037, abs=1e-3)
    # The return lies 15 m from the lidar, which is 1.1 m ahead of the boat's origin: the cone's apex is the
    # lidar, and the bearing is steered from the boat's origin.
    bearing = np.radians([7.0 - cone, -8.0 - cone, -8.0 + cone])
    np.testing.assert_allclose(bearing, np.radians([-12.037, -27.037, 11.037]), atol=1e-4)
    course = np.radians([7.0 - cone, -8.0 - cone, 20.0])
    intended = np.radians([0.0, 5.0, 0.0])
    steering = pilot.steering.numpy()
    for boat in range(3):
        np.testing.assert_allclose(steering[boat, :2],
                                   positions[boat, :2] + 20.0 * np.array([np.cos(bearing[boat]),
                                                                          np.sin(bearing[boat])]), atol=5e-3)
    np.testing.assert_allclose(pilot.course.numpy()[:3], course, atol=2.5e-4)
    np.testing.assert_allclose(pilot.deflection.numpy()[:3], course - intended, atol=2.5e-4)
    np.testing.assert_array_equal(steering[3], targets[3].astype(np.float32))
    assert pilot.deflection.numpy()[3] == 0.0
    # The returns are remembered where they lie in the world: 15 m from the lidar on the sectors' centres.
    points = pilot.returns.numpy()
    for boat, sector, centre in ((0, 12, 7.0), (1, 11, -8.0)):
        lidar = positions[boat, :2] + np.array([1.1, 0.0])
        np.testing.assert_allclose(points[boat, sector, :2],
                                   lidar + 15.0 * np.array([np.cos(np.radians(centre)), np.sin(np.radians(centre))]),
                                   atol=1e-4)
        assert points[boat, sector, 2] == 0.0


def test_memory_and_reset(device):
    """A return the sector stops seeing is avoided for ``avoidance_memory`` seconds (fixed in the world), then
    forgotten; ``reset`` forgets it at once."""
    values = observation(device, [{12: 15.0}])
    boats = FakeBoats(device, [[0.0, 0.0, 0.0]], [0.0], np.radians([90.0]))
    pilot = SailingAutopilot(boats, AutopilotConfig(avoidance_memory=2.0), lidar=task_sectors(values))
    target = [[100.0, 0.0, 0.0]]
    decide(pilot, target, device)
    assert pilot.deflection.numpy()[0] < -0.2
    values.assign(observation(device, [{}]).numpy())  # the sector loses it
    deflections = []
    for _ in range(3):
        decide(pilot, target, device)
        deflections.append(float(pilot.deflection.numpy()[0]))
    assert deflections[0] < -0.2 and deflections[1] < -0.2 and deflections[2] == 0.0  # ages 1, 2, 3 s
    values.assign(observation(device, [{12: 15.0}]).numpy())
    decide(pilot, target, device)
    values.assign(observation(device, [{}]).numpy())
    pilot.reset()
    decide(pilot, target, device)
    assert pilot.deflection.numpy()[0] == 0.0


def test_avoidance_off_ignores_the_lidar(device):
    values = observation(device, [{12: 5.0}])
    boats = FakeBoats(device, [[0.0, 0.0, 0.0]], [0.0], np.radians([90.0]))
    pilot = SailingAutopilot(boats, AutopilotConfig(avoidance=False), lidar=task_sectors(values))
    assert pilot.lidar is None
    plain = SailingAutopilot(boats)
    target = [[100.0, 0.0, 0.0]]
    np.testing.assert_array_equal(decide(pilot, target, device), decide(plain, target, device))


def _pile_ahead_task() -> AvoidConfig:
    """A pile of 1 m radius midway on the line from the start to a waypoint 50 m away, the boat heading
    straight at it on a beam reach in 5 m/s."""
    start = StartConfig(heading_deg=(0.0, 0.0), heading_step_deg=0.0, heading_toward_waypoint=True,
                        wind_speed=(5.0, 5.0), wind_direction_deg=(90.0, 90.0), wind_direction_step_deg=0.0,
                        waypoint_distance=(50.0, 50.0), waypoint_bearing_deg=(0.0, 0.0), sheet_deg=(45.0, 45.0),
                        surge_speed=(1.0, 1.0))
    layout = ObstacleLayoutConfig(count=(1, 1), pile_fraction=1.0, pile_radius=(1.0, 1.0), along_track=(0.5, 0.5),
                                  cross_track=0.0)
    return dataclasses.replace(AvoidConfig(), start=start, obstacles=layout, episode_time=45.0)


def _sail_first_episodes(env, config):
    """Each run's first episode: (collided, reached) per run."""
    from ocean_warp.envs.evaluation import AutopilotController

    env.reset(seed=3)
    controller = AutopilotController(config)
    controller.reset(env)
    # The sectors are the policy's observation after the seed's five values and the reef level.
    assert (controller.pilot.lidar is None) == (not config.avoidance)
    assert config.avoidance is False or controller.pilot.lidar.first == 6
    buffers = env.buffers
    ended = np.zeros(env.num_envs, bool)
    collided = np.zeros(env.num_envs, bool)
    reached = np.zeros(env.num_envs, bool)
    for _ in range(env.max_episode_length):
        controller.act(env)
        env.step()
        done = buffers.done.numpy() & ~ended
        collided |= done & ((buffers.final_status.numpy() & BoatStatus.COLLIDED) != 0)
        reached |= done & (buffers.final_success.numpy() > 0)
        ended |= done
        if ended.all():
            break
    return collided, reached


def test_clears_a_pile_dead_ahead():
    """Sailed straight at the pile, every boat hits it; with the avoidance, none does and each reaches the
    waypoint beyond it (same seed: same starts, waves and gusts)."""
    env = SailingEnv(_pile_ahead_task(), 3, device="cpu", seed=3)
    collided, _ = _sail_first_episodes(env, AutopilotConfig(avoidance=False))
    assert collided.all()
    collided, reached = _sail_first_episodes(env, AutopilotConfig())
    assert not collided.any()
    assert reached.all()


def test_no_sweep_across_an_obstacle(device):
    """Boat 0 heads east (0 deg) and its course is south (-90 deg: a reach in a wind from 135 deg, whose
    no-go zone is 75 ... 195 deg and dead-run zone -75 ... -15 deg). Returns in sector 9 (centre -38 deg) and
    sector 6 (centre -83 deg), 10 m away, block -38 +- 24.96 and -83 +- 24.96 deg (7.5 + asin(0.3)): together
    -107.96 ... -13.04 deg. The edge nearest the course, -107.96 deg, lies beyond the sector-9 obstacle as the
    bow swings clockwise from 0 deg, so the boat takes -13.04 deg (77 deg off the course, clear, sailable).
    Boat 1, the same heading, course -60 deg (a reach in a wind from 180 deg: no-go 120 ... 240, dead run
    -30 ... 30 deg): returns 10 m away in sector 10 (centre -23 deg: -47.96 ... 1.96, which holds the
    heading) and sector 8 (centre -53 deg: -77.96 ... -28.04) make one blocked run from the heading to
    -77.96 deg; turning to its edge sweeps across no other cone, so the boat takes -77.96 deg (17.96 deg off
    its course; +1.96 deg lies in the dead-run zone, +30 deg is 90 deg off). The turn's cost is left out
    (``avoidance_turn_cost`` 0), so that only the sweep keeps boat 0 from -107.96 deg."""
    boats = FakeBoats(device, [[0.0, 0.0, 0.0]] * 2, [0.0, 0.0], np.radians([135.0, 180.0]))
    config = AutopilotConfig(avoidance_turn_cost=0.0)  # the nearest clear course to the intended one
    pilot = SailingAutopilot(boats, config,
                             lidar=task_sectors(observation(device, [{9: 10.0, 6: 10.0}, {10: 10.0, 8: 10.0}])))
    targets = [[0.0, -100.0, 0.0], [50.0, -50.0 * math.sqrt(3.0), 0.0]]
    decide(pilot, targets, device)
    half = 7.5 + math.degrees(math.asin(0.3))
    assert half == pytest.approx(24.958, abs=1e-3)
    expected = np.radians([-38.0 + half, -53.0 - half])
    np.testing.assert_allclose(pilot.course.numpy(), expected, atol=2.5e-4)
    np.testing.assert_allclose(pilot.deflection.numpy(), expected - np.radians([-90.0, -60.0]), atol=2.5e-4)


def test_turn_cost(device):
    """Heading 11 deg, course east (0 deg, a beam reach): a return 15 m away in sector 11 (centre -8 deg, so
    3 deg in the world) blocks -16.04 ... 22.04 deg. The edge nearest the course is -16.04 deg (16.04 deg off
    it, 27.04 deg of turn); the other, 22.04 deg, is 22.04 deg off it but only 11.04 deg of turn. Without the
    turn's cost the boat takes -16.04 deg; with the default weight 1 (16.04 + 27.04 > 22.04 + 11.04), 22.04."""
    chosen = []
    for weight in (0.0, 1.0):
        boats = FakeBoats(device, [[0.0, 0.0, 0.0]], [11.0 * DEG], np.radians([90.0]))
        pilot = SailingAutopilot(boats, AutopilotConfig(avoidance_turn_cost=weight),
                                 lidar=task_sectors(observation(device, [{11: 15.0}])))
        decide(pilot, [[100.0, 0.0, 0.0]], device)
        chosen.append(math.degrees(pilot.course.numpy()[0]))
    assert AutopilotConfig().avoidance_turn_cost == 1.0
    np.testing.assert_allclose(chosen, [3.0 - 19.037, 3.0 + 19.037], atol=0.02)
