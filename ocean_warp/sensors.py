"""Sensors of each boat, read once per step with noise and rates (a Simulator model)."""

from __future__ import annotations

import dataclasses

import numpy as np
import warp as wp

from .device_structs import struct_from
from .kernels.random_streams import SENSOR_NOISE, SENSOR_RESET_NOISE, advance_counter
from .kernels.sensor_readings import CHANNELS, SensorModel, read_sensors, reset_sensors
from .kernels.spatial import vec6
from .masks import mask_of
from .torch_streams import ordered_with_torch
from .validation import require_int_in_range, require_non_negative

__all__ = ["SensorConfig", "Sensors", "CHANNEL_NAMES"]

CHANNEL_NAMES = (
    "gnss_x", "gnss_y", "gnss_z", "gnss_vx", "gnss_vy", "gnss_vz",
    "accel_x", "accel_y", "accel_z", "gyro_x", "gyro_y", "gyro_z",
    "heading", "apparent_wind_angle", "apparent_wind_speed", "water_speed",
)
"""Column names of the reading arrays; units and frames in ``ocean_warp.kernels.sensor_readings``."""


@dataclasses.dataclass(frozen=True)
class SensorConfig:
    """Noise (standard deviations) and refresh rates of each sensor. A rate of 0 refreshes every step;
    otherwise the reading refreshes every round(1 / (rate * step)) steps and holds in between."""

    gnss_rate: float = 5.0
    """[Hz]"""
    gnss_position_std: float = 0.5
    """[m] per axis."""
    gnss_velocity_std: float = 0.05
    """[m/s] per axis."""
    imu_rate: float = 0.0
    """[Hz]; 0: every step."""
    accelerometer_std: float = 0.05
    """[m/s^2]"""
    accelerometer_bias_std: float = 0.02
    """Standard deviation of the per-boat constant bias drawn at each reset [m/s^2]."""
    gyroscope_std: float = 0.005
    """[rad/s]"""
    gyroscope_bias_std: float = 0.002
    """[rad/s]"""
    compass_rate: float = 10.0
    """[Hz]"""
    compass_std: float = 0.02
    """[rad]"""
    wind_rate: float = 5.0
    """[Hz], vane and anemometer."""
    wind_angle_std: float = 0.05
    """[rad]"""
    wind_speed_std: float = 0.2
    """[m/s]"""
    water_speed_rate: float = 5.0
    """[Hz]"""
    water_speed_std: float = 0.05
    """[m/s]"""
    seed: int = 0

    def __post_init__(self):
        for field in dataclasses.fields(self):
            if field.name == "seed":
                object.__setattr__(self, "seed", require_int_in_range("SensorConfig", "seed", self.seed, 0, 2**31 - 1))
            else:
                object.__setattr__(self, field.name, require_non_negative("SensorConfig", field.name,
                                                                          getattr(self, field.name)))

    @classmethod
    def noise_free(cls, **rates) -> "SensorConfig":
        """Exact readings (every noise and bias 0), at the given rates."""
        zero = {f.name: 0.0 for f in dataclasses.fields(cls) if f.name.endswith("_std")}
        return cls(**zero, **rates)

    def channel_noise(self) -> np.ndarray:
        return np.array([self.gnss_position_std] * 3 + [self.gnss_velocity_std] * 3 + [self.accelerometer_std] * 3
                        + [self.gyroscope_std] * 3 + [self.compass_std, self.wind_angle_std, self.wind_speed_std,
                                                      self.water_speed_std], dtype=np.float32)

    def channel_periods(self, step: float) -> np.ndarray:
        """Steps between refreshes per channel for steps of ``step`` [s]."""
        def period(rate):
            return 1 if rate == 0.0 else max(1, round(1.0 / (rate * step)))
        rates = [self.gnss_rate] * 6 + [self.imu_rate] * 6 + [self.compass_rate, self.wind_rate, self.wind_rate,
                                                             self.water_speed_rate]
        return np.array([period(r) for r in rates], dtype=np.int32)


class Sensors:
    """Readings of ``count`` boats: ``truth`` (noise-free) and ``readings`` (noisy, at their rates),
    both (count, 16), columns as :data:`CHANNEL_NAMES`. A Simulator model: it reads once per step.
    Each boat's noise (every channel and the IMU bias) is the config's times its ``noise_scale``."""

    def __init__(self, config: SensorConfig | None, count: int, *, masthead, wind, step: float, gravity: float,
                 device=None, first_index: int = 0):
        """``masthead``: vane and anemometer in the body frame [m]; ``wind``: the :class:`Wind` they
        read; ``step``: the Simulator's dt [s] (sensors read once per step); ``gravity`` [m/s^2];
        ``first_index``: the random-stream number of the first boat (see ``SensorModel.first_index``)."""
        self.config = config if config is not None else SensorConfig()
        self.device = wp.get_device(device)
        self.count = int(count)
        self.wind = wind
        self.truth = wp.zeros((self.count, CHANNELS), dtype=float, device=self.device)
        """(N, 16) exact readings of the last step."""
        self.readings = wp.zeros((self.count, CHANNELS), dtype=float, device=self.device)
        """(N, 16) noisy readings, held between refreshes."""
        self.imu_bias = wp.zeros(self.count, dtype=vec6, device=self.device)
        self.noise_scale = wp.ones(self.count, dtype=float, device=self.device)
        """(N,) factor on every channel's noise and on the IMU bias drawn at a reset, per boat (1: as
        configured, 0: exact readings); set by :meth:`reset_masked`."""
        self._previous_velocity = wp.zeros(self.count, dtype=wp.vec3, device=self.device)
        self._counter = wp.zeros(1, dtype=int, device=self.device)
        self._every_boat = wp.ones(self.count, dtype=wp.int32, device=self.device)
        self._model = struct_from(
            SensorModel, self.config, noise_std=wp.array(self.config.channel_noise(), dtype=float, device=self.device),
            period=wp.array(self.config.channel_periods(step), dtype=int, device=self.device),
            masthead=wp.vec3(*(float(v) for v in masthead)), gravity=gravity, step=step,
            first_index=require_int_in_range("Sensors", "first_index", first_index, 0, 2**30))

    def substep(self, simulator) -> None:
        """Sensors read once per step, not per substep."""

    def step(self, simulator) -> None:
        self._read(self._every_boat, False, SENSOR_NOISE, simulator.fleet)
        wp.launch(advance_counter, dim=1, inputs=[self._counter], device=self.device)

    def restart_stream(self) -> None:
        """Number the noise's random draws from zero again (with the same seed: the same noise)."""
        self._counter.zero_()

    def reset(self, boats: np.ndarray, fleet) -> None:
        """Host path of :meth:`reset_masked` for the boats at the indices ``boats`` (noise factors kept)."""
        with ordered_with_torch(self.device):
            self.reset_masked(mask_of(boats, self.count, self.device), fleet)

    def reset_masked(self, mask: wp.array, fleet, noise_scale: wp.array | None = None) -> None:
        """For every boat whose ``mask`` (N,) int32 is non-zero: its noise factor from its row of
        ``noise_scale`` (N,) (None: kept), a new IMU bias, no false acceleration on its next reading, and
        every channel read at once from its new state. Launches only (graph-safe)."""
        c = self.config
        bias_std = vec6(*([c.accelerometer_bias_std] * 3 + [c.gyroscope_bias_std] * 3))
        wp.launch(reset_sensors, dim=self.count, device=self.device,
                  inputs=[mask, bias_std, self._model, self._counter, fleet.state.orientation, fleet.state.velocity,
                          self.noise_scale if noise_scale is None else noise_scale],
                  outputs=[self.imu_bias, self._previous_velocity, self.noise_scale])
        self._read(mask, True, SENSOR_RESET_NOISE, fleet)

    def _read(self, mask: wp.array, refresh_all: bool, stream: int, fleet) -> None:
        wp.launch(read_sensors, dim=self.count, device=self.device,
                  inputs=[mask, int(refresh_all), stream, self._model, self.wind.gusts, self._counter,
                          fleet.state.position, fleet.state.orientation, fleet.state.velocity, fleet.state.water_velocity,
                          self.wind.state.velocity, self.imu_bias, self.noise_scale],
                  outputs=[self._previous_velocity, self.truth, self.readings])
