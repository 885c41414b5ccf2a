"""Where the exporter puts things in a stage: one layout, shared by the writers and the preview."""

from __future__ import annotations

__all__ = ["WORLD", "OCEAN", "FLEET", "ROUTE", "WAYPOINTS", "ROUTE_PATH", "WIND", "LIBRARY", "BOAT_PROTOTYPE",
           "BOAT_COUNT_ATTRIBUTE", "WIND_DIRECTION_ATTRIBUTE", "WIND_SPEED_ATTRIBUTE", "boat_path"]

WORLD = "/World"
"""The default prim: everything a viewer shows lies below it."""
OCEAN = "/World/Ocean"
"""The ocean surface (Mesh)."""
FLEET = "/World/Fleet"
"""The boats: ``Boat_0000``... (one Xform each) or the instancers ``Bodies``, ``Booms`` and ``Rudders``."""
ROUTE = "/World/Route"
WAYPOINTS = "/World/Route/Waypoints"
"""One marker buoy per waypoint, ``Waypoint_000``..."""
ROUTE_PATH = "/World/Route/Path"
"""The mission path through the waypoints (BasisCurves, linear)."""
WIND = "/World/Wind"
"""The wind arrow (an Xform holding a Mesh), pointing where the wind blows towards."""
LIBRARY = "/Library"
"""A ``class`` prim (not drawn) holding the geometry that boats and instancers reference."""
BOAT_PROTOTYPE = "/Library/EBoat"
"""The E-Boat's parts: ``Body`` (hull, keel, mast), ``Boom`` (spar and sail) and ``Rudder`` (blade)."""

BOAT_COUNT_ATTRIBUTE = "oceanWarp:boatCount"
"""int on :data:`FLEET`: the number of boats recorded."""
WIND_DIRECTION_ATTRIBUTE = "oceanWarp:windDirection"
"""float on :data:`WIND`: the direction the wind blows towards [rad], from +x counter-clockwise."""
WIND_SPEED_ATTRIBUTE = "oceanWarp:windSpeed"
"""float on :data:`WIND`: the wind speed [m/s]."""


def boat_path(index: int) -> str:
    """The Xform of boat ``index`` in the one-prim-per-boat layout."""
    return f"{FLEET}/Boat_{index:04d}"
