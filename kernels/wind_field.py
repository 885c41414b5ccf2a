"""Wind over each environment: a mean, gusts as Ornstein-Uhlenbeck processes, a height profile.

Per environment the wind has a speed U [m/s] and a direction theta [rad] (the direction the air moves,
from +x counter-clockwise, as the waves'). Each relaxes to its mean with time scale tau and standard
deviation sigma, updated exactly over a step dt:

    U <- U_mean + (U - U_mean) e^(-dt/tau_U) + sigma_U sqrt(1 - e^(-2 dt/tau_U)) xi,   xi ~ N(0, 1)

and likewise theta. A speed the noise would drive below zero is held at zero (the air does not blow
backwards), which lifts the mean a little when sigma_U is comparable to U_mean. The speed is the one at
the reference height; at height z the wind is U (z / z_ref)^p (p = 0: the same at every height).
Environment i's wind is read by boat i.
"""

from __future__ import annotations

import warp as wp

from .random_streams import WIND_GUSTS, stream_state

__all__ = ["GustModel", "update_wind", "wind_at_height", "wind_vector", "reset_wind"]

MIN_PROFILE_HEIGHT = wp.constant(0.1)
"""Heights below this [m] use the wind there (the power law vanishes at the surface)."""


@wp.struct
class GustModel:
    speed_decay: float
    """e^(-dt / tau_U) over one substep."""
    speed_noise: float
    """sigma_U sqrt(1 - e^(-2 dt / tau_U)) [m/s]."""
    direction_decay: float
    """e^(-dt / tau_theta) over one substep."""
    direction_noise: float
    """sigma_theta sqrt(1 - e^(-2 dt / tau_theta)) [rad]."""
    profile_exponent: float
    """p of the height profile (dimensionless; 0: none)."""
    reference_height: float
    """[m]"""
    seed: int
    """Seed of the gusts' random stream."""
    first_index: int
    """Number of this batch's first environment in the random stream: environment i draws as environment
    ``first_index + i`` of one larger batch would (a shard of it draws the same gusts)."""


@wp.func
def wind_at_height(wind: wp.vec3, height: float, gusts: GustModel) -> wp.vec3:
    """The wind velocity [m/s, world] at ``height`` [m] above still water, from its reference-height value."""
    if gusts.profile_exponent == 0.0:
        return wind
    ratio = wp.max(height, MIN_PROFILE_HEIGHT) / gusts.reference_height
    return wind * wp.pow(ratio, gusts.profile_exponent)


@wp.func
def wind_vector(speed: float, direction: float) -> wp.vec3:
    """The horizontal wind [m/s, world] of ``speed`` [m/s] blowing towards ``direction`` [rad]."""
    return wp.vec3(speed * wp.cos(direction), speed * wp.sin(direction), 0.0)

@wp.struct
class WindState:
    """The wind over N environments: what moves (the gusts) and each environment's mean."""

    mean_speed: wp.array(dtype=float)
    """Mean speed per environment [m/s]."""
    mean_direction: wp.array(dtype=float)
    """Mean direction per environment, where the wind blows towards, from +x [rad]."""
    gust_scale: wp.array(dtype=float)
    """Factor on the config's gust standard deviations per environment (1: as configured)."""
    speed: wp.array(dtype=float)
    """Current speed with gusts [m/s]."""
    direction: wp.array(dtype=float)
    """Current direction with gusts [rad]."""
    velocity: wp.array(dtype=wp.vec3)
    """Wind vector at the reference height, world frame [m/s]."""



@wp.kernel(enable_backward=False)
def update_wind(
    gusts: GustModel,
    counter: wp.array(dtype=int),
    wind: WindState,
):
    """One substep of the gust processes per environment, their standard deviations scaled by the
    environment's ``gust_scale`` (1: the config's); ``velocity`` gets the wind vector at the
    reference height [m/s, world]. ``counter`` (1,) numbers the substeps for the random stream; the
    caller advances it. A NaN mean stays NaN (``wp.max`` would hide it), for the rig to report."""
    env = wp.tid()
    state = stream_state(gusts.seed, WIND_GUSTS, counter[0], gusts.first_index + env)
    scale = wind.gust_scale[env]
    new_speed = wind.mean_speed[env] + (wind.speed[env] - wind.mean_speed[env]) * gusts.speed_decay
    new_speed += scale * gusts.speed_noise * wp.randn(state)
    if new_speed < 0.0:
        new_speed = 0.0
    new_direction = wind.mean_direction[env] + (wind.direction[env] - wind.mean_direction[env]) * gusts.direction_decay
    new_direction += scale * gusts.direction_noise * wp.randn(state)
    wind.speed[env] = new_speed
    wind.direction[env] = new_direction
    wind.velocity[env] = wind_vector(new_speed, new_direction)


@wp.kernel(enable_backward=False)
def reset_wind(
    mask: wp.array(dtype=wp.int32),
    new_mean_speed: wp.array(dtype=float),
    new_mean_direction: wp.array(dtype=float),
    new_gust_scale: wp.array(dtype=float),
    wind: WindState,
):
    """Every environment whose ``mask`` is non-zero gets its row of the new mean wind [m/s, rad] and
    gust scale, and its gusts restart from that mean."""
    env = wp.tid()
    if mask[env] == 0:
        return
    wind.mean_speed[env] = new_mean_speed[env]
    wind.mean_direction[env] = new_mean_direction[env]
    wind.gust_scale[env] = new_gust_scale[env]
    wind.speed[env] = new_mean_speed[env]
    wind.direction[env] = new_mean_direction[env]
    wind.velocity[env] = wind_vector(new_mean_speed[env], new_mean_direction[env])
