"""The buoyancy of a boat's appendages that its hull mesh leaves out (a keel fin and bulb, a rudder).

They are lifting surfaces to the rig's model, so the mesh does not hold them; what they displace still carries
part of the boat, and the hull pass adds it to the water's wrench on the hull (``hull_forces``). A volume V that
stays under water pushes up (world z) with rho g V at its centroid, whatever the boat's attitude. As the centroid
rises towards the surface (a boat on its beam ends, capsized or airborne) the force fades linearly over a band of
``fade_height`` centred on the local water surface:

    F = rho g V clamp(1/2 + depth / fade_height, 0, 1),   depth = surface height - centroid height.
"""

from __future__ import annotations

import warp as wp

from .spatial import vec6, wrench_at

__all__ = ["appendage_wrench"]


@wp.func
def appendage_wrench(volume: float, center: wp.vec3, fade_height: float, surface_height: float, centroid_height: float,
                     rotation: wp.quat, density: float, gravity: float) -> vec6:
    """The appendages' buoyancy, body frame, about the body origin: ``volume`` [m^3] with its centroid at
    ``center`` [m, body frame] and ``centroid_height`` [m, world], under a surface at ``surface_height`` [m];
    ``fade_height`` [m] (> 0), water ``density`` [kg/m^3] and ``gravity`` [m/s^2]."""
    share = wp.clamp(0.5 + (surface_height - centroid_height) / fade_height, 0.0, 1.0)
    lift = density * gravity * volume * share
    up_body = wp.quat_rotate_inv(rotation, wp.vec3(0.0, 0.0, 1.0))
    return wrench_at(lift * up_body, center)
