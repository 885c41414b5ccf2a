"""Small spatial helpers shared by the kernels: 6-vectors, wrenches, point velocities, headings.

A wrench is a ``vec6`` (Fx, Fy, Fz, Mx, My, Mz) [N, N m]; a body velocity is a ``vec6`` (u, v, w, p,
q, r) [m/s, rad/s] (Fossen's nu). Both are in the body frame (FLU: x bow, y port, z up), about the
body origin, unless a name says otherwise.
"""

from __future__ import annotations

import math

import warp as wp

__all__ = ["vec6", "mat66", "PI", "DEGREES", "wrench", "wrench_at", "point_velocity", "heading_of", "wrap_angle",
           "skew", "block3"]

vec6 = wp.types.vector(length=6, dtype=wp.float32)
mat66 = wp.types.matrix(shape=(6, 6), dtype=wp.float32)

PI = wp.constant(math.pi)
DEGREES = wp.constant(180.0 / math.pi)
"""Degrees per radian."""


@wp.func
def wrench(force: wp.vec3, moment: wp.vec3) -> vec6:
    """Force [N] and moment [N m] packed into one wrench."""
    return vec6(force[0], force[1], force[2], moment[0], moment[1], moment[2])


@wp.func
def wrench_at(force: wp.vec3, point: wp.vec3) -> vec6:
    """The wrench about the origin of ``force`` [N] acting at ``point`` [m]."""
    return wrench(force, wp.cross(point, force))


@wp.func
def point_velocity(nu: vec6, point: wp.vec3) -> wp.vec3:
    """Velocity [m/s] of the body point at ``point`` [m] for the body velocity ``nu``: v + w x r."""
    return wp.vec3(nu[0], nu[1], nu[2]) + wp.cross(wp.vec3(nu[3], nu[4], nu[5]), point)


@wp.func
def heading_of(q: wp.quat) -> float:
    """Yaw [rad] of a body -> world quaternion (Z-Y-X angles; from +x counter-clockwise)."""
    return wp.atan2(2.0 * (q[3] * q[2] + q[0] * q[1]), 1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]))


@wp.func
def wrap_angle(angle: float) -> float:
    """``angle`` [rad] wrapped into [-pi, pi)."""
    return angle - 2.0 * PI * wp.floor((angle + PI) / (2.0 * PI))


@wp.func
def skew(a: wp.vec3) -> wp.mat33:
    """S(a), with S(a) b = a x b."""
    return wp.mat33(0.0, -a[2], a[1], a[2], 0.0, -a[0], -a[1], a[0], 0.0)


@wp.func
def block3(m: mat66, row: int, col: int) -> wp.mat33:
    """The 3x3 block of a 6x6 matrix starting at (row, col)."""
    out = wp.mat33()
    for i in range(3):
        for j in range(3):
            out[i, j] = m[row + i, col + j]
    return out
