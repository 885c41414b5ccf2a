"""A lidar on every boat of a :class:`~ocean_warp.perception.scene.Scene`: configurable beams (a level 2D scan or
a multi-channel 3D one), ranges and what each beam hit, noise and dropouts, batched on the device
(kernels in ``ocean_warp.kernels.lidar``).

Example (a scan every 0.1 s inside every decision of a :class:`~ocean_warp.envs.SailingEnv`)::

    hook = LidarHook(env, LidarConfig.scan_2d(), objects=[SceneObject.buoy((30.0, 5.0))], sectors=36)
    env.attach(hook)
    env.step(actions)
    hook.lidar.ranges          # (N, 360) torch view [m], the decision's last scan
    hook.lidar.kinds           # (N, 360) ray_cast.HIT_* of each beam
    hook.observation           # (N, 36) nearest range per 10 deg sector / max_range, in [0, 1]

Beams: channel c (0 .. C-1) of C > 1 lies at elevation ``elevation_min`` + c (``elevation_max`` -
``elevation_min``) / (C - 1), a single channel at their mean; each channel holds ``beams`` azimuths: on a
full circle (``horizontal_fov`` 2 pi) every 2 pi / B from -pi (astern) counter-clockwise (toward port), so
beam B / 2 of an even B points along the sensor's x; on a partial field of view from -fov / 2 to
+fov / 2, both ends included (a single beam: straight along x). Ranges and kinds are (N, C * B), beam
j = c * B + b.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import torch
import warp as wp

from ..device_structs import struct_from
from ..eboat.eboat import MAST_LENGTH
from ..eboat.sheet import MAST_STEP
from ..envs.sailing_env import DecisionHook, SailingEnv
from ..frames import quaternion_from_roll_pitch_yaw
from ..kernels.lidar import LidarModel, hit_points, scan_lidar, sector_minimum
from ..kernels.random_streams import advance_counter
from ..kernels.ray_cast import SceneView
from ..validation import require_in_range, require_int_in_range, require_non_negative, require_positive
from .scene import Scene

__all__ = ["BOW_MOUNT", "MASTHEAD_MOUNT", "LidarConfig", "Lidar", "LidarHook"]

BOW_MOUNT = (1.1, 0.0, 0.8)
"""A sensor on a short pole on the foredeck, 0.8 m above the waterline (body frame [m]): the default mount."""
MASTHEAD_MOUNT = (MAST_STEP[0], 0.0, MAST_STEP[2] + MAST_LENGTH)
"""The top of the E-Boat's mast, 3.61 m above the waterline (body frame [m])."""

_MAX_STREAM_INDEX = 2**31 - 1
"""Beams are numbered (first boat + boat) x beams + beam in the random stream, a 32-bit signed offset."""


def _require_triple(owner: str, field: str, value) -> tuple[float, float, float]:
    """Three finite numbers as a tuple of floats, else ``ValueError`` naming ``owner.field``."""
    try:
        numbers = np.asarray(value, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise ValueError(f"{owner}.{field} must be three finite numbers, got {value!r}") from None
    if numbers.size != 3 or not np.all(np.isfinite(numbers)):
        raise ValueError(f"{owner}.{field} must be three finite numbers, got {value!r}")
    return tuple(float(v) for v in numbers)


@dataclasses.dataclass(frozen=True)
class LidarConfig:
    """A lidar model, the same on every boat. Angles [rad], lengths [m]; invalid values raise ``ValueError``
    naming the field. The defaults: a level 2D scan of 360 beams (1 deg) from the bow mount, 0.2-50 m, at
    10 Hz, exact (no noise, no dropouts)."""

    channels: int = 1
    """Rows of beams at different elevations: 1 is a 2D scan, more a 3D one."""
    beams: int = 360
    """Beams per channel, spread over ``horizontal_fov``."""
    horizontal_fov: float = 2.0 * math.pi
    """Horizontal field of view [rad], in (0, 2 pi]; 2 pi: the full circle."""
    elevation_min: float = 0.0
    """Elevation of the lowest channel [rad], in [-pi/2, pi/2], up positive."""
    elevation_max: float = 0.0
    """Elevation of the highest channel [rad]; above ``elevation_min`` when there are several channels."""
    min_range: float = 0.2
    """[m]: nothing nearer is seen."""
    max_range: float = 50.0
    """[m]: nothing farther is seen; the range reported by a beam without a return."""
    rate: float = 10.0
    """Scans per second [Hz] (of a :class:`LidarHook`: one scan every round(1 / (rate dt)) physics steps)."""
    mount: tuple[float, float, float] = BOW_MOUNT
    """The sensor's origin in the body frame [m] (default :data:`BOW_MOUNT`; :data:`MASTHEAD_MOUNT` is the
    other usual place)."""
    mount_rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """Roll, pitch and yaw [rad] of the sensor frame against the body frame (Z-Y-X, as
    ``ocean_warp.frames``); pitch > 0 tilts the sensor's x down."""
    water_returns: bool = True
    """Whether the sea returns the beams; False: beams pass through the surface and see what lies beyond it
    within range (the underwater part of a pile, a keel), on open water nothing (HIT_NONE, ``max_range``)."""
    range_noise_std: float = 0.0
    """Standard deviation of the Gaussian noise on the range of each return [m]."""
    dropout: float = 0.0
    """Probability that a beam returns nothing (reported as HIT_NONE at ``max_range``), in [0, 1)."""
    seed: int = 0
    """Seed of the noise and dropouts: one seed, one sequence of scans."""

    def __post_init__(self):
        owner = "LidarConfig"
        set_field = lambda name, value: object.__setattr__(self, name, value)  # noqa: E731 (frozen dataclass)
        set_field("channels", require_int_in_range(owner, "channels", self.channels, 1, 256))
        set_field("beams", require_int_in_range(owner, "beams", self.beams, 1, 2**16))
        fov = require_positive(owner, "horizontal_fov", self.horizontal_fov, unit=" [rad]")
        set_field("horizontal_fov", require_in_range(owner, "horizontal_fov", fov, 0.0, 2.0 * math.pi, unit=" [rad]"))
        for name in ("elevation_min", "elevation_max"):
            set_field(name, require_in_range(owner, name, getattr(self, name), -0.5 * math.pi, 0.5 * math.pi,
                                             unit=" [rad]"))
        if self.elevation_max < self.elevation_min or (self.channels > 1 and self.elevation_max == self.elevation_min):
            raise ValueError(f"{owner}.elevation_max must be above elevation_min {self.elevation_min!r} for "
                             f"{self.channels} channels, got {self.elevation_max!r}")
        set_field("min_range", require_non_negative(owner, "min_range", self.min_range, unit=" [m]"))
        set_field("max_range", require_positive(owner, "max_range", self.max_range, unit=" [m]"))
        if self.min_range >= self.max_range:
            raise ValueError(f"{owner}.min_range must be below max_range {self.max_range!r} [m], "
                             f"got {self.min_range!r}")
        set_field("rate", require_positive(owner, "rate", self.rate, unit=" [Hz]"))
        set_field("mount", _require_triple(owner, "mount", self.mount))
        set_field("mount_rpy", _require_triple(owner, "mount_rpy", self.mount_rpy))
        if not isinstance(self.water_returns, bool):
            raise ValueError(f"{owner}.water_returns must be True or False, got {self.water_returns!r}")
        set_field("range_noise_std", require_non_negative(owner, "range_noise_std", self.range_noise_std, unit=" [m]"))
        dropout = require_in_range(owner, "dropout", self.dropout, 0.0, 1.0)
        if dropout == 1.0:
            raise ValueError(f"{owner}.dropout must be below 1 (a beam that always drops out sees nothing), got 1.0")
        set_field("dropout", dropout)
        set_field("seed", require_int_in_range(owner, "seed", self.seed, 0, 2**31 - 1))

    # --- presets ------------------------------------------------------------------------------------
    @classmethod
    def scan_2d(cls, **changes) -> LidarConfig:
        """A level 2D scan: 360 beams (1 deg) around the bow mount, 0.2-50 m, 10 Hz, 3 cm range noise
        (assumed), then ``changes``."""
        return cls(**({"channels": 1, "beams": 360, "range_noise_std": 0.03} | changes))

    @classmethod
    def multi_channel(cls, channels: int = 16, **changes) -> LidarConfig:
        """A Velodyne VLP-16-like 3D lidar at the masthead: ``channels`` rows (16: 2 deg apart) over
        +-15 deg, 360 deg around, 100 m, 10 Hz, +-3 cm accuracy (the data sheet's, taken as the noise's
        standard deviation), then ``changes``. The real sensor fires about 1 800 beams per channel at 10 Hz
        (0.2 deg); 360 here (1 deg), to keep thousands of boats cheap; set ``beams`` for more. Its minimum
        range (not on the data sheet) is taken as 0.5 m."""
        values = {"channels": channels, "beams": 360, "elevation_min": math.radians(-15.0),
                  "elevation_max": math.radians(15.0), "min_range": 0.5, "max_range": 100.0,
                  "mount": MASTHEAD_MOUNT, "range_noise_std": 0.03}
        return cls(**(values | changes))

    # --- derived ------------------------------------------------------------------------------------
    @property
    def beam_count(self) -> int:
        """Beams of one scan, C x B."""
        return self.channels * self.beams

    def azimuths(self) -> np.ndarray:
        """(B,) azimuth of each beam of a channel [rad] (the module docstring says how they are spread)."""
        if self.horizontal_fov >= 2.0 * math.pi:
            return -math.pi + np.arange(self.beams) * (2.0 * math.pi / self.beams)
        if self.beams == 1:
            return np.zeros(1)
        return np.linspace(-0.5 * self.horizontal_fov, 0.5 * self.horizontal_fov, self.beams)

    def elevations(self) -> np.ndarray:
        """(C,) elevation of each channel [rad]."""
        if self.channels == 1:
            return np.array([0.5 * (self.elevation_min + self.elevation_max)])
        return np.linspace(self.elevation_min, self.elevation_max, self.channels)

    def beam_angles(self) -> tuple[np.ndarray, np.ndarray]:
        """(C * B,) azimuth and (C * B,) elevation [rad] of every beam, beam j = channel * B + b."""
        azimuth = np.tile(self.azimuths(), self.channels)
        elevation = np.repeat(self.elevations(), self.beams)
        return azimuth, elevation

    def scan_period(self, dt: float) -> int:
        """Physics steps of ``dt`` [s] between scans, round(1 / (rate dt)); ``ValueError`` naming
        ``LidarConfig.rate`` unless that is a whole number of steps (within 1 %), at least one."""
        dt = require_positive("LidarConfig.scan_period", "dt", dt, unit=" [s]")
        steps = 1.0 / (self.rate * dt)
        period = max(1, round(steps))
        if abs(period - steps) > 0.01 * steps:
            raise ValueError(f"LidarConfig.rate {self.rate!r} Hz is not a whole number of physics steps of {dt!r} s "
                             f"(1 / (rate dt) = {steps:.4g}); use {1.0 / (period * dt):.6g} Hz, a whole divisor of "
                             f"the step rate {1.0 / dt:.6g} Hz")
        return period


class Lidar:
    """One lidar (``config``) on every boat of ``scene``, read through Warp arrays and torch views bound once.

    The boats' poses are the scene's (``scene.view.boat_position`` and ``boat_orientation``, the simulator's
    arrays: bound, not copied); each boat scans in its own environment of the scene and does not see itself
    (a boat outside the scene, environment -1, reports nothing). Beams are cast with ``ray_cast.cast_ray``
    through the objects, the boats and, when ``config.water_returns`` (whatever ``Scene.water_visible``
    says), the sea's height map. Call ``scene.refresh()`` after the ocean changes, before :meth:`scan` (the
    sea's height map and band and the floating objects; a :class:`LidarHook` does).

    Args:
        config: the sensor (default ``LidarConfig()``).
        scene: the scene the beams are cast through.
        first_index: the random-stream number of the scene's first boat: a shard of a larger batch (see
            ``SailingEnv.first_env``) draws the noise the batch draws for those boats.

    The results of the last scan, on the scene's device:
        range_array, kind_array: (N, C * B) Warp arrays: range [m] and ``ray_cast.HIT_*`` of every beam;
            ``ranges``, ``kinds``: their torch views. A beam that returned nothing (no hit within range, a
            dropout, a boat outside the scene or whose pose is not finite) reports ``max_range`` and HIT_NONE.
        sensor_position, sensor_orientation: (N,) the sensor's world pose at that scan ([m]; sensor -> world).
    """

    def __init__(self, config: LidarConfig | None, scene: Scene, *, first_index: int = 0):
        self.config = config if config is not None else LidarConfig()
        if not isinstance(self.config, LidarConfig):
            raise ValueError(f"Lidar: config must be a LidarConfig, got {self.config!r}")
        if not isinstance(scene, Scene):
            raise ValueError(f"Lidar: scene must be an ocean_warp.perception Scene, got {type(scene).__name__}")
        self.scene, self.device = scene, scene.device
        self.count = scene.view.boat_position.shape[0]
        """N: boats, one lidar each."""
        self.beam_count = self.config.beam_count
        first_index = require_int_in_range("Lidar", "first_index", first_index, 0, 2**30)
        if (first_index + self.count) * self.beam_count > _MAX_STREAM_INDEX:
            raise ValueError(f"Lidar: (first_index + boats) x beams must stay below 2^31 (the random stream's "
                             f"numbering), got ({first_index} + {self.count}) x {self.beam_count}")
        device, shape = self.device, (self.count, self.beam_count)
        self.range_array = wp.full(shape, self.config.max_range, dtype=float, device=device)
        """(N, C * B) range of every beam [m] at the last scan; ``max_range`` where nothing returned."""
        self.kind_array = wp.zeros(shape, dtype=int, device=device)
        """(N, C * B) what every beam hit at the last scan (``ray_cast.HIT_*``; HIT_NONE before any scan)."""
        self.sensor_position = wp.zeros(self.count, dtype=wp.vec3, device=device)
        """(N,) each sensor's world position at the last scan [m]."""
        self.sensor_orientation = wp.zeros(self.count, dtype=wp.quat, device=device)
        """(N,) each sensor's orientation at the last scan (sensor frame -> world)."""
        self.ranges = wp.to_torch(self.range_array)
        """torch view of ``range_array``."""
        self.kinds = wp.to_torch(self.kind_array)
        """torch view of ``kind_array``."""
        self._counter = wp.zeros(1, dtype=int, device=device)
        self._boat_env = wp.array(scene.boat_env.astype(np.int32), dtype=int, device=device)
        self._view = struct_from(SceneView, scene.view, water_visible=int(self.config.water_returns))
        """The scene as the beams see it: its sea there or not as ``water_returns`` says."""
        self._model = _lidar_model(self.config, device, first_index)
        self._sectors: dict[int, tuple[wp.array, torch.Tensor]] = {}

    def scan(self) -> None:
        """One scan of every boat's lidar from the boats' current poses over the scene as last refreshed, then
        every observation asked for with :meth:`downsampled`; the noise stream moves on. Launches only
        (graph-safe). Outside a captured graph wrap it in
        ``ocean_warp.torch_streams.ordered_with_torch(lidar.device)`` before torch reads the views on CUDA."""
        wp.launch(scan_lidar, dim=(self.count, self.beam_count), device=self.device,
                  inputs=[self._view, self._model, self._boat_env, self._counter],
                  outputs=[self.range_array, self.kind_array, self.sensor_position, self.sensor_orientation])
        wp.launch(advance_counter, dim=1, device=self.device, inputs=[self._counter])
        for sectors in self._sectors:
            self._launch_sector_minimum(sectors)

    def restart_stream(self) -> None:
        """Number the noise's draws from zero again (with the same seed: the same noise on the same scene)."""
        self._counter.zero_()

    def downsampled(self, sectors: int) -> torch.Tensor:
        """(N, ``sectors``) torch view of each boat's nearest return per sector: the least range over the
        sector's beams of every channel, over ``max_range`` (so in [0, 1]; 1: nothing within range). The
        sectors split each channel's beams into equal runs of consecutive azimuths (``sectors`` must divide
        ``beams``). Filled from the last scan now and by every later :meth:`scan`; ask for it before a graph
        that scans is captured (before the first ``env.step`` after ``env.attach``), never inside one."""
        beams = self.config.beams
        if isinstance(sectors, bool) or not isinstance(sectors, int) or not 1 <= sectors <= beams or beams % sectors:
            raise ValueError(f"Lidar.downsampled: sectors must be a whole divisor of the {beams} beams per channel, "
                             f"got {sectors!r}")
        if sectors not in self._sectors:
            nearest = wp.ones((self.count, sectors), dtype=float, device=self.device)
            self._sectors[sectors] = (nearest, wp.to_torch(nearest))
            self._launch_sector_minimum(sectors)
        return self._sectors[sectors][1]

    def _launch_sector_minimum(self, sectors: int) -> None:
        nearest = self._sectors[sectors][0]
        wp.launch(sector_minimum, dim=nearest.shape, device=self.device,
                  inputs=[self.range_array, self.config.beams, self.config.max_range], outputs=[nearest])

    def points(self) -> np.ndarray:
        """(N, C * B, 3) numpy: the world point [m] of every beam's return at the last scan (from the sensor's
        pose then and the measured range, noise included); NaN where nothing returned. A host call (it
        allocates and reads the device), for export and tools."""
        points = wp.empty((self.count, self.beam_count), dtype=wp.vec3, device=self.device)
        wp.launch(hit_points, dim=points.shape, device=self.device,
                  inputs=[self._model, self.range_array, self.kind_array, self.sensor_position,
                          self.sensor_orientation], outputs=[points])
        return points.numpy().reshape(self.count, self.beam_count, 3)


def _lidar_model(config: LidarConfig, device, first_index: int) -> LidarModel:
    azimuth, elevation = config.beam_angles()
    mount_rotation = quaternion_from_roll_pitch_yaw(np.array(config.mount_rpy))[0]
    return struct_from(LidarModel, config, water_returns=int(config.water_returns),
                       azimuth=wp.array(azimuth.astype(np.float32), dtype=float, device=device),
                       elevation=wp.array(elevation.astype(np.float32), dtype=float, device=device),
                       mount_position=wp.vec3(*config.mount), mount_rotation=wp.quat(*mount_rotation),
                       first_index=first_index)


class LidarHook(DecisionHook):
    """A lidar scanning inside every decision of a :class:`~ocean_warp.envs.SailingEnv`: after every
    ``period`` = round(1 / (rate dt)) physics steps the scene is refreshed (the sea's band, the floating
    objects) and every boat scans, so a decision of S steps holds F = S / period scans; ``lidar`` keeps the
    last (taken after the decision's physics, before the environments that ended are reset, like
    ``env.final_position``). Attach it with ``env.attach(hook)``.

    Args:
        env: the environment (its boats carry the lidars; boat i in environment i).
        config: the sensor (default ``LidarConfig()``); its rate must be a whole number of physics steps
            that divides the decision's steps, else ``ValueError`` naming ``LidarConfig.rate``.
        objects: the objects of every environment, placed from each environment's origin (as
            ``Scene.for_env``); ignored when ``scene`` is given.
        scene: a scene of this environment's boats to cast through instead.
        sectors: also keep ``observation``, ``lidar.downsampled(sectors)`` (None: not).
        record: also keep every scan of the decision in ``recorded_ranges``, ``recorded_kinds`` (F, N, C * B)
            and the sensor poses ``recorded_sensor_position``, ``recorded_sensor_orientation`` (F, N),
            preallocated on the device (see :meth:`frames`).
    """

    def __init__(self, env: SailingEnv, config: LidarConfig | None = None, *, objects=(), scene: Scene | None = None,
                 sectors: int | None = None, record: bool = False):
        if not isinstance(env, SailingEnv):
            raise ValueError(f"LidarHook: env must be a SailingEnv (it scans inside its decisions), got {env!r}")
        config = config if config is not None else LidarConfig()
        if not isinstance(config, LidarConfig):
            raise ValueError(f"LidarHook: config must be a LidarConfig, got {config!r}")
        if not isinstance(record, bool):
            raise ValueError(f"LidarHook.record must be True or False, got {record!r}")
        self.period = config.scan_period(env.task.simulator.dt)
        """Physics steps between scans."""
        steps = env.steps_per_decision
        if steps % self.period:
            raise ValueError(f"LidarConfig.rate {config.rate!r} Hz: a scan every {self.period} steps does not divide "
                             f"the decision's {steps} steps")
        self.scans_per_decision = steps // self.period
        self.scene = scene if scene is not None else Scene.for_env(env, objects)
        if self.scene.view.boat_position.shape[0] != env.num_envs:
            raise ValueError(f"LidarHook.scene must hold the environment's {env.num_envs} boats, got "
                             f"{self.scene.view.boat_position.shape[0]}")
        self.lidar = Lidar(config, self.scene, first_index=env.first_env)
        self.observation = None if sectors is None else self.lidar.downsampled(sectors)
        """(N, sectors) torch view of the last scan's nearest return per sector (``Lidar.downsampled``), or None."""
        self.record = record
        if record:
            frames, device = (self.scans_per_decision, env.num_envs), env.device
            self.recorded_ranges = wp.zeros(frames + (self.lidar.beam_count,), dtype=float, device=device)
            self.recorded_kinds = wp.zeros(frames + (self.lidar.beam_count,), dtype=int, device=device)
            self.recorded_sensor_position = wp.zeros(frames, dtype=wp.vec3, device=device)
            self.recorded_sensor_orientation = wp.zeros(frames, dtype=wp.quat, device=device)
            self._frame_slots = [self._slots_of_frame(f) for f in range(self.scans_per_decision)]

    def _slots_of_frame(self, frame: int) -> list[tuple[wp.array, wp.array]]:
        """(record slot, source) pairs of scan ``frame`` of a decision."""
        lidar = self.lidar
        return [(self.recorded_ranges[frame], lidar.range_array), (self.recorded_kinds[frame], lidar.kind_array),
                (self.recorded_sensor_position[frame], lidar.sensor_position),
                (self.recorded_sensor_orientation[frame], lidar.sensor_orientation)]

    def after_physics_step(self, env: SailingEnv, step: int) -> None:
        """After every ``period`` steps: refresh the scene, scan, and keep the scan when recording."""
        if (step + 1) % self.period:
            return
        self.scene.refresh()
        self.lidar.scan()
        if self.record:
            for slot, source in self._frame_slots[(step + 1) // self.period - 1]:
                wp.copy(slot, source)

    def frames(self) -> dict[str, np.ndarray]:
        """The last decision's scans on the host (``record`` only): "ranges" [m] and "kinds" (F, N, C * B),
        "sensor_position" (F, N, 3) [m] and "sensor_orientation" (F, N, 4) x y z w, scan f taken after
        physics step (f + 1) x ``period`` of the decision."""
        if not self.record:
            raise ValueError("LidarHook.frames: build the hook with record=True to keep every scan")
        return {"ranges": self.recorded_ranges.numpy(), "kinds": self.recorded_kinds.numpy(),
                "sensor_position": self.recorded_sensor_position.numpy(),
                "sensor_orientation": self.recorded_sensor_orientation.numpy()}
