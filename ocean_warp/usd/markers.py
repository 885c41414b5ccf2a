"""Static scenery: the mission's waypoints as buoys, the path from the start through them and an arrow for
the wind, each with its material."""

from __future__ import annotations

import math

import numpy as np
from pxr import Gf, Kind, Sdf, Tf, Usd, UsdGeom, Vt

from ..meshes import arrow, tube
from .geometry import define_mesh
from .materials import LOOKS_BY_NAME, bind_look, define_look
from .paths import (ROUTE, ROUTE_INDICES_ATTRIBUTE, ROUTE_PATH, WAYPOINTS, WIND, WIND_DIRECTION_ATTRIBUTE,
                    WIND_SPEED_ATTRIBUTE)

__all__ = ["define_route", "define_wind_arrow", "wind_arrow_length", "route_places"]

SAME_PLACE = 1e-3
"""Waypoints closer than this [m] are one place (one buoy)."""


def _color(name: str) -> Vt.Vec3fArray:
    return Vt.Vec3fArray([Gf.Vec3f(*LOOKS_BY_NAME[name].color)])


def route_places(points: np.ndarray) -> tuple[np.ndarray, list[list[int]]]:
    """The distinct places (K, 3) [m] of ``points`` (R, 3), in order of first visit, and for each the
    indices of the points at it (within :data:`SAME_PLACE`)."""
    places, visits = [], []
    for i, point in enumerate(points):
        for k, place in enumerate(places):
            if np.linalg.norm(point - place) < SAME_PLACE:
                visits[k].append(i)
                break
        else:
            places.append(point)
            visits.append([i])
    return np.array(places).reshape(-1, 3), visits


def _define_buoy(stage, path: str, where, *, radius: float, height: float, name: str, indices: list[int]) -> None:
    """An Xform at ``where`` [m] holding ``Buoy_<name>``, a closed cylinder mesh of ``radius`` [m] and
    ``height`` [m] standing upright, a third of it below the still water, with the buoy material. (A mesh,
    not a UsdGeom.Cylinder: Blender 5.0's importer turns USD shapes into meshes without their material; it
    also merges the Xform with its one child, so the child's name is the one Blender shows.)"""
    marker = UsdGeom.Xform.Define(stage, path)
    marker.AddTranslateOp().Set(Gf.Vec3d(*map(float, where)))
    prim = marker.GetPrim()
    prim.SetDisplayName(name)
    prim.CreateAttribute(ROUTE_INDICES_ATTRIBUTE, Sdf.ValueTypeNames.IntArray, custom=True).Set(Vt.IntArray(indices))
    shape = tube((0.0, 0.0, -height / 3.0), (0.0, 0.0, 2.0 * height / 3.0), radius, sides=16)
    body = define_mesh(stage, f"{path}/{Tf.MakeValidIdentifier(f'Buoy_{name}')}", shape,
                       color=LOOKS_BY_NAME["Buoy"].color)
    bind_look(body.GetPrim(), define_look(stage, "Buoy"))


def define_route(stage, waypoints: np.ndarray, *, labels=None, start=None, start_label: str = "start",
                 buoy_radius: float = 0.5, buoy_height: float = 2.0, path_width: float = 0.2,
                 path: bool = True) -> None:
    """The course, a ``component`` model at :data:`~ocean_warp.usd.paths.ROUTE`:

    - buoys: one per distinct place of the waypoints (R, 2) or (R, 3) [m] (a route may visit a place
      several times, as BCDACA visits A and C twice), each a cylinder mesh of ``buoy_radius`` [m] standing
      ``buoy_height`` [m], a third of it below the still water; ``labels`` (R strings, e.g. the mission's
      letters; default: their order from 0) give the buoys' display names, the labels at one place joined
      by commas. ``start`` (2,) or (3,) [m], where the boats set off, gets a buoy too (named
      ``start_label``) unless a waypoint is there already.
    - the path (unless ``path`` is False): from ``start`` (if given) through the waypoints in order, a
      linear BasisCurves of ``path_width`` [m] just above the still water.
    """
    points = np.zeros((len(waypoints), 3))
    points[:, : waypoints.shape[1]] = waypoints
    names = [str(labels[i]) if labels is not None else str(i) for i in range(len(points))]
    route = UsdGeom.Xform.Define(stage, ROUTE)
    Usd.ModelAPI(route.GetPrim()).SetKind(Kind.Tokens.component)
    UsdGeom.Xform.Define(stage, WAYPOINTS)
    drawn = points
    if start is not None:
        origin = np.zeros(3)
        origin[: len(start)] = start
        drawn = np.concatenate([origin[None, :], points])
    places, visits = route_places(points)
    for k, (place, indices) in enumerate(zip(places, visits)):
        label = ",".join(dict.fromkeys(names[i] for i in indices))
        _define_buoy(stage, f"{WAYPOINTS}/Waypoint_{k:03d}", place, radius=buoy_radius, height=buoy_height,
                     name=label, indices=indices)
    if start is not None and not any(np.linalg.norm(drawn[0] - place) < SAME_PLACE for place in places):
        _define_buoy(stage, f"{WAYPOINTS}/Waypoint_{len(places):03d}", drawn[0], radius=buoy_radius,
                     height=buoy_height, name=start_label, indices=[])
    if len(drawn) < 2 or not path:
        return
    curve = UsdGeom.BasisCurves.Define(stage, ROUTE_PATH)
    curve.CreateTypeAttr(UsdGeom.Tokens.linear)
    curve.CreateWrapAttr(UsdGeom.Tokens.nonperiodic)
    lifted = (drawn + (0.0, 0.0, 0.05)).astype(np.float32)
    curve.CreatePointsAttr(Vt.Vec3fArray.FromNumpy(lifted))
    curve.CreateCurveVertexCountsAttr([len(drawn)])
    curve.CreateWidthsAttr([float(path_width)])
    curve.SetWidthsInterpolation(UsdGeom.Tokens.constant)
    half = 0.5 * path_width
    curve.CreateExtentAttr(Vt.Vec3fArray([Gf.Vec3f(*map(float, lifted.min(axis=0) - half)),
                                          Gf.Vec3f(*map(float, lifted.max(axis=0) + half))]))
    curve.CreateDisplayColorPrimvar(UsdGeom.Tokens.constant).Set(_color("Route"))
    bind_look(curve.GetPrim(), define_look(stage, "Route"))


def wind_arrow_length(speed: float) -> float:
    """Length of the wind arrow [m]: 2 m per m/s of wind, 2 m at least."""
    return max(2.0, 2.0 * float(speed))


def define_wind_arrow(stage, direction: float, speed: float, origin) -> None:
    """An arrow from ``origin`` (3,) [m] pointing where the wind blows towards (``direction`` [rad] from +x
    counter-clockwise), :func:`wind_arrow_length` long for ``speed`` [m/s]; the prim (a ``component``
    model) also carries the direction and speed as attributes
    (:data:`~ocean_warp.usd.paths.WIND_DIRECTION_ATTRIBUTE`, ...)."""
    length = wind_arrow_length(speed)
    holder = UsdGeom.Xform.Define(stage, WIND)
    holder.AddTranslateOp().Set(Gf.Vec3d(*map(float, origin)))
    holder.AddRotateZOp().Set(math.degrees(direction))
    prim = holder.GetPrim()
    Usd.ModelAPI(prim).SetKind(Kind.Tokens.component)
    prim.CreateAttribute(WIND_DIRECTION_ATTRIBUTE, Sdf.ValueTypeNames.Float, custom=True).Set(float(direction))
    prim.CreateAttribute(WIND_SPEED_ATTRIBUTE, Sdf.ValueTypeNames.Float, custom=True).Set(float(speed))
    mesh = define_mesh(stage, f"{WIND}/Arrow", arrow(length, shaft_radius=0.03 * length, head_length=0.25 * length,
                                                      head_radius=0.09 * length), color=LOOKS_BY_NAME["Wind"].color)
    bind_look(mesh.GetPrim(), define_look(stage, "Wind"))
