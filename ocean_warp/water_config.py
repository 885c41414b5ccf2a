"""The water: density, gravity and viscosity, one home for every model that needs them.

The sea carries its water (``OceanConfig.water``): the waves' dispersion reads its gravity, and a
:class:`~ocean_warp.Simulator` gives the hull pressure and friction, the buoyancy points, the keel and
rudder, the rigid bodies' weight and the accelerometers the water and gravity of the ocean it sails on.
"""

from __future__ import annotations

import dataclasses

from .validation import require_positive

__all__ = ["WaterConfig"]


@dataclasses.dataclass(frozen=True)
class WaterConfig:
    """Sea water at 15 C by default. The E-Boat's Gazebo twin sailed fresh water: ``WaterConfig(density=997.0)``.

    Invalid values raise ``ValueError`` naming the field."""

    density: float = 1025.0
    """rho [kg/m^3]."""
    gravity: float = 9.81
    """g [m/s^2], for the waves, the boats' weight and buoyancy, and the accelerometers."""
    kinematic_viscosity: float = 1.19e-6
    """nu [m^2/s] (ITTC, sea water at 15 C), for the hull's skin friction."""

    def __post_init__(self):
        owner = "WaterConfig"
        for name, unit in (("density", " [kg/m^3]"), ("gravity", " [m/s^2]"), ("kinematic_viscosity", " [m^2/s]")):
            object.__setattr__(self, name, require_positive(owner, name, getattr(self, name), unit=unit))
