"""Wind per environment: a mean speed and direction, gusts, a height profile (a Simulator model)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import warp as wp

from .kernels.random_streams import advance_counter
from .device_structs import struct_from
from .kernels.wind_field import GustModel, WindState, reset_wind, update_wind
from .masks import mask_of, rows_at
from .torch_streams import ordered_with_torch
from .validation import (
    require_finite,
    require_indices,
    require_int_in_range,
    require_non_negative,
    require_per_item,
    require_positive,
)

__all__ = ["WindConfig", "Wind"]


@dataclasses.dataclass(frozen=True)
class WindConfig:
    """The wind over every environment, until :meth:`Wind.set` changes an environment's mean.

    Gusts are Ornstein-Uhlenbeck processes on speed and direction (see ``ocean_warp.kernels.wind_field``):
    each wanders around its mean with the given standard deviation and correlation time."""

    speed: float = 5.0
    """Mean speed at the reference height [m/s]."""
    direction: float = 0.0
    """Mean direction the wind blows towards [rad], from +x (east) counter-clockwise (as the waves)."""
    gust_speed_std: float = 0.0
    """Standard deviation of the speed around its mean [m/s]; 0: steady."""
    gust_speed_time: float = 10.0
    """Correlation time of the speed [s]."""
    gust_direction_std: float = 0.0
    """Standard deviation of the direction around its mean [rad]; 0: steady."""
    gust_direction_time: float = 30.0
    """Correlation time of the direction [s]."""
    profile_exponent: float = 0.0
    """p in U(z) = U (z / reference_height)^p; 0 (the default, as the original twin): the same at every
    height; 1/7 is a common open-sea value."""
    reference_height: float = 10.0
    """Height [m] at which ``speed`` holds when there is a profile."""
    seed: int = 0
    """Seed of the gusts' random streams."""

    def __post_init__(self):
        owner = "WindConfig"
        for name in ("speed", "gust_speed_std", "gust_direction_std"):
            object.__setattr__(self, name, require_non_negative(owner, name, getattr(self, name)))
        object.__setattr__(self, "direction", require_finite(owner, "direction", self.direction))
        for name in ("gust_speed_time", "gust_direction_time", "reference_height"):
            object.__setattr__(self, name, require_positive(owner, name, getattr(self, name)))
        exponent = require_non_negative(owner, "profile_exponent", self.profile_exponent)
        if exponent > 1.0:
            raise ValueError(f"{owner}.profile_exponent must be in [0, 1], got {exponent!r}")
        object.__setattr__(self, "profile_exponent", exponent)
        object.__setattr__(self, "seed", require_int_in_range(owner, "seed", self.seed, 0, 2**31 - 1))

    def gust_model(self, dt: float, first_index: int = 0) -> GustModel:
        """The kernels' view of this config for substeps of ``dt`` [s]; ``first_index``: the random-stream
        number of the batch's first environment (see ``GustModel.first_index``)."""
        return struct_from(
            GustModel, self, speed_decay=math.exp(-dt / self.gust_speed_time),
            speed_noise=self.gust_speed_std * math.sqrt(1.0 - math.exp(-2.0 * dt / self.gust_speed_time)),
            direction_decay=math.exp(-dt / self.gust_direction_time),
            direction_noise=self.gust_direction_std * math.sqrt(1.0 - math.exp(-2.0 * dt / self.gust_direction_time)),
            first_index=int(first_index))


class Wind:
    """The wind over ``count`` environments: its model (``config``, ``gusts``: the kernels' view of it), its
    ``state`` (a ``WindState`` of device arrays) and the force-model hook that updates it every substep
    (pass it among a Simulator's models, before the models that read it)."""

    def __init__(self, config: WindConfig | None = None, count: int = 1, *, substep: float, device=None,
                 first_index: int = 0):
        """``count`` environments updated every ``substep`` [s] (the Simulator's dt / substeps);
        ``first_index``: the random-stream number of the first one (see ``GustModel.first_index``)."""
        self.config = config if config is not None else WindConfig()
        self.device = wp.get_device(device)
        self.count = int(count)
        full = lambda value: wp.full(self.count, value, dtype=float, device=self.device)  # noqa: E731
        initial = np.tile([self.config.speed * math.cos(self.config.direction),
                           self.config.speed * math.sin(self.config.direction), 0.0], (self.count, 1))
        self.state = struct_from(WindState, mean_speed=full(self.config.speed),
                                 mean_direction=full(self.config.direction), gust_scale=full(1.0),
                                 speed=full(self.config.speed), direction=full(self.config.direction),
                                 velocity=wp.array(initial.astype(np.float32), dtype=wp.vec3, device=self.device))
        """What moves: every environment's mean wind, gust scale and current wind (see ``WindState`` in
        ``ocean_warp.kernels.wind_field``: names, units)."""
        self._counter = wp.zeros(1, dtype=int, device=self.device)
        self.gusts = self.config.gust_model(require_positive("Wind", "substep", substep, unit=" [s]"),
                                            require_int_in_range("Wind", "first_index", first_index, 0, 2**30))

    def substep(self, simulator) -> None:
        wp.launch(update_wind, dim=self.count, device=self.device,
                  inputs=[self.gusts, self._counter], outputs=[self.state])
        wp.launch(advance_counter, dim=1, inputs=[self._counter], device=self.device)

    def restart_stream(self) -> None:
        """Number the gusts' random draws from zero again (with the same seed: the same gusts)."""
        self._counter.zero_()

    def set(self, envs=None, *, speed, direction, gust_scale=1.0) -> None:
        """Set the mean wind of the chosen environments (None: all) and restart their gusts from it:
        ``speed`` [m/s], ``direction`` [rad] and ``gust_scale`` (on the config's gust deviations) per
        environment or one value for all."""
        indices = require_indices("Wind.set", "envs", envs, self.count)
        speeds = require_per_item("Wind.set", "speed", speed, len(indices))
        directions = require_per_item("Wind.set", "direction", direction, len(indices))
        scales = require_per_item("Wind.set", "gust_scale", gust_scale, len(indices))
        if np.any(speeds < 0) or np.any(scales < 0):
            raise ValueError("Wind.set: speed [m/s] and gust_scale must be >= 0")
        if not indices.size:
            return
        device = self.device
        with ordered_with_torch(device):
            self.reset_masked(mask_of(indices, self.count, device),
                              wp.array(rows_at(indices, speeds, self.count), dtype=float, device=device),
                              wp.array(rows_at(indices, directions, self.count), dtype=float, device=device),
                              wp.array(rows_at(indices, scales, self.count), dtype=float, device=device))

    def reset_masked(self, mask: wp.array, speed: wp.array, direction: wp.array, gust_scale: wp.array) -> None:
        """Device path of :meth:`set`: environments whose ``mask`` (N,) int32 is non-zero take their row of
        ``speed`` (N,) [m/s], ``direction`` (N,) [rad] and ``gust_scale`` (N,); launches only (graph-safe)."""
        wp.launch(reset_wind, dim=self.count, device=self.device, inputs=[mask, speed, direction, gust_scale],
                  outputs=[self.state])
