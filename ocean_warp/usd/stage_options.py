"""What a :class:`~ocean_warp.usd.StageRecorder` draws, in option groups: the ocean (:class:`OceanDrawing`),
the fleet (:class:`FleetDrawing`), the route (:class:`RouteDrawing`) and the wind arrow (:class:`WindArrow`).

Each group is a frozen dataclass that checks its fields when it is made and raises ``ValueError`` naming
the field (``OceanDrawing.resolution``, ...). Checked fields are stored normalised: numbers as ``float``
or ``int``, coordinates as tuples of floats.

Example::

    StageRecorder("out/run.usdc", fps=5.0, ocean=OceanDrawing(ocean, resolution=96, loop=True),
                  fleet=FleetDrawing(16, vessel=vessel), route=RouteDrawing(waypoints, labels="BCDACA"),
                  wind=WindArrow(math.pi / 2, speed=6.0))
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from ..ocean import Ocean
from ..validation import require_finite, require_int_in_range, require_non_negative
from ..vessel import require_vessel
from .ocean_mesh import check_extent

__all__ = ["OceanDrawing", "FleetDrawing", "RouteDrawing", "WindArrow"]


def _require_loop(subject: str, ocean: Ocean) -> float:
    """The loop period [s] of ``ocean``; ValueError saying that ``subject`` needs one when it has none."""
    if ocean.config.loop_period is None:
        raise ValueError(f"{subject} needs an ocean built with OceanConfig.loop_period set (its "
                         "frequencies are then multiples of 2 pi / loop_period, so the sea repeats exactly)")
    return ocean.config.loop_period


def _finite_rows(owner: str, name: str, value, widths: tuple[int, ...]) -> np.ndarray:
    """``value`` as a float64 array of one or more rows of one of ``widths`` finite numbers, else ValueError."""
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        array = np.zeros((0,))
    if array.ndim != 2 or array.shape[1] not in widths or len(array) == 0 or not np.all(np.isfinite(array)):
        raise ValueError(f"{owner}.{name} must be finite rows of {' or '.join(map(str, widths))} coordinates [m], "
                         f"got {value!r}")
    return array


def _require_flag(owner: str, name: str, flag) -> bool:
    if not isinstance(flag, bool):
        raise ValueError(f"{owner}.{name} must be True or False, got {flag!r}")
    return flag


def _point(array: np.ndarray) -> tuple[float, ...]:
    return tuple(float(v) for v in array)


def _set(group, name: str, value) -> None:
    """Store the checked, normalised ``value`` in a frozen dataclass (from its ``__post_init__``)."""
    object.__setattr__(group, name, value)


@dataclasses.dataclass(frozen=True)
class OceanDrawing:
    """The ocean surface a stage shows: a mesh per frame, or one seamless loop that the stage repeats."""

    ocean: Ocean
    """The :class:`~ocean_warp.ocean.Ocean` to draw. Each frame evaluates it at the frame's time (its
    clock is left as it was)."""
    resolution: int = 64
    """At most this many mesh vertices along either side of the ocean's extent; the spacing is a whole
    number of the ocean's grid cells (the vertices are grid nodes). Each frame costs 12 bytes per vertex
    for the points, as much again for colours and for normals."""
    extent: tuple[float, float, float, float] | None = None
    """(xmin, xmax, ymin, ymax) [m] of the ocean mesh (the patch is periodic and tiled to cover it). None:
    the route and the boats' positions, plus ``margin`` [m]: the positions at the first frame for a mesh
    per frame (written as it comes), every recorded position for a loop (written when the recorder
    closes), so that a loop's ocean lies under every boat wherever it sailed."""
    margin: float = 20.0
    """Water shown beyond the route and the boats [m] when ``extent`` is None (1 m at least is used)."""
    normals: bool = False
    """Write the mesh's vertex normals."""
    colors: bool = True
    """Write a displayColor by height (deep blue to foam)."""
    loop: bool = False
    """Write one seamless loop of the ocean (a sibling file, :func:`~ocean_warp.usd.loop_path_for`) that
    the stage repeats over the whole recording with value clips, instead of a mesh per frame. Needs an
    ocean with ``OceanConfig.loop_period``; the boats, simulated on that same ocean, ride exactly the
    surface shown. Worth it when the recording is much longer than the loop."""

    def __post_init__(self):
        owner = type(self).__name__
        if not isinstance(self.ocean, Ocean):
            raise ValueError(f"{owner}.ocean must be an Ocean, got {type(self.ocean).__name__}")
        _set(self, "resolution", require_int_in_range(owner, "resolution", self.resolution, 2, 4096))
        if self.extent is not None:
            _set(self, "extent", check_extent(owner, self.extent))
        _set(self, "margin", require_non_negative(owner, "margin", self.margin, unit=" [m]"))
        for name in ("normals", "colors", "loop"):
            _require_flag(owner, name, getattr(self, name))
        if self.loop:
            _require_loop(f"{owner}.loop", self.ocean)


@dataclasses.dataclass(frozen=True)
class FleetDrawing:
    """The boats a stage shows: ``count`` boats of ``vessel``, each part posed and turned at every recorded
    frame."""

    count: int = 0
    """Number of boats (0: none)."""
    instanced: bool | None = None
    """One point instancer per part (True, ``ocean_warp.usd.vessel_instancers``) or one prim per boat (False,
    ``ocean_warp.usd.vessel_prims``); None picks instancers above :data:`~ocean_warp.usd.INSTANCING_THRESHOLD`
    boats."""
    vessel: Any = None
    """The :class:`~ocean_warp.vessel.Vessel` the boats are (``EBoatVessel(config)``, ``Wamv()``...), drawn
    with its ``parts()`` and its ``part_scaling()``; needed when ``count`` > 0."""

    def __post_init__(self):
        owner = type(self).__name__
        _set(self, "count", require_int_in_range(owner, "count", self.count, 0, 2**24))
        if self.instanced is not None and not isinstance(self.instanced, bool):
            raise ValueError(f"{owner}.instanced must be True, False or None, got {self.instanced!r}")
        if self.vessel is not None:
            require_vessel(f"{owner}.vessel", self.vessel)
        elif self.count:
            raise ValueError(f"{owner}.vessel: {self.count} boats need the vessel they are (its parts are what the "
                             "stage draws), e.g. FleetDrawing(count, vessel=EBoatVessel(config))")


@dataclasses.dataclass(frozen=True)
class RouteDrawing:
    """The course a stage shows: a buoy per waypoint and the path from the start through them."""

    points: tuple[tuple[float, ...], ...]
    """Waypoints (R, 2) or (R, 3) [m], drawn as buoys and the path through them (stored as R tuples)."""
    labels: tuple[str, ...] | None = None
    """Their R names (e.g. ``"BCDACA"``), the buoys' display names (stored as a tuple of strings); None:
    their places in the route, from 0."""
    start: tuple[float, ...] | None = None
    """(2,) or (3,) [m]: where the boats set off, the first point of the path (e.g. A for the BCDACA
    mission); None: the path starts at the first waypoint."""
    path: bool = True
    """Draw the path through the waypoints; False: the buoys alone (waypoints that are no route, e.g. each
    boat's own waypoint in a single-waypoint task)."""

    def __post_init__(self):
        owner = type(self).__name__
        points = _finite_rows(owner, "points", self.points, (2, 3))
        _set(self, "points", tuple(_point(row) for row in points))
        if self.labels is not None:
            if len(self.labels) != len(points):
                raise ValueError(f"{owner}.labels must name each of the route's {len(points)} waypoints, "
                                 f"got {len(self.labels)}")
            _set(self, "labels", tuple(str(label) for label in self.labels))
        if self.start is not None:
            _set(self, "start", _point(_finite_rows(owner, "start", [self.start], (2, 3))[0]))
        _require_flag(owner, "path", self.path)


@dataclasses.dataclass(frozen=True)
class WindArrow:
    """The wind arrow a stage shows, with the wind's direction and speed as attributes."""

    direction: float
    """Direction of the wind [rad, where the wind blows towards], counter-clockwise from +x."""
    speed: float = 5.0
    """Wind speed [m/s] (>= 0); the arrow is 2 m long per m/s, 2 m at least."""
    origin: tuple[float, float, float] | None = None
    """(3,) [m]: where the arrow starts; None: a corner of the ocean, 8 m up: (xmin, ymax) of
    ``OceanDrawing.extent``, else of the route and the boats at the first frame plus the margin, else of the
    ocean's tile; (0, 0, 8) when there is none of these."""

    def __post_init__(self):
        owner = type(self).__name__
        _set(self, "direction", require_finite(owner, "direction", self.direction))
        _set(self, "speed", require_non_negative(owner, "speed", self.speed, unit=" [m/s]"))
        if self.origin is not None:
            _set(self, "origin", _point(_finite_rows(owner, "origin", [self.origin], (3,))[0]))
