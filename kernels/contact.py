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

__all__ = ["ContactModel", "contact_wrenches"]
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
        center = scene.object_position[k]
        size = scene.object_size[k]
        shape = scene.object_shape[k]
        boat_point = wp.vec3()
        other_point = wp.vec3()
        reach = model.radius
        if shape == SHAPE_SPHERE:
            boat_point = _closest_on_segment(a, b, center)
            other_point = center
            reach = model.radius + size[0]
        elif shape == SHAPE_CYLINDER:
            axis = wp.quat_rotate(scene.object_orientation[k], wp.vec3(0.0, 0.0, size[1]))
            pair = _closest_pair(a, b, center - axis, center + axis)
            boat_point = a + pair[0] * (b - a)
            other_point = center - axis + pair[1] * (2.0 * axis)
            reach = model.radius + size[0]
        else:
            if _far(center, scene.object_bound[k] + model.radius, a, b):
                continue
            best = float(1.0e30)
            rotation_k = scene.object_orientation[k]
            for i in range(AXIS_SAMPLES):
                sample = a + (float(i) / float(AXIS_SAMPLES - 1)) * (b - a)
                local = wp.quat_rotate_inv(rotation_k, sample - center)
                query = wp.mesh_query_point_no_sign(scene.object_mesh[k], local, model.radius)
                if query.result:
                    nearest = wp.mesh_eval_position(scene.object_mesh[k], query.face, query.u, query.v)
                    distance = wp.length(local - nearest)
                    if distance < best:
                        best = distance
                        boat_point = sample
                        other_point = center + wp.quat_rotate(rotation_k, nearest)
            if best > 1.0e29:
                continue
        gap = boat_point - other_point
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

