"""The line-following controller (ocean_warp.envs.controllers.line_following, Jaulin and Le Bars 2012): each
piece of the law against the published equations evaluated here in numpy for seeded random inputs, the tack's
hysteresis across the corridor, the rudder's sign against the simulator's yaw, a wear after a tack that does
not come through, the config checks, the controller's choice in AutopilotController, and a boat beating to a
waypoint dead upwind under sail alone."""

from __future__ import annotations

import math

import numpy as np
import pytest
import warp as wp

from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.envs.evaluation import AutopilotController
from ocean_warp.envs.apps.evaluation_options import parser as evaluation_parser
from ocean_warp.envs.controllers.line_following import LineFollower, LineFollowingConfig
from ocean_warp.envs.controllers.line_following_kernels import (LineFollowingParameters, desired_heading,
                                                                eased_sheet, nominal_heading, rudder_law,
                                                                sheet_law, signed_distance, update_tack)
from ocean_warp.envs.controllers.sailing_autopilot import AutopilotConfig
from ocean_warp.frames import quaternion_from_roll_pitch_yaw, roll_pitch_yaw
from ocean_warp.wind import WindConfig

DEG = math.pi / 180.0


def wrap(angle):
    return (np.asarray(angle) + math.pi) % (2.0 * math.pi) - math.pi


@wp.kernel
def _law_pieces(p: LineFollowingParameters, a: wp.array(dtype=wp.vec2), b: wp.array(dtype=wp.vec2),
                m: wp.array(dtype=wp.vec2), r: wp.array(dtype=float), psi: wp.array(dtype=float),
                theta: wp.array(dtype=float), q_in: wp.array(dtype=int), roll: wp.array(dtype=float),
                out: wp.array2d(dtype=float)):
    i = wp.tid()
    e = signed_distance(a[i], b[i], m[i])
    d = b[i] - a[i]
    phi = wp.atan2(d[1], d[0])
    theta_star = nominal_heading(phi, e, r[i], p.incidence_angle)
    q = update_tack(q_in[i], e, r[i])
    choice = desired_heading(p, phi, theta_star, e, r[i], psi[i], q)
    sheet = sheet_law(p.beam_reach_sheet, psi[i], choice[0])
    out[i, 0] = e
    out[i, 1] = theta_star
    out[i, 2] = float(q)
    out[i, 3] = choice[0]
    out[i, 4] = choice[1]
    out[i, 5] = rudder_law(p.rudder_limit, p.rudder_gain, theta[i], choice[0])
    out[i, 6] = sheet
    out[i, 7] = eased_sheet(sheet, roll[i], p.heel_limit, p.heel_ease)


def law_pieces(device, config, a, b, m, r, psi, theta, q, roll):
    n = len(a)
    out = wp.zeros((n, 8), dtype=float, device=device)
    arrays = [wp.array(np.asarray(x, dtype=np.float32), dtype=wp.vec2, device=device) for x in (a, b, m)]
    scalars = [wp.array(np.asarray(x, dtype=np.float32), dtype=float, device=device) for x in (r, psi, theta)]
    wp.launch(_law_pieces, dim=n, device=device,
              inputs=[config.parameters(), *arrays, *scalars, wp.array(np.asarray(q, dtype=np.int32), dtype=int,
                                                                           device=device),
                      wp.array(np.asarray(roll, dtype=np.float32), dtype=float, device=device)],
              outputs=[out])
    return out.numpy().astype(np.float64)


def reference_law(config, a, b, m, r, psi, theta, q, roll):
    """The published law, written out here in numpy (float64), our rudder sign (the paper's negated)."""
    d = b - a
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    e = u[:, 0] * (m[:, 1] - a[:, 1]) - u[:, 1] * (m[:, 0] - a[:, 0])
    phi = np.arctan2(d[:, 1], d[:, 0])
    theta_star = phi - 2.0 * config.incidence_angle / math.pi * np.arctan(e / r)
    q = np.where(np.abs(e) > r, np.sign(e), q)
    zeta = config.close_hauled_angle
    hauled = (np.cos(psi - theta_star) + np.cos(zeta) < 0) | ((np.abs(e) < r) & (np.cos(psi - phi) + np.cos(zeta) < 0))
    theta_bar = np.where(hauled, math.pi + psi - q * zeta, theta_star)
    paper_rudder = np.where(np.cos(theta - theta_bar) >= 0,
                            config.rudder_limit * np.sin(theta - theta_bar),
                            config.rudder_limit * np.sign(np.sin(theta - theta_bar)))
    beta = config.beam_reach_sheet
    sheet = 0.5 * math.pi * ((np.cos(psi - theta_bar) + 1.0) / 2.0) ** (math.log(math.pi / (2.0 * beta)) / math.log(2))
    return e, theta_star, q, theta_bar, hauled, -paper_rudder, sheet


def test_law_against_the_published_equations(device, rng):
    """200 random lines, positions, winds, headings and tacks: the signed distance, the nominal heading, the
    tack, the desired heading (close-hauled or nominal), the rudder (the paper's, gain 1, sign reversed) and
    the sheet, as the paper's equations give them in float64 here."""
    n = 200
    config = LineFollowingConfig(rudder_gain=1.0, run_angle=math.pi, incidence_angle=rng.uniform(0.3, 1.4),
                                 close_hauled_angle=rng.uniform(0.6, 1.1), beam_reach_sheet=rng.uniform(0.5, 1.2))
    a = rng.uniform(-200, 200, (n, 2))
    b = a + rng.uniform(30, 150, (n, 1)) * np.column_stack([np.cos(t := rng.uniform(-np.pi, np.pi, n)), np.sin(t)])
    m = a + rng.uniform(-60, 60, (n, 2))
    r = rng.uniform(5, 30, n)
    psi = rng.uniform(-np.pi, np.pi, n)
    theta = rng.uniform(-np.pi, np.pi, n)
    q = rng.choice([-1, 1], n)
    got = law_pieces(device, config, a, b, m, r, psi, theta, q, np.zeros(n))
    e, theta_star, q_ref, theta_bar, hauled, rudder, sheet = reference_law(config, a, b, m, r, psi, theta, q, 0)
    np.testing.assert_allclose(got[:, 0], e, atol=1e-3)  # float32 positions of a few hundred metres
    np.testing.assert_allclose(wrap(got[:, 1] - theta_star), 0.0, atol=1e-4)
    np.testing.assert_array_equal(got[:, 2], q_ref)
    np.testing.assert_array_equal(got[:, 4] == 1.0, hauled)
    assert 20 < hauled.sum() < n - 20  # both branches are exercised
    np.testing.assert_allclose(wrap(got[:, 3] - theta_bar), 0.0, atol=1e-4)
    np.testing.assert_allclose(got[:, 5], rudder, atol=1e-5)
    full = np.cos(theta - theta_bar) < 0
    assert 20 < full.sum() < n - 20  # both branches of the rudder law
    np.testing.assert_allclose(got[:, 6], sheet, atol=1e-4)


def test_sheet_law_anchors_and_heel_easing(device, rng):
    """The sheet law's anchors: 0 head to wind, beta on a beam reach (either side), 90 deg dead downwind.
    Heel easing: heel_ease per rad past heel_limit, capped at 90 deg, never sheeting in."""
    beta = rng.uniform(0.3, 1.3)
    config = LineFollowingConfig(beam_reach_sheet=beta, heel_limit=rng.uniform(0.1, 0.4), heel_ease=rng.uniform(1, 4),
                                 run_angle=math.pi)
    psi = rng.uniform(-np.pi, np.pi)
    # Lines whose nominal heading is psi + pi (head to wind: close-hauled instead), psi +- pi/2, psi.
    headings = np.array([psi + math.pi / 2, psi - math.pi / 2, psi])
    n = len(headings)
    a = np.zeros((n, 2))
    b = 100.0 * np.column_stack([np.cos(headings), np.sin(headings)])
    got = law_pieces(device, config, a, b, a.copy(), np.full(n, 10.0), np.full(n, psi), headings, np.ones(n),
                     np.zeros(n))
    np.testing.assert_allclose(got[:, 6], [beta, beta, math.pi / 2], atol=1e-5)
    # Head to wind: the law's sheet formula at theta_bar = psi + pi is 0.
    upwind = law_pieces(device, config, a[:1], a[:1] + [[1e3 * math.cos(psi + math.pi), 1e3 * math.sin(psi + math.pi)]],
                        a[:1], [10.0], [psi], [0.0], [1], [0.0])
    zeta = config.close_hauled_angle  # it is sailed close-hauled: sheet at psi - theta_bar = pi -+ zeta
    expected = 0.5 * math.pi * ((1.0 - math.cos(zeta)) / 2.0) ** (math.log(math.pi / (2 * beta)) / math.log(2))
    assert upwind[0, 6] == pytest.approx(expected, abs=1e-5)
    rolls = rng.uniform(-0.8, 0.8, 40)
    k = 40
    a = np.zeros((k, 2))
    lines = rng.uniform(-np.pi, np.pi, k)
    b = 100.0 * np.column_stack([np.cos(lines), np.sin(lines)])
    got = law_pieces(device, config, a, b, a.copy(), np.full(k, 10.0), np.full(k, psi), lines, np.ones(k), rolls)
    excess = np.maximum(np.abs(rolls) - config.heel_limit, 0.0)
    expected = np.minimum(got[:, 6] + config.heel_ease * excess, math.pi / 2)
    np.testing.assert_allclose(got[:, 7], np.maximum(expected, got[:, 6]), atol=1e-5)
    assert np.all(got[:, 7] >= got[:, 6] - 1e-7)  # only eases
    assert np.any(excess > 0) and np.any(excess == 0)


class FakeBoats:
    """The arrays the controller reads, set by hand: level boats at ``positions`` with ``headings`` [rad],
    ``surge`` [m/s] ahead, in a true wind blowing toward +x at ``wind`` [m/s]."""

    def __init__(self, device, positions, headings, *, surge=1.0, wind=6.0, roll=0.0):
        n = len(headings)
        self.device = device
        self.position = wp.array(np.asarray(positions, dtype=np.float32), dtype=wp.vec3, device=device)
        self.orientation = wp.zeros(n, dtype=wp.quat, device=device)
        self.set_headings(headings, roll)
        velocity = np.zeros((n, 6), dtype=np.float32)
        velocity[:, 0] = surge
        self.velocity = wp.array(velocity, dtype=wp.types.vector(6, wp.float32), device=device)
        self.wind_velocity = wp.array(np.tile([wind, 0.0, 0.0], (n, 1)).astype(np.float32), dtype=wp.vec3,
                                      device=device)

    def set_headings(self, headings, roll=0.0):
        n = len(headings)
        angles = np.column_stack([np.broadcast_to(roll, n), np.zeros(n), headings])
        self.orientation.assign(quaternion_from_roll_pitch_yaw(angles).astype(np.float32))

    def move(self, positions):
        self.position.assign(np.asarray(positions, dtype=np.float32))


def decide(follower, targets, device):
    actions = wp.zeros((follower.count, 3), dtype=float, device=device)
    follower.act(wp.array(np.asarray(targets, dtype=np.float32), dtype=wp.vec3, device=device), actions)
    return actions.numpy()


def test_tack_hysteresis_across_the_corridor(device):
    """A boat beating to a target 500 m dead upwind (the wind blows toward +x, the target lies to -x) with a
    corridor of 10 m: q keeps its sign while |e| <= 10 m and takes the sign of e beyond, and the desired
    heading is close-hauled on q: pi + psi - q zeta (the wind's source at 180 deg, so 180 - q zeta)."""
    config = LineFollowingConfig(corridor_half_width=10.0, close_hauled_angle=50.0 * DEG)
    boats = FakeBoats(device, [[0.0, 0.0, 0.0]], [math.pi - 0.8])  # on the tack q = +1 (heading 180 - 46 deg)
    follower = LineFollower(boats, config)
    target = [[-500.0, 0.0, 0.0]]
    # The line runs toward -x: its left is -y, so e = -y.
    expected_q = []
    got_q, got_course = [], []
    q = 1
    for y in [0.0, -5.0, -9.9, -10.5, 3.0, 9.9, 10.5, 0.0, -9.0, -10.2]:
        boats.move([[-20.0, y, 0.0]])
        decide(follower, target, device)
        e = -y
        q = int(np.sign(e)) if abs(e) > 10.0 else q
        expected_q.append(q)
        got_q.append(int(follower.tack.numpy()[0]))
        got_course.append(float(follower.course.numpy()[0]))
        assert follower.cross_track.numpy()[0] == pytest.approx(e, abs=1e-4)
    assert got_q == expected_q == [1, 1, 1, 1, 1, 1, -1, -1, -1, 1]
    np.testing.assert_allclose(wrap(np.array(got_course) - (math.pi - np.array(expected_q) * 50.0 * DEG)), 0.0,
                               atol=1e-5)
    assert int(follower.tacks.numpy()[0]) == 2  # two flips, both close-hauled
    assert np.array_equal(follower.side.numpy(), [-expected_q[-1]])


def test_line_starts_where_the_boat_stood_then_at_the_waypoint_reached(device):
    """After a reset the line starts at the boat's position; when the target moves on, at the old target; a
    masked reset starts a new line where the boat then stands."""
    boats = FakeBoats(device, [[3.0, 4.0, 0.0], [-7.0, 2.0, 0.0]], [0.5, 2.0])
    follower = LineFollower(boats)
    decide(follower, [[50.0, 60.0, 0.0], [10.0, -30.0, 0.0]], device)
    np.testing.assert_allclose(follower.line_start.numpy()[:, :2], [[3.0, 4.0], [-7.0, 2.0]])
    boats.move([[48.0, 57.0, 0.0], [9.0, -28.0, 0.0]])
    decide(follower, [[90.0, 10.0, 0.0], [10.0, -30.0, 0.0]], device)  # boat 0 reached its waypoint
    np.testing.assert_allclose(follower.line_start.numpy()[:, :2], [[50.0, 60.0], [-7.0, 2.0]])
    # Boat 0 on its new line (50, 60) -> (90, 10), at (48, 57): e = det(u, m - a) by hand.
    u = np.array([40.0, -50.0]) / math.hypot(40.0, 50.0)
    assert follower.cross_track.numpy()[0] == pytest.approx(u[0] * (57 - 60) - u[1] * (48 - 50), abs=1e-4)
    follower.reset(wp.array([0, 1], dtype=wp.int32, device=device))
    decide(follower, [[90.0, 10.0, 0.0], [10.0, -30.0, 0.0]], device)
    np.testing.assert_allclose(follower.line_start.numpy()[:, :2], [[50.0, 60.0], [9.0, -28.0]])


def test_actions_and_motor_assist(device):
    """The actions: a2 = rudder / 60 deg, a1 = sheet / 45 deg - 1, a0 the assist level (int(5 a0)) on a beat
    with the motor allowed, 0 without; a boat going astern gets the rudder reversed."""
    config = LineFollowingConfig(assist_level=3, rudder_gain=1.0, yaw_rate_gain=0.0)
    # Boat 0 reaching north toward a target 100 m north (on the line); boat 1 going astern, same line,
    # heading 20 deg right of it; boat 2 beating toward a target dead upwind.
    boats = FakeBoats(device, [[0.0, 0.0, 0.0]] * 3, [math.pi / 2, math.pi / 2 - 20 * DEG, math.pi - 50 * DEG])
    velocity = boats.velocity.numpy()
    velocity[1, 0] = -0.4
    boats.velocity.assign(velocity)
    follower = LineFollower(boats, config)
    actions = decide(follower, [[0.0, 100.0, 0.0], [0.0, 100.0, 0.0], [-100.0, 0.0, 0.0]], device)
    beta = config.beam_reach_sheet
    assert (actions[0, 1] + 1.0) * 45.0 * DEG == pytest.approx(beta, abs=1e-5)  # a beam reach
    assert actions[0, 2] == pytest.approx(0.0, abs=1e-6)
    assert actions[1, 2] * 60.0 * DEG == pytest.approx(-config.rudder_limit * math.sin(20 * DEG), abs=1e-5)
    assert int(5 * actions[2, 0]) == 3 and int(5 * actions[0, 0]) == 0
    sailing = LineFollower(boats, LineFollowingConfig.sail_only())
    assert np.all(decide(sailing, [[-100.0, 0.0, 0.0]] * 3, device)[:, 0] == 0.0)


def test_a_tack_that_does_not_come_through_becomes_a_wear(device):
    """A boat stuck close-hauled on q = +1 (heading 130 deg, its heading never changes here) told to tack
    (it is beyond the corridor on the other side): first the full rudder toward the short turn, through
    the wind (to port, +); after tack_timeout of it, the full rudder the other way (a wear), held until
    the heading comes within turn_release_angle of the desired one."""
    config = LineFollowingConfig(tack_timeout=5.0, corridor_half_width=10.0, yaw_rate_gain=0.0)
    boats = FakeBoats(device, [[0.0, 0.0, 0.0]], [math.pi - 50 * DEG])
    follower = LineFollower(boats, config)
    target = [[-500.0, 0.0, 0.0]]
    decide(follower, target, device)  # the line from (0, 0)
    boats.move([[-20.0, 12.0, 0.0]])  # e = -12: q becomes -1, close-hauled at 230 deg
    rudders = [decide(follower, target, device)[0, 2] * 60.0 for _ in range(8)]
    limit = math.degrees(config.rudder_limit)
    np.testing.assert_allclose(rudders[:5], limit, atol=1e-4)  # tacking: 100 deg of error, the full rudder to port
    np.testing.assert_allclose(rudders[5:], -limit, atol=1e-4)  # then wearing, to starboard
    assert int(follower.turn.numpy()[0]) == -1
    boats.set_headings([math.pi + 50 * DEG - 20 * DEG])  # worn round to within 20 deg of 230 deg
    rudder = decide(follower, target, device)[0, 2] * 60.0 * DEG
    assert int(follower.turn.numpy()[0]) == 0
    assert rudder == pytest.approx(config.rudder_limit * min(1.0, config.rudder_gain * math.sin(20 * DEG)), abs=1e-5)


def test_config_validation():
    LineFollowingConfig()  # the defaults are valid
    for field, value in [("rudder_gain", float("nan")), ("rudder_gain", 0.0), ("rudder_limit", 1.2),
                         ("rudder_limit", float("nan")), ("close_hauled_angle", math.pi / 2),
                         ("close_hauled_angle", -0.1), ("incidence_angle", 0.0), ("incidence_angle", 2.0),
                         ("corridor_half_width", 0.5), ("corridor_half_width", float("inf")),
                         ("run_angle", math.pi / 2), ("run_angle", 3.2), ("beam_reach_sheet", 0.0),
                         ("beam_reach_sheet", math.pi / 2), ("heel_limit", -0.1), ("heel_ease", float("nan")),
                         ("yaw_rate_gain", -1.0), ("tack_timeout", -1.0), ("decision_period", 0.0),
                         ("approach_corridor", 0.0), ("turn_release_angle", math.pi / 2), ("assist_level", 6),
                         ("assist_level", 1.5), ("assist_speed", "0.5"), ("max_sheet", 2.0), ("avoidance", 1)]:
        with pytest.raises(ValueError, match=rf"LineFollowingConfig\.{field}"):
            LineFollowingConfig(**{field: value})
    with pytest.raises(ValueError, match=r"LineFollowingConfig\.max_sheet"):
        LineFollowingConfig(min_sheet=1.0, max_sheet=0.5)
    with pytest.raises(ValueError, match="LineFollower: config"):
        LineFollower(FakeBoats("cpu", [[0, 0, 0]], [0.0]), config={"rudder_gain": 1.0})


def test_controller_choice():
    """The line follower is the default autopilot; the legacy one is selectable, by name or by its config,
    and on ``ocean-warp eval --autopilot``."""
    assert AutopilotController().autopilot == "line"
    assert AutopilotController(autopilot="legacy").autopilot == "legacy"
    assert AutopilotController(AutopilotConfig()).autopilot == "legacy"
    assert AutopilotController(LineFollowingConfig()).autopilot == "line"
    with pytest.raises(ValueError, match="AutopilotController: autopilot"):
        AutopilotController(autopilot="pid")
    with pytest.raises(ValueError, match="configures the 'line' autopilot"):
        AutopilotController(LineFollowingConfig(), autopilot="legacy")
    assert evaluation_parser().parse_args([]).autopilot == "line"
    assert evaluation_parser().parse_args(["--autopilot", "legacy"]).autopilot == "legacy"


def sail(device, heading, target, seconds, *, wind=6.0, config=None, stop_within=None):
    """One physics-profile E-Boat (mesh hull) in still water and a steady wind toward +x, from the origin with
    ``heading`` [rad] at 1 m/s, following the line to ``target`` (x, y) [m]; per-decision log."""
    sim_config = EBoatSimulatorConfig(boat=EBoatConfig(), wind=WindConfig(speed=wind, direction=0.0))
    sim = EBoatSimulator(sim_config, 1, device=device)
    config = config if config is not None else LineFollowingConfig()
    sim.reset(position=[[0.0, 0.0, 0.0]], heading=[heading], velocity=[1.0, 0, 0, 0, 0, 0], sheet=25.0 * DEG)
    follower = LineFollower(sim.state, config)
    actions = wp.zeros((1, 3), dtype=float, device=device)
    targets = wp.array(np.array([[*target, 0.0]], dtype=np.float32), dtype=wp.vec3, device=device)
    steps = int(round(config.decision_period / sim_config.dt))
    log = {"position": [], "heading": [], "yaw_rate": [], "rudder": [], "e": [], "status": [], "course": []}
    for _ in range(int(seconds / config.decision_period)):
        follower.act(targets, actions)
        log["rudder"].append(float(actions.numpy()[0, 2]))
        log["e"].append(float(follower.cross_track.numpy()[0]))
        log["course"].append(float(follower.course.numpy()[0]))
        sim.launch_actions(actions)
        for _ in range(steps):
            sim.step()
        log["position"].append(sim.state.position.numpy()[0, :2].copy())
        log["heading"].append(float(roll_pitch_yaw(sim.state.orientation.numpy())[0, 2]))
        log["yaw_rate"].append(float(sim.state.velocity.numpy()[0, 5]))
        log["status"].append(int(sim.state.status.numpy()[0]))
        if stop_within is not None and np.hypot(*(log["position"][-1] - np.asarray(target))) < stop_within:
            break
    return {k: np.array(v) for k, v in log.items()}, follower


def test_the_rudder_turns_the_boat_the_way_the_law_asks(device):
    """Two boats reaching north (wind toward +x) from the same start, on lines to (+-100, 300) m: the line to
    the east asks for a turn clockwise (its nominal heading 18.4 deg to starboard), the one to the west
    counter-clockwise. The first rudders have those signs (ours: negative to starboard), and the simulated
    boats turn that way: the one sent to port heads more than 5 deg further to port than the other from the
    second decision on (the only difference between them is the rudder), and the one sent to starboard, once
    the start's transient is over (the sail filling rounds both up for a second or two), turns clockwise
    (yaw rate < 0) and ends more than 3 deg to starboard of north."""
    config = LineFollowingConfig(yaw_rate_gain=0.0, rudder_limit=15.0 * DEG)
    starboard, _ = sail(device, math.pi / 2, (100.0, 300.0), 7.0, config=config)
    port, _ = sail(device, math.pi / 2, (-100.0, 300.0), 7.0, config=config)
    assert starboard["rudder"][0] < -0.1 and port["rudder"][0] > 0.1  # 15 sin(18.4 deg) x 2.5 = 11.9 deg
    assert np.all(starboard["rudder"][:4] < 0.0) and np.all(port["rudder"][:2] > 0.0)
    assert np.all(wrap(port["heading"][1:] - starboard["heading"][1:]) > 5.0 * DEG)
    assert np.all(starboard["yaw_rate"][3:5] < 0.0)
    assert wrap(starboard["heading"][-1] - math.pi / 2) < -3.0 * DEG


def test_beats_to_a_waypoint_dead_upwind(device):
    """Under sail alone in 6 m/s, a waypoint 70 m dead upwind: the boat beats within the corridor (15 m, a few
    metres of overshoot through the tacks) and comes within the missions' 5 m of it in under 4 minutes, tacking
    at least twice, upright, its desired heading never inside the close-hauled angle of the wind's source."""
    config = LineFollowingConfig()
    log, follower = sail(device, math.pi - 60.0 * DEG, (-70.0, 0.0), 240.0, stop_within=5.0)
    distance = np.hypot(*(log["position"][-1] - [-70.0, 0.0]))
    assert distance < 5.0, (distance, log["position"][-1])
    assert int(follower.tacks.numpy()[0]) >= 2
    assert np.all(log["status"] == 0)
    assert np.abs(log["position"][:, 1]).max() < config.corridor_half_width + 5.0
    assert np.all(np.abs(wrap(log["course"] - math.pi)) >= config.close_hauled_angle - 1e-4)


def test_line_follower_clears_a_pile_dead_ahead():
    """The avoidance task's pile on the line (as in test_avoidance): following the line blindly every boat hits
    it; with the legacy autopilot's collision cones moving the target first, none does and each reaches the
    waypoint beyond it (same seed: same starts, waves and gusts)."""
    from ocean_warp.envs.sailing_env import SailingEnv

    from .test_avoidance import _pile_ahead_task, _sail_first_episodes

    env = SailingEnv(_pile_ahead_task(), 3, device="cpu", seed=3)
    collided, _ = _sail_first_episodes(env, LineFollowingConfig(avoidance=False))
    assert collided.all()
    collided, reached = _sail_first_episodes(env, LineFollowingConfig())
    assert not collided.any()
    assert reached.all()
