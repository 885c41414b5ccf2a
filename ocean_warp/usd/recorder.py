"""Record a simulation into a USD stage while it runs: the ocean surface, the boats of any vessel with their
moving parts (``ocean_warp.vessel``), the route and the wind; and write one seamless loop of an ocean on its own.

Example::

    from ocean_warp.usd import OceanDrawing, RouteDrawing, StageRecorder, record_vessel

    vessel = EBoatVessel(config)                         # any ocean_warp.vessel.Vessel
    sim = vessel.simulator(16, device="cuda:0")
    every = 4                                            # record every 4th step: 5 frames/s at dt 0.05 s
    with StageRecorder.for_vessel("out/run.usdc", vessel, sim, fps=1 / (every * sim.config.dt),
                                  ocean=OceanDrawing(sim.ocean, margin=30.0),
                                  route=RouteDrawing(waypoints)) as recorder:
        for step in range(2400):
            if step % every == 0:
                record_vessel(recorder, sim)
            sim.step()
    # out/run.usdc appears only here, complete.

Layout of the stage: ``ocean_warp.usd.paths``. Time code = time [s] x time_codes_per_second (default 24,
the stage's timeCodesPerSecond and framesPerSecond), so a viewer playing at the stage's frame rate shows
one second of simulation in one second, whatever the rate the frames were recorded at (``fps``). What
the stage shows is given in option groups: :mod:`ocean_warp.usd.stage_options`.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence

import numpy as np
from pxr import Sdf, Usd

from ..ocean import Ocean
from ..perception.scene import SceneObject
from ..validation import require_int_in_range, require_positive
from ..vessel import part_scaling
from .markers import define_route, define_wind_arrow
from .ocean_mesh import OceanLattice, OceanMeshWriter, check_extent, define_referenced_ocean, ocean_fields_at
from .playback import TIME_CODES_PER_SECOND
from .paths import LIBRARY, OCEAN, OCEAN_REST
from .stage_file import StageFile
from .scene_prims import LidarPointsWriter, ObjectsWriter
from .stage_options import FleetDrawing, OceanDrawing, RouteDrawing, WindArrow, _require_loop
from .vessel_instancers import InstancedVesselWriter
from .vessel_prims import VesselFleetWriter, define_vessel_prototype, vessel_prototype_path
from .view import define_camera, define_lights

__all__ = ["StageRecorder", "record_vessel", "write_ocean_loop", "INSTANCING_THRESHOLD",
           "TIME_CODES_PER_SECOND", "loop_path_for"]

INSTANCING_THRESHOLD = 64
"""Fleets larger than this are written as point instancers unless ``FleetDrawing.instanced`` says otherwise."""


def loop_path_for(path) -> str:
    """Where a recording at ``path`` puts its ocean loop (with ``OceanDrawing(loop=True)``): ``<stem>_ocean_loop<ext>``
    beside it."""
    stem, extension = os.path.splitext(os.path.abspath(os.fspath(path)))
    return f"{stem}_ocean_loop{extension}"


def _color_range(ocean: Ocean) -> float:
    """Half the height range [m] the ocean's colours span: 0.6 Hs of the sea on the grid, 5 cm at least."""
    return max(0.6 * ocean.significant_wave_height, 0.05)


def _loop_time_codes(loop_period: float, fps: float, time_codes_per_second: float) -> np.ndarray:
    """Time codes of one loop's frames, both ends included (the last equals the first): about ``fps`` frames
    per second [1/s], at least 2 per loop, at ``time_codes_per_second`` [1/s]."""
    frames = max(2, round(loop_period * fps))
    return np.arange(frames + 1) * (loop_period * time_codes_per_second / frames)


def _write_loop_frames(stage, ocean: Ocean, lattice: OceanLattice, time_codes_per_second: float, *, normals: bool,
                       colors: bool, time_codes: np.ndarray) -> None:
    writer = OceanMeshWriter(stage, OCEAN, lattice, choppiness=ocean.config.choppiness, normals=normals,
                             colors=colors, color_range=_color_range(ocean))
    for code in time_codes:
        writer.write(float(code), ocean_fields_at(ocean, float(code) / time_codes_per_second))


def write_ocean_loop(path, ocean: Ocean, *, fps: float = 10.0, time_codes_per_second: float = TIME_CODES_PER_SECOND,
                     resolution: int = 128, extent=None, normals: bool = False, colors: bool = True,
                     ascii: bool | None = None) -> str:
    """Write one seamless loop of ``ocean`` (built with ``OceanConfig.loop_period`` T [s]) to ``path`` and
    return the path. The stage holds the surface at time codes 0 ... T r, r = ``time_codes_per_second``
    (about ``fps`` frames per second of the sea, the last frame equal to the first), so a viewer that
    repeats the time range shows the sea forever without a seam, in real time at r frames per second;
    time code c shows the ocean at time c / r [s] (modulo T).

    ``resolution``: at most this many vertices along either side of ``extent`` (xmin, xmax, ymin, ymax) [m]
    (default: one tile, [0, tile_size]^2). ``normals``/``colors``: vertex normals and a displayColor by
    height. The ocean's fields are left at the loop's last time; its clock is left as it was.

    A frequency that is not a multiple of 2 pi / T cannot loop, so the loop period costs dispersion error:
    each wave's frequency moves by at most pi / T (see ``OceanConfig.loop_period``)."""
    owner = "write_ocean_loop"
    if not isinstance(ocean, Ocean):
        raise ValueError(f"{owner}: ocean must be an Ocean, got {type(ocean).__name__}")
    period = _require_loop(f"{owner}: ocean_loop", ocean)
    fps = require_positive(owner, "fps", fps, unit=" [frames/s]")
    resolution = require_int_in_range(owner, "resolution", resolution, 2, 4096)
    tile = ocean.config.tile_size
    extent = check_extent(owner, extent) if extent is not None else (0.0, tile, 0.0, tile)
    stage_file = StageFile(path, time_codes_per_second=time_codes_per_second, ascii=ascii, owner=owner)
    try:
        stage = stage_file.stage
        lattice = OceanLattice.covering(ocean.config, extent, resolution)
        rate = stage_file.time_codes_per_second
        codes = _loop_time_codes(period, fps, rate)
        _write_loop_frames(stage, ocean, lattice, rate, normals=normals, colors=colors, time_codes=codes)
        stage.SetStartTimeCode(0.0)
        stage.SetEndTimeCode(float(codes[-1]))
    except BaseException:
        stage_file.abort()
        raise
    return stage_file.commit()


def _require_group(owner: str, name: str, value, group: type, example: str, *, optional: bool) -> None:
    """ValueError unless ``value`` is a ``group`` (or None where ``optional``), saying what to pass."""
    if (value is None and optional) or isinstance(value, group):
        return
    article = "an" if group.__name__[0] in "AEIOU" else "a"
    allowed = f"{article} {group.__name__}" + (" or None" if optional else "")
    raise ValueError(f"{owner}.{name} must be {allowed} (e.g. {name}={example}), got {type(value).__name__}")


def _rows(owner: str, name: str, value, shape: tuple) -> np.ndarray:
    """``value`` (numpy, a list or a torch tensor) as a finite float64 array of ``shape``, else ValueError."""
    if value is None:
        raise ValueError(f"{owner}: {name} is required (the recorder has {shape[0]} boats)")
    if hasattr(value, "detach"):
        value = value.detach().cpu().numpy()
    array = np.asarray(value, dtype=np.float64)
    if array.shape != shape:
        raise ValueError(f"{owner}: {name} must have shape {shape}, got {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{owner}: {name} holds NaN or infinite values")
    return array


class StageRecorder:
    """Writes a USD stage frame by frame while a simulation runs (call :meth:`record` every k-th step).

    Arguments (keyword-only after ``path``):

    - ``path``: the stage to write, ``.usdc`` (crate, default), ``.usda`` (text) or ``.usd`` (crate, or text
      with ``ascii=True``). Nothing appears there until :meth:`close`; see ``ocean_warp.usd.stage_file``.
    - ``fps``: frames recorded per second of simulated time [1/s] (recording every k-th step of dt: 1 / (k dt));
      a looping ocean is written at about this rate too.
    - ``time_codes_per_second``: the stage's timeCodesPerSecond and framesPerSecond [1/s] (default 24,
      Blender's default frame rate; 30, or any positive value). Time code = t [s] x this, so one
      second of simulation plays in one second; the samples stay one per recorded frame (a viewer
      interpolates between them).
    - ``ocean``: an :class:`~ocean_warp.usd.stage_options.OceanDrawing`, the ocean to draw and how (mesh
      resolution, extent and margin, normals, colours, a seamless loop); None: no ocean.
    - ``fleet``: a :class:`~ocean_warp.usd.stage_options.FleetDrawing`, the number of boats (default
      none), the vessel they are and their layout (prims or point instancers).
    - ``route``: a :class:`~ocean_warp.usd.stage_options.RouteDrawing`, the waypoints drawn as buoys and
      the path from the start through them; None: no route.
    - ``wind``: a :class:`~ocean_warp.usd.stage_options.WindArrow`, the wind's direction and speed and
      where the arrow stands; None: no arrow.
    - ``objects``: :class:`~ocean_warp.perception.SceneObject` s placed in the world (one environment), drawn
      under ``/World/Objects``; the floating ones move with the poses given to :meth:`record`.
      ``object_labels``: one display name per object (e.g. "boat 3 pile 2"); None: none.
    - ``lidar``: add ``/World/Lidar``, points time-sampled from :meth:`record`'s ``lidar_points``.
    - ``ascii``: text instead of crate (see ``path``); ``save_every``: frames between saves of a crate file.

    The stage also holds materials for every visible part (``ocean_warp.usd.materials``), a camera framing
    the ocean mesh (without an ocean: the route and everywhere the boats went), and a sun and a sky light
    (``ocean_warp.usd.view``).

    Use it as a context manager, or call :meth:`close` (success) or :meth:`abort` (failure): an exception
    inside the ``with`` block deletes the temporary file and leaves the target path untouched.
    """

    def __init__(self, path, *, fps: float, time_codes_per_second: float = TIME_CODES_PER_SECOND,
                 ocean: OceanDrawing | None = None, fleet: FleetDrawing = FleetDrawing(),
                 route: RouteDrawing | None = None, wind: WindArrow | None = None, objects: Sequence = (),
                 object_labels: Sequence[str] | None = None, lidar: bool = False, ascii: bool | None = None,
                 save_every: int = 100):
        owner = "StageRecorder"
        self.fps = require_positive(owner, "fps", fps, unit=" [frames/s]")
        self.time_codes_per_second = require_positive(owner, "time_codes_per_second", time_codes_per_second,
                                                      unit=" [1/s]")
        _require_group(owner, "ocean", ocean, OceanDrawing, "OceanDrawing(ocean)", optional=True)
        _require_group(owner, "fleet", fleet, FleetDrawing, "FleetDrawing(count)", optional=False)
        _require_group(owner, "route", route, RouteDrawing, "RouteDrawing(points)", optional=True)
        _require_group(owner, "wind", wind, WindArrow, "WindArrow(direction)", optional=True)
        # The groups' fields as the recorder's attributes; without an ocean, OceanDrawing's defaults (the
        # margin still places the wind arrow).
        self.ocean = ocean.ocean if ocean is not None else None
        self.ocean_resolution = ocean.resolution if ocean is not None else OceanDrawing.resolution
        self._extent = ocean.extent if ocean is not None else None
        self.ocean_margin = ocean.margin if ocean is not None else OceanDrawing.margin
        self.ocean_normals = ocean.normals if ocean is not None else OceanDrawing.normals
        self.ocean_colors = ocean.colors if ocean is not None else OceanDrawing.colors
        self.ocean_loop = ocean.loop if ocean is not None else OceanDrawing.loop
        self.boats = fleet.count
        self.instanced = fleet.instanced if fleet.instanced is not None else self.boats > INSTANCING_THRESHOLD
        self.route = np.array(route.points, dtype=np.float64) if route is not None else None
        self.route_labels = list(route.labels) if route is not None and route.labels is not None else None
        self.route_start = np.array(route.start, dtype=np.float64) if route is not None and route.start is not None \
            else None
        self.wind = (wind.direction, wind.speed) if wind is not None else None
        self._wind_origin = np.array(wind.origin, dtype=np.float64) if wind is not None and wind.origin is not None \
            else None
        save_every = require_int_in_range(owner, "save_every", save_every, 1, 10**9)
        objects = list(objects)
        if not all(isinstance(item, SceneObject) for item in objects):
            raise ValueError(f"{owner}.objects must be ocean_warp.perception.SceneObjects")
        if object_labels is not None:
            object_labels = [str(label) for label in object_labels]
            if len(object_labels) != len(objects):
                raise ValueError(f"{owner}.object_labels must name each of the {len(objects)} objects, "
                                 f"got {len(object_labels)}")
        if not isinstance(lidar, bool):
            raise ValueError(f"{owner}.lidar must be True or False, got {lidar!r}")

        self._file = StageFile(path, time_codes_per_second=self.time_codes_per_second, ascii=ascii,
                               save_every=save_every, owner=owner)
        self._loop_file: StageFile | None = None
        self._loop_mesh_prim = None
        try:
            stage = self._file.stage
            stage.CreateClassPrim(LIBRARY)
            self._fleet = None
            self.vessel = fleet.vessel
            self.scaling = part_scaling(self.vessel) if self.vessel is not None else None
            """The vessel's parts drawn at a size of each boat's own (``PartScaling``), None: none."""
            self._joints: tuple[tuple[str, int], ...] = ()
            if self.boats:
                parts = self.vessel.parts()
                self._joints = tuple((part.joint, part.joint_column) for part in parts if part.joint is not None)
                prototype = define_vessel_prototype(stage, vessel_prototype_path(self.vessel), parts)
                layout = InstancedVesselWriter if self.instanced else VesselFleetWriter
                self._fleet = layout(stage, self.boats, prototype, parts, self.scaling)
            if self.route is not None:
                define_route(stage, self.route, labels=self.route_labels, start=self.route_start, path=route.path)
            self._objects = ObjectsWriter(stage, objects, labels=object_labels) if objects else None
            self._lidar = LidarPointsWriter(stage) if lidar else None
        except BaseException:
            self._file.abort()
            raise
        self._ocean_writer: OceanMeshWriter | None = None
        self.lattice: OceanLattice | None = None
        self._visited: np.ndarray | None = None
        self.first_time_code: float | None = None
        self.last_time_code: float | None = None
        self.frames = 0

    # --- construction helpers -------------------------------------------------------------------
    @classmethod
    def for_vessel(cls, path, vessel, simulator, *, fps: float, **options) -> "StageRecorder":
        """A recorder for ``simulator``, a simulator of ``vessel`` (any ``ocean_warp.vessel.Vessel``):
        ``ocean=OceanDrawing(simulator.ocean)``, ``fleet=FleetDrawing(simulator.count, vessel=vessel)`` and a
        ``WindArrow`` of its first boat's mean wind, unless ``options`` give them (``fleet=FleetDrawing(count,
        vessel=vessel, instanced=True)``, ``wind=None``...); frames with :func:`record_vessel`."""
        options.setdefault("ocean", OceanDrawing(simulator.ocean))
        options.setdefault("fleet", FleetDrawing(simulator.count, vessel=vessel))
        if "wind" not in options:
            options["wind"] = WindArrow(float(simulator.state.wind_mean_direction.numpy()[0]),
                                        speed=float(simulator.state.wind_mean_speed.numpy()[0]))
        return cls(path, fps=fps, **options)

    @property
    def joint_names(self) -> tuple[str, ...]:
        """The state arrays the vessel's parts turn with (:meth:`record`'s ``joints``), each once."""
        return tuple(dict.fromkeys(name for name, _ in self._joints))

    @property
    def path(self) -> str:
        """Where the stage will be."""
        return self._file.path

    @property
    def loop_path(self) -> str | None:
        """Where the ocean loop will be (with ``OceanDrawing(loop=True)``), else None."""
        return loop_path_for(self.path) if self.ocean_loop else None

    # --- recording ------------------------------------------------------------------------------
    def time_code(self, time_s: float) -> float:
        """The time code of time ``time_s`` [s]: time x time_codes_per_second, rounded to a whole number when
        within 1e-6 of one."""
        code = float(time_s) * self.time_codes_per_second
        nearest = round(code)
        return float(nearest) if abs(code - nearest) < 1e-6 else code

    def record(self, time_s: float, positions=None, orientations=None, *, joints=None, levels=None,
               object_poses=None, lidar_points=None) -> None:
        """Add the frame at time ``time_s`` [s] (later than the last one): the boats' positions (N, 3) [m],
        orientations (N, 4) (x, y, z, w, body -> world; normalised here), ``joints``, the state array of each
        joint the vessel's parts turn with by name ((N,) or (N, C) [rad], ``{"boom_angle": ...}``), ``levels``
        (N,) each boat's level of the vessel's ``PartScaling`` (the E-Boat's reef; None: level 0), and the ocean
        evaluated at ``time_s``. Boat arguments may be numpy arrays, lists or torch tensors (:func:`record_vessel`
        reads them from a simulator). With ``objects``: ``object_poses`` = (positions (M, 3) [m], orientations
        (M, 4)) of every object (``Scene.view.object_position`` / ``object_orientation``), of which the floating
        ones are sampled (None: they stay where they were). With ``lidar``: ``lidar_points`` (P, 3) [m], the
        frame's returns (NaN rows: no return)."""
        owner = "StageRecorder.record"
        if self._file.closed:
            raise ValueError(f"{owner}: the recorder is closed")
        if isinstance(time_s, bool) or not isinstance(time_s, (int, float, np.floating, np.integer)) \
                or not math.isfinite(time_s):
            raise ValueError(f"{owner}: time_s must be a finite time in seconds, got {time_s!r}")
        code = self.time_code(time_s)
        if self.last_time_code is not None and code <= self.last_time_code:
            raise ValueError(f"{owner}: time_s must increase from frame to frame, got {time_s!r} s (time code {code}) "
                             f"after time code {self.last_time_code}")
        boats = self._boat_frame(owner, positions, orientations)
        if boats is not None:
            boats += (self._joint_frame(owner, joints), self._scale_frame(owner, levels))
        try:
            if self.first_time_code is None:
                self._start(boats[0] if boats is not None else None, code)
            if self._ocean_writer is not None:
                self._ocean_writer.write(code, ocean_fields_at(self.ocean, time_s))
            if boats is not None:
                self._fleet.write(code, *boats)
                self._track_visited(boats[0])
            if object_poses is not None and self._objects is not None:
                where, rotation = (np.asarray(v, dtype=np.float64) for v in object_poses)
                self._objects.write(code, where, rotation)
            if lidar_points is not None:
                if self._lidar is None:
                    raise ValueError(f"{owner}: lidar_points given, but the recorder was made without lidar=True")
                self._lidar.write(code, lidar_points)
            self._file.frame_written()
        except BaseException:
            self.abort()
            raise
        self.last_time_code = code
        self.frames += 1

    def _boat_frame(self, owner, positions, orientations):
        """(positions, unit orientations) as float64 arrays, checked; None without boats."""
        n = self.boats
        if n == 0:
            if positions is not None and len(np.asarray(positions)):
                raise ValueError(f"{owner}: positions given, but the recorder was made for 0 boats")
            return None
        where = _rows(owner, "positions", positions, (n, 3))
        rotation = _rows(owner, "orientations", orientations, (n, 4))
        norm = np.linalg.norm(rotation, axis=1, keepdims=True)
        if np.any(norm < 1e-6):
            raise ValueError(f"{owner}: orientations must be non-zero quaternions (x, y, z, w)")
        return where, rotation / norm

    def _joint_frame(self, owner, joints) -> dict:
        """The joint arrays the vessel's parts turn with, as float64, checked."""
        joints = dict(joints or {})
        frame = {}
        for name, column in self._joints:
            value = joints.get(name)
            if value is None:
                raise ValueError(f"{owner}: joints[{name!r}] is required (the {self.vessel.name}'s parts turn with it)")
            if hasattr(value, "detach"):
                value = value.detach().cpu().numpy()
            array = np.asarray(value, dtype=np.float64)
            if array.shape[:1] != (self.boats,) or array.ndim > 2 or (array.ndim == 2 and column >= array.shape[1]):
                raise ValueError(f"{owner}: joints[{name!r}] must have shape ({self.boats},) or ({self.boats}, C) "
                                 f"with column {column}, got {array.shape}")
            if not np.all(np.isfinite(array)):
                raise ValueError(f"{owner}: joints[{name!r}] holds NaN or infinite values")
            frame[name] = array
        unknown = sorted(set(joints) - set(frame))
        if unknown:
            raise ValueError(f"{owner}: the {self.vessel.name}'s parts turn with no joint {unknown[0]!r}")
        return frame

    def _scale_frame(self, owner, levels) -> np.ndarray | None:
        """Each boat's linear factor on the vessel's scaled parts (``levels`` through ``PartScaling.scales``)."""
        if levels is None:
            return None if self.scaling is None else np.full(self.boats, self.scaling.scales[0])
        if self.scaling is None:
            raise ValueError(f"{owner}: levels given, but the {self.vessel.name} draws no part at a size of each "
                             "boat's own")
        array = _rows(owner, "levels", levels, (self.boats,))
        count = len(self.scaling.scales)
        if np.any(array != np.round(array)) or np.any(array < 0) or np.any(array >= count):
            raise ValueError(f"{owner}: levels must be whole numbers in [0, {count}) (the {self.vessel.name}'s "
                             f"{self.scaling.level}), got {array.min()} to {array.max()}")
        return np.asarray(self.scaling.scales, dtype=np.float64)[array.astype(np.int64)]

    def _start(self, positions: np.ndarray | None, code: float) -> None:
        """At the first frame: fix the ocean's extent and lattice, and the wind arrow's place."""
        self.first_time_code = code
        stage = self._file.stage
        extent = self._extent or self._default_extent(positions)
        if self.wind is not None:
            origin = self._wind_origin
            if origin is None:
                origin = (np.array([extent[0], extent[3], 8.0]) if extent is not None else np.array([0.0, 0.0, 8.0]))
            define_wind_arrow(stage, self.wind[0], self.wind[1], origin)
        if self.ocean is None:
            return
        if self.ocean_loop:
            # The loop does not depend on the frames: it is written at close, over every place a boat went.
            return
        self.lattice = OceanLattice.covering(self.ocean.config, extent, self.ocean_resolution)
        self._ocean_writer = OceanMeshWriter(stage, OCEAN, self.lattice, choppiness=self.ocean.config.choppiness,
                                             normals=self.ocean_normals, colors=self.ocean_colors,
                                             color_range=_color_range(self.ocean))

    def _default_extent(self, positions: np.ndarray | None):
        start = self.route_start[None, :] if self.route_start is not None else None
        points = [p[:, :2] for p in (positions, self.route, start) if p is not None and len(p)]
        if self._visited is not None:
            points.append(self._visited.reshape(2, 2))
        if not points:
            if self.ocean is None:
                return None
            tile = self.ocean.config.tile_size
            return (0.0, tile, 0.0, tile)
        xy = np.concatenate(points)
        margin = max(self.ocean_margin, 1.0)
        return (float(xy[:, 0].min() - margin), float(xy[:, 0].max() + margin),
                float(xy[:, 1].min() - margin), float(xy[:, 1].max() + margin))

    def _track_visited(self, positions: np.ndarray) -> None:
        """Grow the box (xmin, ymin, xmax, ymax) [m] of every boat position recorded so far."""
        low = positions[:, :2].min(axis=0)
        high = positions[:, :2].max(axis=0)
        if self._visited is None:
            self._visited = np.concatenate([low, high])
        else:
            self._visited = np.concatenate([np.minimum(self._visited[:2], low), np.maximum(self._visited[2:], high)])

    def _start_loop(self) -> None:
        """Fix the lattice over the extent (the user's, or every boat position recorded and the route, plus
        the margin) and write the loop file; the clips that repeat it are authored at close."""
        extent = self._extent or self._default_extent(None)
        self.lattice = OceanLattice.covering(self.ocean.config, extent, self.ocean_resolution)
        rate = self.time_codes_per_second
        self._loop_file = StageFile(self.loop_path, time_codes_per_second=rate, ascii=self._file.format == "usda",
                                    owner="StageRecorder")
        codes = _loop_time_codes(self.ocean.config.loop_period, self.fps, rate)
        loop_stage = self._loop_file.stage
        _write_loop_frames(loop_stage, self.ocean, self.lattice, rate, normals=self.ocean_normals,
                           colors=self.ocean_colors, time_codes=codes)
        loop_stage.SetStartTimeCode(0.0)
        loop_stage.SetEndTimeCode(float(codes[-1]))
        # The main stage's ocean: a reference to its still first frame (topology and values at the default
        # time, in the weaker referenced prim), with the animated attributes from the clips, which are
        # stronger wherever they have samples.
        stage = self._file.stage
        rest = OceanMeshWriter(stage, OCEAN_REST, self.lattice, choppiness=self.ocean.config.choppiness,
                               normals=self.ocean_normals, colors=self.ocean_colors,
                               color_range=_color_range(self.ocean), model=False)
        rest.write(None, ocean_fields_at(self.ocean, self.first_time_code / rate))
        mesh = define_referenced_ocean(stage, OCEAN, OCEAN_REST, colors=self.ocean_colors)
        self._loop_mesh_prim = mesh.GetPrim()

    def _author_loop_clips(self) -> None:
        """Value clips that map every stretch of loop_period on the stage to the loop's time codes."""
        span = self.ocean.config.loop_period * self.time_codes_per_second
        first = math.floor(self.first_time_code / span)
        last = math.floor(self.last_time_code / span)
        times = []
        for k in range(first, last + 1):
            times += [(k * span, 0.0), ((k + 1) * span, span)]
        clips = Usd.ClipsAPI(self._loop_mesh_prim)
        clips.SetClipAssetPaths([Sdf.AssetPath(f"./{os.path.basename(self.loop_path)}")])
        clips.SetClipPrimPath(OCEAN)
        clips.SetClipActive([(times[0][0], 0.0)])
        clips.SetClipTimes(times)

    # --- finishing ------------------------------------------------------------------------------
    def _view_area(self):
        """(xmin, xmax, ymin, ymax) [m] for the camera: the ocean mesh's area where there is one, else the
        route and every recorded boat position plus a margin of 5 m; None when there is nothing to frame."""
        if self.lattice is not None:
            x, y = self.lattice.ix * self.lattice.cell_size, self.lattice.iy * self.lattice.cell_size
            return (float(x[0]), float(x[-1]), float(y[0]), float(y[-1]))
        start = self.route_start[None, :] if self.route_start is not None else None
        points = [p[:, :2] for p in (self.route, start) if p is not None]
        if self._visited is not None:
            points.append(self._visited.reshape(2, 2))
        if not points:
            return None
        xy = np.concatenate(points)
        return (float(xy[:, 0].min() - 5.0), float(xy[:, 0].max() + 5.0), float(xy[:, 1].min() - 5.0),
                float(xy[:, 1].max() + 5.0))

    def close(self) -> str:
        """Write the time range (and the loop's clips), the camera and lights, save, and move the stage (and
        the loop) to their paths; returns the stage's path. A recorder with no frame still writes a valid,
        empty stage."""
        if self._file.closed:
            raise ValueError("StageRecorder.close: the recorder is already closed")
        try:
            stage = self._file.stage
            first = self.first_time_code if self.first_time_code is not None else 0.0
            last = self.last_time_code if self.last_time_code is not None else first
            stage.SetStartTimeCode(first)
            stage.SetEndTimeCode(last)
            if self.ocean_loop and self.first_time_code is not None:
                self._start_loop()
            area = self._view_area()
            if area is not None:
                define_camera(stage, area)
            define_lights(stage)
            if self._loop_file is not None:
                # The loop first, at its final path, so that the clips find it when anything reads them.
                self._loop_file.commit()
                self._author_loop_clips()
            self._ocean_writer = None
            self._fleet = None
            self._loop_mesh_prim = None
            return self._file.commit()
        except BaseException:
            self.abort()
            raise

    def abort(self) -> None:
        """Give up: delete the temporary file(s); nothing is written at the target paths."""
        self._ocean_writer = None
        self._fleet = None
        self._loop_mesh_prim = None
        if self._loop_file is not None and not self._loop_file.closed:
            self._loop_file.abort()
        if not self._file.closed:
            self._file.abort()

    @property
    def closed(self) -> bool:
        return self._file.closed

    def __enter__(self) -> "StageRecorder":
        return self

    def __exit__(self, exc_type, exc, traceback) -> None:
        if exc_type is not None:
            self.abort()
        elif not self.closed:
            self.close()


def record_vessel(recorder: StageRecorder, simulator, time_s: float | None = None) -> None:
    """Add the current state of ``simulator`` (of the recorder's ``FleetDrawing.vessel``) as a frame at ``time_s``
    [s] (default: the simulator's clock, ``state.time``): positions, orientations, every joint state array its
    vessel's parts turn with and the level array of its ``PartScaling``, one host copy of each."""
    if recorder.vessel is None:
        raise ValueError("record_vessel: the recorder draws no boats (FleetDrawing without a vessel)")
    state = simulator.state
    joints = {name: getattr(state, name).numpy() for name in recorder.joint_names}
    levels = getattr(state, recorder.scaling.level).numpy() if recorder.scaling is not None else None
    time_s = float(state.time.numpy()[0]) if time_s is None else time_s
    recorder.record(time_s, state.position.numpy(), state.orientation.numpy(), joints=joints, levels=levels)
