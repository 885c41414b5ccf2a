"""Rays through a sailing scene on the device: the ocean surface, the boats and the objects of one environment.

A ray is cast in one environment: it sees that environment's objects (spheres and vertical cylinders,
analytic; any other shape as a Warp mesh with its BVH, ``wp.mesh_query_ray``), the boats of that
environment (each a vessel's parts: rigid meshes, fixed in the body frame or turned about their pivot's z by a
joint angle, one may be scaled per boat, as the E-Boat's sail by its reef) except the one the sensor rides on,
and the sea.

The sea is a height map: the surface height above every node of the ocean's periodic grid, resampled
when the scene is refreshed (:func:`resample_heights`; exactly the ocean's surface at the nodes, its
choppy displacement included, and bilinear between them). A ray crosses the map cell by cell (a 2D DDA)
within the band of heights the map holds (:func:`water_band`) and meets each cell's bilinear patch exactly
(a quadratic along the ray): no march steps, no bisection. A ray that starts below every trough, or below
the surface, meets the water at once. Its normal is the ocean's own at the hit.
"""

from __future__ import annotations

import warp as wp

from .ocean_spectrum import FIELD_HEIGHT
from .ocean_surface import OceanSurface, surface_height, surface_normal, undisplaced_position

__all__ = ["HIT_NONE", "HIT_WATER", "HIT_OBJECT", "HIT_BOAT", "SHAPE_SPHERE", "SHAPE_CYLINDER", "SHAPE_MESH",
           "SceneView", "RayHit", "cast_ray", "cast_rays", "resample_heights", "water_distance", "water_band",
           "float_objects"]

HIT_NONE = wp.constant(0)
"""Nothing within range."""
HIT_WATER = wp.constant(1)
HIT_OBJECT = wp.constant(2)
"""A buoy or a fixed object."""
HIT_BOAT = wp.constant(3)

SHAPE_SPHERE = wp.constant(0)
"""``size[0]`` radius [m], centred on the object's position."""
SHAPE_CYLINDER = wp.constant(1)
"""Upright in its own frame: ``size[0]`` radius, ``size[1]`` half height [m], centred on its position."""
SHAPE_MESH = wp.constant(2)
"""``mesh`` (a ``wp.Mesh`` id) in the object's frame."""

MAX_CELLS = wp.constant(8192)
"""Most grid cells a beam crosses within the water band (more than any range on any grid this project runs)."""


@wp.struct
class SceneView:
    """What a ray sees, as the kernels read it (built by ``ocean_warp.perception.scene.Scene``)."""

    surface: OceanSurface
    heights: wp.array2d(dtype=float)
    """(n, n) the sea's height above every node of the ocean's grid [m] (:func:`resample_heights`): the
    surface rays meet, bilinear between the nodes."""
    water_band: wp.array(dtype=float)
    """(2,) lowest and highest of ``heights`` [m] (:func:`water_band`)."""
    water_visible: int
    """1: rays see the sea; 0: they pass through it."""
    object_start: wp.array(dtype=int)
    """(E + 1,) environment e's objects are [object_start[e], object_start[e + 1])."""
    object_shape: wp.array(dtype=int)
    """SHAPE_SPHERE, SHAPE_CYLINDER or SHAPE_MESH."""
    object_position: wp.array(dtype=wp.vec3)
    """World position of each object's frame [m]."""
    object_orientation: wp.array(dtype=wp.quat)
    """Object frame -> world."""
    object_size: wp.array(dtype=wp.vec3)
    """Shape parameters [m] (see the SHAPE_ constants)."""
    object_mesh: wp.array(dtype=wp.uint64)
    """Mesh id of a SHAPE_MESH object (0 otherwise)."""
    object_bound: wp.array(dtype=float)
    """Radius of a sphere about the object's position that holds all of it [m] (for culling)."""
    object_color: wp.array(dtype=wp.vec3)
    """Linear RGB in 0-1, for the camera."""
    boat_start: wp.array(dtype=int)
    """(E + 1,) environment e's boats are boat_list[boat_start[e] : boat_start[e + 1]]."""
    boat_list: wp.array(dtype=int)
    """Boat indices, environment by environment."""
    boat_position: wp.array(dtype=wp.vec3)
    boat_orientation: wp.array(dtype=wp.quat)
    part_mesh: wp.array(dtype=wp.uint64)
    """(P,) each part of the vessel: its mesh, in its own frame (see ``part_origin``)."""
    part_pivot: wp.array(dtype=wp.vec3)
    """(P,) where each part's pivot sits in the body frame [m] (a fixed part: the body origin)."""
    part_origin: wp.array(dtype=wp.vec3)
    """(P,) where the mesh's origin sits in the pivot's frame [m]: a scaled part scales about it."""
    part_joint: wp.array(dtype=int)
    """(P,) -1: a fixed part; k in 0..2: the part turns by minus ``joint_k[boat, part_column]`` about its pivot's
    z axis."""
    part_column: wp.array(dtype=int)
    part_scaled: wp.array(dtype=int)
    """(P,) 1: the part is drawn scaled by ``reef_scale[reef_level[boat]]`` about its mesh's origin."""
    part_look: wp.array(dtype=int)
    """(P,) what ``RayHit.part`` reports for the part: 0 a hull's colour, 1 a sail's or a spar's."""
    joint_0: wp.array2d(dtype=float)
    """(B, C) a joint state of the boats [rad] (a vessel's ``boom_angle``, ``thruster_angle``...)."""
    joint_1: wp.array2d(dtype=float)
    joint_2: wp.array2d(dtype=float)
    reef_level: wp.array(dtype=int)
    """Each boat's level of its scaled part, an index into ``reef_scale`` (the E-Boat's reef)."""
    reef_scale: wp.array(dtype=float)
    """(levels,) the linear factor on the scaled part about its origin at each level (level 0: 1)."""
    boat_bound: float
    """Radius of a sphere about the body origin that holds the whole boat, its parts turned any way [m]."""


@wp.struct
class RayHit:
    t: float
    """Distance along the (unit) ray [m]; the ray's maximum when nothing was hit."""
    kind: int
    """HIT_NONE, HIT_WATER, HIT_OBJECT or HIT_BOAT."""
    index: int
    """The object's or the boat's index (-1 for the water or nothing)."""
    part: int
    """Of a boat: the look of the part hit (``SceneView.part_look``: 0 a hull, 1 a sail or a spar)."""
    normal: wp.vec3
    """Unit normal of the surface hit, world frame, facing the ray."""


@wp.func
def _facing(normal: wp.vec3, direction: wp.vec3) -> wp.vec3:
    if wp.dot(normal, direction) > 0.0:
        return -normal
    return normal


@wp.func
def _misses_bound(center: wp.vec3, radius: float, origin: wp.vec3, direction: wp.vec3, t_max: float) -> bool:
    """Whether the ray [0, t_max] passes wide of the sphere (center, radius)."""
    to_center = center - origin
    along = wp.clamp(wp.dot(to_center, direction), 0.0, t_max)
    closest = to_center - along * direction
    return wp.dot(closest, closest) > radius * radius


@wp.func
def _sphere(center: wp.vec3, radius: float, origin: wp.vec3, direction: wp.vec3, t_min: float) -> wp.vec4:
    """(t, outward normal) of the nearest t >= t_min where the unit ray meets the sphere; t = -1 on a miss."""
    oc = origin - center
    b = wp.dot(oc, direction)
    c = wp.dot(oc, oc) - radius * radius
    disc = b * b - c
    if disc < 0.0:
        return wp.vec4(-1.0, 0.0, 0.0, 0.0)
    root = wp.sqrt(disc)
    t = -b - root
    if t < t_min:
        t = -b + root
    if t < t_min:
        return wp.vec4(-1.0, 0.0, 0.0, 0.0)
    normal = (oc + t * direction) / radius
    return wp.vec4(t, normal[0], normal[1], normal[2])


@wp.func
def _nearer(hit: RayHit, found: wp.vec4, t_min: float, kind: int, index: int, part: int) -> RayHit:
    """``hit``, or the hit ``found`` (t [m], normal) of a body of ``kind``, ``index`` and ``part`` when it
    lies in [t_min, hit.t) (t = -1: a miss)."""
    if found[0] < t_min or found[0] >= hit.t:
        return hit
    nearer = RayHit()
    nearer.t = found[0]
    nearer.kind = kind
    nearer.index = index
    nearer.part = part
    nearer.normal = wp.vec3(found[1], found[2], found[3])
    return nearer


@wp.func
def _cylinder(radius: float, half_height: float, origin: wp.vec3, direction: wp.vec3, t_min: float) -> wp.vec4:
    """Nearest hit (t, normal) of a unit ray with the closed upright cylinder at the origin of its frame;
    t = -1 when it misses."""
    best = float(-1.0)
    normal = wp.vec3(0.0, 0.0, 0.0)
    a = direction[0] * direction[0] + direction[1] * direction[1]
    if a > 1.0e-12:
        b = origin[0] * direction[0] + origin[1] * direction[1]
        c = origin[0] * origin[0] + origin[1] * origin[1] - radius * radius
        disc = b * b - a * c
        if disc >= 0.0:
            root = wp.sqrt(disc)
            for sign in range(2):
                t = (-b - root) / a
                if sign == 1:
                    t = (-b + root) / a
                z = origin[2] + t * direction[2]
                if t >= t_min and wp.abs(z) <= half_height and (best < 0.0 or t < best):
                    best = t
                    normal = wp.vec3(origin[0] + t * direction[0], origin[1] + t * direction[1], 0.0) / radius
    if wp.abs(direction[2]) > 1.0e-12:
        for sign in range(2):
            cap = half_height
            if sign == 1:
                cap = -half_height
            t = (cap - origin[2]) / direction[2]
            x = origin[0] + t * direction[0]
            y = origin[1] + t * direction[1]
            if t >= t_min and x * x + y * y <= radius * radius and (best < 0.0 or t < best):
                best = t
                normal = wp.vec3(0.0, 0.0, wp.sign(cap))
    return wp.vec4(best, normal[0], normal[1], normal[2])


@wp.func
def _mesh_in_frame(mesh: wp.uint64, position: wp.vec3, orientation: wp.quat, origin: wp.vec3, direction: wp.vec3,
                   t_max: float) -> wp.vec4:
    """(t, world normal) of the unit ray against ``mesh`` posed at (position, orientation); t = -1 on a miss."""
    local_origin = wp.quat_rotate_inv(orientation, origin - position)
    local_direction = wp.quat_rotate_inv(orientation, direction)
    query = wp.mesh_query_ray(mesh, local_origin, local_direction, t_max)
    if query.result:
        normal = wp.quat_rotate(orientation, query.normal)
        return wp.vec4(query.t, normal[0], normal[1], normal[2])
    return wp.vec4(-1.0, 0.0, 0.0, 0.0)


@wp.func
def _scaled_mesh_in_frame(mesh: wp.uint64, position: wp.vec3, orientation: wp.quat, scale: float, origin: wp.vec3,
                          direction: wp.vec3, t_max: float) -> wp.vec4:
    """(t, world normal) of the unit ray against ``mesh`` scaled by ``scale`` > 0 about its frame's origin and
    posed at (position, orientation); t = -1 on a miss. In the unscaled frame the ray runs from (origin -
    position) / scale along the same unit direction, t / scale for t along the world ray; a uniform scale keeps
    the normals."""
    local_origin = wp.quat_rotate_inv(orientation, origin - position) / scale
    local_direction = wp.quat_rotate_inv(orientation, direction)
    query = wp.mesh_query_ray(mesh, local_origin, local_direction, t_max / scale)
    if query.result:
        normal = wp.quat_rotate(orientation, query.normal)
        return wp.vec4(scale * query.t, normal[0], normal[1], normal[2])
    return wp.vec4(-1.0, 0.0, 0.0, 0.0)


@wp.func
def _joint_angle(scene: SceneView, joint: int, boat: int, column: int) -> float:
    if joint == 0:
        return scene.joint_0[boat, column]
    if joint == 1:
        return scene.joint_1[boat, column]
    return scene.joint_2[boat, column]


@wp.func
def _part(scene: SceneView, p: int, boat: int, position: wp.vec3, rotation: wp.quat, origin: wp.vec3,
          direction: wp.vec3, t_max: float) -> wp.vec4:
    """(t, world normal) of the unit ray against part ``p`` of ``boat`` (at ``position``, ``rotation``), posed by
    its joint and scaled by its level; t = -1 on a miss."""
    frame = rotation
    joint = scene.part_joint[p]
    if joint >= 0:
        angle = _joint_angle(scene, joint, boat, scene.part_column[p])
        frame = rotation * wp.quat_from_axis_angle(wp.vec3(0.0, 0.0, 1.0), -angle)
    at = position + wp.quat_rotate(rotation, scene.part_pivot[p]) + wp.quat_rotate(frame, scene.part_origin[p])
    if scene.part_scaled[p] != 0:
        level = wp.clamp(scene.reef_level[boat], 0, scene.reef_scale.shape[0] - 1)
        return _scaled_mesh_in_frame(scene.part_mesh[p], at, frame, scene.reef_scale[level], origin, direction,
                                     t_max)
    return _mesh_in_frame(scene.part_mesh[p], at, frame, origin, direction, t_max)


@wp.kernel(enable_backward=False)
def resample_heights(surface: OceanSurface, heights: wp.array2d(dtype=float)):
    """One thread per grid node (iy, ix): the surface height [m] above the node's world point
    (ix, iy) x cell size, into ``heights`` [iy, ix] (the node's own height where there is no choppiness)."""
    iy, ix = wp.tid()
    if surface.choppiness == 0.0:
        heights[iy, ix] = surface.fields[FIELD_HEIGHT, iy, ix][0]
        return
    cell = 1.0 / surface.inv_cell_size
    heights[iy, ix] = surface_height(surface, wp.vec2(float(ix) * cell, float(iy) * cell))


@wp.func
def _first_root(a: float, b: float, c: float, length: float) -> float:
    """The least s in [0, ``length``] with a s^2 + b s + c = 0, where c > 0; -1 if none."""
    if a == 0.0:
        if b >= 0.0:
            return -1.0
        s = -c / b
        if s <= length:
            return s
        return -1.0
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return -1.0
    root = wp.sqrt(disc)
    q = -0.5 * (b - root)
    if b >= 0.0:
        q = -0.5 * (b + root)
    # Both roots without cancellation: q / a and c / q (q is not 0: c > 0 and a != 0).
    near = wp.min(q / a, c / q)
    far = wp.max(q / a, c / q)
    if near >= 0.0 and near <= length:
        return near
    if near < 0.0 and far >= 0.0 and far <= length:
        return far
    return -1.0


@wp.func
def _patch_crossing(heights: wp.array2d(dtype=float), mask: int, ix: int, iy: int, u0: float, v0: float,
                    du: float, dv: float, z0: float, dz: float, length: float) -> float:
    """First s in [0, ``length``] [m] where the beam, at grid coordinates (ix + u0 + du s, iy + v0 + dv s) and
    height z0 + dz s [m], meets the bilinear patch of cell (ix, iy); -1 if it stays above it."""
    x0 = ix & mask
    y0 = iy & mask
    x1 = (ix + 1) & mask
    y1 = (iy + 1) & mask
    h00 = heights[y0, x0]
    h10 = heights[y0, x1]
    h01 = heights[y1, x0]
    h11 = heights[y1, x1]
    if wp.min(z0, z0 + dz * length) > wp.max(wp.max(h00, h10), wp.max(h01, h11)):
        return -1.0
    along_u = h10 - h00
    along_v = h01 - h00
    twist = h00 - h10 - h01 + h11
    # Height above the patch along the beam: (z0 - h(s)) + (dz - h'(0)) s - twist du dv s^2.
    gap = z0 - (h00 + along_u * u0 + along_v * v0 + twist * u0 * v0)
    if gap <= 0.0:
        return 0.0
    slope = dz - (along_u * du + along_v * dv + twist * (u0 * dv + v0 * du))
    return _first_root(-twist * du * dv, slope, gap, length)


@wp.func
def _cell_boundary(start: float, grid: float, rate: float) -> wp.vec2:
    """(distance [m] to the first grid line the beam crosses along one axis, distance between such lines);
    1e30 for a beam that does not move along it. ``grid``: its grid coordinate at the start, ``rate``:
    cells per metre of beam."""
    if rate > 0.0:
        return wp.vec2(start + (wp.floor(grid) + 1.0 - grid) / rate, 1.0 / rate)
    if rate < 0.0:
        return wp.vec2(start + (wp.floor(grid) - grid) / rate, -1.0 / rate)
    return wp.vec2(1.0e30, 1.0e30)


@wp.func
def _cross_cells(heights: wp.array2d(dtype=float), surface: OceanSurface, origin: wp.vec3, direction: wp.vec3,
                 t_start: float, t_end: float) -> float:
    """First t in [t_start, t_end] [m] where the unit beam meets the height map, cell by cell; -1 if none."""
    inv = surface.inv_cell_size
    mask = surface.index_mask
    du = direction[0] * inv
    dv = direction[1] * inv
    start = origin + t_start * direction
    ix = int(wp.floor(start[0] * inv))
    iy = int(wp.floor(start[1] * inv))
    next_x = _cell_boundary(t_start, start[0] * inv, du)
    next_y = _cell_boundary(t_start, start[1] * inv, dv)
    step_x = int(wp.sign(du))
    step_y = int(wp.sign(dv))
    t = t_start
    for _ in range(MAX_CELLS):
        t_exit = wp.min(wp.min(next_x[0], next_y[0]), t_end)
        entry = origin + t * direction
        s = _patch_crossing(heights, mask, ix, iy, entry[0] * inv - float(ix), entry[1] * inv - float(iy), du, dv,
                            entry[2], direction[2], t_exit - t)
        if s >= 0.0:
            return t + s
        if t_exit >= t_end:
            return -1.0
        t = t_exit
        if next_x[0] < next_y[0]:
            ix = ix + step_x
            next_x = wp.vec2(next_x[0] + next_x[1], next_x[1])
        else:
            iy = iy + step_y
            next_y = wp.vec2(next_y[0] + next_y[1], next_y[1])
    return -1.0


@wp.func
def water_distance(heights: wp.array2d(dtype=float), surface: OceanSurface, band: wp.array(dtype=float),
                   origin: wp.vec3, direction: wp.vec3, t_min: float, t_max: float) -> float:
    """First t in [t_min, t_max] [m] where the unit beam meets the sea's height map ``heights`` (on the grid
    of ``surface``; its heights within ``band`` (low, high) [m]), or -1. Only the stretch of the beam
    inside the band is crossed; a beam below every trough at t_min meets the water there, and one that
    leaves the band through its bottom within range has met it by then (taken there if rounding hid the
    crossing, as on a flat sea, where the band has no height)."""
    low = band[0]
    high = band[1]
    dz = direction[2]
    t_start = t_min
    t_end = t_max
    sinks_under = False
    if wp.abs(dz) < 1.0e-9:
        if origin[2] < low:
            return t_min
        if origin[2] > high:
            return -1.0
    else:
        if origin[2] + t_min * dz < low:
            return t_min
        t_high = (high - origin[2]) / dz
        t_low = (low - origin[2]) / dz
        t_start = wp.max(t_min, wp.min(t_high, t_low))
        t_end = wp.min(t_max, wp.max(t_high, t_low))
        sinks_under = dz < 0.0 and t_low <= t_max
    if t_start > t_end:
        return -1.0
    t = _cross_cells(heights, surface, origin, direction, t_start, t_end)
    if t < 0.0 and sinks_under:
        return t_end
    return t


@wp.func
def cast_ray(scene: SceneView, env: int, origin: wp.vec3, direction: wp.vec3, t_min: float, t_max: float,
             own_boat: int) -> RayHit:
    """The nearest hit of the unit ray ``origin`` + t ``direction``, t in [t_min, t_max] [m], in environment
    ``env``, ignoring boat ``own_boat`` (-1: none)."""
    hit = RayHit()
    hit.t = t_max
    hit.kind = HIT_NONE
    hit.index = -1
    hit.part = 0
    hit.normal = wp.vec3(0.0, 0.0, 1.0)
    for k in range(scene.object_start[env], scene.object_start[env + 1]):
        position = scene.object_position[k]
        bound = scene.object_bound[k]
        if bound <= 0.0 or _misses_bound(position, bound, origin, direction, hit.t):  # bound 0: an empty row
            continue
        shape = scene.object_shape[k]
        size = scene.object_size[k]
        rotation = scene.object_orientation[k]
        found = wp.vec4(-1.0, 0.0, 0.0, 0.0)
        if shape == SHAPE_SPHERE:
            found = _sphere(position, size[0], origin, direction, t_min)
        elif shape == SHAPE_CYLINDER:
            local = _cylinder(size[0], size[1], wp.quat_rotate_inv(rotation, origin - position),
                              wp.quat_rotate_inv(rotation, direction), t_min)
            normal = wp.quat_rotate(rotation, wp.vec3(local[1], local[2], local[3]))
            found = wp.vec4(local[0], normal[0], normal[1], normal[2])
        else:
            found = _mesh_in_frame(scene.object_mesh[k], position, rotation, origin, direction, hit.t)
        hit = _nearer(hit, found, t_min, HIT_OBJECT, k, 0)
    for slot in range(scene.boat_start[env], scene.boat_start[env + 1]):
        boat = scene.boat_list[slot]
        if boat == own_boat:
            continue
        position = scene.boat_position[boat]
        if _misses_bound(position, scene.boat_bound, origin, direction, hit.t):
            continue
        rotation = scene.boat_orientation[boat]
        for p in range(scene.part_mesh.shape[0]):
            hit = _nearer(hit, _part(scene, p, boat, position, rotation, origin, direction, hit.t), t_min, HIT_BOAT,
                          boat, scene.part_look[p])
    if scene.water_visible != 0:
        t = water_distance(scene.heights, scene.surface, scene.water_band, origin, direction, t_min, hit.t)
        if t >= 0.0 and (t < hit.t or hit.kind == HIT_NONE):
            hit.t = t
            hit.kind = HIT_WATER
            hit.index = -1
            hit.part = 0
            point = origin + t * direction
            hit.normal = surface_normal(scene.surface, undisplaced_position(scene.surface, wp.vec2(point[0], point[1])))
    hit.normal = _facing(hit.normal, direction)
    return hit


@wp.kernel(enable_backward=False)
def water_band(heights: wp.array2d(dtype=float), band: wp.array(dtype=float)):
    """One thread a grid row: the lowest and highest height of the map into ``band`` (which must hold
    (+inf, -inf) before the launch). Heights between nodes are bilinear, so they lie in the band."""
    row = wp.tid()
    low = float(1.0e30)
    high = float(-1.0e30)
    for column in range(heights.shape[1]):
        height = heights[row, column]
        low = wp.min(low, height)
        high = wp.max(high, height)
    wp.atomic_min(band, 0, low)
    wp.atomic_max(band, 1, high)


@wp.kernel(enable_backward=False)
def float_objects(surface: OceanSurface, floats: wp.array(dtype=int), draft: wp.array(dtype=float),
                  anchor: wp.array(dtype=wp.vec3), position: wp.array(dtype=wp.vec3),
                  orientation: wp.array(dtype=wp.quat)):
    """Each object with ``floats`` set rides the sea at its anchor's x, y: its frame sits ``draft`` [m] below
    the surface there and tilts with the surface normal. Others stay at their anchor."""
    k = wp.tid()
    place = anchor[k]
    if floats[k] == 0:
        position[k] = place
        return
    xy = wp.vec2(place[0], place[1])
    q = undisplaced_position(surface, xy)
    height = surface_height(surface, xy)
    normal = surface_normal(surface, q)
    position[k] = wp.vec3(place[0], place[1], height - draft[k])
    up = wp.vec3(0.0, 0.0, 1.0)
    axis = wp.cross(up, normal)
    sine = wp.length(axis)
    if sine < 1.0e-9:
        orientation[k] = wp.quat_identity()
    else:
        orientation[k] = wp.quat_from_axis_angle(axis / sine, wp.atan2(sine, wp.dot(up, normal)))


@wp.kernel(enable_backward=False)
def cast_rays(scene: SceneView, env: wp.array(dtype=int), origin: wp.array(dtype=wp.vec3),
              direction: wp.array(dtype=wp.vec3), own_boat: wp.array(dtype=int), t_min: float, t_max: float,
              distance: wp.array(dtype=float), kind: wp.array(dtype=int), index: wp.array(dtype=int),
              normal: wp.array(dtype=wp.vec3)):
    """One ray a thread (directions normalised here): its hit's distance [m], kind, index and normal."""
    r = wp.tid()
    hit = cast_ray(scene, env[r], origin[r], wp.normalize(direction[r]), t_min, t_max, own_boat[r])
    distance[r] = hit.t
    kind[r] = hit.kind
    index[r] = hit.index
    normal[r] = hit.normal
