"""The buoyancy of a boat's appendages that its hull mesh leaves out (a keel fin and bulb, a rudder).

They are lifting surfaces to the rig's model, so the hull pass does not see them; what they displace still
carries part of the boat. A volume V that stays under water pushes up (world z) with rho g V at its centroid,
whatever the boat's attitude. As the centroid rises towards the surface (a boat on its beam ends, capsized or
airborne) the force fades linearly over a band of ``fade_height`` centred on the local water surface:

    F = rho g V clamp(1/2 + depth / fade_height, 0, 1),   depth = surface height - centroid height.
"""

from __future__ import annotations

import warp as wp

from .ocean_surface import OceanSurface, surface_height
from .spatial import vec6, wrench_at

__all__ = ["AppendageBuoyancy", "appendage_buoyancy"]


@wp.struct
class AppendageBuoyancy:
    volume: float
    """V [m^3]."""
    center: wp.vec3
    """Centroid of the volume, body frame [m]."""
    fade_height: float
    """Height of the band about the surface over which the force fades [m] (> 0)."""
    density: float
    """Water [kg/m^3]."""
    gravity: float
    """[m/s^2]"""


@wp.kernel(enable_backward=False)
def appendage_buoyancy(
    buoyancy: AppendageBuoyancy,
    surface: OceanSurface,
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    model_wrench: wp.array(dtype=vec6),
):
    """Add the appendages' buoyancy to each boat's model wrench (body frame, about the origin)."""
    boat = wp.tid()
    rotation = orientation[boat]
    world = position[boat] + wp.quat_rotate(rotation, buoyancy.center)
    depth = surface_height(surface, wp.vec2(world[0], world[1])) - world[2]
    share = wp.clamp(0.5 + depth / buoyancy.fade_height, 0.0, 1.0)
    lift = buoyancy.density * buoyancy.gravity * buoyancy.volume * share
    up_body = wp.quat_rotate_inv(rotation, wp.vec3(0.0, 0.0, 1.0))
    model_wrench[boat] = model_wrench[boat] + wrench_at(lift * up_body, buoyancy.center)
