"""A lidar scanning inside every decision of a :class:`~ocean_warp.envs.SailingEnv` (the core's
:class:`~ocean_warp.perception.lidar.Lidar` on every boat of the env, driven by a decision hook).

Example::

    hook = LidarHook(env, LidarConfig.scan_2d(), objects=[SceneObject.buoy((30.0, 5.0))], sectors=36)
    env.attach(hook)
    env.step(actions)
    hook.lidar.ranges          # (N, 360) torch view [m], the decision's last scan
    hook.lidar.kinds           # (N, 360) ray_cast.HIT_* of each beam
    hook.observation           # (N, 36) nearest range per 10 deg sector / max_range, in [0, 1]
"""

from __future__ import annotations

import numpy as np
import warp as wp

from ocean_warp.perception.lidar import Lidar
from ocean_warp.perception.lidar_config import LidarConfig
from ocean_warp.perception.scene import Scene

from ..decision_hook import DecisionHook
from ..sailing_env import SailingEnv

__all__ = ["LidarHook"]


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
