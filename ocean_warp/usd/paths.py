"""Where the exporter puts things in a stage: one layout, shared by the writers and the preview."""

from __future__ import annotations

__all__ = ["WORLD", "OCEAN", "FLEET", "ROUTE", "OBJECTS", "LIDAR", "WAYPOINTS", "ROUTE_PATH", "WIND", "LOOKS", "CAMERA",
           "LIGHTS", "SUN", "SKY", "LIBRARY", "OCEAN_REST", "BOAT_COUNT_ATTRIBUTE", "BOAT_ORIGINS_ATTRIBUTE",
           "WIND_DIRECTION_ATTRIBUTE", "WIND_SPEED_ATTRIBUTE", "ROUTE_INDICES_ATTRIBUTE", "boat_path"]

WORLD = "/World"
"""The default prim, a ``group`` model: everything a viewer shows lies below it."""
OCEAN = "/World/Ocean"
"""The ocean surface (Mesh, a ``component`` model)."""
FLEET = "/World/Fleet"
"""The boats (an ``assembly`` model): ``Boat_0000``... (one Xform each, a ``component`` model, one child per part
of the vessel) or one point instancer per part, named as the part's prim."""
ROUTE = "/World/Route"
"""The course (a ``component`` model): the buoys and the path."""
WAYPOINTS = "/World/Route/Waypoints"
"""One buoy per place the route visits, ``Waypoint_000``... in route order of first visit: an Xform at the
place, its display name the place's label(s), holding the buoy's mesh ``Buoy_<label>``."""
ROUTE_PATH = "/World/Route/Path"
"""The mission path from the start through the waypoints (BasisCurves, linear)."""
OBJECTS = "/World/Objects"
"""The scene's objects (ocean_warp.perception.SceneObject): ``Object_000``... (an Xform each, a ``component``
model, holding its mesh ``Shape`` with a material of its colour, ``Looks/Object_RRGGBB``; its display name
the recorder's ``object_labels`` entry, e.g. "boat 3 pile 2"); a floating one's pose is time-sampled."""
LIDAR = "/World/Lidar"
"""Lidar returns (Points, time-sampled): every hit point of the recorded scans [m], world frame."""
WIND = "/World/Wind"
"""The wind arrow (an Xform holding a Mesh, a ``component`` model), pointing where the wind blows towards."""
LOOKS = "/World/Looks"
"""The materials (UsdPreviewSurface), one per look: ``Hull``, ``Sail``, ``Ocean``..."""
CAMERA = "/World/Camera"
"""A camera framing the area the route and the boats cover, from the south and above."""
LIGHTS = "/World/Lights"
SUN = "/World/Lights/Sun"
"""A DistantLight, the sun."""
SKY = "/World/Lights/Sky"
"""A DomeLight of uniform sky colour."""
LIBRARY = "/Library"
"""A ``class`` prim (not drawn) holding the geometry that boats and instancers reference: ``/Library/<vessel>``,
one Xform per part (``ocean_warp.usd.vessel_prims``)."""
OCEAN_REST = "/Library/OceanRest"
"""With a looping ocean: the ocean mesh at the first frame (topology, points, extent, colours), which the
ocean references, so that its attributes have a value outside the value clips (at the default time); the
clips, a stronger opinion, give the animation."""

BOAT_COUNT_ATTRIBUTE = "oceanWarp:boatCount"
"""int on :data:`FLEET`: the number of boats recorded."""
BOAT_ORIGINS_ATTRIBUTE = "oceanWarp:boatOrigins"
"""bool on the point instancer (of a fixed part) whose instances stand at the boats' origins."""
WIND_DIRECTION_ATTRIBUTE = "oceanWarp:windDirection"
"""float on :data:`WIND`: the direction the wind blows towards [rad], from +x counter-clockwise."""
WIND_SPEED_ATTRIBUTE = "oceanWarp:windSpeed"
"""float on :data:`WIND`: the wind speed [m/s]."""
ROUTE_INDICES_ATTRIBUTE = "oceanWarp:routeIndices"
"""int[] on each waypoint buoy: the places in the route (from 0) that visit it."""


def boat_path(index: int) -> str:
    """The Xform of boat ``index`` in the one-prim-per-boat layout."""
    return f"{FLEET}/Boat_{index:04d}"
