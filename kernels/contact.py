"""Contact between a boat and the objects and other boats of its environment, one thread per boat.

Every boat is a horizontal capsule in its body frame (the segment from ``stern`` to ``bow`` at the height of
the hull's sides, swept by ``radius``: its half beam). Against a sphere the capsule's nearest point is
exact; against an upright cylinder (a pile) and against another boat's capsule it is the nearest pair of
points of two segments; against a mesh object it is the nearest point of the mesh to the capsule's axis,
sampled at ``AXIS_SAMPLES`` points. Where they overlap by p > 0 the boat is flagged ``STATUS_COLLIDED`` and,
with a stiffness, pushed out by a penalty force k p + c max(-v_n, 0) along the contact normal, applied at
the contact point (added to the simulator's body-frame ``model_wrench`` about the origin). Objects do not
move (a buoy rides the waves kinematically); two boats push each other equally and oppositely (each thread
computes its own side of the pair from the same overlap).
"""

from __future__ import annotations

import warp as wp

from .ray_cast import SHAPE_CYLINDER, SHAPE_SPHERE, SceneView
from .rigid_body import STATUS_COLLIDED, STATUS_NONFINITE
from .spatial import point_velocity, vec6

__all__ = ["ContactModel", "ObjectNearness", "contact_wrenches", "object_clearances"]
AXIS_SAMPLES = wp.constant(7)
"""Points along the capsule's axis where a mesh object's nearest point is looked up."""


@wp.struct
class ContactModel:
    """The boats' capsule and the contact force's law."""

    stern: wp.vec3
    """One end of the capsule's axis, body frame [m]."""
    bow: wp.vec3
    """The other end [m]."""
    radius: float
    """[m]"""
    stiffness: float
    """k [N/m] of the penalty force (0: contacts are flagged, not pushed)."""
    damping: float
    """c [N s/m] on the approach speed."""


@wp.func
def _closest_on_segment(a: wp.vec3, b: wp.vec3, p: wp.vec3) -> wp.vec3:
    ab = b - a
    t = wp.clamp(wp.dot(p - a, ab) / wp.max(wp.dot(ab, ab), 1.0e-12), 0.0, 1.0)
    return a + t * ab


@wp.func
def _closest_pair(p1: wp.vec3, q1: wp.vec3, p2: wp.vec3, q2: wp.vec3) -> wp.vec2:
    """Parameters (s on p1-q1, t on p2-q2), each in [0, 1], of the nearest points of two segments."""
    d1 = q1 - p1
    d2 = q2 - p2
    r = p1 - p2
    a = wp.dot(d1, d1)
    e = wp.dot(d2, d2)
    f = wp.dot(d2, r)
    s = float(0.0)
    t = float(0.0)
    if a <= 1.0e-12 and e <= 1.0e-12:
        return wp.vec2(0.0, 0.0)
    if a <= 1.0e-12:
        t = wp.clamp(f / e, 0.0, 1.0)
    else:
        c = wp.dot(d1, r)
        if e <= 1.0e-12:
            s = wp.clamp(-c / a, 0.0, 1.0)
        else:
            b = wp.dot(d1, d2)
            denom = a * e - b * b
            if denom > 1.0e-12:
                s = wp.clamp((b * f - c * e) / denom, 0.0, 1.0)
            t = (b * s + f) / e
            if t < 0.0:
                t = 0.0
                s = wp.clamp(-c / a, 0.0, 1.0)
            elif t > 1.0:
                t = 1.0
                s = wp.clamp((b - c) / a, 0.0, 1.0)
    return wp.vec2(s, t)


@wp.func
def _push(model: ContactModel, boat_point: wp.vec3, normal: wp.vec3, depth: float, position: wp.vec3,
          rotation: wp.quat, nu: vec6) -> vec6:
    """Body-frame wrench about the origin of the penalty force on the boat at world ``boat_point``, pushed
    along world ``normal`` (out of the other body) by an overlap ``depth`` [m]."""
    local_point = wp.quat_rotate_inv(rotation, boat_point - position)
    local_normal = wp.quat_rotate_inv(rotation, normal)
    approach = wp.dot(point_velocity(nu, local_point), local_normal)
    magnitude = model.stiffness * depth + model.damping * wp.max(-approach, 0.0)
    force = magnitude * local_normal
    moment = wp.cross(local_point, force)
    return vec6(force[0], force[1], force[2], moment[0], moment[1], moment[2])


@wp.func
def _far(center: wp.vec3, reach: float, a: wp.vec3, b: wp.vec3) -> bool:
    closest = _closest_on_segment(a, b, center)
    return wp.length(center - closest) > reach


@wp.struct
class ObjectNearness:
    """The nearest points of a boat's capsule axis and an object (``_nearest_to_object``)."""

    boat_point: wp.vec3
    """On the capsule's axis, world [m]."""
    other_point: wp.vec3
    """On the object: a sphere's centre, a point of a pile's axis, a point of a mesh's surface [m]."""
    reach: float
    """Centre distance at which they touch [m]: the capsule's radius plus a sphere's or pile's radius (plus
    nothing for a mesh, whose point is on its surface)."""
    found: int
    """0: a mesh object farther than the search distance (the points mean nothing)."""


@wp.func
def _nearest_to_object(scene: SceneView, model: ContactModel, k: int, a: wp.vec3, b: wp.vec3,
                       search: float) -> ObjectNearness:
    """Object ``k`` against the capsule axis a-b: exact for a sphere and a pile; for a mesh, its nearest
    point to ``AXIS_SAMPLES`` points of the axis, looked up within ``search`` [m] of the axis."""
    near = ObjectNearness()
    near.found = 1
    center = scene.object_position[k]
    size = scene.object_size[k]
    shape = scene.object_shape[k]
    if shape == SHAPE_SPHERE:
        near.boat_point = _closest_on_segment(a, b, center)
        near.other_point = center
        near.reach = model.radius + size[0]
    elif shape == SHAPE_CYLINDER:
        axis = wp.quat_rotate(scene.object_orientation[k], wp.vec3(0.0, 0.0, size[1]))
        pair = _closest_pair(a, b, center - axis, center + axis)
        near.boat_point = a + pair[0] * (b - a)
        near.other_point = center - axis + pair[1] * (2.0 * axis)
        near.reach = model.radius + size[0]
    else:
        near.reach = model.radius
        near.found = 0
        if _far(center, scene.object_bound[k] + search, a, b):
            return near
        best = float(1.0e30)
        rotation_k = scene.object_orientation[k]
        for i in range(AXIS_SAMPLES):
            sample = a + (float(i) / float(AXIS_SAMPLES - 1)) * (b - a)
            local = wp.quat_rotate_inv(rotation_k, sample - center)
            query = wp.mesh_query_point_no_sign(scene.object_mesh[k], local, search)
            if query.result:
                nearest = wp.mesh_eval_position(scene.object_mesh[k], query.face, query.u, query.v)
                distance = wp.length(local - nearest)
                if distance < best:
                    best = distance
                    near.boat_point = sample
                    near.other_point = center + wp.quat_rotate(rotation_k, nearest)
                    near.found = 1
    return near


@wp.kernel(enable_backward=False)
def contact_wrenches(scene: SceneView, model: ContactModel, boat_env: wp.array(dtype=int),
                     velocity: wp.array(dtype=vec6), status: wp.array(dtype=int),
                     model_wrench: wp.array(dtype=vec6), contacts: wp.array(dtype=int)):
    """One thread per boat: its overlaps with the objects and boats of its environment flag it and (with a
    stiffness) add the penalty wrench to ``model_wrench``; ``contacts`` gets how many bodies it touches."""
    boat = wp.tid()
    env = boat_env[boat]
    contacts[boat] = 0
    if env < 0 or (status[boat] & STATUS_NONFINITE) != 0:
        return
    position = scene.boat_position[boat]
    rotation = scene.boat_orientation[boat]
    nu = velocity[boat]
    a = position + wp.quat_rotate(rotation, model.stern)
    b = position + wp.quat_rotate(rotation, model.bow)
    total = vec6()
    touching = int(0)
    for k in range(scene.object_start[env], scene.object_start[env + 1]):
        near = _nearest_to_object(scene, model, k, a, b, model.radius)
        if near.found == 0:
            continue
        boat_point = near.boat_point
        reach = near.reach
        gap = boat_point - near.other_point
        distance = wp.length(gap)
        depth = reach - distance
        if depth > 0.0 and distance > 1.0e-9:
            normal = gap / distance
            total = total + _push(model, boat_point - model.radius * normal, normal, depth, position, rotation, nu)
            touching = touching + 1
    for slot in range(scene.boat_start[env], scene.boat_start[env + 1]):
        other = scene.boat_list[slot]
        if other == boat:
            continue
        other_position = scene.boat_position[other]
        other_rotation = scene.boat_orientation[other]
        c = other_position + wp.quat_rotate(other_rotation, model.stern)
        d = other_position + wp.quat_rotate(other_rotation, model.bow)
        pair = _closest_pair(a, b, c, d)
        boat_point = a + pair[0] * (b - a)
        gap = boat_point - (c + pair[1] * (d - c))
        distance = wp.length(gap)
        depth = 2.0 * model.radius - distance
        if depth > 0.0 and distance > 1.0e-9:
            normal = gap / distance
            total = total + _push(model, boat_point - model.radius * normal, normal, depth, position, rotation, nu)
            touching = touching + 1
    contacts[boat] = touching
    if touching > 0:
        status[boat] = status[boat] | STATUS_COLLIDED
        model_wrench[boat] = model_wrench[boat] + total



@wp.kernel(enable_backward=False)
def object_clearances(scene: SceneView, model: ContactModel, boat_env: wp.array(dtype=int), search: float,
                      clearance: wp.array(dtype=float)):
    """One thread per boat: the gap between its capsule and the nearest object of its environment [m] (0 when
    they overlap; ``search`` where none is nearer than that, or the boat is in no environment)."""
    boat = wp.tid()
    env = boat_env[boat]
    nearest = search
    if env >= 0:
        position = scene.boat_position[boat]
        rotation = scene.boat_orientation[boat]
        a = position + wp.quat_rotate(rotation, model.stern)
        b = position + wp.quat_rotate(rotation, model.bow)
        for k in range(scene.object_start[env], scene.object_start[env + 1]):
            near = _nearest_to_object(scene, model, k, a, b, search + model.radius)
            if near.found != 0:
                gap = wp.length(near.boat_point - near.other_point) - near.reach
                nearest = wp.min(nearest, wp.max(gap, 0.0))
    clearance[boat] = nearest
