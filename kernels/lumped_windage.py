"""Wind on a hull as three lumped coefficients (VRX's ``usv_gazebo_wind_plugin`` law, after Sarda et al. 2016),
one thread per boat.

In the boat's yawed body frame, with w = (w_x, w_y) the wind relative to the boat: X = c_x w_x |w_x|,
Y = c_y w_y |w_y| [N] and N = -2 c_z w_x w_y [N m]. VRX rotates the true wind into the body frame and leaves
the boat's own velocity out of w (it computes the apparent wind and does not use it); here w is the apparent
wind, the true wind less the boat's velocity over the ground, which is what the air presses with.
"""

from __future__ import annotations

import warp as wp

from .spatial import vec6

__all__ = ["lumped_windage"]


@wp.kernel(enable_backward=False)
def lumped_windage(
    coefficients: wp.vec3,
    wind_velocity: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    model_wrench: wp.array(dtype=vec6),
):
    """``coefficients`` (c_x, c_y [N s^2/m^2], c_z [N m s^2/m^2]); ``wind_velocity`` world [m/s]; ``velocity``
    Fossen's nu; the wind's wrench added to ``model_wrench`` (body frame, about the origin). A non-finite wind or
    pose adds nothing (the integrator flags the boat)."""
    boat = wp.tid()
    nu = velocity[boat]
    wind = wp.quat_rotate_inv(orientation[boat], wind_velocity[boat])
    wx = wind[0] - nu[0]
    wy = wind[1] - nu[1]
    fx = coefficients[0] * wx * wp.abs(wx)
    fy = coefficients[1] * wy * wp.abs(wy)
    mz = -2.0 * coefficients[2] * wx * wy
    if not (wp.isfinite(fx) and wp.isfinite(fy) and wp.isfinite(mz)):
        return
    model_wrench[boat] = model_wrench[boat] + vec6(fx, fy, 0.0, 0.0, 0.0, mz)
