"""Two stern thrusters per boat (the WAM-V's): command -> thrust by VRX's mapping, azimuth, out-of-water cut.

A thrust command c in [-1, 1] gives, like VRX's thrust plugin with its generalised-logistic mapping
(``ocean_warp.wamv.figures.GLF_FORWARD``), T = A + (K - A) / (C + exp(-B (c - M)))^(1 / nu) [N], the forward
curve's figures for c > 0.01 (T at most ``max_forward``) and the reverse curve's for c < -0.01 (T at least
-``max_reverse``); |c| <= 0.01 gives none (VRX's reverse curve leaves 0.04 N at c = 0, which would creep a
stopped boat ahead).

Thruster k swings about its engine's vertical pivot by -angle (seen from above, clockwise for a positive angle), so
that a positive angle turns the boat to port as a rudder does; VRX's engine joint angle is its negative. The
propeller sits at ``propeller_offset`` from the pivot in the engine's frame, and the thrust acts there along the
engine's x axis. A propeller above the ocean's surface gives no thrust. A NaN or infinite command flags the boat
(BAD_INPUT and NONFINITE) instead of being clamped into a real value.
"""

from __future__ import annotations

import warp as wp

from .ocean_surface import OceanSurface, surface_height
from .rigid_body import STATUS_BAD_INPUT, STATUS_NONFINITE
from .spatial import vec6, wrench_at

__all__ = ["ThrusterParameters", "glf_thrust", "thrusters", "reset_thrusters", "thruster_actions"]

DEAD_BAND = wp.constant(0.01)
"""|command| at or below which a thruster gives no thrust."""


@wp.struct
class ThrusterParameters:
    pivot_left: wp.vec3
    """The left engine's pivot, body frame [m]."""
    pivot_right: wp.vec3
    """The right engine's pivot, body frame [m]."""
    propeller_offset: wp.vec3
    """The propeller from its pivot, engine frame [m]."""
    max_forward: float
    """Largest thrust ahead [N]."""
    max_reverse: float
    """Largest thrust astern, a magnitude [N]."""
    angle_limit: float
    """Largest angle either side [rad]; 0: fixed thrusters."""


@wp.func
def _logistic(c: float, a: float, k: float, b: float, nu: float, shift: float, m: float) -> float:
    return a + (k - a) / wp.pow(shift + wp.exp(-b * (c - m)), 1.0 / nu)


@wp.func
def glf_thrust(command: float, max_forward: float, max_reverse: float) -> float:
    """Thrust [N] of a finite ``command`` (clamped to [-1, 1]) by VRX's forward and reverse logistic curves."""
    c = wp.clamp(command, -1.0, 1.0)
    if c > DEAD_BAND:
        return wp.min(_logistic(c, 0.01, 59.82, 5.0, 0.38, 0.56, 0.28), max_forward)
    if c < -DEAD_BAND:
        return wp.max(_logistic(c, -199.13, -0.09, 8.84, 5.34, 0.99, -0.57), -max_reverse)
    return 0.0


@wp.kernel(enable_backward=False)
def thrusters(
    parameters: ThrusterParameters,
    surface: OceanSurface,
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    thrust_command: wp.array2d(dtype=float),
    angle_command: wp.array2d(dtype=float),
    thrust: wp.array2d(dtype=float),
    thruster_angle: wp.array2d(dtype=float),
    model_wrench: wp.array(dtype=vec6),
    status: wp.array(dtype=int),
):
    """Both thrusters of each boat: angles clamped to the limit, thrust from the commands where the propeller is
    under the surface, their wrench added to ``model_wrench`` (body frame, about the origin)."""
    boat = wp.tid()
    for k in range(2):
        if not (wp.isfinite(thrust_command[boat, k]) and wp.isfinite(angle_command[boat, k])):
            status[boat] = status[boat] | STATUS_BAD_INPUT | STATUS_NONFINITE
            return
    total = model_wrench[boat]
    rotation = orientation[boat]
    origin = position[boat]
    offset = parameters.propeller_offset
    for k in range(2):
        pivot = parameters.pivot_left
        if k == 1:
            pivot = parameters.pivot_right
        angle = wp.clamp(angle_command[boat, k], -parameters.angle_limit, parameters.angle_limit)
        c = wp.cos(angle)
        s = wp.sin(angle)
        propeller = pivot + wp.vec3(c * offset[0] + s * offset[1], -s * offset[0] + c * offset[1], offset[2])
        world = origin + wp.quat_rotate(rotation, propeller)
        force = float(0.0)
        if world[2] < surface_height(surface, wp.vec2(world[0], world[1])):
            force = glf_thrust(thrust_command[boat, k], parameters.max_forward, parameters.max_reverse)
        thrust[boat, k] = force
        thruster_angle[boat, k] = angle
        total += wrench_at(wp.vec3(force * c, -force * s, 0.0), propeller)
    model_wrench[boat] = total


@wp.kernel(enable_backward=False)
def reset_thrusters(
    mask: wp.array(dtype=wp.int32),
    thrust_command: wp.array2d(dtype=float),
    angle_command: wp.array2d(dtype=float),
    thrust: wp.array2d(dtype=float),
    thruster_angle: wp.array2d(dtype=float),
):
    """Every boat whose ``mask`` is non-zero: commands, thrust and angles to zero."""
    boat = wp.tid()
    if mask[boat] == 0:
        return
    for k in range(2):
        thrust_command[boat, k] = 0.0
        angle_command[boat, k] = 0.0
        thrust[boat, k] = 0.0
        thruster_angle[boat, k] = 0.0


@wp.func
def _action(value: float) -> float:
    """An action clamped to [-1, 1]; NaN and infinities pass, for the thrusters to flag."""
    if wp.isfinite(value):
        return wp.clamp(value, -1.0, 1.0)
    return value


@wp.kernel(enable_backward=False)
def thruster_actions(
    actions: wp.array2d(dtype=float),
    enabled: wp.array(dtype=wp.int32),
    angle_limit: float,
    thrust_command: wp.array2d(dtype=float),
    angle_command: wp.array2d(dtype=float),
):
    """Columns 0 and 1 of each boat's actions (left, right) are its thrust commands, and with azimuth thrusters
    (``angle_limit`` > 0) columns 2 and 3 times ``angle_limit`` [rad] its angles; a column whose ``enabled`` entry
    is 0 commands 0 (no thrust, thruster centred)."""
    boat = wp.tid()
    for k in range(2):
        thrust = float(0.0)
        if enabled[k] != 0:
            thrust = _action(actions[boat, k])
        thrust_command[boat, k] = thrust
        if angle_limit > 0.0:
            angle = float(0.0)
            if enabled[2 + k] != 0:
                angle = _action(actions[boat, 2 + k]) * angle_limit
            angle_command[boat, k] = angle
