"""Water currents: a horizontal stream per environment, steady or tidal, uniform or sheared with depth.

Environment i's current is felt by boat i. At the surface it sets toward the direction theta [rad] (from +x,
east, counter-clockwise: where the water goes, as the wind's and the waves' directions) at

    U(t) = U_0 + A cos(omega t + phi)                                          [m/s]

with U_0 the steady speed and A the tidal amplitude (omega = 2 pi / T; where A exceeds U_0 the stream turns
and runs the other way, as a tidal stream does). Below the surface it falls off over a profile depth D:

    u(z) = U (1 + z / D)^p    for -D < z < 0,    0 for z <= -D,    U for z >= 0

where z is a point's height above still water [m]: p = 1/7 the power law of a tidal stream's boundary layer,
p = 1 a linear shear; D = 0 gives the same current at every depth. The current is horizontal.

The force kernels read a :class:`CurrentField` (the surface current of every boat and its profile). A field
without rows (a simulator without a current) is still water: every function here then hands its input back
unchanged, bit for bit, as it does where a boat's current is zero.
"""

from __future__ import annotations

import warp as wp

__all__ = ["TideModel", "CurrentState", "CurrentField", "profile_factor", "surface_current", "current_at",
           "with_current", "with_current_at_point", "with_current_shift", "update_current", "reset_current"]


@wp.struct
class TideModel:
    """The tidal part of every environment's current (a ``CurrentConfig`` as the kernels read it)."""

    amplitude: float
    """A [m/s]; 0: a steady current."""
    angular_frequency: wp.float64
    """omega = 2 pi / T [rad/s]."""
    phase: wp.float64
    """phi [rad]."""


@wp.struct
class CurrentState:
    """The current over N environments: each one's steady speed, direction and profile depth, and the surface
    current they give at the last evaluation."""

    speed: wp.array(dtype=float)
    """U_0 per environment [m/s] (>= 0)."""
    direction: wp.array(dtype=float)
    """theta per environment: where the current sets toward, from +x counter-clockwise [rad]."""
    profile_depth: wp.array(dtype=float)
    """D per environment [m]; 0: the same current at every depth."""
    velocity: wp.array(dtype=wp.vec3)
    """The surface current now, world frame [m/s]."""


@wp.struct
class CurrentField:
    """What the force kernels read of the current, N rows (boat i in environment i); arrays without rows: none."""

    velocity: wp.array(dtype=wp.vec3)
    """Surface current, world frame [m/s] (``CurrentState.velocity``)."""
    profile_depth: wp.array(dtype=float)
    """D [m] (``CurrentState.profile_depth``)."""
    profile_exponent: float
    """p of the depth profile (dimensionless)."""


@wp.func
def profile_factor(depth: float, exponent: float, height: float) -> float:
    """u(z) / U at ``height`` z [m] above still water for a profile ``depth`` D [m] and ``exponent`` p."""
    if depth <= 0.0 or height >= 0.0:
        return 1.0
    if height <= -depth:
        return 0.0
    return wp.pow(1.0 + height / depth, exponent)


@wp.func
def surface_current(tide: TideModel, speed: float, direction: float, time: wp.float64) -> wp.vec3:
    """The surface current [m/s, world] at ``time`` [s] of a steady ``speed`` [m/s] toward ``direction`` [rad]."""
    tidal = tide.amplitude * float(wp.cos(tide.angular_frequency * time + tide.phase))
    magnitude = speed + tidal
    return wp.vec3(magnitude * wp.cos(direction), magnitude * wp.sin(direction), 0.0)


@wp.func
def current_at(field: CurrentField, boat: int, height: float) -> wp.vec3:
    """Boat ``boat``'s current at ``height`` [m] above still water, world frame [m/s] (zero without a current)."""
    if field.velocity.shape[0] == 0:
        return wp.vec3()
    return profile_factor(field.profile_depth[boat], field.profile_exponent, height) * field.velocity[boat]


@wp.func
def _flows(field: CurrentField, boat: int) -> int:
    """1 where boat ``boat`` has a current that is not zero, else 0."""
    if field.velocity.shape[0] == 0:
        return 0
    surface = field.velocity[boat]
    if surface[0] == 0.0 and surface[1] == 0.0 and surface[2] == 0.0:
        return 0
    return 1


@wp.func
def with_current(flow: wp.vec3, field: CurrentField, boat: int, rotation: wp.quat, height: float) -> wp.vec3:
    """``flow`` [m/s, body frame of a boat turned by ``rotation``] plus boat ``boat``'s current at ``height`` [m]
    above still water; ``flow`` itself where there is no current."""
    if _flows(field, boat) == 0:
        return flow
    return flow + wp.quat_rotate_inv(rotation, current_at(field, boat, height))


@wp.func
def with_current_at_point(water: wp.vec4, field: CurrentField, boat: int, origin: wp.vec3, rotation: wp.quat,
                          local: wp.vec3) -> wp.vec4:
    """``water`` (depth [m], water velocity [m/s, body frame]) at the hull point ``local`` [m, body frame] of a boat
    at ``origin`` [m] turned by ``rotation``, with the current there added to its velocity."""
    if _flows(field, boat) == 0:
        return water
    height = origin[2] + wp.quat_rotate(rotation, local)[2]
    flow = with_current(wp.vec3(water[1], water[2], water[3]), field, boat, rotation, height)
    return wp.vec4(water[0], flow[0], flow[1], flow[2])


@wp.func
def with_current_shift(flow: wp.vec3, field: CurrentField, boat: int, rotation: wp.quat, from_height: float,
                       to_height: float) -> wp.vec3:
    """``flow`` [m/s, body frame], which holds the current at ``from_height``, moved to hold the one at
    ``to_height`` instead [m above still water] (a foil below the boat's origin); ``flow`` itself where the
    current is the same at both heights or there is none."""
    if _flows(field, boat) == 0 or field.profile_depth[boat] <= 0.0:
        return flow
    exponent = field.profile_exponent
    depth = field.profile_depth[boat]
    change = profile_factor(depth, exponent, to_height) - profile_factor(depth, exponent, from_height)
    if change == 0.0:
        return flow
    return flow + wp.quat_rotate_inv(rotation, change * field.velocity[boat])


@wp.kernel(enable_backward=False)
def update_current(
    mask: wp.array(dtype=wp.int32),
    tide: TideModel,
    clock: wp.array(dtype=wp.float64),
    current: CurrentState,
):
    """The surface current of every environment whose ``mask`` is non-zero at the time ``clock[0]`` [s]."""
    env = wp.tid()
    if mask[env] == 0:
        return
    current.velocity[env] = surface_current(tide, current.speed[env], current.direction[env], clock[0])


@wp.kernel(enable_backward=False)
def reset_current(
    mask: wp.array(dtype=wp.int32),
    new_speed: wp.array(dtype=float),
    new_direction: wp.array(dtype=float),
    new_profile_depth: wp.array(dtype=float),
    tide: TideModel,
    clock: wp.array(dtype=wp.float64),
    current: CurrentState,
):
    """Every environment whose ``mask`` is non-zero gets its row of the new steady speed [m/s], direction [rad]
    and profile depth [m] (may be ``current.profile_depth`` itself, to keep it), and its surface current at
    ``clock[0]`` [s]."""
    env = wp.tid()
    if mask[env] == 0:
        return
    current.speed[env] = new_speed[env]
    current.direction[env] = new_direction[env]
    current.profile_depth[env] = new_profile_depth[env]
    current.velocity[env] = surface_current(tide, new_speed[env], new_direction[env], clock[0])
