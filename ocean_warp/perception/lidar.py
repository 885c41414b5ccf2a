"""A lidar on every boat of a :class:`~ocean_warp.perception.scene.Scene`: configurable beams (a level 2D scan or
a multi-channel 3D one), ranges and what each beam hit, noise and dropouts, batched on the device
(kernels in ``ocean_warp.kernels.lidar``).

Example::

    lidar = Lidar(LidarConfig.scan_2d(), scene)   # one on every boat of the scene
    scene.refresh()            # after the sea moved
    lidar.scan()
    lidar.ranges               # (N, 360) torch view [m]
    lidar.kinds                # (N, 360) ray_cast.HIT_* of each beam
    lidar.downsampled(36)      # (N, 36) nearest range per 10 deg sector / max_range, in [0, 1]

A lidar that scans inside every decision of an environment: ``ocean_warp.envs.sensors.LidarHook``.

How the beams are spread: ``ocean_warp.perception.lidar_config``.
"""

from __future__ import annotations

import numpy as np
import torch
import warp as wp

from ..device_structs import struct_from
from ..frames import quaternion_from_roll_pitch_yaw
from ..kernels.lidar import LidarModel, hit_points, scan_lidar, sector_minimum
from ..kernels.random_streams import advance_counter
from ..kernels.ray_cast import SceneView
from ..validation import require_int_in_range
from .lidar_config import BOW_MOUNT, LidarConfig
from .scene import Scene

__all__ = ["BOW_MOUNT", "LidarConfig", "Lidar"]

_MAX_STREAM_INDEX = 2**31 - 1
"""Beams are numbered (first boat + boat) x beams + beam in the random stream, a 32-bit signed offset."""


class Lidar:
    """One lidar (``config``) on every boat of ``scene``, read through Warp arrays and torch views bound once.

    The boats' poses are the scene's (``scene.view.boat_position`` and ``boat_orientation``, the simulator's
    arrays: bound, not copied); each boat scans in its own environment of the scene and does not see itself
    (a boat outside the scene, environment -1, reports nothing). Beams are cast with ``ray_cast.cast_ray``
    through the objects, the boats and, when ``config.water_returns`` (whatever ``Scene.water_visible``
    says), the sea's height map. Call ``scene.refresh()`` after the ocean changes, before :meth:`scan` (the
    sea's height map and band and the floating objects; ``ocean_warp.envs.sensors.LidarHook`` does).

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
