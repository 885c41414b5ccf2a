"""The lidar's model as a person writes it: :class:`LidarConfig` (beams, ranges, rate, mount, noise). A module of
its own, with no simulator in it, so that task configs can hold one (``ocean_warp.perception.lidar`` scans).

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

from ..validation import require_in_range, require_int_in_range, require_non_negative, require_positive

__all__ = ["BOW_MOUNT", "LidarConfig"]

BOW_MOUNT = (1.1, 0.0, 0.8)
"""A sensor on a short pole on the foredeck, 0.8 m above the waterline (body frame [m]): the default mount."""


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
    """Scans per second [Hz] (of an ``ocean_warp.envs.sensors.LidarHook``: one scan every round(1 / (rate dt))
    physics steps)."""
    mount: tuple[float, float, float] = BOW_MOUNT
    """The sensor's origin in the body frame [m] (default :data:`BOW_MOUNT`; a vessel names its own places,
    ``ocean_warp.vessel.sensor_mount(vessel, "masthead")``)."""
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
    def multi_channel(cls, channels: int = 16, *, mount, **changes) -> LidarConfig:
        """A Velodyne VLP-16-like 3D lidar at ``mount`` (body frame [m]; where a vessel carries it:
        ``sensor_mount(vessel, "masthead")``, ``ocean_warp.vessel``): ``channels`` rows (16: 2 deg apart) over
        +-15 deg, 360 deg around, 100 m, 10 Hz, +-3 cm accuracy (the data sheet's, taken as the noise's
        standard deviation), then ``changes``. The real sensor fires about 1 800 beams per channel at 10 Hz
        (0.2 deg); 360 here (1 deg), to keep thousands of boats cheap; set ``beams`` for more. Its minimum
        range (not on the data sheet) is taken as 0.5 m."""
        values = {"channels": channels, "beams": 360, "elevation_min": math.radians(-15.0),
                  "elevation_max": math.radians(15.0), "min_range": 0.5, "max_range": 100.0,
                  "mount": mount, "range_noise_std": 0.03}
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
