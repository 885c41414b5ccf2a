"""Rays through a sailing scene on the device: the ocean surface, the boats and the objects of one environment.

A ray is cast in one environment: it sees that environment's objects (spheres and vertical cylinders,
analytic; any other shape as a Warp mesh with its BVH, ``wp.mesh_query_ray``), the boats of that
environment (the hull, keel and mast as one mesh in the body frame; the boom and sail as one mesh in
the boom's pivot frame, turned by the boom angle) except the one the sensor rides on, and the sea.

The sea is a height field over the periodic grid of ``ocean_surface`` (choppy displacement inverted as
the hull pass does). The ray is marched only where it lies inside the band of heights the grid holds
now (``SceneView.water_low`` .. ``water_high``, refreshed from the fields by :func:`water_band`), with
steps that cannot jump over the surface for the steepest slope the grid holds, and the first crossing is
refined by bisection. A ray that starts below the surface hits the water at once.
"""

from __future__ import annotations

import warp as wp

from .ocean_spectrum import FIELD_HEIGHT, FIELD_SLOPE
from .ocean_surface import OceanSurface, surface_height, surface_normal, undisplaced_position

__all__ = ["HIT_NONE", "HIT_WATER", "HIT_OBJECT", "HIT_BOAT", "SHAPE_SPHERE", "SHAPE_CYLINDER", "SHAPE_MESH",
           "SceneView", "RayHit", "cast_ray", "cast_rays", "water_band", "float_objects"]

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

MARCH_STEPS = wp.constant(512)
"""Most steps of the march through the water band (a ray that needs more reports no water)."""
BISECTIONS = wp.constant(12)
MIN_STEP = wp.constant(0.02)
"""Shortest march step [m]."""
BAND_MARGIN = wp.constant(0.01)
"""[m] added above and below the sea's height band."""


@wp.struct
class SceneView:
    """What a ray sees, as the kernels read it (built by ``ocean_warp.perception.scene.Scene``)."""

    surface: OceanSurface
    water_band: wp.array(dtype=float)
    """(3,) lowest and highest surface height of the grid now [m], and its steepest slope (|grad h|)."""
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
    boom_angle: wp.array(dtype=float)
    """[rad], positive to port: the boom mesh turns by -boom about the pivot's z axis."""
    body_mesh: wp.uint64
    """Hull, keel and mast in the body frame."""
    boom_mesh: wp.uint64
    """Spar and sail in the boom's pivot frame."""
    boom_pivot: wp.vec3
    """Boom pivot in the body frame [m]."""
    boat_bound: float
    """Radius of a sphere about the body origin that holds the whole boat, boom swung included [m]."""


@wp.struct
class RayHit:
    t: float
    """Distance along the (unit) ray [m]; the ray's maximum when nothing was hit."""
    kind: int
    """HIT_NONE, HIT_WATER, HIT_OBJECT or HIT_BOAT."""
    index: int
    """The object's or the boat's index (-1 for the water or nothing)."""
    part: int
    """Of a boat: 0 the hull, keel and mast, 1 the boom and sail."""
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
def _sphere(center: wp.vec3, radius: float, origin: wp.vec3, direction: wp.vec3, t_min: float) -> float:
    """Nearest t >= t_min where the unit ray meets the sphere, or -1."""
    oc = origin - center
    b = wp.dot(oc, direction)
    c = wp.dot(oc, oc) - radius * radius
    disc = b * b - c
    if disc < 0.0:
        return -1.0
    root = wp.sqrt(disc)
    t = -b - root
    if t < t_min:
        t = -b + root
    if t < t_min:
        return -1.0
    return t


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
def _water_gap(surface: OceanSurface, point: wp.vec3) -> float:
    """Height of ``point`` above the surface below it [m] (negative under water)."""
    return point[2] - surface_height(surface, wp.vec2(point[0], point[1]))


@wp.func
def _march_water(scene: SceneView, origin: wp.vec3, direction: wp.vec3, t_min: float, t_max: float) -> float:
    """First t in [t_min, t_max] where the ray meets the sea, or -1."""
    # A centimetre of margin: a flat sea's band has no width, and rounding must not leave its plane outside.
    low = scene.water_band[0] - BAND_MARGIN
    high = scene.water_band[1] + BAND_MARGIN
    slope = scene.water_band[2]
    dz = direction[2]
    t_start = t_min
    t_end = t_max
    if wp.abs(dz) < 1.0e-9:
        if origin[2] < low:
            return t_min  # level, below every trough: under water
        if origin[2] > high:
            return -1.0
    else:
        t_high = (high - origin[2]) / dz
        t_low = (low - origin[2]) / dz
        t_start = wp.max(t_min, wp.min(t_high, t_low))
        t_end = wp.min(t_max, wp.max(t_high, t_low))
        if origin[2] + t_min * dz < low:
            return t_min  # starts below every trough: under water
    if t_start > t_end:
        return -1.0
    # A gap g above the surface closes at most at (descent + slope x horizontal speed) per metre of ray.
    horizontal = wp.sqrt(direction[0] * direction[0] + direction[1] * direction[1])
    closing = wp.max(-dz, 0.0) + slope * horizontal + 1.0e-3
    t = t_start
    gap = _water_gap(scene.surface, origin + t * direction)
    if gap <= 0.0:
        return t
    for _ in range(MARCH_STEPS):
        step = wp.max(gap / closing, MIN_STEP)
        t_next = wp.min(t + step, t_end)
        gap_next = _water_gap(scene.surface, origin + t_next * direction)
        if gap_next <= 0.0:
            a = t
            b = t_next
            for _ in range(BISECTIONS):
                middle = 0.5 * (a + b)
                if _water_gap(scene.surface, origin + middle * direction) > 0.0:
                    a = middle
                else:
                    b = middle
            return 0.5 * (a + b)
        if t_next >= t_end:
            return -1.0
        t = t_next
        gap = gap_next
    return -1.0


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
        if _misses_bound(position, scene.object_bound[k], origin, direction, hit.t):
            continue
        shape = scene.object_shape[k]
        size = scene.object_size[k]
        if shape == SHAPE_SPHERE:
            t = _sphere(position, size[0], origin, direction, t_min)
            if t >= 0.0 and t < hit.t:
                hit.t = t
                hit.kind = HIT_OBJECT
                hit.index = k
                hit.normal = wp.normalize(origin + t * direction - position)
        elif shape == SHAPE_CYLINDER:
            rotation = scene.object_orientation[k]
            local = _cylinder(size[0], size[1], wp.quat_rotate_inv(rotation, origin - position),
                              wp.quat_rotate_inv(rotation, direction), t_min)
            if local[0] >= 0.0 and local[0] < hit.t:
                hit.t = local[0]
                hit.kind = HIT_OBJECT
                hit.index = k
                hit.normal = wp.quat_rotate(rotation, wp.vec3(local[1], local[2], local[3]))
        else:
            found = _mesh_in_frame(scene.object_mesh[k], position, scene.object_orientation[k], origin, direction,
                                   hit.t)
            if found[0] >= t_min and found[0] < hit.t:
                hit.t = found[0]
                hit.kind = HIT_OBJECT
                hit.index = k
                hit.normal = wp.vec3(found[1], found[2], found[3])
    for slot in range(scene.boat_start[env], scene.boat_start[env + 1]):
        boat = scene.boat_list[slot]
        if boat == own_boat:
            continue
        position = scene.boat_position[boat]
        if _misses_bound(position, scene.boat_bound, origin, direction, hit.t):
            continue
        rotation = scene.boat_orientation[boat]
        found = _mesh_in_frame(scene.body_mesh, position, rotation, origin, direction, hit.t)
        if found[0] >= t_min and found[0] < hit.t:
            hit.t = found[0]
            hit.kind = HIT_BOAT
            hit.index = boat
            hit.part = 0
            hit.normal = wp.vec3(found[1], found[2], found[3])
        boom = rotation * wp.quat_from_axis_angle(wp.vec3(0.0, 0.0, 1.0), -scene.boom_angle[boat])
        pivot = position + wp.quat_rotate(rotation, scene.boom_pivot)
        found = _mesh_in_frame(scene.boom_mesh, pivot, boom, origin, direction, hit.t)
        if found[0] >= t_min and found[0] < hit.t:
            hit.t = found[0]
            hit.kind = HIT_BOAT
            hit.index = boat
            hit.part = 1
            hit.normal = wp.vec3(found[1], found[2], found[3])
    if scene.water_visible != 0:
        t = _march_water(scene, origin, direction, t_min, hit.t)
        if t >= 0.0 and (t < hit.t or hit.kind == HIT_NONE):
            hit.t = t
            hit.kind = HIT_WATER
            hit.index = -1
            point = origin + t * direction
            hit.normal = surface_normal(scene.surface, undisplaced_position(scene.surface, wp.vec2(point[0], point[1])))
    hit.normal = _facing(hit.normal, direction)
    return hit


@wp.kernel(enable_backward=False)
def water_band(surface: OceanSurface, band: wp.array(dtype=float)):
    """One thread a grid row: the lowest and highest node height and the steepest slope into ``band``
    (which must hold (+inf, -inf, 0) before the launch). Heights between nodes are bilinear, so they lie in
    the band; the choppy displacement moves the nodes sideways only."""
    row = wp.tid()
    n = surface.index_mask + 1
    low = float(1.0e30)
    high = float(-1.0e30)
    steepest = float(0.0)
    for column in range(n):
        height = surface.fields[FIELD_HEIGHT, row, column][0]
        slope = surface.fields[FIELD_SLOPE, row, column]
        low = wp.min(low, height)
        high = wp.max(high, height)
        steepest = wp.max(steepest, wp.length(wp.vec2(slope[0], slope[1])))
    wp.atomic_min(band, 0, low)
    wp.atomic_max(band, 1, high)
    wp.atomic_max(band, 2, steepest)


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
