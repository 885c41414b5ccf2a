"""The water current of every environment, as a person writes it: steady, tidal, uniform or sheared with depth."""

from __future__ import annotations

import dataclasses
import math

from .device_structs import struct_from
from .kernels.water_current import TideModel
from .validation import require_finite, require_non_negative, require_positive

__all__ = ["CurrentConfig", "M2_PERIOD"]

M2_PERIOD = 12.42 * 3600.0
"""Period of the principal lunar semidiurnal tide M2 [s] (12.42 h), the tidal stream's usual rhythm."""


@dataclasses.dataclass(frozen=True)
class CurrentConfig:
    """A horizontal current at the surface, U(t) = speed + tidal_amplitude cos(2 pi t / tidal_period +
    tidal_phase) toward ``direction``, falling off below the surface as (1 + z / profile_depth)^profile_exponent
    (see ``ocean_warp.kernels.water_current``). Every environment starts with it until
    :meth:`~ocean_warp.Current.set` (or a task's start) changes its speed and direction. The default is still
    water: no current at all.

    Hulls, keels, rudders and propellers feel it through the water's velocity relative to the boat: a boat
    left alone drifts with it, and the log reads speed through the water while the GNSS reads speed over the
    ground."""

    speed: float = 0.0
    """U_0: the steady speed at the surface [m/s]; 0 (with no tide): no current."""
    direction: float = 0.0
    """Where the current sets toward [rad], from +x (east) counter-clockwise (as the wind's and the waves')."""
    tidal_amplitude: float = 0.0
    """A: the tidal part's amplitude along ``direction`` [m/s]; 0: steady. Above ``speed`` the stream turns
    and runs the other way for part of each period."""
    tidal_period: float = M2_PERIOD
    """T [s] (default the M2 tide's 12.42 h)."""
    tidal_phase: float = 0.0
    """phi [rad]: at t = 0 the tidal part is A cos(phi) (0: the flood at its strongest)."""
    profile_depth: float = 0.0
    """D [m]: the current fades to nothing at this depth below still water; 0: the same at every depth."""
    profile_exponent: float = 1.0 / 7.0
    """p in (0, 1]: 1/7 the power law of a tidal stream's boundary layer, 1 a linear shear (only with a
    ``profile_depth``)."""

    def __post_init__(self):
        owner = "CurrentConfig"
        for name in ("speed", "tidal_amplitude"):
            object.__setattr__(self, name, require_non_negative(owner, name, getattr(self, name), unit=" [m/s]"))
        for name in ("direction", "tidal_phase"):
            object.__setattr__(self, name, require_finite(owner, name, getattr(self, name)))
        object.__setattr__(self, "tidal_period", require_positive(owner, "tidal_period", self.tidal_period,
                                                                  unit=" [s]"))
        object.__setattr__(self, "profile_depth", require_non_negative(owner, "profile_depth", self.profile_depth,
                                                                       unit=" [m]"))
        exponent = require_finite(owner, "profile_exponent", self.profile_exponent)
        if not 0.0 < exponent <= 1.0:
            raise ValueError(f"{owner}.profile_exponent must be in (0, 1], got {exponent!r}")
        object.__setattr__(self, "profile_exponent", exponent)

    @property
    def still(self) -> bool:
        """True where the config holds no current (no steady speed, no tide)."""
        return self.speed == 0.0 and self.tidal_amplitude == 0.0

    def tide_model(self) -> TideModel:
        """The kernels' view of the tidal part."""
        return struct_from(TideModel, amplitude=self.tidal_amplitude,
                           angular_frequency=2.0 * math.pi / self.tidal_period, phase=self.tidal_phase)
