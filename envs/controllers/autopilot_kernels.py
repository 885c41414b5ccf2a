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

Obstacle avoidance (``steer_clear``, launched before ``sail_to_targets`` where the boats carry a lidar):
collision cones about the lidar's nearest return per sector turn each boat's target into a steering
target; ``SailingAutopilot`` documents the law.

Angles: radians, headings as yaw from +x counter-clockwise; the wind "direction" is where the air
blows towards (as ``ocean_warp.WindConfig``); a boat's side is +1 when the wind comes over its
starboard side (starboard tack: heading counter-clockwise of the wind's source), -1 on port, 0 unset.
"""

from __future__ import annotations

import warp as wp

from ocean_warp.kernels.spatial import PI, heading_of, vec6, wrap_angle

__all__ = ["AutopilotParameters", "AvoidanceParameters", "sail_to_targets", "reset_autopilot", "steer_clear",
           "forget_returns", "NO_RETURN_AGE",
           "course_to_target", "trim_sheet", "steer_rudder", "roll_of", "tacking_turn",
           "RUDDER_ACTION_SCALE", "SHEET_ACTION_SCALE", "PROPELLER_ACTION_SCALE", "roll_of", "side_of"]

RUDDER_ACTION_SCALE = wp.constant(PI / 3.0)
"""Rudder angle of action a2 = 1 [rad] (60 deg)."""
SHEET_ACTION_SCALE = wp.constant(PI / 4.0)
"""Sheet angle per unit of (a1 + 1) [rad] (45 deg)."""
PROPELLER_ACTION_SCALE = wp.constant(5.0)
"""Propeller levels per unit of a0."""
NO_RETURN_AGE = wp.constant(1.0e30)
"""Age [s] of a sector's remembered return when it holds none (after a reset)."""


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


@wp.struct
class AvoidanceParameters:
    """The avoidance kernel's view of an ``AutopilotConfig`` and of the lidar whose sectors it reads."""

    avoidance_range: float
    """Returns nearer than this [m] are avoided."""
    avoidance_clearance: float
    """Gap [m] the boat's track keeps from a return."""
    avoidance_cone: float
    """The widest a cone spreads for the clearance [rad], beyond half a sector."""
    avoidance_lookahead: float
    """Distance of the steering target from the boat [m]."""
    avoidance_memory: float
    """How long a sector's last return is still avoided after its sector stops seeing it [s]."""
    avoidance_turn_cost: float
    """Weight of the turn from the heading against the departure from the intended course."""
    decision_period: float
    """Time between decisions [s]: how much a remembered return ages per call."""
    sector_range: float
    """The lidar's max range [m]: a sector's value times this is its nearest return's range."""
    sector_half_width: float
    """Half a sector's angular width [rad]: how far from its centre a return may lie."""
    mount: wp.vec3
    """The lidar's origin in the body frame [m]."""


@wp.func
def roll_of(q: wp.quat) -> float:
    """Roll [rad] of a body -> world quaternion (Z-Y-X angles; positive: starboard side down)."""
    return wp.atan2(2.0 * (q[3] * q[0] + q[1] * q[2]), 1.0 - 2.0 * (q[0] * q[0] + q[1] * q[1]))


@wp.func
def side_of(angle: float) -> int:
    """+1 for an angle >= 0 (counter-clockwise, to port), else -1."""
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
        current = side_of(upwind)
    # Cross-track room the boat keeps: the angular margin grows as the target nears (capped below).
    room = wp.atan(p.lane_half_width / wp.max(distance, 1.0e-3))
    margin = wp.max(p.tack_hysteresis, room)
    run_half_width = PI - p.run_angle
    result = wp.vec2(bearing, float(side_of(upwind)))
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
    return side_of(now) != side_of(then) and wp.abs(now) + wp.abs(then) < PI


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
        old_side = side_of(wrap_angle(heading - (wind_to + PI)))
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
                forced = -side_of(error)
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
    if side_of(error) == side_of(off_wind):
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
        a0 = (float(level) + 0.5 * float(side_of(float(level)))) / PROPELLER_ACTION_SCALE
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


@wp.func
def _cone(a: AvoidanceParameters, point: wp.vec3, sensor_x: float, sensor_y: float) -> wp.vec3:
    """The collision cone of a remembered return ``point`` (world x, y [m], age [s]) seen from the sensor at
    (sensor_x, sensor_y) [m]: (world bearing [rad], half-width [rad], 1 if it is avoided now else 0)."""
    dx = point[0] - sensor_x
    dy = point[1] - sensor_y
    distance = wp.sqrt(dx * dx + dy * dy)
    avoided = 0.0
    if point[2] <= a.avoidance_memory and distance < a.avoidance_range:
        avoided = 1.0
    half_width = a.sector_half_width + wp.min(wp.asin(wp.min(a.avoidance_clearance / wp.max(distance, 1.0e-6), 1.0)),
                                              a.avoidance_cone)
    return wp.vec3(wp.atan2(dy, dx), half_width, avoided)


@wp.func
def _blocked(a: AvoidanceParameters, returns: wp.array2d(dtype=wp.vec3), boat: int, sensor_x: float,
             sensor_y: float, course: float) -> bool:
    """Whether ``course`` [rad] heads into the collision cone of one of ``boat``'s returns."""
    result = int(0)
    for sector in range(returns.shape[1]):
        cone = _cone(a, returns[boat, sector], sensor_x, sensor_y)
        if cone[2] > 0.0 and wp.abs(wrap_angle(course - cone[0])) < cone[1]:
            result = 1
    return result != 0


@wp.func
def _turn_span(cone: wp.vec3, heading: float, direction: float) -> wp.vec2:
    """Where ``cone`` (bearing, half-width [rad]) lies along a turn from ``heading`` in ``direction`` (+1
    counter-clockwise): (near edge, far edge) [rad of turn]; a cone that holds the heading starts below 0,
    one behind the heading is put a full turn on."""
    centre = direction * wrap_angle(cone[0] - heading)
    if centre + cone[1] <= 0.0:
        centre = centre + 2.0 * PI
    return wp.vec2(centre - cone[1], centre + cone[1])


@wp.func
def _crosses(a: AvoidanceParameters, returns: wp.array2d(dtype=wp.vec3), boat: int, sensor_x: float,
             sensor_y: float, heading: float, course: float) -> bool:
    """Whether the short turn from ``heading`` to ``course`` [rad] sweeps the bow, once clear, into a
    collision cone of ``boat``'s returns again (across another obstacle). The blocked run the turn starts in
    (the cones that hold the heading and those that overlap them, in the turn's direction) is left first."""
    turn = wrap_angle(course - heading)
    direction = 1.0
    if turn < 0.0:
        direction = -1.0
    # The end of the blocked run from the heading: extended by every cone that starts within it.
    clear_from = float(0.0)
    for sweep in range(returns.shape[1]):
        reached = clear_from
        for sector in range(returns.shape[1]):
            cone = _cone(a, returns[boat, sector], sensor_x, sensor_y)
            if cone[2] > 0.0:
                span = _turn_span(cone, heading, direction)
                if span[0] <= clear_from and span[1] > clear_from:
                    clear_from = span[1]
        if clear_from == reached:
            break
    result = int(0)
    for sector in range(returns.shape[1]):
        cone = _cone(a, returns[boat, sector], sensor_x, sensor_y)
        if cone[2] > 0.0:
            span = _turn_span(cone, heading, direction)
            if span[0] > clear_from and span[0] < wp.abs(turn):
                result = 1
    return result != 0


@wp.kernel(enable_backward=False)
def steer_clear(
    p: AutopilotParameters,
    a: AvoidanceParameters,
    sectors: wp.array2d(dtype=float),
    first: int,
    azimuth: wp.array(dtype=float),
    targets: wp.array(dtype=wp.vec3),
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    wind_velocity: wp.array(dtype=wp.vec3),
    side: wp.array(dtype=wp.int32),
    returns: wp.array2d(dtype=wp.vec3),
    steering: wp.array(dtype=wp.vec3),
    deflection: wp.array(dtype=float),
):
    """One thread per boat: the steering target [m, world] that keeps the boat's course out of the collision
    cones of what its lidar sees (the law of ``SailingAutopilot``'s docstring).

    ``sectors`` (N, P): columns ``first`` .. ``first + S - 1`` hold the S sectors' nearest return over the
    lidar's max range (1: none), sector s centred on ``azimuth[s]`` [rad, counter-clockwise from the bow].
    ``returns`` (N, S): each sector's last return, world x, y [m] and its age [s] (z), updated here.
    ``side`` is read, not written (``sail_to_targets`` updates it). ``steering`` gets the target itself
    where the course to it is clear, else the point ``avoidance_lookahead`` from the boat on the clear
    bearing chosen; ``deflection`` the angle of the course steered for it off the course to the target
    [rad] (0: clear)."""
    boat = wp.tid()
    q = orientation[boat]
    heading = heading_of(q)
    c = wp.cos(heading)
    s = wp.sin(heading)
    origin = position[boat]
    # The sensor's place over the water (the boat taken level: roll and pitch move it by centimetres).
    sensor_x = origin[0] + c * a.mount[0] - s * a.mount[1]
    sensor_y = origin[1] + s * a.mount[0] + c * a.mount[1]
    for sector in range(returns.shape[1]):
        value = sectors[boat, first + sector]
        point = returns[boat, sector]
        if value < 1.0:
            reach = value * a.sector_range
            angle = heading + azimuth[sector]
            point = wp.vec3(sensor_x + reach * wp.cos(angle), sensor_y + reach * wp.sin(angle), 0.0)
        else:
            point = wp.vec3(point[0], point[1], point[2] + a.decision_period)
        returns[boat, sector] = point

    # The course the autopilot would steer to the target (as sail_to_targets chooses it).
    goal = targets[boat]
    offset = goal - origin
    bearing = wp.atan2(offset[1], offset[0])
    distance = wp.sqrt(offset[0] * offset[0] + offset[1] * offset[1])
    wind = wind_velocity[boat]
    wind_to = wp.atan2(wind[1], wind[0])
    current = side[boat]
    if current == 0:
        current = side_of(wrap_angle(heading - (wind_to + PI)))
    intended = course_to_target(p, bearing, distance, wind_to, current)[0]
    if not _blocked(a, returns, boat, sensor_x, sensor_y, intended):
        steering[boat] = goal
        deflection[boat] = 0.0
        return

    # Candidates: bearings on the edges of every cone and of the no-go and dead-run zones, clear of every
    # cone. Each is costed by the course the course logic steers for a target on it: off the intended
    # course, plus the turn from the heading (weighted), plus 10 where that course (the zone's edge, for a
    # bearing in a zone) heads into a cone, plus 20 where the bow would sweep across another obstacle on
    # the way. The cheapest wins; boxed in (no clear bearing), straight away from the nearest return.
    chosen = float(0.0)
    chosen_course = float(0.0)
    chosen_cost = float(1.0e9)
    away = heading + PI
    nearest = float(1.0e9)
    run_half_width = PI - p.run_angle
    for candidate in range(2 * returns.shape[1] + 4):
        course = float(0.0)
        valid = int(1)
        if candidate < 2 * returns.shape[1]:
            point = returns[boat, candidate // 2]
            cone = _cone(a, point, sensor_x, sensor_y)
            valid = int(cone[2])
            gap = wp.length(wp.vec2(point[0] - sensor_x, point[1] - sensor_y))
            if valid == 1 and gap < nearest:
                nearest = gap
                away = cone[0] + PI
            # Two edges per cone, each just outside it (the union's edges are among them).
            course = wrap_angle(cone[0] + float(1 - 2 * (candidate % 2)) * (cone[1] + 1.0e-4))
        else:
            zone = candidate - 2 * returns.shape[1]
            sign = float(1 - 2 * (zone % 2))
            if zone < 2:
                course = wrap_angle(wind_to + PI + sign * (p.no_go_angle + 1.0e-4))
            else:
                course = wrap_angle(wind_to + sign * (run_half_width + 1.0e-4))
        if valid == 1 and not _blocked(a, returns, boat, sensor_x, sensor_y, course):
            # What the course logic steers for a target on this bearing (close-hauled on the boat's side for
            # one in the no-go zone, a broad reach for one dead downwind), and what that costs.
            sailed = course_to_target(p, course, a.avoidance_lookahead, wind_to, current)[0]
            cost = wp.abs(wrap_angle(sailed - intended)) + a.avoidance_turn_cost * wp.abs(wrap_angle(sailed - heading))
            if sailed != course and _blocked(a, returns, boat, sensor_x, sensor_y, sailed):
                cost = cost + 10.0
            # (The sweep is looked for only where it could matter: it adds to the cost.)
            if cost < chosen_cost and _crosses(a, returns, boat, sensor_x, sensor_y, heading, sailed):
                cost = cost + 20.0
            if cost < chosen_cost:
                chosen = course
                chosen_course = sailed
                chosen_cost = cost
    if chosen_cost > 1.0e8:
        chosen = wrap_angle(away)
        chosen_course = course_to_target(p, chosen, a.avoidance_lookahead, wind_to, current)[0]
    steering[boat] = wp.vec3(origin[0] + a.avoidance_lookahead * wp.cos(chosen),
                             origin[1] + a.avoidance_lookahead * wp.sin(chosen), goal[2])
    deflection[boat] = wrap_angle(chosen_course - intended)


@wp.kernel(enable_backward=False)
def forget_returns(mask: wp.array(dtype=wp.int32), returns: wp.array2d(dtype=wp.vec3)):
    """One thread per (boat, sector): forget the remembered returns of boats whose ``mask`` != 0."""
    boat, sector = wp.tid()
    if mask[boat] != 0:
        returns[boat, sector] = wp.vec3(0.0, 0.0, NO_RETURN_AGE)
