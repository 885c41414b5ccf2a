"""Configuration of the spectral ocean surface."""

from __future__ import annotations

import dataclasses
import enum
import math
import numbers

from .water_config import WaterConfig
from .validation import (
    require_choice,
    require_finite,
    require_int_in_range,
    require_non_negative,
    require_positive,
)

__all__ = ["Spectrum", "OceanConfig", "MIN_RESOLUTION", "MAX_RESOLUTION", "MAX_SIGNIFICANT_WAVE_HEIGHT",
           "SIGNIFICANT_WAVE_HEIGHT_RULE", "is_valid_significant_wave_height", "require_significant_wave_height"]

MIN_RESOLUTION = 16
"""Smallest grid the tiled FFT runs (points per side)."""
MAX_RESOLUTION = 2048
"""Largest grid the tiled FFT runs (points per side): one block holds a whole row."""

MAX_SIGNIFICANT_WAVE_HEIGHT = 5.0
"""The highest significant wave height [m] of any sea here: every config, job option and
``Ocean.set_significant_wave_height`` checks against it. The models are for a small craft in seas it can
sail: linear (Airy) waves that never break, Froude-Krylov pressure with no green water, calm-water
resistance and foil fits, a 2.5 m boat whose tasks use Hs 0.3-0.5 m. At Hs 5 m (the WMO's "very rough"
sea, waves twice the boat's length high) they are already far outside what they were made for; beyond it
their numbers mean nothing."""
SIGNIFICANT_WAVE_HEIGHT_RULE = (f"a number from 0 to {MAX_SIGNIFICANT_WAVE_HEIGHT:g} [m] (the wave and boat "
                                "models hold for seas a small craft sails)")
"""The rule in words, for error messages: "<field> must be <rule>, got <value>"."""


def is_valid_significant_wave_height(value) -> bool:
    """Whether ``value`` is a finite number from 0 to :data:`MAX_SIGNIFICANT_WAVE_HEIGHT` [m]."""
    return (not isinstance(value, bool) and isinstance(value, numbers.Real) and math.isfinite(value)
            and 0.0 <= value <= MAX_SIGNIFICANT_WAVE_HEIGHT)


def require_significant_wave_height(name: str, value) -> float:
    """``value`` as a float, or ValueError naming it (``name``: "OceanConfig.significant_wave_height", ...),
    the value and the rule."""
    if not is_valid_significant_wave_height(value):
        raise ValueError(f"{name} must be {SIGNIFICANT_WAVE_HEIGHT_RULE}, got {value!r}")
    return float(value)


class Spectrum(str, enum.Enum):
    """The closed set of sea states an :class:`OceanConfig` can describe."""

    JONSWAP = "jonswap"
    """Fetch-limited wind sea, DNV-RP-C205 form (see :func:`ocean_warp.spectra.jonswap`)."""
    PIERSON_MOSKOWITZ = "pierson_moskowitz"
    """Fully developed sea: from ``wind_speed`` if given, else from Hs and Tp."""
    REGULAR = "regular"
    """One Airy wave of ``amplitude``, ``period``, ``direction`` and ``phase``."""


@dataclasses.dataclass(frozen=True)
class OceanConfig:
    """A periodic square patch of ocean, evaluated on a grid by inverse FFTs.

    The patch repeats without seams in x and y, so it covers the whole plane. Angles are in radians.
    Invalid values raise ``ValueError`` naming the field.
    """

    tile_size: float = 256.0
    """Side of the periodic patch [m]; the longest wave it holds has this wavelength."""
    resolution: int = 256
    """Grid points per side: a power of two from 16 to 2048. Grid spacing = tile_size / resolution."""
    spectrum: Spectrum | str = Spectrum.JONSWAP
    """"jonswap", "pierson_moskowitz" or "regular"."""
    significant_wave_height: float = 1.0
    """Hs [m] of "jonswap", and of "pierson_moskowitz" when ``wind_speed`` is None: 0 to
    ``MAX_SIGNIFICANT_WAVE_HEIGHT`` (5 m)."""
    peak_period: float = 6.0
    """Tp [s] of "jonswap", and of "pierson_moskowitz" when ``wind_speed`` is None."""
    gamma: float = 3.3
    """JONSWAP peak enhancement factor, from 1 (Pierson-Moskowitz shape) to 10."""
    wind_speed: float | None = None
    """Wind speed at 19.5 m [m/s] for "pierson_moskowitz"; None uses Hs and Tp instead. Ignored otherwise."""
    direction: float = 0.0
    """Mean direction the waves travel [rad], from +x counter-clockwise."""
    spreading: float | None = 10.0
    """Exponent s of the cos-2s directional spreading (larger = narrower); 0 or None = long-crested."""
    pressure_depths: tuple = (0.05, 0.15, 0.35)
    """Three depths [m] below still water, increasing, at which the ocean also evaluates the dynamic pressure
    head of its waves (Airy: each wave's amplitude times cosh(k (z + d)) / cosh(k d)), and at the second the
    water's orbital velocity. Hulls feel the Froude-Krylov pressure interpolated between the surface and
    these depths (held below the last), and the water's motion at the second. The defaults suit a small
    craft of 0.1-0.3 m draft; a deeper hull wants deeper levels."""
    depth: float = math.inf
    """Water depth [m]; inf for deep water. Enters the dispersion relation and the orbital motion."""
    choppiness: float = 0.0
    """Scale of the horizontal (choppy) displacement; 0 = linear Airy surface, 1 = Gerstner-like."""
    min_wavelength: float = 0.0
    """Waves shorter than this [m] are left out (0 keeps all the grid resolves), e.g. to keep waves
    much shorter than a hull's triangles from aliasing against it."""
    amplitude: float = 0.5
    """Amplitude [m] of the "regular" wave (half its height)."""
    period: float = 6.0
    """Period [s] of the "regular" wave; its wavevector is snapped to the grid (see ``Ocean.regular_wave``)."""
    phase: float = 0.0
    """Phase [rad] of the "regular" wave: h = a cos(k.x - omega t + phase)."""
    seed: int = 0
    """Seed of the random amplitudes and phases of the spectral seas: one seed, one sea."""
    water: WaterConfig = dataclasses.field(default_factory=WaterConfig)
    """The water of this sea: density, gravity (the waves' dispersion) and viscosity (see ``WaterConfig``)."""
    inversion_iterations: int = 8
    """Most fixed-point iterations that undo the choppy displacement when sampling (0 to 32). Each shrinks
    the error by about choppiness * |grad D|: a few hundredths on a moderate sea, up to about 0.4 on a
    steep sea at choppiness 1, where 8 iterations from the asked point leave a few millimetres."""
    inversion_tolerance: float = 1e-3
    """The iteration stops once a step moves the grid position less than this [m]; the error left is then
    about as small. A hull's vertices start from their boat's origin's solution and mostly stop after one
    or two iterations."""
    loop_period: float | None = None
    """Make the sea repeat exactly every ``loop_period`` [s] (None: it never repeats). Each wave's angular
    frequency omega is moved to the nearest multiple of 2 pi / loop_period (one multiple at least, so no
    wave stands still; the mean, omega = 0, stays 0), and the time is taken modulo loop_period, so every
    field at t + loop_period equals the field at t. It is what lets a USD stage show one seamless loop of
    the ocean that the boats, simulated on this same ocean, really ride (``ocean_warp.usd``).

    The price is dispersion error: omega moves by at most pi / loop_period, so a wave of period T_w gets a
    period off by at most T_w / (2 loop_period) of itself, and its phase speed by as much. With
    loop_period = 10 Tp the waves near the peak are off by 5 % at most, with 50 Tp by 1 %; a wave longer
    than 2 loop_period (which would round to omega = 0) is sped up to one cycle per loop."""

    def __post_init__(self):
        owner = "OceanConfig"
        set_field = lambda name, value: object.__setattr__(self, name, value)  # noqa: E731 (frozen dataclass)

        set_field("tile_size", require_positive(owner, "tile_size", self.tile_size, unit=" [m]"))
        resolution = require_int_in_range(owner, "resolution", self.resolution, MIN_RESOLUTION, MAX_RESOLUTION)
        if resolution & (resolution - 1):
            raise ValueError(
                f"{owner}.resolution must be a power of two from {MIN_RESOLUTION} to {MAX_RESOLUTION} "
                f"(the tiled FFT needs one), got {resolution}"
            )
        set_field("resolution", resolution)
        set_field("spectrum", require_choice(owner, "spectrum", self.spectrum, Spectrum))
        set_field("significant_wave_height",
                  require_significant_wave_height(f"{owner}.significant_wave_height", self.significant_wave_height))
        set_field("peak_period", require_positive(owner, "peak_period", self.peak_period, unit=" [s]"))
        gamma = require_finite(owner, "gamma", self.gamma)
        if not 1.0 <= gamma <= 10.0:
            raise ValueError(f"{owner}.gamma must be in [1, 10], got {gamma!r}")
        set_field("gamma", gamma)
        if self.wind_speed is not None:
            set_field("wind_speed", require_positive(owner, "wind_speed", self.wind_speed, unit=" [m/s]"))
        set_field("direction", require_finite(owner, "direction", self.direction))
        if self.spreading is not None:
            spreading = require_non_negative(owner, "spreading", self.spreading)
            if spreading > 1000.0:
                raise ValueError(f"{owner}.spreading must be in [0, 1000] or None, got {spreading!r}")
            set_field("spreading", spreading)
        set_field("depth", require_positive(owner, "depth", self.depth, allow_inf=True, unit=" [m]"))
        set_field("pressure_depths", _pressure_depths(owner, self.pressure_depths))
        set_field("choppiness", require_non_negative(owner, "choppiness", self.choppiness))
        set_field("min_wavelength", require_non_negative(owner, "min_wavelength", self.min_wavelength, unit=" [m]"))
        set_field("amplitude", require_non_negative(owner, "amplitude", self.amplitude, unit=" [m]"))
        set_field("period", require_positive(owner, "period", self.period, unit=" [s]"))
        set_field("phase", require_finite(owner, "phase", self.phase))
        set_field("seed", require_int_in_range(owner, "seed", self.seed, 0, 2**63 - 1))
        if not isinstance(self.water, WaterConfig):
            raise ValueError(f"{owner}.water must be a WaterConfig, got {self.water!r}")
        set_field(
            "inversion_iterations",
            require_int_in_range(owner, "inversion_iterations", self.inversion_iterations, 0, 32),
        )
        set_field(
            "inversion_tolerance",
            require_positive(owner, "inversion_tolerance", self.inversion_tolerance, unit=" [m]"),
        )
        if self.loop_period is not None:
            set_field("loop_period", require_positive(owner, "loop_period", self.loop_period, unit=" [s] or None"))
        if self.min_wavelength >= self.tile_size:
            raise ValueError(
                f"{owner}.min_wavelength must be shorter than tile_size ({self.tile_size} m), "
                f"got {self.min_wavelength!r}: it would leave no waves"
            )

    @property
    def cell_size(self) -> float:
        """Grid spacing [m]."""
        return self.tile_size / self.resolution

    @property
    def long_crested(self) -> bool:
        """True when all waves travel in ``direction`` (no directional spreading)."""
        return self.spreading is None or self.spreading == 0.0


def _pressure_depths(owner: str, depths) -> tuple[float, float, float]:
    """Three finite depths [m], 0 < d1 < d2 < d3, or ValueError naming the field."""
    try:
        values = tuple(float(d) for d in depths)
    except (TypeError, ValueError):
        values = ()
    if (len(values) != 3 or isinstance(depths, (str, bytes)) or not all(math.isfinite(d) for d in values)
            or not 0.0 < values[0] < values[1] < values[2]):
        raise ValueError(f"{owner}.pressure_depths must be three depths [m] below still water with "
                         f"0 < d1 < d2 < d3, got {depths!r}")
    return values
