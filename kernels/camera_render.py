"""Pinhole cameras over the ray-cast scene: a depth image and an RGB image per camera, one thread a pixel.

Frames (ROS conventions, REP 103 and REP 105):

- A camera's pose is that of its *link* frame: x forward (the viewing direction), y left, z up, as a
  boat's body frame. With the identity orientation a camera looks along the world's +x, level.
- The image lives in the camera's *optical* frame (ROS ``*_optical_frame``): z forward, x right, y down;
  it is the link frame turned so (x_opt, y_opt, z_opt) = (-y_link, -z_link, x_link). The intrinsics
  (:class:`CameraLens`, as ``sensor_msgs/CameraInfo``'s K) map a point (x, y, z) of the optical frame to the
  pixel (u, v) = (fx x / z + cx, fy y / z + cy); pixel (u, v) is column u (0 at the left), row v (0 at the
  top), its centre at integer coordinates, so a W-pixel-wide image spans u in [-0.5, W - 0.5].

Depth (``sensor_msgs/Image`` 32FC1, REP 117): the distance along the optical axis [m], z in the optical
frame (not along the ray). Where nothing lies within ``max_range`` of depth: +inf; where the nearest hit
is nearer than ``min_range``: -inf. A camera whose pose is not finite sees nothing: depth +inf and a black
RGB pixel; no NaN leaves the kernel (a non-finite hit distance from the scene counts as no hit).

RGB (8 bits a channel, sRGB encoded): shading in linear RGB, then the sRGB transfer curve.

- Sky (a ray that hits nothing): a gradient with the ray's elevation, from :data:`HORIZON_COLOR` to
  :data:`ZENITH_COLOR`; below the horizon (sea beyond the range) the horizon's colour.
- Water: Fresnel's reflectance for water (n = 1.33, Schlick's approximation, 2 % head-on) mixes the sky
  seen in the mirror direction about the surface normal with :data:`DEEP_WATER_COLOR`: dark looking
  down, bright at grazing angles.
- Objects and boats: Lambert, ``albedo (AMBIENT + (1 - AMBIENT) max(n . sun, 0))`` with the sun in
  :data:`SUN_DIRECTION`; an object's albedo is its ``SceneView.object_color``, a boat's :data:`HULL_COLOR`
  (a part of look 0: ``RayHit.part``, the E-Boat's hull, keel and mast) or :data:`SAIL_COLOR` (look 1: sails and
  spars, the E-Boat's boom and sail).
- Haze (``CameraLens.haze_distance`` > 0): every hit fades toward the horizon's colour by
  1 - exp(-distance / haze_distance).
"""

from __future__ import annotations

import warp as wp

from .ray_cast import HIT_BOAT, HIT_NONE, HIT_OBJECT, HIT_WATER, SceneView, cast_ray

__all__ = ["CameraLens", "count_decisions", "render_cameras", "mounted_camera_poses", "look_at_poses", "follow_boat",
           "look_at_rotation", "ZENITH_COLOR", "HORIZON_COLOR", "DEEP_WATER_COLOR", "HULL_COLOR", "SAIL_COLOR",
           "SUN_DIRECTION", "AMBIENT", "WATER_REFLECTANCE"]

ZENITH_COLOR = wp.constant(wp.vec3(0.10, 0.24, 0.58))
"""Linear RGB of the sky straight up."""
HORIZON_COLOR = wp.constant(wp.vec3(0.62, 0.74, 0.88))
"""Linear RGB of the sky at the horizon, of the haze and of the sea beyond the range."""
DEEP_WATER_COLOR = wp.constant(wp.vec3(0.006, 0.035, 0.06))
"""Linear RGB of the light that comes up out of deep water (what looking straight down shows)."""
HULL_COLOR = wp.constant(wp.vec3(0.80, 0.80, 0.78))
"""Albedo of a boat's hull, keel and mast."""
SAIL_COLOR = wp.constant(wp.vec3(0.92, 0.88, 0.76))
"""Albedo of a boat's boom and sail."""
SUN_DIRECTION = wp.constant(wp.vec3(0.4082483, 0.4082483, 0.8164966))
"""Unit vector toward the sun, world frame (about 55 degrees high)."""
AMBIENT = wp.constant(0.35)
"""Share of an object's albedo lit by the sky alone (a face turned away from the sun)."""
WATER_REFLECTANCE = wp.constant(0.02006)
"""Fresnel reflectance of water seen head-on: ((1.33 - 1) / (1.33 + 1))^2."""


@wp.struct
class CameraLens:
    """Intrinsics and ranges that every camera of a launch shares."""

    fx: float
    """Focal length in pixels along u (the optical x axis)."""
    fy: float
    """Focal length in pixels along v (the optical y axis)."""
    cx: float
    """Principal point, column [px]: (W - 1) / 2 for a centred axis."""
    cy: float
    """Principal point, row [px]: (H - 1) / 2."""
    min_range: float
    """Depth below which a hit reads -inf [m]."""
    max_range: float
    """Depth beyond which nothing is seen [m] (+inf in the depth image, sky or haze in the RGB one)."""
    haze_distance: float
    """Distance over which haze takes 63 % of the colour [m]; 0: no haze."""


@wp.func
def _finite_vec3(v: wp.vec3) -> bool:
    return wp.isfinite(v[0]) and wp.isfinite(v[1]) and wp.isfinite(v[2])


@wp.func
def _finite_quat(q: wp.quat) -> bool:
    return wp.isfinite(q[0]) and wp.isfinite(q[1]) and wp.isfinite(q[2]) and wp.isfinite(q[3])


@wp.func
def sky_color(direction: wp.vec3) -> wp.vec3:
    """Linear RGB of the sky seen along the unit ``direction`` (the horizon's below it)."""
    elevation = wp.sqrt(wp.clamp(direction[2], 0.0, 1.0))
    return wp.lerp(HORIZON_COLOR, ZENITH_COLOR, elevation)


@wp.func
def water_color(direction: wp.vec3, normal: wp.vec3) -> wp.vec3:
    """Linear RGB of water hit along unit ``direction`` with unit ``normal`` facing the ray: Schlick's Fresnel
    term mixes the reflected sky with the deep water's colour."""
    cosine = wp.clamp(-wp.dot(direction, normal), 0.0, 1.0)
    grazing = 1.0 - cosine
    fresnel = WATER_REFLECTANCE + (1.0 - WATER_REFLECTANCE) * grazing * grazing * grazing * grazing * grazing
    mirrored = direction - 2.0 * wp.dot(direction, normal) * normal
    return wp.lerp(DEEP_WATER_COLOR, sky_color(mirrored), fresnel)


@wp.func
def lit_color(albedo: wp.vec3, normal: wp.vec3) -> wp.vec3:
    """Lambert under the sun and the sky's ambient light."""
    sunlit = wp.max(wp.dot(normal, SUN_DIRECTION), 0.0)
    return albedo * (AMBIENT + (1.0 - AMBIENT) * sunlit)


@wp.func
def _srgb_channel(linear: float) -> wp.uint8:
    """One linear channel in [0, 1] (clamped) to its 8-bit sRGB code."""
    c = wp.clamp(linear, 0.0, 1.0)
    encoded = 12.92 * c
    if c > 0.0031308:
        encoded = 1.055 * wp.pow(c, 1.0 / 2.4) - 0.055
    return wp.uint8(int(encoded * 255.0 + 0.5))


@wp.func
def shade(scene: SceneView, lens: CameraLens, direction: wp.vec3, kind: int, index: int, part: int, normal: wp.vec3,
          distance: float) -> wp.vec3:
    """Linear RGB of what the unit ray ``direction`` met (``kind``, ``index``, ``part``, ``normal`` as
    ``RayHit``) at ``distance`` [m]."""
    if kind == HIT_NONE:
        return sky_color(direction)
    color = HORIZON_COLOR
    if kind == HIT_WATER:
        color = water_color(direction, normal)
    elif kind == HIT_OBJECT:
        color = lit_color(scene.object_color[index], normal)
    elif kind == HIT_BOAT:
        albedo = HULL_COLOR
        if part == 1:
            albedo = SAIL_COLOR
        color = lit_color(albedo, normal)
    if lens.haze_distance > 0.0:
        color = wp.lerp(color, HORIZON_COLOR, 1.0 - wp.exp(-distance / lens.haze_distance))
    return color


@wp.func
def pixel_ray(lens: CameraLens, orientation: wp.quat, u: int, v: int) -> wp.vec4:
    """The world direction (unit) through pixel centre (u, v) of a camera whose link frame has
    ``orientation``, and as w the ray's length per metre of depth (its direction's length in the optical
    frame with z = 1)."""
    right = (float(u) - lens.cx) / lens.fx
    down = (float(v) - lens.cy) / lens.fy
    link = wp.vec3(1.0, -right, -down)  # optical (right, down, 1) in the link frame (x forward, y left, z up)
    stretch = wp.length(link)
    world = wp.quat_rotate(orientation, link / stretch)
    return wp.vec4(world[0], world[1], world[2], stretch)


@wp.kernel(enable_backward=False)
def render_cameras(scene: SceneView, lens: CameraLens, position: wp.array(dtype=wp.vec3),
                   orientation: wp.array(dtype=wp.quat), env: wp.array(dtype=int), own_boat: wp.array(dtype=int),
                   gate: wp.array(dtype=int), write_depth: int, write_rgb: int, depth: wp.array3d(dtype=float),
                   rgb: wp.array4d(dtype=wp.uint8)):
    """One thread a pixel, dim (cameras, height, width): camera c (link-frame pose ``position`` [m],
    ``orientation``) in environment ``env[c]``, blind to boat ``own_boat[c]`` (-1: none), writes its depth
    [m] into ``depth[c, v, u]`` (with ``write_depth``) and its sRGB colour into ``rgb[c, v, u]`` (with
    ``write_rgb``). Nothing is written unless ``gate[0]`` is 0 (a sensor that skips decisions)."""
    c, v, u = wp.tid()
    if gate[0] != 0:
        return
    origin = position[c]
    rotation = orientation[c]
    far = float(wp.inf)
    if not (_finite_vec3(origin) and _finite_quat(rotation)):
        if write_depth != 0:
            depth[c, v, u] = far
        if write_rgb != 0:
            for channel in range(3):
                rgb[c, v, u, channel] = wp.uint8(0)
        return
    ray = pixel_ray(lens, wp.normalize(rotation), u, v)
    direction = wp.vec3(ray[0], ray[1], ray[2])
    stretch = ray[3]
    hit = cast_ray(scene, env[c], origin, direction, 0.0, lens.max_range * stretch, own_boat[c])
    kind = hit.kind
    if not wp.isfinite(hit.t):
        kind = HIT_NONE
    if write_depth != 0:
        z = far
        if kind != HIT_NONE:
            z = hit.t / stretch
            if z < lens.min_range:
                z = -far
        depth[c, v, u] = z
    if write_rgb != 0:
        color = shade(scene, lens, direction, kind, hit.index, hit.part, hit.normal, hit.t)
        for channel in range(3):
            rgb[c, v, u, channel] = _srgb_channel(color[channel])


@wp.kernel(enable_backward=False)
def mounted_camera_poses(boat_position: wp.array(dtype=wp.vec3), boat_orientation: wp.array(dtype=wp.quat),
                         boats: wp.array(dtype=int), mount_position: wp.vec3, mount_orientation: wp.quat,
                         position: wp.array(dtype=wp.vec3), orientation: wp.array(dtype=wp.quat)):
    """Camera c rides boat ``boats[c]``: its link frame sits at ``mount_position`` [m] in the body frame,
    turned by ``mount_orientation`` (link -> body); writes its world pose."""
    c = wp.tid()
    boat = boats[c]
    rotation = boat_orientation[boat]
    position[c] = boat_position[boat] + wp.quat_rotate(rotation, mount_position)
    orientation[c] = rotation * mount_orientation


@wp.func
def look_at_rotation(eye: wp.vec3, target: wp.vec3) -> wp.quat:
    """Link frame -> world for a camera at ``eye`` looking at ``target``, level (no roll: its y axis
    horizontal). Straight up or down it faces the world's +x; eye = target gives the identity."""
    forward = target - eye
    if wp.length(forward) < 1.0e-9:
        return wp.quat_identity()
    forward = wp.normalize(forward)
    left = wp.cross(wp.vec3(0.0, 0.0, 1.0), forward)
    if wp.length(left) < 1.0e-6:
        left = wp.vec3(0.0, 1.0, 0.0)
    left = wp.normalize(left)
    up = wp.cross(forward, left)
    return wp.quat_from_matrix(wp.matrix_from_cols(forward, left, up))


@wp.kernel(enable_backward=False)
def look_at_poses(eye: wp.array(dtype=wp.vec3), target: wp.array(dtype=wp.vec3), position: wp.array(dtype=wp.vec3),
                  orientation: wp.array(dtype=wp.quat)):
    """Camera c at ``eye[c]`` [m] looking at ``target[c]`` [m] (:func:`look_at_rotation`)."""
    c = wp.tid()
    position[c] = eye[c]
    orientation[c] = look_at_rotation(eye[c], target[c])


@wp.kernel(enable_backward=False)
def follow_boat(boat_position: wp.array(dtype=wp.vec3), boat_orientation: wp.array(dtype=wp.quat), boat: int,
                behind: float, above: float, ahead: float, smoothing: float, primed: wp.array(dtype=int),
                eye: wp.array(dtype=wp.vec3), target: wp.array(dtype=wp.vec3)):
    """A chase camera (one thread): the eye ``behind`` [m] astern of boat ``boat`` along its heading and
    ``above`` [m] over it, looking at a point ``ahead`` [m] before its bow; eye and target move toward
    those places by the fraction ``smoothing`` (in (0, 1]) of the way each call, or jump there on the first
    call (``primed[0]`` 0, then set to 1). A boat whose pose is not finite leaves the camera where it is."""
    p = boat_position[boat]
    q = boat_orientation[boat]
    if not (_finite_vec3(p) and _finite_quat(q)):
        return
    bow = wp.quat_rotate(q, wp.vec3(1.0, 0.0, 0.0))
    heading = wp.vec3(bow[0], bow[1], 0.0)
    if wp.length(heading) < 1.0e-6:
        heading = wp.vec3(1.0, 0.0, 0.0)
    heading = wp.normalize(heading)
    wanted_eye = p - behind * heading + wp.vec3(0.0, 0.0, above)
    wanted_target = p + ahead * heading + wp.vec3(0.0, 0.0, 1.0)
    share = smoothing
    if primed[0] == 0:
        share = 1.0
        primed[0] = 1
    eye[0] = wp.lerp(eye[0], wanted_eye, share)
    target[0] = wp.lerp(target[0], wanted_target, share)


@wp.kernel(enable_backward=False)
def count_decisions(gate: wp.array(dtype=int), period: int):
    """``gate`` (1,) counts decisions modulo ``period``: a camera slower than the decisions renders when it is 0."""
    gate[0] = (gate[0] + 1) % period
