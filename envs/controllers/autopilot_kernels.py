"""Kernels of the classical sailing autopilot (``ocean_warp.envs.controllers.sailing_autopilot``): one thread per boat.

Each decision, a boat picks a course to its target and turns it into normalised actions:

- Course: line of sight to the target, unless that bearing lies in the no-go zone upwind (closer
  than ``no_go_angle`` to the wind's source: the closest track the boat makes good, leeway included)
  or in the dead-run zone downwind (deeper than ``run_angle``). There it sails on its current side,
  close-hauled (heading ``close_hauled_angle`` off the wind) or on broad reaches, and only changes
  side (tacks or gybes) once the target's bearing has crossed the zone's axis by a margin:
  ``tack_hysteresis`` far from the target, widened near it so that the boat keeps at least
  ``lane_half_width`` of cross-track room, and never wider than the zone (the layline), at which
  point the line of sight is sailable on the other side and takes over. A boat that overshoots a
  close target holds its course until ``approach_radius`` away instead of circling it.
- Turns through the wind that do not come through within ``tack_timeout`` go the long way round
  (a wear): the E-Boat's lee helm and low speed close-hauled defeat most tacks in 10 m/s.
- Rudder: a PI on the heading error with yaw-rate damping (reversed when the boat moves astern).
- Sheet: the boom limit from the apparent wind angle minus an angle of attack, eased when the boat
  heels too far and while it bears away (to shed the weather helm that holds a heeled bow up).

Angles: radians, headings as yaw from +x counter-clockwise; the wind "direction" is where the air
blows towards (as ``ocean_warp.WindConfig``); a boat's side is +1 when the wind comes over its
starboard side (starboard tack: heading counter-clockwise of the wind's source), -1 on port, 0 unset.
"""

from __future__ import annotations

import warp as wp

from ocean_warp.kernels.spatial import PI, heading_of, vec6, wrap_angle

__all__ = ["AutopilotParameters", "sail_to_targets", "reset_autopilot",
           "course_to_target", "trim_sheet", "steer_rudder", "roll_of", "tacking_turn",
           "RUDDER_ACTION_SCALE", "SHEET_ACTION_SCALE", "PROPELLER_ACTION_SCALE"]

RUDDER_ACTION_SCALE = wp.constant(PI / 3.0)
"""Rudder angle of action a2 = 1 [rad] (60 deg)."""
SHEET_ACTION_SCALE = wp.constant(PI / 4.0)
"""Sheet angle per unit of (a1 + 1) [rad] (45 deg)."""
PROPELLER_ACTION_SCALE = wp.constant(5.0)
"""Propeller levels per unit of a0."""


@wp.struct
class AutopilotParameters:
    """The kernels' view of an ``AutopilotConfig`` (same names, SI units, radians)."""

    decision_period: float
    close_hauled_angle: float
    no_go_angle: float
    run_angle: float
    tack_hysteresis: float
    lane_half_width: float
    heading_gain: float
    heading_integral_gain: float
    yaw_rate_gain: float
    rudder_limit: float
    attack_angle: float
    min_sheet: float
    max_sheet: float
    heel_limit: float
    heel_ease: float
    propeller_level: int
    tack_timeout: float
    turn_release_angle: float
    bear_away_ease: float
    approach_radius: float
    assist_level: int
    assist_speed: float


@wp.func
def roll_of(q: wp.quat) -> float:
    """Roll [rad] of a body -> world quaternion (Z-Y-X angles; positive: starboard side down)."""
    return wp.atan2(2.0 * (q[3] * q[0] + q[1] * q[2]), 1.0 - 2.0 * (q[0] * q[0] + q[1] * q[1]))


@wp.func
def _side_of(angle: float) -> int:
    if angle >= 0.0:
        return 1
    return -1


@wp.func
def _zone_course(center: float, half_width: float, offset: float, margin: float, zone_side: int) -> wp.vec2:
    """Course along the edge of a no-sail zone centred on ``center`` [rad] with ``half_width`` [rad], for a
    target at ``offset`` = wrap(bearing - center) [rad]: stays on ``zone_side`` (+1: counter-clockwise
    edge) until the target has crossed the axis by ``margin``; returns (course, new zone side)."""
    side = zone_side
    if float(side) * offset < -margin:
        side = -side
    return wp.vec2(wrap_angle(center + float(side) * half_width), float(side))


@wp.func
def course_to_target(p: AutopilotParameters, bearing: float, distance: float, wind_to: float,
                     side: int) -> wp.vec2:
    """Course [rad] to a target at ``bearing`` [rad] and ``distance`` [m] in a true wind blowing towards
    ``wind_to`` [rad], for a boat on ``side`` (+1 starboard, -1 port, 0 unset: the target's side);
    returns (course, new side)."""
    wind_from = wind_to + PI
    upwind = wrap_angle(bearing - wind_from)
    downwind = wrap_angle(bearing - wind_to)
    current = side
    if current == 0:
        current = _side_of(upwind)
    # Cross-track room the boat keeps: the angular margin grows as the target nears (capped below).
    room = wp.atan(p.lane_half_width / wp.max(distance, 1.0e-3))
    margin = wp.max(p.tack_hysteresis, room)
    run_half_width = PI - p.run_angle
    result = wp.vec2(bearing, float(_side_of(upwind)))
    if wp.abs(upwind) < p.no_go_angle:
        # Beat: the zone's counter-clockwise edge is the starboard tack; the boat heads close-hauled,
        # and leeway puts its track near the zone's edge.
        edge = _zone_course(wind_from, p.no_go_angle, upwind, wp.min(margin, p.no_go_angle), current)
        result = wp.vec2(wrap_angle(wind_from + edge[1] * p.close_hauled_angle), edge[1])
    elif wp.abs(downwind) < run_half_width:
        # Broad reaches: the zone's counter-clockwise edge (around the wind's heading) is the port gybe.
        edge = _zone_course(wind_to, run_half_width, downwind, wp.min(margin, run_half_width), -current)
        result = wp.vec2(edge[0], -edge[1])
    return result


@wp.func
def tacking_turn(heading: float, course: float, wind_to: float) -> bool:
    """Whether the short turn from ``heading`` to ``course`` [rad] passes through the wind's source."""
    wind_from = wind_to + PI
    now = wrap_angle(heading - wind_from)
    then = wrap_angle(course - wind_from)
    return _side_of(now) != _side_of(then) and wp.abs(now) + wp.abs(then) < PI


@wp.func
def trim_sheet(p: AutopilotParameters, apparent_wind_angle: float, roll: float) -> float:
    """Boom limit [rad] for an apparent wind from ``apparent_wind_angle`` [rad, from the bow] with the boat
    rolled ``roll`` [rad]: |AWA| - attack angle, plus ``heel_ease`` per rad of heel past ``heel_limit``,
    within [min_sheet, max_sheet]."""
    sheet = wp.abs(apparent_wind_angle) - p.attack_angle
    sheet = sheet + p.heel_ease * wp.max(wp.abs(roll) - p.heel_limit, 0.0)
    return wp.clamp(sheet, p.min_sheet, p.max_sheet)


@wp.func
def steer_rudder(p: AutopilotParameters, error: float, yaw_rate: float, surge: float, integral: float) -> wp.vec2:
    """Rudder [rad] for a heading ``error`` [rad] (course - heading) and ``yaw_rate`` [rad/s]: a PI on the
    error with rate damping, clamped to +-rudder_limit, reversed when going astern (``surge`` < 0). The
    integral [rad s] only grows while the rudder is not saturated; returns (rudder, new integral)."""
    accumulated = integral + error * p.decision_period
    command = p.heading_gain * error + p.heading_integral_gain * accumulated - p.yaw_rate_gain * yaw_rate
    new_integral = integral
    if wp.abs(command) < p.rudder_limit:
        new_integral = accumulated
    rudder = wp.clamp(command, -p.rudder_limit, p.rudder_limit)
    if surge < 0.0:
        rudder = -rudder
    return wp.vec2(rudder, new_integral)


@wp.kernel(enable_backward=False)
def sail_to_targets(
    p: AutopilotParameters,
    targets: wp.array(dtype=wp.vec3),
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    wind_velocity: wp.array(dtype=wp.vec3),
    side: wp.array(dtype=wp.int32),
    integral: wp.array(dtype=float),
    tacks: wp.array(dtype=wp.int32),
    gybes: wp.array(dtype=wp.int32),
    turn: wp.array(dtype=wp.int32),
    stalled: wp.array(dtype=float),
    course: wp.array(dtype=float),
    actions: wp.array2d(dtype=float),
):
    """One decision per boat: course to ``targets`` [m, world], rudder and sheet, written as normalised
    actions (a0 propeller, a1 sheet, a2 rudder) in [-1, 1]. ``wind_velocity``: true wind, world [m/s].
    Updates the boat's side, heading integral [rad s] and tack / gybe counts; ``course`` gets the
    course steered to [rad]."""
    boat = wp.tid()
    q = orientation[boat]
    nu = velocity[boat]
    heading = heading_of(q)
    offset = targets[boat] - position[boat]
    bearing = wp.atan2(offset[1], offset[0])
    distance = wp.sqrt(offset[0] * offset[0] + offset[1] * offset[1])
    wind = wind_velocity[boat]
    wind_to = wp.atan2(wind[1], wind[0])

    old_side = side[boat]
    # Astern, beyond a tack on the layline's turn (2 close-hauled angles), and sailable straight on.
    behind = wp.abs(wrap_angle(bearing - heading)) > wp.max(2.0 * PI / 3.0,
                                                            p.no_go_angle + p.close_hauled_angle + 0.2)
    sailable = wp.abs(wrap_angle(bearing - (wind_to + PI))) > p.no_go_angle
    if old_side != 0 and distance < p.approach_radius and behind and sailable:
        # Overshot a close target: hold the last course to come round wide instead of circling it.
        bearing = course[boat]
        distance = 1.0e6
    if old_side == 0:
        # A fresh boat starts on the tack it is on.
        old_side = _side_of(wrap_angle(heading - (wind_to + PI)))
    choice = course_to_target(p, bearing, distance, wind_to, old_side)
    new_course = choice[0]
    new_side = int(choice[1])
    accumulated = integral[boat]
    if new_side != old_side:
        # The weather helm the integral held is mirrored on the new side.
        accumulated = -accumulated
        if wp.abs(wrap_angle(new_course - wind_to)) > 0.5 * PI:
            tacks[boat] = tacks[boat] + 1
        else:
            gybes[boat] = gybes[boat] + 1
    side[boat] = new_side
    course[boat] = new_course

    # Turning through the wind, which this boat may fail to do (lee helm, little way on): after
    # ``tack_timeout`` of trying, turn the other way round, through the wind's eye's opposite (wear).
    error = wrap_angle(new_course - heading)
    forced = turn[boat]
    waiting = stalled[boat]
    if forced != 0:
        if wp.abs(error) < p.turn_release_angle:
            forced = 0
    if forced == 0:
        if tacking_turn(heading, new_course, wind_to):
            waiting = waiting + p.decision_period
            if waiting > p.tack_timeout:
                forced = -_side_of(error)
                waiting = 0.0
        else:
            waiting = 0.0
    if forced != 0 and float(forced) * error < 0.0:
        error = error + float(forced) * 2.0 * PI
    turn[boat] = forced
    stalled[boat] = waiting
    steer = steer_rudder(p, error, nu[5], nu[0], accumulated)
    integral[boat] = steer[1]

    # Apparent wind over the horizontal plane: true wind minus the boat's velocity over ground.
    ground = wp.quat_rotate(q, wp.vec3(nu[0], nu[1], nu[2]))
    apparent_x = wind[0] - ground[0]
    apparent_y = wind[1] - ground[1]
    apparent_wind_angle = wrap_angle(wp.atan2(-apparent_y, -apparent_x) - heading)
    sheet = trim_sheet(p, apparent_wind_angle, roll_of(q))
    off_wind = wrap_angle(heading - (wind_to + PI))
    if _side_of(error) == _side_of(off_wind):
        # Bearing away: ease the sheet to shed the weather helm that holds the bow up.
        sheet = wp.min(sheet + p.bear_away_ease * wp.abs(error), p.max_sheet)

    level = p.propeller_level
    # Motor assist: on a beat, through a turn, or with too little way on to steer.
    upwind = wp.abs(wrap_angle(new_course - (wind_to + PI))) < 0.5 * PI
    if p.assist_level > 0 and (upwind or forced != 0 or waiting > 0.0 or nu[0] < p.assist_speed):
        level = wp.max(level, p.assist_level)
    a0 = 0.0
    if level != 0:
        # Half a level beyond, so that int(5 a0) truncates to the level itself.
        a0 = (float(level) + 0.5 * float(_side_of(float(level)))) / PROPELLER_ACTION_SCALE
    actions[boat, 0] = wp.clamp(a0, -1.0, 1.0)
    actions[boat, 1] = wp.clamp(sheet / SHEET_ACTION_SCALE - 1.0, -1.0, 1.0)
    actions[boat, 2] = wp.clamp(steer[0] / RUDDER_ACTION_SCALE, -1.0, 1.0)


@wp.kernel(enable_backward=False)
def reset_autopilot(mask: wp.array(dtype=wp.int32), side: wp.array(dtype=wp.int32),
                    integral: wp.array(dtype=float), tacks: wp.array(dtype=wp.int32),
                    gybes: wp.array(dtype=wp.int32), turn: wp.array(dtype=wp.int32),
                    stalled: wp.array(dtype=float)):
    """Forget the side, the heading integral and the tack / gybe counts of boats whose ``mask`` != 0."""
    boat = wp.tid()
    if mask[boat] != 0:
        side[boat] = 0
        integral[boat] = 0.0
        tacks[boat] = 0
        gybes[boat] = 0
        turn[boat] = 0
        stalled[boat] = 0.0
