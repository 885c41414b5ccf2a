"""One config for a WAM-V simulation: the boat, the sea, the wind, the current, the sensors and the clock."""

from __future__ import annotations

import dataclasses
import math

from ..current_config import CurrentConfig
from ..eboat.simulator_config import still_water
from ..hydrodynamics_config import HydrodynamicsConfig
from ..ocean_config import OceanConfig
from ..sensors import SensorConfig
from ..simulator import SimulatorConfig
from ..validation import require_in_range, require_int_in_range, require_positive
from ..water_config import WaterConfig
from ..wind import WindConfig
from .boat import wamv_hydrodynamics
from .config import WamvConfig

__all__ = ["WamvSimulatorConfig"]


@dataclasses.dataclass(frozen=True)
class WamvSimulatorConfig:
    """Everything a :class:`~ocean_warp.wamv.WamvSimulator` is built from (as ``EBoatSimulatorConfig`` for the
    E-Boat). The water (density, gravity, viscosity) is the sea's, ``ocean.water``."""

    boat: WamvConfig = dataclasses.field(default_factory=WamvConfig)
    """Which WAM-V (profile, thrusters, figures)."""
    ocean: OceanConfig = dataclasses.field(default_factory=still_water)
    """The sea and its water (default: still sea water)."""
    wind: WindConfig = dataclasses.field(default_factory=lambda: WindConfig(speed=0.0))
    """Mean wind and gusts (default calm air, as VRX's worlds start): the windage (``WamvConfig.wind_coefficients``)
    and the sensors read it."""
    current: CurrentConfig = dataclasses.field(default_factory=CurrentConfig)
    """The water's current (default: none)."""
    sensors: SensorConfig = dataclasses.field(default_factory=SensorConfig)
    """Noise and rates of the sensors."""
    hydrodynamics: HydrodynamicsConfig | None = None
    """The per-triangle hull model; None (default): the boat profile's (``wamv_hydrodynamics``)."""
    dt: float = 0.05
    """Duration of one ``step()`` [s]; the sensors read once per step."""
    substeps: int = 5
    """Substeps per step: ocean, current, water forces, thrusters and integration run every dt / substeps."""
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
    """Capture a step as a graph on its first call and replay it."""

    def __post_init__(self):
        owner = "WamvSimulatorConfig"
        if self.hydrodynamics is None and isinstance(self.boat, WamvConfig):
            object.__setattr__(self, "hydrodynamics", wamv_hydrodynamics(self.boat))
        for name, kind in (("boat", WamvConfig), ("ocean", OceanConfig), ("wind", WindConfig),
                           ("current", CurrentConfig), ("sensors", SensorConfig),
                           ("hydrodynamics", HydrodynamicsConfig)):
            if not isinstance(getattr(self, name), kind):
                raise ValueError(f"{owner}.{name} must be a {kind.__name__}, got {getattr(self, name)!r}")
        object.__setattr__(self, "dt", require_positive(owner, "dt", self.dt, unit=" [s]"))
        object.__setattr__(self, "substeps", require_int_in_range(owner, "substeps", self.substeps, 1, 1000))
        object.__setattr__(self, "max_tilt", require_in_range(owner, "max_tilt", self.max_tilt, 0.0, math.pi,
                                                              unit=" [rad]"))
        self.simulator_config()  # the rest is checked there, with the same messages

    @property
    def water(self) -> WaterConfig:
        """The water the boats float in: the sea's (``ocean.water``)."""
        return self.ocean.water

    @property
    def substep_dt(self) -> float:
        """[s]"""
        return self.dt / self.substeps

    def simulator_config(self) -> SimulatorConfig:
        """The generic :class:`~ocean_warp.SimulatorConfig` this config amounts to."""
        return SimulatorConfig(dt=self.dt, substeps=self.substeps, hydrodynamics=self.hydrodynamics,
                               ocean_every_substep=self.ocean_every_substep, hull_pressure=True,
                               max_altitude=self.max_altitude, max_depth=self.max_depth, max_tilt=self.max_tilt,
                               block_dim=self.block_dim, capture_graph=self.capture_graph)
