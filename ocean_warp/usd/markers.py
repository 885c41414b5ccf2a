"""Static scenery: the mission's waypoints as buoys, the path through them and an arrow for the wind."""

from __future__ import annotations

import math

import numpy as np
from pxr import Gf, Sdf, UsdGeom, Vt

from .geometry import arrow, define_mesh, tube
from .paths import LIBRARY, ROUTE, ROUTE_PATH, WAYPOINTS, WIND, WIND_DIRECTION_ATTRIBUTE, WIND_SPEED_ATTRIBUTE

__all__ = ["define_route", "define_wind_arrow", "wind_arrow_length"]

BUOY = f"{LIBRARY}/Buoy"
BUOY_COLOR = (1.0, 0.45, 0.05)
PATH_COLOR = (1.0, 0.85, 0.1)
WIND_COLOR = (0.85, 0.1, 0.1)


def define_route(stage, waypoints: np.ndarray, *, labels=None, buoy_radius: float = 0.5,
                 buoy_height: float = 2.0, path_width: float = 0.2) -> None:
    """Waypoints (R, 2) or (R, 3) [m] as buoys (cylinders of ``buoy_radius`` [m] standing ``buoy_height``
    [m], a third of it below the still water) and the path through them in order as a linear BasisCurves
    of ``path_width`` [m] just above the still water. ``labels`` (R strings, e.g. the mission's letters)
    become the buoys' display names; default: their order from 0."""
    points = np.zeros((len(waypoints), 3))
    points[:, : waypoints.shape[1]] = waypoints
    define_mesh(stage, BUOY, tube((0.0, 0.0, -buoy_height / 3.0), (0.0, 0.0, 2.0 * buoy_height / 3.0), buoy_radius,
                                  sides=16), color=BUOY_COLOR)
    UsdGeom.Xform.Define(stage, ROUTE)
    UsdGeom.Xform.Define(stage, WAYPOINTS)
    for i, point in enumerate(points):
        marker = UsdGeom.Xform.Define(stage, f"{WAYPOINTS}/Waypoint_{i:03d}")
        marker.AddTranslateOp().Set(Gf.Vec3d(*map(float, point)))
        marker.GetPrim().GetReferences().AddInternalReference(BUOY)
        marker.GetPrim().SetDisplayName(str(labels[i]) if labels is not None else str(i))
    if len(points) < 2:
        return
    curve = UsdGeom.BasisCurves.Define(stage, ROUTE_PATH)
    curve.CreateTypeAttr(UsdGeom.Tokens.linear)
    curve.CreateWrapAttr(UsdGeom.Tokens.nonperiodic)
    lifted = (points + (0.0, 0.0, 0.05)).astype(np.float32)
    curve.CreatePointsAttr(Vt.Vec3fArray.FromNumpy(lifted))
    curve.CreateCurveVertexCountsAttr([len(points)])
    curve.CreateWidthsAttr([float(path_width)])
    curve.SetWidthsInterpolation(UsdGeom.Tokens.constant)
    half = 0.5 * path_width
    curve.CreateExtentAttr(Vt.Vec3fArray([Gf.Vec3f(*map(float, lifted.min(axis=0) - half)),
                                          Gf.Vec3f(*map(float, lifted.max(axis=0) + half))]))
    curve.CreateDisplayColorPrimvar(UsdGeom.Tokens.constant).Set(Vt.Vec3fArray([Gf.Vec3f(*PATH_COLOR)]))


def wind_arrow_length(speed: float) -> float:
    """Length of the wind arrow [m]: 2 m per m/s of wind, 2 m at least."""
    return max(2.0, 2.0 * float(speed))


def define_wind_arrow(stage, direction: float, speed: float, origin) -> None:
    """An arrow from ``origin`` (3,) [m] pointing where the wind blows towards (``direction`` [rad] from +x
    counter-clockwise), :func:`wind_arrow_length` long for ``speed`` [m/s]; the prim also carries the
    direction and speed as attributes (:data:`~ocean_warp.usd.paths.WIND_DIRECTION_ATTRIBUTE`, ...)."""
    length = wind_arrow_length(speed)
    holder = UsdGeom.Xform.Define(stage, WIND)
    holder.AddTranslateOp().Set(Gf.Vec3d(*map(float, origin)))
    holder.AddRotateZOp().Set(math.degrees(direction))
    prim = holder.GetPrim()
    prim.CreateAttribute(WIND_DIRECTION_ATTRIBUTE, Sdf.ValueTypeNames.Float, custom=True).Set(float(direction))
    prim.CreateAttribute(WIND_SPEED_ATTRIBUTE, Sdf.ValueTypeNames.Float, custom=True).Set(float(speed))
    define_mesh(stage, f"{WIND}/Arrow", arrow(length, shaft_radius=0.03 * length, head_length=0.25 * length,
                                               head_radius=0.09 * length), color=WIND_COLOR)
