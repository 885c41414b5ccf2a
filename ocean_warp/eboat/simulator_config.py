"""One config for an E-Boat simulation: the boat, the sea, the wind, the sensors, the water and the clock."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..current_config import CurrentConfig
from ..hydrodynamics_config import HydrodynamicsConfig
from ..ocean_config import OceanConfig
from ..sensors import SensorConfig
from ..simulator import SimulatorConfig
from ..validation import require_in_range, require_int_in_range, require_positive
from ..water_config import WaterConfig
from ..wind import WindConfig
from .eboat import EBoatConfig, Hydrostatics, eboat_hydrodynamics

__all__ = ["EBoatSimulatorConfig", "still_water"]


def still_water() -> OceanConfig:
    """A flat sea on the smallest grid (no waves to compute)."""
    return OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.0)


@dataclasses.dataclass(frozen=True)
class EBoatSimulatorConfig:
    """Everything an :class:`~ocean_warp.eboat.EBoatSimulator` is built from; an environment config nests it.

    The water (density, gravity, viscosity) is the sea's, ``ocean.water`` (also read as ``config.water``):
    the waves, the hull's pressure and friction, the keel and rudder, the four-point buoyancy, the boats'
    weight and the accelerometers all take it from there.
    """

    boat: EBoatConfig = dataclasses.field(default_factory=EBoatConfig)
    """Which E-Boat (version, profile, mesh or four-point hydrostatics, the real or the procedural hull, ballast,
    original tuning)."""
    ocean: OceanConfig = dataclasses.field(default_factory=still_water)
    """The sea and its water (default: still sea water)."""
    wind: WindConfig = dataclasses.field(default_factory=WindConfig)
    """Mean wind, gusts and height profile (every environment starts with this mean)."""
    current: CurrentConfig = dataclasses.field(default_factory=CurrentConfig)
    """The water's current: steady speed and direction, tide, depth profile (default: none; every environment
    starts with this one)."""
    sensors: SensorConfig = dataclasses.field(default_factory=SensorConfig)
    """Noise and rates of the boat's sensors."""
    hydrodynamics: HydrodynamicsConfig | None = None
    """The per-triangle hull model; None (default): the boat profile's (``eboat_hydrodynamics``)."""
    dt: float = 0.05
    """Duration of one ``step()`` [s]; the sensors read once per step."""
    substeps: int = 5
    """Substeps per step: ocean, current, water forces, wind, rig and integration run every dt / substeps."""
    ocean_every_substep: bool = True
    """Evaluate the ocean every substep (True) or once per step (False, cheaper)."""
    max_tilt: float = math.pi / 2
    """A boat tilted further than this from upright is flagged CAPSIZED [rad]."""
    max_altitude: float = 20.0
    """A boat whose origin rises this far above still water is flagged FLYING [m]."""
    max_depth: float = 50.0
    """A boat whose origin sinks this deep is flagged SUNK [m]."""
    block_dim: int | None = None
    """Threads per boat in the hull pass; None: 1 on the CPU, 128 on CUDA."""
    capture_graph: bool = True
    """Capture a step as a graph on its first call and replay it (on CUDA and on the CPU)."""
    mass_variation: float = 0.0
    """Domain randomisation of the boat's mass, as a fraction (0 to 0.3; 0: every boat as built). With
    v > 0 the fleet holds ``mass_variants`` boat types whose mass and inertia about the centre of mass
    are the E-Boat's times ``np.linspace(1 - v, 1 + v, mass_variants)``; boat i is variant i % K, for
    the simulator's life (``EBoatSimulator.mass_scale``). Added mass and damping belong to the water
    and stay as they are."""
    mass_variants: int = 5
    """Number K of mass variants (1 to 64) when ``mass_variation`` > 0; K = 1 is the nominal boat alone."""

    def __post_init__(self):
        owner = "EBoatSimulatorConfig"
        if self.hydrodynamics is None and isinstance(self.boat, EBoatConfig):
            object.__setattr__(self, "hydrodynamics", eboat_hydrodynamics(
                self.boat.profile, radiation=self.boat.uses_hydro_database))
        for name, kind in (("boat", EBoatConfig), ("ocean", OceanConfig), ("wind", WindConfig),
                           ("current", CurrentConfig), ("sensors", SensorConfig),
                           ("hydrodynamics", HydrodynamicsConfig)):
            if not isinstance(getattr(self, name), kind):
                raise ValueError(f"{owner}.{name} must be a {kind.__name__}, got {getattr(self, name)!r}")
        object.__setattr__(self, "dt", require_positive(owner, "dt", self.dt, unit=" [s]"))
        object.__setattr__(self, "substeps", require_int_in_range(owner, "substeps", self.substeps, 1, 1000))
        object.__setattr__(self, "mass_variation", require_in_range(owner, "mass_variation", self.mass_variation,
                                                                    0.0, 0.3))
        object.__setattr__(self, "mass_variants", require_int_in_range(owner, "mass_variants", self.mass_variants,
                                                                       1, 64))
        object.__setattr__(self, "max_tilt", require_in_range(owner, "max_tilt", self.max_tilt, 0.0, math.pi,
                                                              unit=" [rad]"))
        # The rest is checked where it is used, with the same messages.
        self.simulator_config()

    @property
    def water(self) -> WaterConfig:
        """The water the boats sail in: the sea's (``ocean.water``)."""
        return self.ocean.water

    def mass_factors(self) -> np.ndarray:
        """(K,) factors on mass and inertia of the fleet's boat types: [1.0] without mass variation, else
        ``np.linspace(1 - v, 1 + v, K)`` (K = 1: [1.0])."""
        if self.mass_variation == 0.0 or self.mass_variants == 1:
            return np.ones(1)
        return np.linspace(1.0 - self.mass_variation, 1.0 + self.mass_variation, self.mass_variants)

    @property
    def substep_dt(self) -> float:
        """[s]"""
        return self.dt / self.substeps

    def simulator_config(self) -> SimulatorConfig:
        """The generic :class:`~ocean_warp.SimulatorConfig` this config amounts to."""
        return SimulatorConfig(dt=self.dt, substeps=self.substeps, hydrodynamics=self.hydrodynamics,
                               ocean_every_substep=self.ocean_every_substep,
                               hull_pressure=self.boat.hydrostatics is Hydrostatics.MESH,
                               max_altitude=self.max_altitude, max_depth=self.max_depth, max_tilt=self.max_tilt,
                               block_dim=self.block_dim, capture_graph=self.capture_graph)
