"""The seakeeping frame: where a hull's hydrodynamic database applies when the hull heels, trims and drifts.

A database (``ocean_warp.seakeeping``) holds the infinite-frequency added mass A_inf and the radiation kernels
of the hull at rest and upright, about the body origin: small motions about that equilibrium. Fossen's unified
seakeeping-manoeuvring model (Fossen 2005, "A nonlinear unified state-space model for ship maneuvering and
control in a seaway"; Perez & Fossen 2007, "Kinematic models for manoeuvring and seakeeping of marine
vessels") keeps these quantities in a seakeeping frame that follows the hull's mean heading and speed but not
its roll and pitch. Here that frame is the heading frame: its origin at the body origin, its z axis the
world's vertical, its x axis the horizontal projection of the bow (the body frame turned back by the Z-Y-X
pitch and roll): T = diag(R_t, R_t), R_t = R_z(psi)^T R, maps body-frame 6-vectors into it. A heeled hull
then keeps its large heave added mass along the vertical, where the waterplane and the free surface put it,
instead of carrying it round with the heel into the direction it drifts.

The water's impulse in the heading frame is p = A_inf nu_h, nu_h = T nu_r. Its rate in the inertial frame,
written in the heading frame (which turns at psi_dot about the vertical), gives the added-mass load about the
moving origin (Kirchhoff's form: Lamb, Hydrodynamics, sec. 124; Fossen 2011, sec. 6.4):

    -(T^T A_inf T) dnu/dt - c_A,   c_A = T^T [A_inf (w_t x v_h, w_t x w_h) + (w_f x p1, w_f x p2 + v_h x p1)]

with (p1, p2) = A_inf nu_h, w_f = (0, 0, psi_dot) the frame's rate and w_t = w_h - w_f the roll and pitch rate
relative to it: d(T nu)/dt = T dnu/dt + (w_t x v_h, w_t x w_h). Body-fixed added mass (Kirchhoff's equations,
``kernels.rigid_body.added_mass_coriolis``) is the case T = I, w_t = 0. Linearised about a hull sailing upright
at speed U, c_A holds U A_inf (0, r, -q, 0, 0, 0) in heave and pitch, the speed terms of Fossen's unified
model (strip theory's B35 = U A33); a hull rolling while it drifts at a steady velocity feels no added-mass
load, and a hull heeled 90 deg that drifts sideways meets the upright sway added mass, not the heave's.
"""

from __future__ import annotations

import warp as wp

from .spatial import block3, heading_of, mat66, skew, vec6, wrench

__all__ = ["MIN_HEADING_COSINE", "heading_tilt", "to_heading_frame", "from_heading_frame",
           "heading_frame_added_mass", "HeadingAddedMass"]

MIN_HEADING_COSINE = wp.constant(0.1)
"""The smallest horizontal share of the bow axis (cosine of the pitch) that the heading rate divides by: a hull
pitched beyond 84 deg has no meaningful heading; the clamp keeps its rate finite."""


@wp.func
def heading_tilt(rotation: wp.quat) -> wp.mat33:
    """R_t = R_z(psi)^T R: body frame -> heading frame (the orientation's Z-Y-X pitch and roll only)."""
    psi = heading_of(rotation)
    c = wp.cos(psi)
    s = wp.sin(psi)
    unturn = wp.mat33(c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0)
    return unturn * wp.quat_to_matrix(rotation)


@wp.func
def to_heading_frame(tilt: wp.mat33, body: vec6) -> vec6:
    """T x: a body-frame 6-vector (velocity or wrench) in the heading frame."""
    return wrench(tilt * wp.vec3(body[0], body[1], body[2]), tilt * wp.vec3(body[3], body[4], body[5]))


@wp.func
def from_heading_frame(tilt: wp.mat33, heading: vec6) -> vec6:
    """T^T x: a heading-frame 6-vector in the body frame."""
    back = wp.transpose(tilt)
    return wrench(back * wp.vec3(heading[0], heading[1], heading[2]),
                  back * wp.vec3(heading[3], heading[4], heading[5]))


@wp.func
def _congruent(tilt: wp.mat33, lin_lin: wp.mat33, lin_ang: wp.mat33, ang_lin: wp.mat33, ang_ang: wp.mat33) -> mat66:
    """T^T [[lin_lin, lin_ang], [ang_lin, ang_ang]] T."""
    back = wp.transpose(tilt)
    b00 = back * lin_lin * tilt
    b01 = back * lin_ang * tilt
    b10 = back * ang_lin * tilt
    b11 = back * ang_ang * tilt
    out = mat66()
    for i in range(3):
        for j in range(3):
            out[i, j] = b00[i, j]
            out[i, j + 3] = b01[i, j]
            out[i + 3, j] = b10[i, j]
            out[i + 3, j + 3] = b11[i, j]
    return out


@wp.struct
class HeadingAddedMass:
    """The added-mass terms of a hull with a database, body frame, about the origin."""

    mass: mat66
    """T^T A_inf T [kg, kg m, kg m^2]: the added mass the acceleration meets."""
    terms: vec6
    """c_A [N, N m]: the velocity terms (on the left of the equations of motion, as C_A(nu_r) nu_r is)."""
    jacobian: mat66
    """d c_A / d nu at the current attitude."""


@wp.func
def heading_frame_added_mass(tilt: wp.mat33, nu_r: vec6, added_mass: mat66) -> HeadingAddedMass:
    """A_inf applied in the heading frame (module docstring): the body-frame added mass, velocity terms and
    their Jacobian for the relative velocity ``nu_r`` (body frame [m/s, rad/s]) at the attitude ``tilt``
    (:func:`heading_tilt`)."""
    v = tilt * wp.vec3(nu_r[0], nu_r[1], nu_r[2])
    w = tilt * wp.vec3(nu_r[3], nu_r[4], nu_r[5])
    # psi_dot = g . w_h with g = (tan(theta), 0, 1); the bow axis in the heading frame is (cos, 0, -sin theta)
    bow = wp.vec3(tilt[0, 0], tilt[1, 0], tilt[2, 0])
    g = wp.vec3(-bow[2] / wp.max(bow[0], MIN_HEADING_COSINE), 0.0, 1.0)
    up = wp.vec3(0.0, 0.0, 1.0)
    frame_rate = wp.dot(g, w) * up
    tilt_rate = w - frame_rate
    nu_h = wrench(v, w)
    a = added_mass * nu_h
    a1 = wp.vec3(a[0], a[1], a[2])
    a2 = wp.vec3(a[3], a[4], a[5])
    turned = added_mass * wrench(wp.cross(tilt_rate, v), wp.cross(tilt_rate, w))
    terms_h = turned + wrench(wp.cross(frame_rate, a1), wp.cross(frame_rate, a2) + wp.cross(v, a1))

    # Jacobian in the heading frame: tilt_rate = P w, frame_rate = Z w with Z = up g^T, P = I - Z
    z_g = wp.outer(up, g)
    p = wp.identity(n=3, dtype=float) - z_g
    s_t = skew(tilt_rate)
    s_f = skew(frame_rate)
    s_v = skew(v)
    s_w = skew(w)
    a11 = block3(added_mass, 0, 0)
    a12 = block3(added_mass, 0, 3)
    a21 = block3(added_mass, 3, 0)
    a22 = block3(added_mass, 3, 3)
    # d(w_t x v)/dv = S(w_t), d/dw = -S(v) P; d(w_t x w)/dw = S(w_t) - S(w) P
    d_lin_w = -(s_v * p)
    d_ang_w = s_t - s_w * p
    f_v = a11 * s_t + s_f * a11
    f_w = a11 * d_lin_w + a12 * d_ang_w + s_f * a12 - skew(a1) * z_g
    m_v = a21 * s_t + s_f * a21 + s_v * a11 - skew(a1)
    m_w = a21 * d_lin_w + a22 * d_ang_w + s_f * a22 - skew(a2) * z_g + s_v * a12

    out = HeadingAddedMass()
    out.mass = _congruent(tilt, a11, a12, a21, a22)
    out.terms = from_heading_frame(tilt, terms_h)
    out.jacobian = _congruent(tilt, f_v, f_w, m_v, m_w)
    return out
