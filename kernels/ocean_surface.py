"""Device-side lookup of the ocean surface: height, normal and water velocity above world points.

The fields live on a periodic grid (``OceanSurface.fields``, shape (4, n, n), index [field, iy, ix],
node (ix, iy) at world (ix, iy) * cell size) in the pairs of ``ocean_spectrum``. A grid node q moves
to q + choppiness * D(q), so the surface above a world point p is the one of the node q with
q + choppiness * D(q) = p, found by fixed-point iteration q <- p - choppiness * D(q); the iteration
contracts while the surface does not fold over (choppiness * |grad D| < 1).
"""

from __future__ import annotations

import warp as wp

from .ocean_spectrum import (
    FIELD_DISPLACEMENT,
    FIELD_HEIGHT,
    FIELD_PRESSURE_LOWER,
    FIELD_PRESSURE_UPPER,
    FIELD_SLOPE,
    FIELD_VELOCITY,
    FIELD_VELOCITY_BELOW,
)

__all__ = [
    "OceanSurface",
    "periodic_bilinear",
    "undisplaced_position",
    "undisplaced_position_near",
    "LocalInversion",
    "local_inversion",
    "undisplaced_position_local",
    "contracted_inversion",
    "inverted_displacement",
    "height_velocity_at_grid",
    "pressure_head",
    "velocity_at_depth",
    "surface_height",
    "surface_height_velocity",
    "surface_normal",
    "sample_surface_kernel",
]


@wp.struct
class OceanSurface:
    """What a kernel needs to read the ocean: the fields and the grid's geometry."""

    fields: wp.array3d(dtype=wp.vec2f)
    """(4, n, n) field pairs, index [field, iy, ix]."""
    inv_cell_size: float
    """1 / grid spacing [1/m]."""
    index_mask: int
    """Grid points per side (a power of two) less one: ``i & index_mask`` wraps any grid index, negative
    ones too (two's complement)."""
    choppiness: float
    """Scale of the horizontal displacement."""
    inversion_iterations: int
    """Most fixed-point iterations of :func:`inverted_displacement` (0 when choppiness is 0)."""
    inversion_tolerance_sq: float
    """Square of the step [m^2] below which :func:`inverted_displacement` stops."""
    pressure_depths: wp.vec3
    """Heights z1 > z2 > z3 [m] (negative: below still water) of the pressure-head fields 4 and 5; the
    velocity field 6 and the vertical velocity of field 5 are at z2."""


@wp.func
def periodic_bilinear(surface: OceanSurface, field: int, xy: wp.vec2) -> wp.vec2f:
    """Field pair ``field`` at world point ``xy`` [m], bilinear between the four surrounding nodes.
    Valid within 2^31 grid cells of the origin."""
    mask = surface.index_mask
    gx = xy[0] * surface.inv_cell_size
    gy = xy[1] * surface.inv_cell_size
    fx_floor = wp.floor(gx)
    fy_floor = wp.floor(gy)
    tx = gx - fx_floor
    ty = gy - fy_floor
    # The grid is a power of two: a mask wraps the indices, with no integer division.
    ix = int(fx_floor)
    iy = int(fy_floor)
    ix0 = ix & mask
    iy0 = iy & mask
    ix1 = (ix + 1) & mask
    iy1 = (iy + 1) & mask
    f = surface.fields
    lower = (1.0 - tx) * f[field, iy0, ix0] + tx * f[field, iy0, ix1]
    upper = (1.0 - tx) * f[field, iy1, ix0] + tx * f[field, iy1, ix1]
    return (1.0 - ty) * lower + ty * upper


@wp.func
def contracted_inversion(surface: OceanSurface, xy: wp.vec2, start: wp.vec2, contraction: float) -> wp.vec2:
    """The grid position q [m] whose displaced position q + choppiness * D(q) is ``xy`` [m], by the
    fixed-point iteration q <- xy - choppiness * D(q) from ``start`` [m]. Each iteration leaves about
    ``contraction`` (choppiness * |grad D|, at most 1) of the error before it, so once a step has moved q by s
    the error left is about contraction * s: the loop stops when that is below the tolerance, or after
    ``inversion_iterations``."""
    q = start
    for _ in range(surface.inversion_iterations):
        displacement = periodic_bilinear(surface, FIELD_DISPLACEMENT, q)
        next_q = xy - surface.choppiness * wp.vec2(displacement[0], displacement[1])
        step = next_q - q
        q = next_q
        if contraction * contraction * wp.dot(step, step) < surface.inversion_tolerance_sq:
            break
    return q


@wp.func
def inverted_displacement(surface: OceanSurface, xy: wp.vec2, start: wp.vec2) -> wp.vec2:
    """:func:`contracted_inversion` without knowing the contraction: each iteration shrinks the error by about
    choppiness * |grad D|, which a steep sea at choppiness 1 brings to about 0.4, so the loop stops once a step
    moves q less than the tolerance (the error left is then about as small)."""
    return contracted_inversion(surface, xy, start, 1.0)


@wp.func
def undisplaced_position(surface: OceanSurface, xy: wp.vec2) -> wp.vec2:
    """The grid position q [m] whose displaced position is ``xy`` [m], started from ``xy`` itself."""
    return inverted_displacement(surface, xy, xy)


@wp.func
def undisplaced_position_near(surface: OceanSurface, xy: wp.vec2, shift: wp.vec2) -> wp.vec2:
    """:func:`undisplaced_position` of ``xy`` [m], started from ``xy - shift`` where ``shift`` [m] is
    choppiness * D at a nearby point (``p - undisplaced_position(p)``). On a sea whose displacement varies
    little over a boat's length the start is already close, and the iteration stops after one or two steps."""
    return inverted_displacement(surface, xy, xy - shift)


@wp.struct
class LocalInversion:
    """What a boat's block finds once at an anchor (its origin) to undo the choppy displacement at its points
    cheaply: to first order about the anchor, the grid position of a world point p is
    grid + (I + choppiness dD/dq)^-1 (p - anchor), within a few millimetres over a boat's length on a
    moderate sea, so the fixed-point iteration started there usually ends after one step."""

    anchor: wp.vec2
    """World x, y [m] of the anchor."""
    grid: wp.vec2
    """Its grid position [m]."""
    inverse_jacobian: wp.mat22
    """(I + choppiness dD/dq)^-1 at the anchor."""
    contraction: float
    """Twice choppiness * |dD/dq| (Frobenius) at the anchor, at most 1: a bound on the share of its error each
    iteration leaves near it (see :func:`contracted_inversion`)."""


@wp.func
def local_inversion(surface: OceanSurface, anchor: wp.vec2) -> LocalInversion:
    """The :class:`LocalInversion` about world point ``anchor`` [m]: its grid position (to the tolerance) and the
    displacement's gradient there by central differences over one cell of the interpolated field."""
    local = LocalInversion()
    local.anchor = anchor
    local.grid = undisplaced_position(surface, anchor)
    local.inverse_jacobian = wp.identity(n=2, dtype=float)
    local.contraction = 0.0
    if surface.inversion_iterations == 0:
        return local
    half = 0.5 / surface.inv_cell_size
    scale = surface.choppiness * surface.inv_cell_size
    q = local.grid
    d_dx = scale * (periodic_bilinear(surface, FIELD_DISPLACEMENT, q + wp.vec2(half, 0.0))
                    - periodic_bilinear(surface, FIELD_DISPLACEMENT, q - wp.vec2(half, 0.0)))
    d_dy = scale * (periodic_bilinear(surface, FIELD_DISPLACEMENT, q + wp.vec2(0.0, half))
                    - periodic_bilinear(surface, FIELD_DISPLACEMENT, q - wp.vec2(0.0, half)))
    gradient = wp.mat22(d_dx[0], d_dy[0], d_dx[1], d_dy[1])
    local.inverse_jacobian = wp.inverse(wp.identity(n=2, dtype=float) + gradient)
    frobenius = wp.sqrt(wp.ddot(gradient, gradient))
    local.contraction = wp.min(2.0 * frobenius, 1.0)
    return local


@wp.func
def undisplaced_position_local(surface: OceanSurface, xy: wp.vec2, local: LocalInversion) -> wp.vec2:
    """:func:`undisplaced_position` of ``xy`` [m] near ``local``'s anchor: started from the first-order estimate,
    stopped by the anchor's contraction."""
    start = local.grid + local.inverse_jacobian * (xy - local.anchor)
    return contracted_inversion(surface, xy, start, local.contraction)


@wp.func
def height_velocity_at_grid(surface: OceanSurface, q: wp.vec2) -> wp.vec4:
    """(height [m], u, v, w [m/s]) of the surface particle of grid position ``q`` [m]."""
    height_rate = periodic_bilinear(surface, FIELD_HEIGHT, q)
    horizontal = periodic_bilinear(surface, FIELD_VELOCITY, q)
    return wp.vec4(height_rate[0], horizontal[0], horizontal[1], height_rate[1])


@wp.func
def _between(z: float, z_upper: float, z_lower: float, upper: float, lower: float) -> float:
    """Linear interpolation at height ``z`` between the values at ``z_upper`` and ``z_lower`` [m]."""
    return upper + (z - z_upper) / (z_lower - z_upper) * (lower - upper)


@wp.func
def pressure_head(surface: OceanSurface, q: wp.vec2, z: float, height: float) -> float:
    """p / (rho g) [m] at height ``z`` [m] (world) under the surface particle of grid position ``q``, whose
    surface is at ``height`` [m]: positive in the water, negative above it (dry).

    Above still water the pressure is hydrostatic up to the surface, height - z. Below it, it is -z plus the
    waves' dynamic head, interpolated linearly in z between the surface (z = 0, where it is the height) and the
    ocean's depths (``pressure_depths``), and held below the deepest."""
    if z >= 0.0:
        return height - z
    levels = surface.pressure_depths
    upper = periodic_bilinear(surface, FIELD_PRESSURE_UPPER, q)
    dynamic = float(0.0)
    if z >= levels[0]:
        dynamic = _between(z, 0.0, levels[0], height, upper[0])
    elif z >= levels[1]:
        dynamic = _between(z, levels[0], levels[1], upper[0], upper[1])
    else:
        deepest = periodic_bilinear(surface, FIELD_PRESSURE_LOWER, q)[0]
        dynamic = deepest
        if z >= levels[2]:
            dynamic = _between(z, levels[1], levels[2], upper[1], deepest)
    return dynamic - z


@wp.func
def velocity_at_depth(surface: OceanSurface, q: wp.vec2) -> wp.vec3:
    """The orbital velocity [m/s] (world frame) at the ocean's middle depth z2 under grid position ``q``."""
    lower = periodic_bilinear(surface, FIELD_PRESSURE_LOWER, q)
    below = periodic_bilinear(surface, FIELD_VELOCITY_BELOW, q)
    return wp.vec3(below[0], below[1], lower[1])


@wp.func
def surface_height(surface: OceanSurface, xy: wp.vec2) -> float:
    """Height of the surface [m] above world point ``xy`` [m] (z up, still water at 0)."""
    q = undisplaced_position(surface, xy)
    return periodic_bilinear(surface, FIELD_HEIGHT, q)[0]


@wp.func
def surface_height_velocity(surface: OceanSurface, xy: wp.vec2) -> wp.vec4:
    """(height [m], u, v, w [m/s]) of the surface above ``xy``: the water velocity is the linear
    orbital velocity of the surface particle there."""
    return height_velocity_at_grid(surface, undisplaced_position(surface, xy))


@wp.func
def surface_normal(surface: OceanSurface, q: wp.vec2) -> wp.vec3:
    """Unit upward normal of the displaced surface at grid position ``q`` [m]: the cross product of
    the tangents d(q + c D, h)/dqx and d(q + c D, h)/dqy. The gradient of D is a central difference
    over one cell of the interpolated field."""
    half = 0.5 / surface.inv_cell_size
    c = surface.choppiness
    d_dx = (
        periodic_bilinear(surface, FIELD_DISPLACEMENT, q + wp.vec2(half, 0.0))
        - periodic_bilinear(surface, FIELD_DISPLACEMENT, q - wp.vec2(half, 0.0))
    ) * surface.inv_cell_size
    d_dy = (
        periodic_bilinear(surface, FIELD_DISPLACEMENT, q + wp.vec2(0.0, half))
        - periodic_bilinear(surface, FIELD_DISPLACEMENT, q - wp.vec2(0.0, half))
    ) * surface.inv_cell_size
    slope = periodic_bilinear(surface, FIELD_SLOPE, q)
    tangent_x = wp.vec3(1.0 + c * d_dx[0], c * d_dx[1], slope[0])
    tangent_y = wp.vec3(c * d_dy[0], 1.0 + c * d_dy[1], slope[1])
    return wp.normalize(wp.cross(tangent_x, tangent_y))


@wp.kernel(enable_backward=False)
def sample_surface_kernel(
    surface: OceanSurface,
    points: wp.array(dtype=wp.vec2),
    heights: wp.array(dtype=float),
    normals: wp.array(dtype=wp.vec3),
    velocities: wp.array(dtype=wp.vec3),
    grid_positions: wp.array(dtype=wp.vec2),
):
    """Per world point [m]: surface height [m], unit normal, water velocity [m/s] and the grid
    position whose displaced image is the point [m]."""
    i = wp.tid()
    xy = points[i]
    q = undisplaced_position(surface, xy)
    height_rate = periodic_bilinear(surface, FIELD_HEIGHT, q)
    horizontal = periodic_bilinear(surface, FIELD_VELOCITY, q)
    heights[i] = height_rate[0]
    velocities[i] = wp.vec3(horizontal[0], horizontal[1], height_rate[1])
    normals[i] = surface_normal(surface, q)
    grid_positions[i] = q
