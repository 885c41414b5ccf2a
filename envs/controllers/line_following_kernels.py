"""Kernels of the line-following controller (``ocean_warp.envs.controllers.line_following``): the law of
Jaulin and Le Bars (2012) as ``@wp.func`` pieces, and one kernel that makes one decision per boat.

Angles: radians, headings as yaw from +x counter-clockwise (ENU); ``psi`` is the direction the true wind
blows towards (as ``ocean_warp.WindConfig``). The tack variable q is +1 or -1 (0: not chosen yet); with
q = +1 the close-hauled heading lies clockwise of the wind's source (the wind over the port side).
Rudder angles are ours: positive turns the boat to port (yaw rate > 0; ``kernels.sailing_rig``), the
opposite of the paper's.
"""

from __future__ import annotations

import warp as wp

from ocean_warp.kernels.spatial import PI, heading_of, vec6, wrap_angle

from .autopilot_kernels import PROPELLER_ACTION_SCALE, RUDDER_ACTION_SCALE, SHEET_ACTION_SCALE, side_of, roll_of

__all__ = ["LineFollowingParameters", "signed_distance", "nominal_heading", "update_tack", "desired_heading",
           "favoured_tack", "rudder_law", "sheet_law", "eased_sheet", "follow_lines",
           "reset_line_following",
           "MODE_NOMINAL", "MODE_CLOSE_HAULED", "MODE_RUN"]

MODE_NOMINAL = wp.constant(0)
"""The desired heading is the nominal one, theta* (toward the line)."""
MODE_CLOSE_HAULED = wp.constant(1)
"""The desired heading is close-hauled on tack q."""
MODE_RUN = wp.constant(2)
"""The desired heading is a broad reach at the run angle on gybe q (the optional downwind zone)."""


@wp.struct
class LineFollowingParameters:
    """The kernel's view of a ``LineFollowingConfig`` (same names, SI units, radians)."""

    decision_period: float
    corridor_half_width: float
    approach_corridor: float
    incidence_angle: float
    close_hauled_angle: float
    run_angle: float
    rudder_limit: float
    rudder_gain: float
    yaw_rate_gain: float
    beam_reach_sheet: float
    min_sheet: float
    max_sheet: float
    heel_limit: float
    heel_ease: float
    tack_timeout: float
    turn_release_angle: float
    assist_level: int
    assist_speed: float
    astern_speed: float


@wp.func
def signed_distance(a: wp.vec2, b: wp.vec2, m: wp.vec2) -> float:
    """Signed distance [m] of ``m`` from the line through ``a`` toward ``b`` (positive to its left):
    det((b - a) / |b - a|, m - a); 0 where a and b coincide."""
    d = b - a
    length = wp.length(d)
    result = float(0.0)
    if length > 1.0e-6:
        result = (d[0] * (m[1] - a[1]) - d[1] * (m[0] - a[0])) / length
    return result


@wp.func
def nominal_heading(phi: float, e: float, r: float, incidence: float) -> float:
    """Heading [rad] that brings a boat ``e`` [m] left of a line of direction ``phi`` [rad] back to it:
    phi - (2 incidence / pi) atan(e / r), crossing the line at up to ``incidence`` [rad] from afar."""
    return phi - 2.0 * incidence / PI * wp.atan(e / r)


@wp.func
def update_tack(q: int, e: float, r: float) -> int:
    """The tack variable after a boat at ``e`` [m] from the line: sign(e) outside the corridor of half-width
    ``r`` [m], else ``q`` kept (the hysteresis that makes the boat beat across the corridor)."""
    result = q
    if e > r:
        result = 1
    elif e < -r:
        result = -1
    return result


@wp.func
def desired_heading(p: LineFollowingParameters, phi: float, theta_star: float, e: float, r: float, psi: float,
                    q: int) -> wp.vec2:
    """(desired heading [rad], mode) for the nominal heading ``theta_star`` on a line of direction ``phi``,
    at ``e`` [m] from it in a corridor of half-width ``r`` [m], in a wind blowing toward ``psi`` [rad], on
    tack ``q``. Close-hauled (pi + psi - q zeta) when theta_star lies within zeta of the wind's source, or
    inside the corridor when the line itself does; the same with the run angle downwind (pi - run_angle
    off the wind's direction), which is off at a run angle of pi."""
    zeta = p.close_hauled_angle
    inside = wp.abs(e) < r
    result = wp.vec2(theta_star, float(MODE_NOMINAL))
    if wp.cos(psi - theta_star) + wp.cos(zeta) < 0.0 or (inside and wp.cos(psi - phi) + wp.cos(zeta) < 0.0):
        result = wp.vec2(wrap_angle(PI + psi - float(q) * zeta), float(MODE_CLOSE_HAULED))
    else:
        run = PI - p.run_angle
        if run > 0.0:
            if wp.cos(psi - theta_star) > wp.cos(run) or (inside and wp.cos(psi - phi) > wp.cos(run)):
                result = wp.vec2(wrap_angle(psi - float(q) * run), float(MODE_RUN))
    return result


@wp.func
def favoured_tack(phi: float, psi: float, zeta: float, q: int) -> int:
    """The tack whose close-hauled heading pi + psi - q zeta makes more way along a line of direction ``phi``
    [rad]; ``q`` where the two make nearly the same (within 0.05 of cos: a line within about 3 deg of
    dead upwind or downwind)."""
    starboard = wp.cos(PI + psi - zeta - phi)
    port = wp.cos(PI + psi + zeta - phi)
    result = q
    if starboard > port + 0.05:
        result = 1
    elif port > starboard + 0.05:
        result = -1
    return result


@wp.func
def rudder_law(rudder_limit: float, gain: float, theta: float, theta_bar: float) -> float:
    """Rudder [rad, ours: positive turns to port] that turns heading ``theta`` toward ``theta_bar`` [rad]:
    rudder_limit clamp(gain sin(theta_bar - theta), -1, 1) while the error is under 90 deg, else the full
    rudder toward it (the paper's law, gain 1, with its sign reversed)."""
    error = theta_bar - theta
    result = rudder_limit * wp.clamp(gain * wp.sin(error), -1.0, 1.0)
    if wp.cos(error) < 0.0:
        result = rudder_limit * wp.sign(wp.sin(error))
    return result


@wp.func
def sheet_law(beam_reach_sheet: float, psi: float, theta_bar: float) -> float:
    """Boom limit [rad] for the desired heading ``theta_bar`` in a wind blowing toward ``psi`` [rad]:
    (pi / 2) ((cos(psi - theta_bar) + 1) / 2)^(log(pi / (2 beta)) / log 2), beta ``beam_reach_sheet``:
    0 head to wind, beta on a beam reach, pi / 2 dead downwind."""
    exponent = wp.log(PI / (2.0 * beam_reach_sheet)) / wp.log(2.0)
    base = wp.max(0.5 * (wp.cos(psi - theta_bar) + 1.0), 0.0)
    return 0.5 * PI * wp.pow(base, exponent)


@wp.func
def eased_sheet(sheet: float, roll: float, heel_limit: float, heel_ease: float) -> float:
    """``sheet`` [rad] eased by ``heel_ease`` per rad of heel past ``heel_limit`` [rad] for a boat rolled
    ``roll`` [rad], up to pi / 2; never sheeted in."""
    eased = sheet + heel_ease * wp.max(wp.abs(roll) - heel_limit, 0.0)
    return wp.max(sheet, wp.min(eased, 0.5 * PI))


@wp.kernel(enable_backward=False)
def follow_lines(
    p: LineFollowingParameters,
    targets: wp.array(dtype=wp.vec3),
    steering: wp.array(dtype=wp.vec3),
    deflection: wp.array(dtype=float),
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    wind_velocity: wp.array(dtype=wp.vec3),
    fresh: wp.array(dtype=wp.int32),
    line_start: wp.array(dtype=wp.vec3),
    line_end: wp.array(dtype=wp.vec3),
    tack: wp.array(dtype=wp.int32),
    side: wp.array(dtype=wp.int32),
    turn: wp.array(dtype=wp.int32),
    stalled: wp.array(dtype=float),
    tacks: wp.array(dtype=wp.int32),
    gybes: wp.array(dtype=wp.int32),
    course: wp.array(dtype=float),
    cross_track: wp.array(dtype=float),
    actions: wp.array2d(dtype=float),
):
    """One decision per boat: the line from the last waypoint to ``targets`` [m, world], the desired heading,
    rudder, sheet and propeller, written as normalised actions (a0 propeller, a1 sheet, a2 rudder).

    The line: a boat's line starts where it stood at its first decision after a reset (``fresh`` != 0) and,
    when its target moves on, at the target it had (the waypoint reached), as the task's leg does. Where
    ``deflection`` != 0 (the lidar's avoidance turned the course), the boat follows the line from itself to
    ``steering`` instead. Updates the tack q, the side (-q, the autopilot's convention for its avoidance),
    the forced turn and its timer, the tack and gybe counts; ``course`` gets the desired heading [rad],
    ``cross_track`` the signed distance e [m]."""
    boat = wp.tid()
    rot = orientation[boat]
    nu = velocity[boat]
    theta = heading_of(rot)
    here = position[boat]
    target = targets[boat]
    new_line = False
    if fresh[boat] != 0:
        line_start[boat] = here
        line_end[boat] = target
        fresh[boat] = 0
        new_line = True
    elif wp.length(target - line_end[boat]) > 1.0e-3:
        line_start[boat] = line_end[boat]
        line_end[boat] = target
        new_line = True
    m = wp.vec2(here[0], here[1])
    a = wp.vec2(line_start[boat][0], line_start[boat][1])
    b = wp.vec2(target[0], target[1])
    if deflection[boat] != 0.0:
        a = m
        b = wp.vec2(steering[boat][0], steering[boat][1])
    direction = b - a
    length = wp.length(direction)
    if length < 1.0e-3:
        # No line (a boat on its target): the line of sight to it.
        a = m
        direction = b - m
        length = wp.length(direction)
    u = direction / wp.max(length, 1.0e-6)
    remaining = wp.dot(b - m, u)
    if remaining < 0.0:
        # Past the target's abeam: the line mirrored about it, which leads back to it.
        a = 2.0 * b - a
        u = -u
        remaining = -remaining
    phi = wp.atan2(u[1], u[0])
    e = signed_distance(a, b, m)
    # The corridor narrows near the target, so that the boat crosses the line close to it.
    r = wp.clamp(remaining * p.approach_corridor, 1.0, p.corridor_half_width)

    wind = wind_velocity[boat]
    psi = wp.atan2(wind[1], wind[0])
    q = tack[boat]
    if q == 0:
        # A fresh boat starts on the tack it is on.
        q = -side_of(wrap_angle(theta - (psi + PI)))
    if new_line:
        # A new line starts on the tack that makes more way along it (the paper keeps the last leg's q, which
        # on a line at about zeta off the wind can sail the boat away from b until it leaves the corridor).
        q = favoured_tack(phi, psi, p.close_hauled_angle, q)
    old_q = q
    q = update_tack(q, e, r)
    theta_star = nominal_heading(phi, e, r, p.incidence_angle)
    choice = desired_heading(p, phi, theta_star, e, r, psi, q)
    theta_bar = choice[0]
    mode = int(choice[1])
    if q != old_q:
        if mode == MODE_CLOSE_HAULED:
            tacks[boat] = tacks[boat] + 1
        elif mode == MODE_RUN:
            gybes[boat] = gybes[boat] + 1
    tack[boat] = q
    side[boat] = -q
    course[boat] = theta_bar
    cross_track[boat] = e

    # A turn through the wind's source that does not come through within tack_timeout goes the other way
    # round (a wear), with the full rudder, until the heading is within turn_release_angle of theta_bar.
    error = wrap_angle(theta_bar - theta)
    forced = turn[boat]
    waiting = stalled[boat]
    if forced != 0 and wp.abs(error) < p.turn_release_angle:
        forced = 0
    if forced == 0:
        from_wind = wrap_angle(theta - (psi + PI))
        to_wind = wrap_angle(theta_bar - (psi + PI))
        through_wind = side_of(from_wind) != side_of(to_wind) and wp.abs(from_wind) + wp.abs(to_wind) < PI
        if through_wind:
            waiting = waiting + p.decision_period
            if waiting > p.tack_timeout:
                forced = -side_of(error)
                waiting = 0.0
        else:
            waiting = 0.0
    turn[boat] = forced
    stalled[boat] = waiting

    rudder = float(0.0)
    if forced != 0:
        rudder = float(forced) * p.rudder_limit
    else:
        rudder = wp.clamp(rudder_law(p.rudder_limit, p.rudder_gain, theta, theta_bar) - p.yaw_rate_gain * nu[5],
                          -p.rudder_limit, p.rudder_limit)
    if nu[0] < -p.astern_speed and forced == 0:
        # Going astern, the rudder's force turns the boat the other way.
        rudder = -rudder

    # The law at the boat's own heading, but at the desired one while the bow is inside the no-go zone
    # (through a tack, or in irons), where the law at the heading sheets hard in and pins the bow to the wind
    # (see LineFollower's docstring).
    trim_heading = theta
    if wp.cos(psi - theta) + wp.cos(p.close_hauled_angle) < 0.0:
        trim_heading = theta_bar
    sheet = eased_sheet(sheet_law(p.beam_reach_sheet, psi, trim_heading), roll_of(rot), p.heel_limit,
                        p.heel_ease)
    sheet = wp.clamp(sheet, p.min_sheet, p.max_sheet)

    level = int(0)
    if p.assist_level > 0 and (mode == MODE_CLOSE_HAULED or forced != 0 or waiting > 0.0 or nu[0] < p.assist_speed):
        level = p.assist_level
    a0 = float(0.0)
    if level != 0:
        # Half a level beyond, so that int(5 a0) truncates to the level itself.
        a0 = (float(level) + 0.5) / PROPELLER_ACTION_SCALE
    actions[boat, 0] = wp.clamp(a0, -1.0, 1.0)
    actions[boat, 1] = wp.clamp(sheet / SHEET_ACTION_SCALE - 1.0, -1.0, 1.0)
    actions[boat, 2] = wp.clamp(rudder / RUDDER_ACTION_SCALE, -1.0, 1.0)


@wp.kernel(enable_backward=False)
def reset_line_following(mask: wp.array(dtype=wp.int32), fresh: wp.array(dtype=wp.int32),
                         tack: wp.array(dtype=wp.int32), side: wp.array(dtype=wp.int32), turn: wp.array(dtype=wp.int32),
                         stalled: wp.array(dtype=float), tacks: wp.array(dtype=wp.int32),
                         gybes: wp.array(dtype=wp.int32)):
    """Forget the line, the tack, the forced turn and the counts of boats whose ``mask`` != 0: their next
    decision starts a line where they stand."""
    boat = wp.tid()
    if mask[boat] != 0:
        fresh[boat] = 1
        tack[boat] = 0
        side[boat] = 0
        turn[boat] = 0
        stalled[boat] = 0.0
        tacks[boat] = 0
        gybes[boat] = 0
