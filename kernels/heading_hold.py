"""A heading-holding autopilot: the rudder command from the heading error and the yaw rate; and the
running sums that tell how well a course was kept."""

from __future__ import annotations

import warp as wp

from .spatial import heading_of, vec6, wrap_angle

__all__ = ["HeadingGains", "hold_heading", "accumulate_course_keeping"]


@wp.struct
class HeadingGains:
    proportional: float
    """[rad of rudder per rad of heading error]"""
    integral: float
    """[rad of rudder per rad s of accumulated error]"""
    damping: float
    """[rad of rudder per rad/s of yaw rate]"""
    rudder_limit: float
    """[rad]"""
    dt: float
    """Time between calls [s]."""


@wp.kernel(enable_backward=False)
def hold_heading(
    target_heading: wp.array(dtype=float),
    gains: HeadingGains,
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    integral: wp.array(dtype=float),
    rudder_command: wp.array(dtype=float),
):
    """A PID rudder: clamp(P e + I sum(e dt) - D yaw rate, +-limit) with e = wrap(target - heading) [rad];
    a positive rudder turns to port, towards a larger heading (yaw from +x, counter-clockwise). The
    integral stops growing while the rudder is at its limit (anti-windup)."""
    boat = wp.tid()
    error = wrap_angle(target_heading[boat] - heading_of(orientation[boat]))
    accumulated = integral[boat] + error * gains.dt
    command = gains.proportional * error + gains.integral * accumulated - gains.damping * velocity[boat][5]
    if wp.abs(command) < gains.rudder_limit:
        integral[boat] = accumulated
    rudder_command[boat] = wp.clamp(command, -gains.rudder_limit, gains.rudder_limit)


@wp.kernel(enable_backward=False)
def accumulate_course_keeping(
    target_heading: wp.array(dtype=float),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    sums: wp.array(dtype=wp.vec3),
):
    """Add each boat's (surge [m/s], heading error wrap(heading - target) [rad], roll [rad], > 0 heeled to
    starboard) to its running ``sums``: a window's means without reading the state back every step."""
    boat = wp.tid()
    q = orientation[boat]
    roll = wp.atan2(2.0 * (q[3] * q[0] + q[1] * q[2]), 1.0 - 2.0 * (q[0] * q[0] + q[1] * q[1]))
    error = wrap_angle(heading_of(q) - target_heading[boat])
    sums[boat] = sums[boat] + wp.vec3(velocity[boat][0], error, roll)
