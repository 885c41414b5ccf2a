"""Water forces on hull meshes, per triangle, per boat: one block per boat, in one kernel.

1. The block samples the ocean (``ocean_surface`` lookups) at every vertex of its boat's hull: the
   depth below the local surface [m] (positive when submerged) and the water velocity in the body
   frame [m/s], into a shared tile, so this per-vertex state never travels through device memory.
2. Each thread takes triangles in steps of the block size, clips each exactly at the waterline
   (depth is linear over a triangle) into 0, 1 or 2 submerged triangles, integrates pressure, drag
   and friction over them, and the block sums the threads' wrenches with ``wp.tile_sum`` (no
   atomics). All vectors are formed in the body frame.

A wrench is a ``vec6`` (Fx, Fy, Fz, Mx, My, Mz) in the body frame, moments about the body origin:
Fossen's tau. The model and its coefficients are documented in ``ocean_warp.HydrodynamicsConfig``.
"""

from __future__ import annotations

import functools
from typing import Any

import warp as wp

from .ocean_surface import (
    FIELD_PRESSURE_LOWER,
    FIELD_VELOCITY_BELOW,
    LocalInversion,
    OceanSurface,
    local_inversion,
    undisplaced_position_local,
    height_velocity_at_grid,
    periodic_bilinear,
    surface_height_velocity,
    undisplaced_position_near,
    pressure_head,
)
from .spatial import vec6, wrench, wrench_at
from .water_current import CurrentField, current_at, with_current, with_current_at_point

__all__ = [
    "HullMeshes",
    "WaterModel",
    "submerged_piece_wrench",
    "triangle_wrench",
    "slamming_wrench",
    "NO_SWEPT_RATE",
    "sample_vertex_water",
    "origin_water_velocity",
    "hull_wrenches_kernel",
    "sample_origin_water",
    "MAX_HULL_VERTICES",
    "residuary_wrench",
    "NO_WAVE_HISTORY",
    "wave_motion_update",
    "WAVE_POINTS",
    "water_motion_under_hull",
]

# Triangles (or clipped pieces) smaller than this [m^2] carry no force: their normal is undefined.
MIN_PIECE_AREA = wp.constant(1.0e-12)
# Relative speeds below this [m/s] carry no drag: the flow direction is undefined.
MIN_FLOW_SPEED = wp.constant(1.0e-6)
# The ITTC-1957 line is defined for Re well above 100; below 1e5 it is held at its 1e5 value.
MIN_REYNOLDS = wp.constant(1.0e5)


@wp.struct
class HullMeshes:
    """The hull meshes of a fleet, every hull type's arrays one after another."""

    vertices: wp.array(dtype=wp.vec3)
    """Vertex positions in the body frame [m]."""
    triangles: wp.array(dtype=wp.vec3i)
    """Vertex indices counted from the type's first vertex; counter-clockwise seen from outside."""
    vertex_start: wp.array(dtype=int)
    """Per hull type: index of its first vertex."""
    vertex_count: wp.array(dtype=int)
    triangle_start: wp.array(dtype=int)
    """Per hull type: index of its first triangle."""
    triangle_count: wp.array(dtype=int)
    reference_length: wp.array(dtype=float)
    """Per hull type: length for the Reynolds number [m]."""
    surface_area: wp.array(dtype=float)
    """Per hull type: total triangle area [m^2] (slamming shares the mass by area)."""
    mass: wp.array(dtype=float)
    """Per hull type: the boat's mass [kg] (slamming)."""
    residuary_length: wp.array(dtype=float)
    """Per hull type: Lwl [m] of its residuary resistance's Froude number; 0: the type has none."""
    residuary_volume: wp.array(dtype=float)
    """Per hull type: displaced volume at rest [m^3] that scales its residuary resistance."""
    residuary_center: wp.array(dtype=wp.vec3)
    """Per hull type: where the residuary resistance acts [m]."""
    residuary_upright: wp.array(dtype=float)
    """RESIDUARY_SAMPLES values per hull type: Rr / (volume rho g) at Fn = 0, RESIDUARY_STEP, ..."""
    residuary_heel: wp.array(dtype=float)
    """The same layout: its increase at 20 deg of heel (scaled by 6 phi^1.7)."""
    wave_points: wp.array(dtype=wp.vec2)
    """WAVE_POINTS per hull type: where the water's motion under the hull is sampled, body frame x, y [m] of a
    grid over the hull's plan (``ocean_warp.seakeeping.wave_points``)."""
    wave_point_weights: wp.array(dtype=vec6)
    """WAVE_POINTS x WAVE_POINT_INPUTS per hull type, point-major: the weights (one per DOF) of each point's u, v,
    w [m/s] at the ocean's middle depth and dynamic pressure head [m] at its deepest in the effective water
    velocity (see :func:`water_motion_under_hull`)."""
    seakeeping: wp.array(dtype=int)
    """Per hull type: 1 where it has a hydrodynamic database, whose radiation and diffraction need the water's
    motion under the hull (the wave points are sampled only then)."""


@wp.struct
class WaterModel:
    """``HydrodynamicsConfig`` as the kernels read it (0/1 for the switches)."""

    density: float
    """[kg/m^3]"""
    gravity: float
    """[m/s^2]"""
    kinematic_viscosity: float
    """[m^2/s]"""
    inverse_reference_speed: float
    """1 / v_r [s/m]."""
    pressure_drag_linear: float
    """[N/m^2]"""
    pressure_drag_quadratic: float
    """[N/m^2]"""
    pressure_drag_falloff: float
    """Exponent of cos t (dimensionless)."""
    suction_linear: float
    """[N/m^2]"""
    suction_quadratic: float
    """[N/m^2]"""
    suction_falloff: float
    """Exponent of |cos t| (dimensionless)."""
    skin_friction: int
    friction_factor: float
    """(1 + k): the form factor on the ITTC-1957 friction (dimensionless)."""
    cross_flow_only: int
    """1: pressure drag and suction see only the flow across the hull (its body-x part removed), forward
    resistance being friction and residuary resistance; 0: they see the whole flow (Kerner)."""
    slamming: int
    slamming_power: float
    """p of the slamming ramp (dimensionless)."""
    inverse_slamming_max_acceleration: float
    """1 / Gamma_max [s^2/m]."""
    substep: float
    """Time step [s] of the substep, for the slamming rate."""


@wp.func
def friction_coefficient(speed: float, length: float, water: WaterModel) -> float:
    """ITTC-1957 friction line C_F = 0.075 / (log10 Re - 2)^2 for a hull of ``length`` [m] moving at
    ``speed`` [m/s] through the water."""
    reynolds = wp.max(speed * length / water.kinematic_viscosity, MIN_REYNOLDS)
    denominator = wp.log(reynolds) / wp.log(10.0) - 2.0
    return 0.075 / (denominator * denominator)


@wp.func
def falloff(cosine: float, exponent: float) -> float:
    """cosine ** exponent for cosine >= 0, with the common exponents 0.5 and 1 without ``pow``."""
    if exponent == 0.5:
        return wp.sqrt(cosine)
    if exponent == 1.0:
        return cosine
    return wp.pow(cosine, exponent)


@wp.func
def submerged_piece_wrench(
    r0: wp.vec3, r1: wp.vec3, r2: wp.vec3,
    d0: float, d1: float, d2: float,
    u0: wp.vec3, u1: wp.vec3, u2: wp.vec3,
    velocity: wp.vec3, angular_velocity: wp.vec3,
    friction: float, water: WaterModel,
) -> vec6:
    """Wrench of the water on one fully submerged triangle (r0, r1, r2) [m] whose corners lie at depths
    d >= 0 [m] in water moving at u [m/s]; the boat's origin moves at ``velocity`` [m/s] and turns at
    ``angular_velocity`` [rad/s] (body frame). ``friction`` is C_F."""
    area_vector = 0.5 * wp.cross(r1 - r0, r2 - r0)
    area = wp.length(area_vector)
    if area < MIN_PIECE_AREA:
        return vec6()
    normal = area_vector / area
    rho_g = water.density * water.gravity
    p0 = rho_g * d0
    p1 = rho_g * d1
    p2 = rho_g * d2
    pressure_sum = p0 + p1 + p2
    # Pressure is linear over the piece: the force is the mean pressure times the area, and
    # int p r dA = A/12 (sum p_i r_i + sum p_i sum r_i) places it at the centre of pressure.
    force = -(pressure_sum / 3.0) * area_vector
    pressure_moment = (area / 12.0) * (p0 * r0 + p1 * r1 + p2 * r2 + pressure_sum * (r0 + r1 + r2))
    moment = wp.cross(normal, pressure_moment)

    centroid = (r0 + r1 + r2) / 3.0
    relative = velocity + wp.cross(angular_velocity, centroid) - (u0 + u1 + u2) / 3.0
    speed = wp.length(relative)
    if speed > MIN_FLOW_SPEED:
        drag = wp.vec3()
        flow = relative
        if water.cross_flow_only != 0:
            flow = wp.vec3(0.0, relative[1], relative[2])
        flow_speed = wp.length(flow)
        if flow_speed > MIN_FLOW_SPEED:
            cos_t = wp.dot(normal, flow) / flow_speed
            s = flow_speed * water.inverse_reference_speed
            if cos_t > 0.0:
                pressure = (water.pressure_drag_linear + water.pressure_drag_quadratic * s) * s
                drag = -(pressure * falloff(cos_t, water.pressure_drag_falloff) * area) * normal
            else:
                pressure = (water.suction_linear + water.suction_quadratic * s) * s
                drag = (pressure * falloff(-cos_t, water.suction_falloff) * area) * normal
        if water.skin_friction != 0:
            tangential = relative - wp.dot(relative, normal) * normal
            drag -= (0.5 * water.density * water.friction_factor * friction * area * wp.length(tangential)) * tangential
        force += drag
        moment += wp.cross(centroid, drag)
    return wrench(force, moment)


@wp.func
def _cut_fraction(wet_depth: float, dry_depth: float) -> float:
    """Fraction of the edge from a submerged corner (depth > 0) to a dry one (depth <= 0) at which the
    depth is zero; the denominator is > 0 by construction."""
    return wet_depth / (wet_depth - dry_depth)


@wp.func
def _pick(index: int, a: Any, b: Any, c: Any):
    """a, b or c for index 0, 1 or 2."""
    if index == 0:
        return a
    if index == 1:
        return b
    return c


@wp.func
def _odd_corner(s1: int, s2: int, submerged: int) -> int:
    """The corner alone on its side of the waterline, from the submerged flags of corners 1 and 2
    and the count of submerged corners: the wet one of one, the dry one of two (0 otherwise)."""
    if submerged == 1:
        return s1 + 2 * s2
    if submerged == 2:
        return (1 - s1) + 2 * (1 - s2)
    return 0


@wp.func
def triangle_wrench(
    r0: wp.vec3, r1: wp.vec3, r2: wp.vec3,
    w0: wp.vec4, w1: wp.vec4, w2: wp.vec4,
    velocity: wp.vec3, angular_velocity: wp.vec3, friction: float, water: WaterModel,
) -> vec6:
    """Wrench of the water on hull triangle (r0, r1, r2) [m, body frame], its corners' water state
    w = (depth [m], water velocity [m/s]): clipped at the waterline into 0, 1 or 2 submerged pieces.

    With a the odd corner (the only submerged one, or the only dry one) and (a, b, c) in winding
    order, the pieces are (a, ab, ac) for one corner submerged and (ba, b, c), (ba, c, ca) for two,
    where xy is the point of edge x-y at the waterline. The piece integral is written once and looped
    over, which keeps the kernel small (it spent half its time waiting for instructions otherwise)."""
    s0 = int(w0[0] > 0.0)
    s1 = int(w1[0] > 0.0)
    s2 = int(w2[0] > 0.0)
    submerged = s0 + s1 + s2
    if submerged == 0:
        return vec6()
    odd = _odd_corner(s1, s2, submerged)
    ra = _pick(odd, r0, r1, r2)
    rb = _pick((odd + 1) % 3, r0, r1, r2)
    rc = _pick((odd + 2) % 3, r0, r1, r2)
    wa = _pick(odd, w0, w1, w2)
    wb = _pick((odd + 1) % 3, w0, w1, w2)
    wc = _pick((odd + 2) % 3, w0, w1, w2)

    # First piece: the whole triangle, (a, ab, ac), or (ba, b, c); second piece (ba, c, ca) if any.
    p0 = ra
    p1 = rb
    p2 = rc
    q0 = wa
    q1 = wb
    q2 = wc
    second0 = wp.vec3()
    second2 = wp.vec3()
    second_q0 = wp.vec4()
    second_q2 = wp.vec4()
    pieces = 1
    if submerged == 1:
        tb = _cut_fraction(wa[0], wb[0])
        tc = _cut_fraction(wa[0], wc[0])
        p1 = ra + tb * (rb - ra)
        p2 = ra + tc * (rc - ra)
        q1 = wa + tb * (wb - wa)
        q2 = wa + tc * (wc - wa)
        q1[0] = 0.0
        q2[0] = 0.0
    elif submerged == 2:
        tb = _cut_fraction(wb[0], wa[0])
        tc = _cut_fraction(wc[0], wa[0])
        p0 = rb + tb * (ra - rb)
        q0 = wb + tb * (wa - wb)
        q0[0] = 0.0
        second0 = p0
        second_q0 = q0
        second2 = rc + tc * (ra - rc)
        second_q2 = wc + tc * (wa - wc)
        second_q2[0] = 0.0
        pieces = 2

    total = vec6()
    for piece in range(pieces):
        if piece == 1:
            p0 = second0
            p1 = rc
            p2 = second2
            q0 = second_q0
            q1 = wc
            q2 = second_q2
        total += submerged_piece_wrench(
            p0, p1, p2, q0[0], q1[0], q2[0], wp.vec3(q0[1], q0[2], q0[3]), wp.vec3(q1[1], q1[2], q1[3]),
            wp.vec3(q2[1], q2[2], q2[3]), velocity, angular_velocity, friction, water)
    return total


@wp.func
def _submerged_area(r0: wp.vec3, r1: wp.vec3, r2: wp.vec3, d0: float, d1: float, d2: float) -> float:
    """Area [m^2] of the part of a triangle below the waterline (depth linear over it)."""
    area = 0.5 * wp.length(wp.cross(r1 - r0, r2 - r0))
    s0 = int(d0 > 0.0)
    s1 = int(d1 > 0.0)
    s2 = int(d2 > 0.0)
    submerged = s0 + s1 + s2
    if submerged == 0 or submerged == 3:
        return area * float(submerged) / 3.0
    # Fraction of the area on the odd corner's side: t_b t_c, with t the edge fractions to the cuts.
    odd = _odd_corner(s1, s2, submerged)
    da = _pick(odd, d0, d1, d2)
    db = _pick((odd + 1) % 3, d0, d1, d2)
    dc = _pick((odd + 2) % 3, d0, d1, d2)
    corner_fraction = (da / (da - db)) * (da / (da - dc))
    if submerged == 1:
        return area * corner_fraction
    return area * (1.0 - corner_fraction)


RESIDUARY_STEP = wp.constant(0.05)
"""Froude-number spacing of the residuary tables (``ocean_warp.resistance.FROUDE_STEP``)."""
RESIDUARY_SAMPLES = wp.constant(16)
"""Entries per hull type (``ocean_warp.resistance.FROUDE_SAMPLES``)."""
MAX_RESIDUARY_FROUDE = wp.constant(1.0)
"""The tables' last slope is extended to this Froude number, and held there."""


@wp.func
def _residuary_at(table: wp.array(dtype=float), first: int, froude: float) -> float:
    """Linear interpolation of one hull type's table at ``froude``, its last slope extended beyond."""
    position = wp.min(froude, MAX_RESIDUARY_FROUDE) / RESIDUARY_STEP
    lower = wp.min(int(position), RESIDUARY_SAMPLES - 2)
    fraction = position - float(lower)
    return table[first + lower] + fraction * (table[first + lower + 1] - table[first + lower])


@wp.func
def residuary_wrench(meshes: HullMeshes, kind: int, surge: float, rotation: wp.quat, water: WaterModel) -> vec6:
    """Residuary (wave-making) resistance of hull type ``kind`` moving ahead or astern at ``surge`` [m/s]
    through the water, heeled as ``rotation`` says: volume rho g (r(Fn) + dr20(Fn) 6 phi^1.7) against the
    motion, at the type's centre (see ``ocean_warp.resistance``). Zero for a type without tables."""
    length = meshes.residuary_length[kind]
    if length <= 0.0:
        return vec6()
    froude = wp.abs(surge) / wp.sqrt(water.gravity * length)
    first = kind * RESIDUARY_SAMPLES
    up = wp.quat_rotate(rotation, wp.vec3(0.0, 0.0, 1.0))
    heel = wp.acos(wp.clamp(up[2], -1.0, 1.0))
    ratio = _residuary_at(meshes.residuary_upright, first, froude)
    if heel > 0.0:
        ratio += _residuary_at(meshes.residuary_heel, first, froude) * 6.0 * wp.pow(heel, 1.7)
    magnitude = meshes.residuary_volume[kind] * water.density * water.gravity * wp.max(ratio, 0.0)
    direction = wp.where(surge < 0.0, 1.0, -1.0)
    return wrench_at(wp.vec3(direction * magnitude, 0.0, 0.0), meshes.residuary_center[kind])


# Marks a triangle whose swept rate is not known yet (a fresh or reset boat): it cannot slam.
NO_SWEPT_RATE = wp.constant(-1.0)


@wp.func
def slamming_wrench(
    r0: wp.vec3, r1: wp.vec3, r2: wp.vec3,
    w0: wp.vec4, w1: wp.vec4, w2: wp.vec4,
    velocity: wp.vec3, angular_velocity: wp.vec3,
    mass: float, hull_area: float,
    swept_rate: wp.array(dtype=float), index: int, water: WaterModel,
) -> vec6:
    """Kerner's slamming on a triangle that enters the water fast, and the update of its swept rate.

    With A_sub the submerged area and v the relative velocity of the centroid, the swept rate is
    A_sub |v| [m^3/s]; its growth per area, Gamma = (rate - previous rate) / (A dt) [m/s^2], ramps a
    force that would stop the triangle's share of the mass (2 A_sub / S of it) within the substep:
    F = -clamp(Gamma / Gamma_max, 0, 1)^p cos(t) m v 2 A_sub / (S dt), on triangles facing the flow."""
    ua = wp.vec3(w0[1], w0[2], w0[3])
    ub = wp.vec3(w1[1], w1[2], w1[3])
    uc = wp.vec3(w2[1], w2[2], w2[3])
    area_vector = 0.5 * wp.cross(r1 - r0, r2 - r0)
    area = wp.length(area_vector)
    submerged = _submerged_area(r0, r1, r2, w0[0], w1[0], w2[0])
    centroid = (r0 + r1 + r2) / 3.0
    relative = velocity + wp.cross(angular_velocity, centroid) - (ua + ub + uc) / 3.0
    speed = wp.length(relative)
    rate = submerged * speed
    previous = swept_rate[index]
    swept_rate[index] = rate
    if previous == NO_SWEPT_RATE or area < MIN_PIECE_AREA or speed < MIN_FLOW_SPEED:
        return vec6()
    growth = (rate - previous) / (area * water.substep)
    cos_t = wp.dot(area_vector, relative) / (area * speed)
    if growth <= 0.0 or cos_t <= 0.0:
        return vec6()
    ramp = wp.pow(wp.min(growth * water.inverse_slamming_max_acceleration, 1.0), water.slamming_power)
    force = -(ramp * cos_t * mass * 2.0 * submerged / (hull_area * water.substep)) * relative
    return wrench_at(force, centroid)


@wp.func
def sample_vertex_water(surface: OceanSurface, local: wp.vec3, origin: wp.vec3, rotation: wp.quat,
                        near: LocalInversion) -> wp.vec4:
    """(pressure head p / (rho g) [m], positive where submerged, water velocity [m/s] in the body frame) at the
    hull point ``local`` (body frame) of a boat at ``origin`` turned by ``rotation``: hydrostatic plus the waves'
    Froude-Krylov head decaying with depth (:func:`pressure_head`). The velocity, which only the drag and
    friction see, is the surface's orbital velocity above the point (viscous forces of a hull's small orbital
    speeds are small; the decay with depth is left out to keep this pass cheap). ``near`` undoes the choppy
    displacement about the boat's origin (:func:`~ocean_surface.local_inversion`)."""
    offset = wp.quat_rotate(rotation, local)
    xy = wp.vec2(origin[0] + offset[0], origin[1] + offset[1])
    q = undisplaced_position_local(surface, xy, near)
    water = height_velocity_at_grid(surface, q)
    flow = wp.quat_rotate_inv(rotation, wp.vec3(water[1], water[2], water[3]))
    return wp.vec4(pressure_head(surface, q, origin[2] + offset[2], water[0]), flow[0], flow[1], flow[2])


NO_WAVE_HISTORY = wp.constant(3.0e38)
"""Marks a boat whose water motion of the last substep is not known (fresh or reset): no acceleration yet."""
WAVE_POINTS = wp.constant(33)
"""Points per hull type where the water's motion under the hull is sampled: 11 along by 3 across."""
WAVE_POINT_INPUTS = wp.constant(4)
"""What a wave point reads: u, v, w at the middle depth and the dynamic pressure head at the deepest."""
wave_moments = vec6
"""The effective water velocity V (body frame, about the origin [m/s, rad/s]): the weighted sum over the wave
points that the block reduces."""


@wp.func
def wave_point_moments(surface: OceanSurface, meshes: HullMeshes, kind: int, point: int, origin: wp.vec3,
                       rotation: wp.quat, origin_shift: wp.vec2, currents: CurrentField, boat: int) -> wave_moments:
    """One wave point's share of V: its weights times the water's velocity at the ocean's middle depth under it
    (orbital plus current, body frame [m/s]) and the dynamic pressure head at the deepest [m] (one lookup of the
    two fields holds both)."""
    r = meshes.wave_points[kind * WAVE_POINTS + point]
    offset = wp.quat_rotate(rotation, wp.vec3(r[0], r[1], 0.0))
    q = undisplaced_position_near(surface, wp.vec2(origin[0] + offset[0], origin[1] + offset[1]), origin_shift)
    depth = surface.pressure_depths[1]
    lower = periodic_bilinear(surface, FIELD_PRESSURE_LOWER, q)
    below = periodic_bilinear(surface, FIELD_VELOCITY_BELOW, q)
    orbital = wp.vec3(below[0], below[1], lower[1])
    v = wp.quat_rotate_inv(rotation, orbital + current_at(currents, boat, depth))
    first = (kind * WAVE_POINTS + point) * WAVE_POINT_INPUTS
    return (v[0] * meshes.wave_point_weights[first] + v[1] * meshes.wave_point_weights[first + 1]
            + v[2] * meshes.wave_point_weights[first + 2] + lower[0] * meshes.wave_point_weights[first + 3])


wrench_and_moments = wp.types.vector(length=12, dtype=wp.float32)
"""A wrench (6) and the effective water velocity (6), reduced over a block in one pass."""


@wp.func
def _wrench_and_moments(w: vec6, m: wave_moments) -> wrench_and_moments:
    return wrench_and_moments(w[0], w[1], w[2], w[3], w[4], w[5], m[0], m[1], m[2], m[3], m[4], m[5])


@wp.func
def _wrench_part(both: wrench_and_moments) -> vec6:
    return vec6(both[0], both[1], both[2], both[3], both[4], both[5])


@wp.func
def _moments_part(both: wrench_and_moments) -> wave_moments:
    return wave_moments(both[6], both[7], both[8], both[9], both[10], both[11])


@wp.func
def water_motion_under_hull(meshes: HullMeshes, kind: int, sums: wave_moments, rotation: wp.quat) -> vec6:
    """The effective water velocity V reduced over the wave points (body frame, about the origin) in the WORLD
    frame: linear [m/s] and angular [rad/s] parts rotated. Its weights are the type's database's, fitted so that
    A_inf dV/dt and the radiation memory of the relative velocity give the BEM's diffraction load
    (``ocean_warp.seakeeping.diffraction_fit``), or the least-squares rigid motion of the velocities."""
    linear = wp.quat_rotate(rotation, wp.vec3(sums[0], sums[1], sums[2]))
    angular = wp.quat_rotate(rotation, wp.vec3(sums[3], sums[4], sums[5]))
    return vec6(linear[0], linear[1], linear[2], angular[0], angular[1], angular[2])


@wp.func
def wave_motion_update(motion: vec6, substep: float, boat: int, wave_velocity: wp.array(dtype=vec6),
                       wave_acceleration: wp.array(dtype=vec6)):
    """Keep the water's effective velocity under the hull (world frame [m/s, rad/s]) and its rate of change along the
    boat's path since the last substep [m/s^2, rad/s^2] (0 without a last one)."""
    before = wave_velocity[boat]
    acceleration = vec6()
    if before[0] != NO_WAVE_HISTORY:
        acceleration = (motion - before) / substep
    wave_velocity[boat] = motion
    wave_acceleration[boat] = acceleration


@wp.func
def origin_water_velocity(surface: OceanSurface, origin: wp.vec3, rotation: wp.quat) -> wp.vec3:
    """Water velocity at the boat's origin, body frame [m/s]."""
    water = surface_height_velocity(surface, wp.vec2(origin[0], origin[1]))
    return wp.quat_rotate_inv(rotation, wp.vec3(water[1], water[2], water[3]))


@wp.kernel(enable_backward=False)
def sample_origin_water(
    surface: OceanSurface,
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    currents: CurrentField,
    boat_water_velocity: wp.array(dtype=wp.vec3),
):
    """Water velocity at each boat's origin, its current included, body frame [m/s] (one thread per boat)."""
    boat = wp.tid()
    origin = position[boat]
    rotation = orientation[boat]
    boat_water_velocity[boat] = with_current(origin_water_velocity(surface, origin, rotation), currents, boat,
                                             rotation, origin[2])


# The per-vertex water state of one hull lives in shared memory: 16 bytes a vertex, within the
# 227 KB of an H100 block and the 256 KB CPU arena, with room to spare.
MAX_HULL_VERTICES = 12288


@functools.cache
def hull_wrenches_kernel(vertex_rounds: int, block_dim: int, max_registers: int = 128, *, wave_points: bool = True,
                         currents: bool = True):
    """Kernel: the water's wrench on each boat, one block of ``block_dim`` threads per boat, launched
    with ``wp.launch_tiled`` over dim [boats]. ``vertex_rounds`` rounds of ``block_dim`` vertex slots
    must cover the largest hull (on the CPU a block has one thread: rounds = most vertices). ``currents``: the
    current of each boat (``water_current``; a field without rows: none), added to the water's velocity at every
    vertex and at the origin.

    A fleet without a hull type that has a hydrodynamic database builds it with ``wave_points=False``, one
    without a current with ``currents=False``: the code of what it does not need is left out of the kernel (its
    registers and its wider block reduction slowed the pass by 5 %: 342 against 325 us for 4 096 E-Boats on an H200).

    Compiled with fast math and at most ``max_registers`` registers a thread: on an H100 (4096 boats
    x 2112 triangles) that took the pass from 323 to 214 us with the same results to 1e-7."""
    slots = vertex_rounds * block_dim
    with_wave_points = wave_points
    with_currents = currents

    @wp.kernel(enable_backward=False, module="unique", module_options={"fast_math": True},
               cuda_max_registers=max_registers)
    def hull_wrenches(
        surface: OceanSurface,
        meshes: HullMeshes,
        water: WaterModel,
        hull_type: wp.array(dtype=int),
        triangle_offset: wp.array(dtype=int),
        position: wp.array(dtype=wp.vec3),
        orientation: wp.array(dtype=wp.quat),
        velocity: wp.array(dtype=vec6),
        swept_rate: wp.array(dtype=float),
        currents: CurrentField,
        boat_water_velocity: wp.array(dtype=wp.vec3),
        wave_velocity: wp.array(dtype=vec6),
        wave_acceleration: wp.array(dtype=vec6),
        wrench: wp.array(dtype=vec6),
    ):
        boat, lane = wp.tid()
        kind = hull_type[boat]
        origin = position[boat]
        rotation = orientation[boat]
        first_vertex = meshes.vertex_start[kind]
        vertex_count = meshes.vertex_count[kind]

        # Every thread undoes the choppy displacement at the boat's origin and finds its gradient there (the same
        # few lookups in each thread cost less than a broadcast): its vertices start from there.
        origin_xy = wp.vec2(origin[0], origin[1])
        near = local_inversion(surface, origin_xy)
        origin_grid = near.grid
        origin_shift = origin_xy - origin_grid
        origin_water = height_velocity_at_grid(surface, origin_grid)
        flow_at_origin = wp.quat_rotate_inv(rotation, wp.vec3(origin_water[1], origin_water[2], origin_water[3]))
        if wp.static(with_currents):
            flow_at_origin = with_current(flow_at_origin, currents, boat, rotation, origin[2])
        if lane == 0:
            boat_water_velocity[boat] = flow_at_origin
        moments = wave_moments()
        seakeeping = False
        if wp.static(with_wave_points):
            seakeeping = meshes.seakeeping[kind] != 0
            if seakeeping:
                for point in range(lane, WAVE_POINTS, wp.block_dim()):
                    moments += wave_point_moments(surface, meshes, kind, point, origin, rotation, origin_shift,
                                                  currents, boat)

        water_at = wp.tile_zeros(shape=(slots,), dtype=wp.vec4, storage="shared")
        for round_index in range(vertex_rounds):
            vertex = round_index * block_dim + lane
            state = wp.vec4()
            if vertex < vertex_count:
                state = sample_vertex_water(surface, meshes.vertices[first_vertex + vertex], origin, rotation, near)
                if wp.static(with_currents):
                    state = with_current_at_point(state, currents, boat, origin, rotation,
                                                  meshes.vertices[first_vertex + vertex])
            wp.tile_assign(water_at, wp.tile(state, preserve_type=True), offset=(round_index * block_dim,))
        # (tile_assign synchronises the block: every thread now sees every vertex's state)

        nu = velocity[boat]
        linear = wp.vec3(nu[0], nu[1], nu[2])
        angular = wp.vec3(nu[3], nu[4], nu[5])
        friction = friction_coefficient(wp.length(linear - flow_at_origin), meshes.reference_length[kind], water)
        first_triangle = meshes.triangle_start[kind]
        total = vec6()
        for t in range(lane, meshes.triangle_count[kind], wp.block_dim()):
            corners = meshes.triangles[first_triangle + t]
            r0 = meshes.vertices[first_vertex + corners[0]]
            r1 = meshes.vertices[first_vertex + corners[1]]
            r2 = meshes.vertices[first_vertex + corners[2]]
            w0 = water_at[corners[0]]
            w1 = water_at[corners[1]]
            w2 = water_at[corners[2]]
            total += triangle_wrench(r0, r1, r2, w0, w1, w2, linear, angular, friction, water)
            if water.slamming != 0:
                total += slamming_wrench(r0, r1, r2, w0, w1, w2, linear, angular, meshes.mass[kind],
                                         meshes.surface_area[kind], swept_rate, triangle_offset[boat] + t, water)
        surge = linear[0] - flow_at_origin[0]
        if wp.static(with_wave_points):
            # One block reduction for the wrench and the wave moments together.
            summed = wp.tile_sum(wp.tile(_wrench_and_moments(total, moments), preserve_type=True))[0]
            if lane == 0:
                wrench[boat] = _wrench_part(summed) + residuary_wrench(meshes, kind, surge, rotation, water)
                if seakeeping:
                    wave_motion_update(water_motion_under_hull(meshes, kind, _moments_part(summed), rotation),
                                       water.substep, boat, wave_velocity, wave_acceleration)
        else:
            summed_wrench = wp.tile_sum(wp.tile(total, preserve_type=True))[0]
            if lane == 0:
                wrench[boat] = summed_wrench + residuary_wrench(meshes, kind, surge, rotation, water)

    return hull_wrenches
