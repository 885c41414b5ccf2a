"""Water current per environment: a steady speed and direction, a tide, a depth profile (read by a Simulator)."""

from __future__ import annotations

import numpy as np
import warp as wp

from .current_config import CurrentConfig
from .device_structs import struct_from
from .kernels.water_current import CurrentField, CurrentState, reset_current, update_current
from .masks import mask_of, rows_at
from .torch_streams import ordered_with_torch
from .validation import require_indices, require_per_item

__all__ = ["Current", "CurrentConfig", "no_current"]


class Current:
    """The current over ``count`` environments (boat i in environment i): its ``config``, its ``state`` (a
    ``CurrentState`` of device arrays: each environment's steady speed, direction and profile depth, and the
    surface current they give now) and ``field``, what the force kernels read of it.

    Give it to a :class:`~ocean_warp.Simulator` (``Simulator(..., current=current)``): the simulator hands it
    its clock (:meth:`follow`) and calls :meth:`update` at the start of every substep, before the hull pass,
    so the tide moves with the simulated time and every force of the substep sees the same water."""

    def __init__(self, config: CurrentConfig | None = None, count: int = 1, *, device=None):
        self.config = config if config is not None else CurrentConfig()
        if not isinstance(self.config, CurrentConfig):
            raise ValueError(f"Current: config must be a CurrentConfig, got {self.config!r}")
        self.device = wp.get_device(device)
        self.count = int(count)
        if self.count < 1:
            raise ValueError(f"Current: count must be >= 1, got {count!r}")
        full = lambda value: wp.full(self.count, value, dtype=float, device=self.device)  # noqa: E731
        self.state = struct_from(CurrentState, speed=full(self.config.speed), direction=full(self.config.direction),
                                 profile_depth=full(self.config.profile_depth),
                                 velocity=wp.zeros(self.count, dtype=wp.vec3, device=self.device))
        """What the current is (see ``CurrentState`` in ``ocean_warp.kernels.water_current``: names, units)."""
        self.tide = self.config.tide_model()
        """The kernels' view of the tidal part (``TideModel``)."""
        self.field = struct_from(CurrentField, velocity=self.state.velocity, profile_depth=self.state.profile_depth,
                                 profile_exponent=self.config.profile_exponent)
        """What the force kernels read (``CurrentField``): the state's surface current and profile depth."""
        self.clock = wp.zeros(1, dtype=wp.float64, device=self.device)
        """(1,) float64 time [s] the tide is read at: its own zero until :meth:`follow` names another."""
        self._every_env = wp.ones(self.count, dtype=wp.int32, device=self.device)
        self.update()

    def follow(self, clock: wp.array) -> None:
        """Read the tide at ``clock`` ((1,) float64 [s], a Simulator's own) from now on, and evaluate it now."""
        if not isinstance(clock, wp.array) or clock.dtype != wp.float64 or clock.shape != (1,):
            raise ValueError(f"Current.follow: clock must be a (1,) float64 Warp array, got {clock!r}")
        if clock.device != self.device:
            raise ValueError(f"Current.follow: the clock is on {clock.device} but the current on {self.device}")
        self.clock = clock
        self.update()

    def update(self) -> None:
        """Every environment's surface current at the clock's time (launches only: graph-safe)."""
        wp.launch(update_current, dim=self.count, device=self.device,
                  inputs=[self._every_env, self.tide, self.clock], outputs=[self.state])

    def set(self, envs=None, *, speed, direction, profile_depth=None) -> None:
        """Set the steady current of the chosen environments (None: all): ``speed`` [m/s] toward ``direction``
        [rad] and optionally ``profile_depth`` [m] (None: kept), per environment or one value for all; the
        tide stays as configured."""
        owner = "Current.set"
        indices = require_indices(owner, "envs", envs, self.count)
        speeds = require_per_item(owner, "speed", speed, len(indices))
        directions = require_per_item(owner, "direction", direction, len(indices))
        if np.any(speeds < 0.0):
            raise ValueError(f"{owner}: speed must be >= 0 [m/s], got {speed!r}")
        depths = None
        if profile_depth is not None:
            depths = require_per_item(owner, "profile_depth", profile_depth, len(indices))
            if np.any(depths < 0.0):
                raise ValueError(f"{owner}: profile_depth must be >= 0 [m], got {profile_depth!r}")
        if not indices.size:
            return
        device = self.device
        with ordered_with_torch(device):
            if depths is None:
                depths = self.state.profile_depth.numpy()[indices]
            rows = [wp.array(rows_at(indices, values, self.count), dtype=float, device=device)
                    for values in (speeds, directions, depths)]
            self.reset_masked(mask_of(indices, self.count, device), *rows)

    def reset_masked(self, mask: wp.array, speed: wp.array, direction: wp.array,
                     profile_depth: wp.array | None = None) -> None:
        """Device path of :meth:`set`: environments whose ``mask`` (N,) int32 is non-zero take their row of
        ``speed`` (N,) [m/s], ``direction`` (N,) [rad] and ``profile_depth`` (N,) [m] (None: kept), and their
        surface current at the clock's time; launches only (graph-safe)."""
        depth = self.state.profile_depth if profile_depth is None else profile_depth
        wp.launch(reset_current, dim=self.count, device=self.device,
                  inputs=[mask, speed, direction, depth, self.tide, self.clock], outputs=[self.state])


def no_current(device) -> CurrentField:
    """The field of still water: arrays without rows, which the force kernels read as no current at all."""
    return struct_from(CurrentField, velocity=wp.zeros(0, dtype=wp.vec3, device=device),
                       profile_depth=wp.zeros(0, dtype=float, device=device), profile_exponent=1.0)
