"""A picture of a written stage, drawn with matplotlib on the CPU, for a person without a USD viewer.

Everything is read back from the stage file (not from the simulation), so the picture shows what was
written: the ocean mesh seen from above and coloured by height, each boat's parts as filled outlines
(from both layouts: one prim per boat or point instancers) and its path over the whole stage, the
scene's objects under ``/World/Objects`` (buoys, piles: their outlines from above, in their colours), the
waypoints and the path through them, and the wind's direction.
"""

from __future__ import annotations

import math
import os

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure
from pxr import Usd, UsdGeom

from ..atomic_files import atomic_output
from .paths import (BOAT_ORIGINS_ATTRIBUTE, FLEET, OBJECTS, OCEAN, ROUTE_PATH, WAYPOINTS, WIND,
                    WIND_DIRECTION_ATTRIBUTE, WIND_SPEED_ATTRIBUTE)

__all__ = ["render_preview", "spread_time_code", "boat_tracks", "MAX_OUTLINED_BOATS"]

MAX_OUTLINED_BOATS = 256
"""Boats beyond this many are drawn as dots only (outlines cost time and are too small to see anyway)."""


def _convex_hull(points: np.ndarray) -> np.ndarray:
    """(K, 2) counter-clockwise convex hull of (P, 2) points (Andrew's monotone chain)."""
    unique = np.unique(np.round(points, 6), axis=0)  # sorted by x, then y
    if len(unique) < 3:
        return unique

    def half(sequence):
        chain = []
        for p in sequence:
            while len(chain) >= 2 and ((chain[-1][0] - chain[-2][0]) * (p[1] - chain[-2][1])
                                       - (chain[-1][1] - chain[-2][1]) * (p[0] - chain[-2][0])) <= 0.0:
                chain.pop()
            chain.append(p)
        return chain[:-1]

    return np.array(half(unique) + half(unique[::-1]))


def _extreme_points(points: np.ndarray, directions: int = 200) -> np.ndarray:
    """The points (P, 3) farthest along each of ``directions`` directions spread over the sphere: nearly
    every vertex of their convex hull, so the outline of any projection of them is that of all points."""
    i = np.arange(directions) + 0.5
    polar, azimuth = np.arccos(1.0 - 2.0 * i / directions), math.pi * (1.0 + 5.0**0.5) * i
    spread = np.stack([np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)], axis=1)
    return points[np.unique(np.argmax(points @ spread.T, axis=0))]


class _MeshPoints:
    """Each mesh's points at a time code, reduced to :func:`_extreme_points`; meshes that take their points
    from the same authored attribute (boats referencing one prototype) share one entry."""

    def __init__(self, time_code):
        self.time_code = time_code
        self._cache = {}

    def __call__(self, mesh: UsdGeom.Mesh) -> np.ndarray:
        attribute = mesh.GetPointsAttr()
        stack = attribute.GetPropertyStack(self.time_code)
        key = str(attribute.GetPath())
        if stack and not attribute.ValueMightBeTimeVarying():
            key = (stack[0].layer.identifier, str(stack[0].path))
        if key not in self._cache:
            self._cache[key] = _extreme_points(np.array(attribute.Get(self.time_code), dtype=np.float64))
        return self._cache[key]


def _transform(points: np.ndarray, matrix) -> np.ndarray:
    """Points (P, 3) through a Gf.Matrix4d (USD's row-vector convention: p' = p M)."""
    m = np.array(matrix, dtype=np.float64).reshape(4, 4)
    return points @ m[:3, :3] + m[3, :3]


def _mesh_color(mesh: UsdGeom.Mesh, time_code) -> tuple:
    primvar = UsdGeom.PrimvarsAPI(mesh).GetPrimvar("displayColor")
    value = primvar.Get(time_code) if primvar else None
    return tuple(value[0]) if value is not None and len(value) else (0.8, 0.8, 0.8)


def _meshes_below(prim):
    return [UsdGeom.Mesh(p) for p in Usd.PrimRange(prim) if p.IsA(UsdGeom.Mesh)]


def _boat_centres(stage, time_code, cache: UsdGeom.XformCache) -> np.ndarray:
    """(B, 2) every boat's origin in the world at ``time_code`` [m], from either layout (``cache`` at that
    time code)."""
    fleet = stage.GetPrimAtPath(FLEET)
    centres = []
    for child in fleet.GetChildren() if fleet else []:
        if child.IsA(UsdGeom.PointInstancer):
            positions = UsdGeom.PointInstancer(child).GetPositionsAttr().Get(time_code)
            marked = child.GetAttribute(BOAT_ORIGINS_ATTRIBUTE)
            if marked and marked.Get() and positions is not None:
                centres.append(_transform(np.array(positions, dtype=np.float64), cache.GetLocalToWorldTransform(child))
                               [:, :2])
        elif child.IsA(UsdGeom.Xformable):
            centres.append(_transform(np.zeros((1, 3)), cache.GetLocalToWorldTransform(child))[:, :2])
    return np.concatenate(centres) if centres else np.zeros((0, 2))


def boat_tracks(stage, samples: int = 400) -> tuple[np.ndarray, np.ndarray]:
    """(time codes (T,), boat origins (T, B, 2) [m]) at ``samples`` time codes spread evenly over the stage's
    time range, rounded to whole time codes (fewer where the range is shorter)."""
    start, end = stage.GetStartTimeCode(), stage.GetEndTimeCode()
    codes = np.unique(np.rint(np.linspace(start, end, int(max(1, min(samples, end - start + 1))))))
    cache = UsdGeom.XformCache(float(codes[0]))
    positions = []
    for code in codes:
        cache.SetTime(float(code))
        positions.append(_boat_centres(stage, float(code), cache))
    return codes, np.stack(positions)


def spread_time_code(stage_path) -> float:
    """The time code at which the stage's boats stand farthest apart (largest mean distance from their
    centroid, among :func:`boat_tracks`' samples): a frame that shows every boat, where the first one of a
    fleet starting together shows a heap. The start time code for a stage without boats."""
    stage = Usd.Stage.Open(os.fspath(stage_path))
    if stage is None:
        raise ValueError(f"spread_time_code: USD cannot open {os.fspath(stage_path)!r}")
    codes, positions = boat_tracks(stage)
    if positions.shape[1] == 0:
        return float(stage.GetStartTimeCode())
    spread = np.linalg.norm(positions - positions.mean(axis=1, keepdims=True), axis=2).mean(axis=1)
    return float(codes[int(np.argmax(spread))])


def _draw_tracks(axes, stage) -> None:
    """Every boat's path over the whole stage, a thin line each."""
    codes, positions = boat_tracks(stage)
    if len(codes) < 2 or positions.shape[1] == 0:
        return
    for boat in range(positions.shape[1]):
        axes.plot(positions[:, boat, 0], positions[:, boat, 1], "-", color="crimson", lw=0.7, alpha=0.6, zorder=6,
                  label="boat paths (whole run)" if boat == 0 else None)


def _boat_shapes(stage, time_code, cache: UsdGeom.XformCache):
    """(outlines [(K, 2) polygons], colours) of every boat part in the world at ``time_code``, from either
    layout (at most :data:`MAX_OUTLINED_BOATS` boats)."""
    mesh_points = _MeshPoints(time_code)
    fleet = stage.GetPrimAtPath(FLEET)
    outlines, colors, boats = [], [], 0
    if not fleet:
        return outlines, colors
    for child in fleet.GetChildren():
        if child.IsA(UsdGeom.PointInstancer):
            instancer = UsdGeom.PointInstancer(child)
            transforms = instancer.ComputeInstanceTransformsAtTime(time_code, time_code)
            to_world = cache.GetLocalToWorldTransform(child)
            for target in instancer.GetPrototypesRel().GetTargets():
                prototype = stage.GetPrimAtPath(target)
                # The instances' transforms include the prototype's own (USD's IncludeProtoXform).
                above = cache.GetLocalToWorldTransform(prototype).GetInverse()
                for mesh in _meshes_below(prototype):
                    local = _transform(mesh_points(mesh), cache.GetLocalToWorldTransform(mesh.GetPrim()) * above)
                    color = _mesh_color(mesh, time_code)
                    for transform in list(transforms)[:MAX_OUTLINED_BOATS]:
                        outlines.append(_convex_hull(_transform(local, transform * to_world)[:, :2]))
                        colors.append(color)
        elif child.IsA(UsdGeom.Xformable):
            boats += 1
            if boats > MAX_OUTLINED_BOATS:
                continue
            for mesh in _meshes_below(child):
                world = _transform(mesh_points(mesh), cache.GetLocalToWorldTransform(mesh.GetPrim()))
                outlines.append(_convex_hull(world[:, :2]))
                colors.append(_mesh_color(mesh, time_code))
    return outlines, colors


def _draw_ocean(figure, axes, stage, time_code) -> bool:
    mesh = UsdGeom.Mesh.Get(stage, OCEAN)
    points = mesh.GetPointsAttr().Get(time_code) if mesh else None
    if points is None or len(points) == 0:
        return False
    points = np.array(points, dtype=np.float64)
    counts = np.array(mesh.GetFaceVertexCountsAttr().Get())
    indices = np.array(mesh.GetFaceVertexIndicesAttr().Get())
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    triangles = np.array([(indices[s], indices[s + j], indices[s + j + 1])
                          for s, c in zip(starts, counts) for j in range(1, c - 1)])
    bound = max(float(np.abs(points[:, 2]).max()), 1e-3)
    image = axes.tripcolor(points[:, 0], points[:, 1], triangles, points[:, 2], shading="gouraud", cmap="Blues_r",
                           vmin=-1.2 * bound, vmax=1.2 * bound)
    figure.colorbar(image, ax=axes, shrink=0.8, label="surface height [m]")
    return True


def _draw_route(axes, stage, cache) -> None:
    waypoints = stage.GetPrimAtPath(WAYPOINTS)
    if waypoints:
        buoys = waypoints.GetChildren()
        marks = np.array([_transform(np.zeros((1, 3)), cache.GetLocalToWorldTransform(p))[0, :2] for p in buoys])
        if len(marks):
            axes.scatter(marks[:, 0], marks[:, 1], s=60, marker="o", facecolor="orange", edgecolor="black",
                         zorder=5, label="waypoints")
            # A route may visit one buoy several times (BCDACA): one label per place, its names joined.
            names_at: dict[tuple, list[str]] = {}
            for prim, (x, y) in zip(buoys, marks):
                names = names_at.setdefault((round(x, 1), round(y, 1)), [])
                name = prim.GetDisplayName() or prim.GetName()
                if name not in names:
                    names.append(name)
            for (x, y), names in names_at.items():
                axes.annotate(",".join(names), (x, y), textcoords="offset points", xytext=(6, 6), fontsize=10,
                              fontweight="bold", zorder=6)
    path = UsdGeom.BasisCurves.Get(stage, ROUTE_PATH)
    if path:
        points = np.array(path.GetPointsAttr().Get(), dtype=np.float64)
        axes.plot(points[:, 0], points[:, 1], "--", color="gold", lw=1.5, zorder=4, label="route")


def _draw_objects(axes, stage, time_code, cache: UsdGeom.XformCache) -> None:
    """The outline from above of every object under :data:`~ocean_warp.usd.paths.OBJECTS`, in its colour."""
    objects = stage.GetPrimAtPath(OBJECTS)
    if not objects:
        return
    mesh_points = _MeshPoints(time_code)
    outlines, colors = [], []
    for mesh in _meshes_below(objects):
        world = _transform(mesh_points(mesh), cache.GetLocalToWorldTransform(mesh.GetPrim()))
        outlines.append(_convex_hull(world[:, :2]))
        colors.append(_mesh_color(mesh, time_code))
    if outlines:
        axes.add_collection(PolyCollection(outlines, facecolors=colors, edgecolors="black", linewidths=0.3,
                                           zorder=6, label=f"{len(outlines)} objects"))


def _draw_wind(axes, stage) -> None:
    wind = stage.GetPrimAtPath(WIND)
    if not wind:
        return
    direction = wind.GetAttribute(WIND_DIRECTION_ATTRIBUTE).Get()
    speed = wind.GetAttribute(WIND_SPEED_ATTRIBUTE).Get()
    if direction is None:
        return
    centre, half = np.array([0.1, 0.9]), 0.06
    tip = centre + half * np.array([math.cos(direction), math.sin(direction)])
    tail = centre - half * np.array([math.cos(direction), math.sin(direction)])
    axes.annotate("", xy=tuple(tip), xytext=tuple(tail), xycoords="axes fraction",
                  arrowprops=dict(arrowstyle="-|>", color="red", lw=2.5), zorder=7)
    axes.text(centre[0], centre[1] - 0.09, f"wind {speed:.1f} m/s", transform=axes.transAxes, ha="center",
              color="red", fontsize=9, zorder=7)


def render_preview(stage_path, png_path=None, *, time_code: float | None = None, dpi: int = 120) -> str:
    """Draw the stage at ``stage_path`` at ``time_code`` (default: its first; :func:`spread_time_code` gives
    one where the boats stand apart) from above, with every boat's path over the whole stage, and write the
    picture to ``png_path`` (default: the stage's path with ``.png``), atomically; returns the PNG's path."""
    stage_path = os.fspath(stage_path)
    if not os.path.isfile(stage_path):
        raise ValueError(f"render_preview: no stage at {stage_path!r}")
    png_path = os.fspath(png_path) if png_path is not None else os.path.splitext(stage_path)[0] + ".png"
    stage = Usd.Stage.Open(stage_path)
    if stage is None:
        raise ValueError(f"render_preview: USD cannot open {stage_path!r}")
    code = stage.GetStartTimeCode() if time_code is None else float(time_code)
    cache = UsdGeom.XformCache(code)

    figure = Figure(figsize=(9, 8))
    FigureCanvasAgg(figure)
    axes = figure.add_subplot()
    has_ocean = _draw_ocean(figure, axes, stage, code)
    if not has_ocean:
        axes.set_facecolor((0.75, 0.85, 0.95))
    _draw_route(axes, stage, cache)
    _draw_objects(axes, stage, code, cache)
    _draw_tracks(axes, stage)
    outlines, colors = _boat_shapes(stage, code, cache)
    centres = _boat_centres(stage, code, cache)
    if outlines:
        axes.add_collection(PolyCollection(outlines, facecolors=colors, edgecolors="black", linewidths=0.4,
                                           zorder=8))
    if len(centres):
        axes.scatter(centres[:, 0], centres[:, 1], s=16, color="crimson", edgecolors="black", linewidths=0.4,
                     zorder=9, label=f"{len(centres)} boats")
    _draw_wind(axes, stage)
    axes.set_aspect("equal")
    axes.autoscale_view()
    axes.set_xlabel("x (east) [m]")
    axes.set_ylabel("y (north) [m]")
    seconds = code / stage.GetTimeCodesPerSecond()
    axes.set_title(f"{os.path.basename(stage_path)}: t = {seconds:.2f} s (time code {code:g})")
    if axes.get_legend_handles_labels()[0]:
        axes.legend(loc="lower right", fontsize=8)
    with atomic_output(png_path, suffix=".png") as temporary:
        figure.savefig(temporary, dpi=dpi)
    del stage
    return png_path
