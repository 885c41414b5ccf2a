"""Wind over each environment: a mean, gusts as Ornstein-Uhlenbeck processes, a height profile.

Per environment the wind has a speed U [m/s] and a direction theta [rad] (the direction the air moves,
from +x counter-clockwise, as the waves'). Each relaxes to its mean with time scale tau and standard
deviation sigma, updated exactly over a step dt:

    U <- U_mean + (U - U_mean) e^(-dt/tau_U) + sigma_U sqrt(1 - e^(-2 dt/tau_U)) xi,   xi ~ N(0, 1)

and likewise theta. The speed is the one at the reference height; at height z the wind is
U (z / z_ref)^p (p = 0: the same at every height).
"""

from __future__ import annotations

import warp as wp

__all__ = ["GustModel", "update_wind", "advance_wind_counter", "wind_at_height", "reset_wind"]

MIN_PROFILE_HEIGHT = wp.constant(0.1)
"""Heights below this [m] use the wind there (the power law vanishes at the surface)."""


@wp.struct
class GustModel:
    speed_decay: float
    """e^(-dt / tau_U) over one substep."""
    speed_noise: float
    """sigma_U sqrt(1 - e^(-2 dt / tau_U)) [m/s]."""
    direction_decay: float
    direction_noise: float
    """[rad]"""
    profile_exponent: float
    reference_height: float
    """[m]"""
    seed: int


@wp.func
def wind_at_height(wind: wp.vec3, height: float, gusts: GustModel) -> wp.vec3:
    """The wind velocity [m/s, world] at ``height`` [m] above still water, from its reference-height value."""
    if gusts.profile_exponent == 0.0:
        return wind
    ratio = wp.max(height, MIN_PROFILE_HEIGHT) / gusts.reference_height
    return wind * wp.pow(ratio, gusts.profile_exponent)


@wp.kernel(enable_backward=False)
def update_wind(
    gusts: GustModel,
    counter: wp.array(dtype=int),
    mean_speed: wp.array(dtype=float),
    mean_direction: wp.array(dtype=float),
    speed: wp.array(dtype=float),
    direction: wp.array(dtype=float),
    velocity: wp.array(dtype=wp.vec3),
):
    """One substep of the gust processes per environment; ``velocity`` gets the wind vector at the
    reference height [m/s, world]. ``counter`` (1,) numbers the substeps for the random streams and is
    advanced by ``advance_wind_counter``."""
    env = wp.tid()
    state = wp.rand_init(gusts.seed, (counter[0] * speed.shape[0] + env) * 2)
    new_speed = mean_speed[env] + (speed[env] - mean_speed[env]) * gusts.speed_decay + gusts.speed_noise * wp.randn(state)
    new_speed = wp.max(new_speed, 0.0)
    new_direction = mean_direction[env] + (direction[env] - mean_direction[env]) * gusts.direction_decay
    new_direction += gusts.direction_noise * wp.randn(state)
    speed[env] = new_speed
    direction[env] = new_direction
    velocity[env] = wp.vec3(new_speed * wp.cos(new_direction), new_speed * wp.sin(new_direction), 0.0)


@wp.kernel(enable_backward=False)
def advance_wind_counter(counter: wp.array(dtype=int)):
    counter[0] = counter[0] + 1


@wp.kernel(enable_backward=False)
def reset_wind(
    envs: wp.array(dtype=int),
    new_mean_speed: wp.array(dtype=float),
    new_mean_direction: wp.array(dtype=float),
    mean_speed: wp.array(dtype=float),
    mean_direction: wp.array(dtype=float),
    speed: wp.array(dtype=float),
    direction: wp.array(dtype=float),
    velocity: wp.array(dtype=wp.vec3),
):
    """Set the chosen environments' mean wind and start their gusts from it."""
    i = wp.tid()
    env = envs[i]
    mean_speed[env] = new_mean_speed[i]
    mean_direction[env] = new_mean_direction[i]
    speed[env] = new_mean_speed[i]
    direction[env] = new_mean_direction[i]
    velocity[env] = wp.vec3(new_mean_speed[i] * wp.cos(new_mean_direction[i]),
                            new_mean_speed[i] * wp.sin(new_mean_direction[i]), 0.0)
