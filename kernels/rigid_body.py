"""6-DOF rigid bodies in water: Fossen's equations of motion, semi-implicit Euler, status flags.

State per boat: position of the body origin (world, ENU) [m], orientation body -> world (Warp quaternion,
x y z w), and Fossen's nu = (u, v, w, p, q, r): the body-frame velocity of the origin [m/s] and the
angular velocity [rad/s]. With the water velocity nu_c (the ocean's orbital velocity at the boat, body
frame) and nu_r = nu - nu_c:

    (M_RB + M_A) dnu/dt = tau - c(nu) - mu + A_inf a_w,   c(nu) = c_RB(nu) + C_A(nu_r) nu_r + D_l nu_r + D_q |nu_r| nu_r

about the body origin, where c_RB holds the gyroscopic and centre-of-mass coupling terms of the
Newton-Euler equations, C_A(nu_r) nu_r = (w x a1, v_r x a1 + w x a2) with (a1, a2) = M_A nu_r is the
added-mass Coriolis (Munk) term, and tau is the hydrodynamic wrench plus gravity and the external
wrenches. For a hull type with a hydrodynamic database M_A is its infinite-frequency added mass A_inf, mu
the radiation memory of Cummins' equation and A_inf a_w the diffraction load of the water's acceleration
a_w (``kernels.radiation``), all applied in the heading frame, which follows the heading but not the heel and
trim: M_A = T^T A_inf T and C_A that frame's added-mass terms (``kernels.seakeeping_frame``); without one, mu
and a_w are absent and M_A is the type's constant added mass, fixed in the body frame. Semi-implicit Euler:
the velocity first, then the pose with the new velocity; the orientation turns by the exponential map and is renormalised. The velocity terms c(nu) are taken
linearly implicit at the midpoint, (M + h/2 dc/dnu) dnu = h (tau - c(nu)): an explicit gyroscopic
term pumps energy into a tumbling body (+1.3 % in 5 s in the Kirchhoff test), a fully implicit one
drains it (-1.2 %), the midpoint keeps it and stays stable under any damping.
"""

from __future__ import annotations

import warp as wp

from .hull_forces import NO_WAVE_HISTORY
from .radiation import RadiationModel, diffraction_wrench, radiation_force
from .seakeeping_frame import from_heading_frame, heading_frame_added_mass, heading_tilt, to_heading_frame
from .spatial import block3, mat66, skew, vec6, wrench

__all__ = [
    "mat66",
    "BodyParameters",
    "SafetyBounds",
    "STATUS_NONFINITE",
    "STATUS_CAPSIZED",
    "STATUS_FLYING",
    "STATUS_SUNK",
    "STATUS_BAD_INPUT",
    "STATUS_COLLIDED",
    "rigid_body_coriolis",
    "added_mass_coriolis",
    "damping_force",
    "velocity_terms",
    "velocity_terms_jacobian",
    "rigid_body_mass_matrix",
    "solve6",
    "integrate_boats",
    "place_boat",
    "reset_boats_masked",
    "reset_swept_rates_masked",
    "advance_time",
]


STATUS_NONFINITE = wp.constant(1)
"""The state turned NaN or infinite; the boat is frozen at its last finite state until reset."""
STATUS_CAPSIZED = wp.constant(2)
"""The body's z axis tilted further from the vertical than ``SafetyBounds`` allow."""
STATUS_FLYING = wp.constant(4)
"""The body origin rose above ``max_altitude``."""
STATUS_SUNK = wp.constant(8)
"""The body origin sank below ``-max_depth``."""
STATUS_BAD_INPUT = wp.constant(16)
"""A force model was handed a NaN or infinite input (a command, the wind); set with STATUS_NONFINITE,
so the boat is frozen at its last finite state until reset."""
STATUS_COLLIDED = wp.constant(32)
"""The boat touched an object or another boat of its environment (``ocean_warp.contact``); not frozen."""


@wp.struct
class BodyParameters:
    """Per hull type: mass properties and Fossen coefficients, about the body origin."""

    mass: wp.array(dtype=float)
    """[kg]"""
    center_of_mass: wp.array(dtype=wp.vec3)
    """r_g, body frame [m]."""
    inertia_origin: wp.array(dtype=wp.mat33)
    """Rigid-body inertia about the body origin [kg m^2]."""
    added_mass: wp.array(dtype=mat66)
    """M_A [kg, kg m, kg m^2]."""
    mass_matrix: wp.array(dtype=mat66)
    """M_RB + M_A about the body origin."""
    linear_damping: wp.array(dtype=vec6)
    """Diagonal of D_l [N s/m, N m s/rad]."""
    quadratic_damping: wp.array(dtype=vec6)
    """Diagonal of D_q [N s^2/m^2, N m s^2/rad^2]."""
    astern_surge_factor: wp.array(dtype=float)
    """Surge damping multiplier while moving astern relative to the water."""


@wp.struct
class SafetyBounds:
    max_altitude: float
    """[m] of the body origin above still water."""
    max_depth: float
    """[m] of the body origin below still water."""
    min_uprightness: float
    """Smallest allowed world-z component of the body's z axis (cosine of the largest tilt)."""


@wp.func
def rigid_body_coriolis(nu: vec6, mass: float, center_of_mass: wp.vec3, inertia_origin: wp.mat33) -> vec6:
    """Newton-Euler velocity terms about the body origin with the centre of mass at r_g:
    (m (w x v + w x (w x r_g)), w x (I_o w) + m r_g x (w x v))."""
    v = wp.vec3(nu[0], nu[1], nu[2])
    w = wp.vec3(nu[3], nu[4], nu[5])
    w_cross_v = wp.cross(w, v)
    force = mass * (w_cross_v + wp.cross(w, wp.cross(w, center_of_mass)))
    moment = wp.cross(w, inertia_origin * w) + mass * wp.cross(center_of_mass, w_cross_v)
    return wrench(force, moment)


@wp.func
def added_mass_coriolis(nu_r: vec6, added_mass: mat66) -> vec6:
    """Fossen's C_A(nu_r) nu_r = (w x a1, v_r x a1 + w x a2), (a1, a2) = M_A nu_r."""
    a = added_mass * nu_r
    a1 = wp.vec3(a[0], a[1], a[2])
    a2 = wp.vec3(a[3], a[4], a[5])
    v = wp.vec3(nu_r[0], nu_r[1], nu_r[2])
    w = wp.vec3(nu_r[3], nu_r[4], nu_r[5])
    force = wp.cross(w, a1)
    moment = wp.cross(v, a1) + wp.cross(w, a2)
    return wrench(force, moment)


@wp.func
def damping_force(nu_r: vec6, linear_damping: vec6, quadratic_damping: vec6) -> vec6:
    """D_l nu_r + D_q |nu_r| nu_r (diagonal damping on the velocity relative to the water)."""
    magnitude = vec6(wp.abs(nu_r[0]), wp.abs(nu_r[1]), wp.abs(nu_r[2]), wp.abs(nu_r[3]), wp.abs(nu_r[4]),
                     wp.abs(nu_r[5]))
    return wp.cw_mul(linear_damping, nu_r) + wp.cw_mul(quadratic_damping, wp.cw_mul(magnitude, nu_r))


@wp.func
def velocity_terms(
    nu: vec6, nu_r: vec6, mass: float, r_g: wp.vec3, inertia_origin: wp.mat33, added_mass: mat66,
    linear_damping: vec6, quadratic_damping: vec6,
) -> vec6:
    """c(nu) = c_RB(nu) + C_A(nu_r) nu_r + D_l nu_r + D_q |nu_r| nu_r: everything on the left of
    M dnu/dt + c(nu) = tau but the acceleration."""
    return (rigid_body_coriolis(nu, mass, r_g, inertia_origin) + added_mass_coriolis(nu_r, added_mass)
            + damping_force(nu_r, linear_damping, quadratic_damping))


@wp.func
def velocity_terms_jacobian(
    nu: vec6, nu_r: vec6, mass: float, r_g: wp.vec3, inertia_origin: wp.mat33, added_mass: mat66,
    linear_damping: vec6, quadratic_damping: vec6,
) -> mat66:
    """d c / d nu of c(nu) = c_RB(nu) + C_A(nu_r) nu_r + D_l nu_r + D_q |nu_r| nu_r (analytic)."""
    v = wp.vec3(nu[0], nu[1], nu[2])
    w = wp.vec3(nu[3], nu[4], nu[5])
    v_r = wp.vec3(nu_r[0], nu_r[1], nu_r[2])
    s_w = skew(w)
    s_v = skew(v)
    s_r = skew(r_g)
    eye = wp.identity(n=3, dtype=float)
    # rigid body: d/dv, d/dw of m (w x v + w x (w x r)) and w x I w + m r x (w x v)
    f_v = mass * s_w
    f_w = mass * (-s_v + wp.dot(w, r_g) * eye + wp.outer(w, r_g) - 2.0 * wp.outer(r_g, w))
    m_v = mass * (s_r * s_w)
    m_w = s_w * inertia_origin - skew(inertia_origin * w) - mass * (s_r * s_v)
    # added mass: (w x a1, v_r x a1 + w x a2), a = M_A nu_r
    a = added_mass * nu_r
    a1 = wp.vec3(a[0], a[1], a[2])
    a2 = wp.vec3(a[3], a[4], a[5])
    a11 = block3(added_mass, 0, 0)
    a12 = block3(added_mass, 0, 3)
    a21 = block3(added_mass, 3, 0)
    a22 = block3(added_mass, 3, 3)
    s_vr = skew(v_r)
    f_v += s_w * a11
    f_w += -skew(a1) + s_w * a12
    m_v += -skew(a1) + s_vr * a11 + s_w * a21
    m_w += s_vr * a12 - skew(a2) + s_w * a22
    jacobian = mat66()
    for i in range(3):
        for j in range(3):
            jacobian[i, j] = f_v[i, j]
            jacobian[i, j + 3] = f_w[i, j]
            jacobian[i + 3, j] = m_v[i, j]
            jacobian[i + 3, j + 3] = m_w[i, j]
    for i in range(6):
        jacobian[i, i] = jacobian[i, i] + linear_damping[i] + 2.0 * quadratic_damping[i] * wp.abs(nu_r[i])
    return jacobian


@wp.func
def rigid_body_mass_matrix(mass: float, r_g: wp.vec3, inertia_origin: wp.mat33) -> mat66:
    """Fossen's M_RB about the body origin: [[m I, -m S(r_g)], [m S(r_g), I_o]]."""
    s_r = mass * skew(r_g)
    out = mat66()
    for i in range(3):
        out[i, i] = mass
        for j in range(3):
            out[i, j + 3] = -s_r[i, j]
            out[i + 3, j] = s_r[i, j]
            out[i + 3, j + 3] = inertia_origin[i, j]
    return out


@wp.func
def solve6(matrix: mat66, rhs: vec6) -> vec6:
    """x with matrix x = rhs, by Gaussian elimination without pivoting: the matrices solved here are
    M + h dc/dnu, close to the positive definite mass matrix for any sensible step."""
    a = matrix
    b = rhs
    for k in range(6):
        for i in range(k + 1, 6):
            factor = a[i, k] / a[k, k]
            for j in range(k, 6):
                a[i, j] = a[i, j] - factor * a[k, j]
            b[i] = b[i] - factor * b[k]
    x = vec6()
    for step in range(6):
        i = 5 - step
        total = b[i]
        for j in range(i + 1, 6):
            total = total - a[i, j] * x[j]
        x[i] = total / a[i, i]
    return x


@wp.func
def _rotate_wrench_to_body(rotation: wp.quat, world: vec6) -> vec6:
    force = wp.quat_rotate_inv(rotation, wp.vec3(world[0], world[1], world[2]))
    moment = wp.quat_rotate_inv(rotation, wp.vec3(world[3], world[4], world[5]))
    return wrench(force, moment)


@wp.func
def _turned(rotation: wp.quat, angular_velocity: wp.vec3, dt: float) -> wp.quat:
    """The orientation after turning at the body-frame ``angular_velocity`` [rad/s] for ``dt`` [s]."""
    rate = wp.length(angular_velocity)
    step = wp.quat_identity()
    if rate * dt > 1.0e-12:
        step = wp.quat_from_axis_angle(angular_velocity / rate, rate * dt)
    return wp.normalize(rotation * step)


@wp.kernel(enable_backward=False)
def integrate_boats(
    body: BodyParameters,
    hull_type: wp.array(dtype=int),
    gravity: float,
    dt: float,
    bounds: SafetyBounds,
    hydro_wrench: wp.array(dtype=vec6),
    model_wrench: wp.array(dtype=vec6),
    wrench_world: wp.array(dtype=vec6),
    wrench_body: wp.array(dtype=vec6),
    water_velocity: wp.array(dtype=wp.vec3),
    radiation: RadiationModel,
    wave_acceleration: wp.array(dtype=vec6),
    radiation_output: wp.array(dtype=float),
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    status: wp.array(dtype=int),
):
    """One substep of ``dt`` [s] per boat (velocity terms linearly implicit at the midpoint, then the pose). ``hydro_wrench`` and ``model_wrench``
    (foils, propellers, point buoyancy) are body-frame wrenches about the origin. External wrenches:
    forces act at the centre of mass, moments are couples; ``wrench_world`` in the world frame,
    ``wrench_body`` in the body frame. A boat flagged non-finite is not integrated."""
    boat = wp.tid()
    flags = status[boat]
    if (flags & STATUS_NONFINITE) != 0:
        return
    kind = hull_type[boat]
    rotation = orientation[boat]
    nu = velocity[boat]
    mass = body.mass[kind]
    r_g = body.center_of_mass[kind]

    external = _rotate_wrench_to_body(rotation, wrench_world[boat]) + wrench_body[boat]
    force = wp.vec3(external[0], external[1], external[2]) + wp.quat_rotate_inv(rotation, wp.vec3(0.0, 0.0, -mass * gravity))
    moment = wp.vec3(external[3], external[4], external[5]) + wp.cross(r_g, force)
    tau = hydro_wrench[boat] + model_wrench[boat] + wrench(force, moment)
    current = water_velocity[boat]
    nu_r = nu - vec6(current[0], current[1], current[2], 0.0, 0.0, 0.0)
    inertia_origin = body.inertia_origin[kind]
    added_mass = body.added_mass[kind]
    mass_matrix = body.mass_matrix[kind]
    heading_terms = vec6()
    heading_jacobian = mat66()
    if radiation.has_database[kind] != 0:
        # The database's A_inf, memory and diffraction act in the heading frame (kernels.seakeeping_frame).
        tilt = heading_tilt(rotation)
        water_acceleration = to_heading_frame(tilt, _rotate_wrench_to_body(rotation, wave_acceleration[boat]))
        tau = tau + from_heading_frame(tilt, diffraction_wrench(radiation, kind, water_acceleration)
                                       - radiation_force(radiation, kind, boat, radiation_output))
        heading = heading_frame_added_mass(tilt, nu_r, radiation.added_mass_infinite[kind])
        added_mass = mat66()
        mass_matrix = rigid_body_mass_matrix(mass, r_g, inertia_origin) + heading.mass
        heading_terms = heading.terms
        heading_jacobian = heading.jacobian

    linear_damping = body.linear_damping[kind]
    quadratic_damping = body.quadratic_damping[kind]
    if nu_r[0] < 0.0:
        astern = body.astern_surge_factor[kind]
        linear_damping[0] = astern * linear_damping[0]
        quadratic_damping[0] = astern * quadratic_damping[0]
    terms = (velocity_terms(nu, nu_r, mass, r_g, inertia_origin, added_mass, linear_damping, quadratic_damping)
             + heading_terms)
    jacobian = (velocity_terms_jacobian(nu, nu_r, mass, r_g, inertia_origin, added_mass, linear_damping,
                                        quadratic_damping) + heading_jacobian)
    new_nu = nu + solve6(mass_matrix + (0.5 * dt) * jacobian, dt * (tau - terms))

    linear = wp.vec3(new_nu[0], new_nu[1], new_nu[2])
    angular = wp.vec3(new_nu[3], new_nu[4], new_nu[5])
    new_position = position[boat] + dt * wp.quat_rotate(rotation, linear)
    new_rotation = _turned(rotation, angular, dt)

    finite = wp.isfinite(new_nu) and wp.isfinite(new_position) and wp.isfinite(new_rotation)
    if not finite:
        velocity[boat] = vec6()
        status[boat] = flags | STATUS_NONFINITE
        return
    velocity[boat] = new_nu
    position[boat] = new_position
    orientation[boat] = new_rotation
    if wp.quat_rotate(new_rotation, wp.vec3(0.0, 0.0, 1.0))[2] < bounds.min_uprightness:
        flags = flags | STATUS_CAPSIZED
    if new_position[2] > bounds.max_altitude:
        flags = flags | STATUS_FLYING
    if new_position[2] < -bounds.max_depth:
        flags = flags | STATUS_SUNK
    status[boat] = flags


@wp.func
def place_boat(
    boat: int,
    new_position: wp.vec3,
    new_orientation: wp.quat,
    new_velocity: vec6,
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    status: wp.array(dtype=int),
    wrench_world: wp.array(dtype=vec6),
    wrench_body: wp.array(dtype=vec6),
    water_velocity: wp.array(dtype=wp.vec3),
    wave_velocity: wp.array(dtype=vec6),
):
    """Put ``boat`` at the new state; clear its flags, its external wrenches and the water velocity seen
    at its old place, and forget the wave velocity of its last substep (the next substep samples the new
    place; the water's acceleration starts from there)."""
    position[boat] = new_position
    orientation[boat] = wp.normalize(new_orientation)
    velocity[boat] = new_velocity
    status[boat] = 0
    wrench_world[boat] = vec6()
    wrench_body[boat] = vec6()
    water_velocity[boat] = wp.vec3()
    wave_velocity[boat] = vec6(NO_WAVE_HISTORY, 0.0, 0.0, 0.0, 0.0, 0.0)


@wp.kernel(enable_backward=False)
def reset_boats_masked(
    mask: wp.array(dtype=wp.int32),
    new_position: wp.array(dtype=wp.vec3),
    new_orientation: wp.array(dtype=wp.quat),
    new_velocity: wp.array(dtype=vec6),
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    status: wp.array(dtype=int),
    wrench_world: wp.array(dtype=vec6),
    wrench_body: wp.array(dtype=vec6),
    water_velocity: wp.array(dtype=wp.vec3),
    wave_velocity: wp.array(dtype=vec6),
):
    """Every boat whose ``mask`` is non-zero to its row of the new state (launch dim: all boats); the
    others are left alone. No index list, so a captured graph can reset whichever boats ended."""
    boat = wp.tid()
    if mask[boat] == 0:
        return
    place_boat(boat, new_position[boat], new_orientation[boat], new_velocity[boat], position, orientation, velocity,
               status, wrench_world, wrench_body, water_velocity, wave_velocity)


@wp.func
def forget_swept_rate(boat: int, triangle: int, hull_type: wp.array(dtype=int), triangle_count: wp.array(dtype=int),
                      triangle_offset: wp.array(dtype=int), no_history: float, swept_rate: wp.array(dtype=float)):
    if triangle < triangle_count[hull_type[boat]]:
        swept_rate[triangle_offset[boat] + triangle] = no_history


@wp.kernel(enable_backward=False)
def reset_swept_rates_masked(
    mask: wp.array(dtype=wp.int32),
    hull_type: wp.array(dtype=int),
    triangle_count: wp.array(dtype=int),
    triangle_offset: wp.array(dtype=int),
    no_history: float,
    swept_rate: wp.array(dtype=float),
):
    """Forget the slamming history of every boat whose ``mask`` is non-zero (launch dim (all boats, most
    triangles))."""
    boat, triangle = wp.tid()
    if mask[boat] != 0:
        forget_swept_rate(boat, triangle, hull_type, triangle_count, triangle_offset, no_history, swept_rate)


@wp.kernel(enable_backward=False)
def advance_time(time: wp.array(dtype=wp.float64), dt: wp.float64):
    """time[0] += dt [s], on the device so a captured graph advances it."""
    time[0] = time[0] + dt
