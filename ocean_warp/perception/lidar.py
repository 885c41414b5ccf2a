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

How the beams are spread: ``ocean_warp.perception.lidar_config``.
"""

from __future__ import annotations
from typing import TYPE_CHECKING

import numpy as np
import torch
import warp as wp

from ..device_structs import struct_from
from ..envs.decision_hook import DecisionHook
from ..frames import quaternion_from_roll_pitch_yaw
from ..kernels.lidar import LidarModel, hit_points, scan_lidar, sector_minimum
from ..kernels.random_streams import advance_counter
from ..kernels.ray_cast import SceneView
from ..validation import require_int_in_range
from .lidar_config import BOW_MOUNT, MASTHEAD_MOUNT, LidarConfig
from .scene import Scene

__all__ = ["BOW_MOUNT", "MASTHEAD_MOUNT", "LidarConfig", "Lidar", "LidarHook"]

if TYPE_CHECKING:
    from ..envs.sailing_env import SailingEnv

_MAX_STREAM_INDEX = 2**31 - 1
"""Beams are numbered (first boat + boat) x beams + beam in the random stream, a 32-bit signed offset."""


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

    def downsampled_array(self, sectors: int) -> wp.array:
        """The Warp array behind :meth:`downsampled` (for kernels that read it), kept up to date the same way."""
        self.downsampled(sectors)
        return self._sectors[sectors][0]

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
        from ..envs.sailing_env import SailingEnv  # deferred: the environment imports the sensors' configs

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
