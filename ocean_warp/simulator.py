"""The Simulator: an ocean and a fleet advanced together, one captured CUDA graph per step."""

from __future__ import annotations

import dataclasses
import math

import warp as wp

from .current import Current, no_current
from .device_structs import struct_from
from .fleet import Fleet
from .hydrodynamics_config import HydrodynamicsConfig
from .kernels.hull_forces import WaterModel, hull_wrenches_kernel, sample_origin_water
from .kernels.rigid_body import SafetyBounds, advance_time, integrate_boats
from .ocean import Ocean
from .kernels.radiation import advance_radiation_terms
from .radiation import check_wave_point_depths, radiation_model
from .replay import ReplayedLaunches
from .torch_streams import ordered_with_torch
from .validation import require_in_range, require_int_in_range, require_positive
from .water_config import WaterConfig

__all__ = ["Simulator", "SimulatorConfig", "ocean_updates_of_step", "launch_clock_advance"]


@dataclasses.dataclass(frozen=True)
class SimulatorConfig:
    """Time stepping and the limits past which a boat is flagged."""

    dt: float = 0.01
    """Duration of one ``step()`` [s]."""
    substeps: int = 4
    """Substeps per step: ocean, water forces and integration run this often, each dt / substeps."""
    hydrodynamics: HydrodynamicsConfig = dataclasses.field(default_factory=HydrodynamicsConfig)
    """The per-triangle force model (the water it acts in is the ocean's: ``OceanConfig.water``)."""
    ocean_every_substep: bool = True
    """Re-evaluate the ocean every substep (True) or once per step, at its start (False, cheaper)."""
    hull_pressure: bool = True
    """Compute the per-triangle water forces; False leaves buoyancy to a force model (e.g. the E-Boat's
    original four-point buoyancy)."""
    max_altitude: float = 20.0
    """A boat whose origin rises this far above still water is flagged FLYING [m]."""
    max_depth: float = 50.0
    """A boat whose origin sinks this deep is flagged SUNK [m]."""
    max_tilt: float = math.pi / 2
    """A boat whose z axis tilts further than this from the vertical is flagged CAPSIZED [rad]."""
    block_dim: int | None = None
    """Threads per boat in the hull-force pass; None: 1 on the CPU, 128 on CUDA (fastest on an H100)."""
    capture_graph: bool = True
    """Capture one step as a graph on the first call and replay it afterwards (a CUDA graph, or Warp's
    recorded launches on the CPU; see ``ocean_warp.replay``)."""

    def __post_init__(self):
        owner = "SimulatorConfig"
        object.__setattr__(self, "dt", require_positive(owner, "dt", self.dt, unit=" [s]"))
        object.__setattr__(self, "substeps", require_int_in_range(owner, "substeps", self.substeps, 1, 1000))
        if not isinstance(self.hydrodynamics, HydrodynamicsConfig):
            raise ValueError(f"{owner}.hydrodynamics must be a HydrodynamicsConfig, got {self.hydrodynamics!r}")
        object.__setattr__(self, "max_altitude", require_positive(owner, "max_altitude", self.max_altitude, unit=" [m]"))
        object.__setattr__(self, "max_depth", require_positive(owner, "max_depth", self.max_depth, unit=" [m]"))
        object.__setattr__(self, "max_tilt", require_in_range(owner, "max_tilt", self.max_tilt, 0.0, math.pi, unit=" [rad]"))
        if self.block_dim is not None:
            object.__setattr__(self, "block_dim", require_int_in_range(owner, "block_dim", self.block_dim, 1, 1024))

    @property
    def substep_dt(self) -> float:
        return self.dt / self.substeps


class Simulator:
    """An :class:`Ocean` and a :class:`Fleet` on one device, advanced by :meth:`step`.

    Each substep: evaluate the ocean at the current time, sample it at every hull vertex, compute
    each boat's water wrench (one block per boat), run the force models, integrate the rigid bodies,
    advance the time; after the last substep, the models' per-step work (sensors). On CUDA the whole
    step is captured once as a graph and replayed: no allocation, no host synchronisation. Change the
    fleet's state and external wrenches between steps through its arrays or torch views; they are
    read on the device.

    ``models`` are objects with ``substep(simulator)``, which launches kernels that add body-frame
    wrenches about the origin to ``fleet.forces.model_wrench`` (zeroed before them every substep), and
    optionally ``step(simulator)``, run once per step after the substeps. They launch in list order.

    ``current``: a :class:`~ocean_warp.Current` of one environment per boat, updated at the start of every
    substep (before the hull pass) from the simulator's clock; the hull, the boats' damping and the force
    models then feel the water's velocity relative to the boat, current included. None: still water.
    """

    def __init__(self, ocean: Ocean, fleet: Fleet, config: SimulatorConfig | None = None, *, models=(),
                 current: Current | None = None):
        self.config = config if config is not None else SimulatorConfig()
        if not isinstance(ocean, Ocean) or not isinstance(fleet, Fleet):
            raise ValueError("Simulator needs an ocean_warp.Ocean and an ocean_warp.Fleet")
        if ocean.device != fleet.device:
            raise ValueError(f"Simulator: the ocean is on {ocean.device} but the fleet on {fleet.device}")
        self.ocean = ocean
        self.fleet = fleet
        self.device = fleet.device
        self.clock = wp.clone(ocean.time)
        """(1,) float64 simulated time [s], the simulation's state beside the fleet's (starts at the ocean's
        time); every substep evaluates the ocean at it and advances it on the device."""
        if self.config.hull_pressure and not ocean.depth_fields:
            raise ValueError("Simulator: the hull pass reads the ocean's pressure at depth, which this ocean does not "
                             "evaluate; build it with Ocean(..., depth_fields=True)")
        self.block_dim = self.config.block_dim or (128 if self.device.is_cuda else 1)
        vertex_rounds = -(-fleet.model.max_vertex_count // self.block_dim)
        self.water = _water_model(self.config.hydrodynamics, ocean.config.water, self.config.substep_dt)
        """The hull pass's view of the hull model and of the ocean's water (its density, gravity, viscosity)."""
        check_wave_point_depths(fleet.model.boat_types, ocean.config.pressure_depths)
        self.radiation = radiation_model(fleet.model.boat_types, self.config.substep_dt, self.device)
        """The fleet's radiation models discretised for the substep (``ocean_warp.kernels.radiation``)."""
        if current is not None:
            if not isinstance(current, Current):
                raise ValueError(f"Simulator: current must be an ocean_warp.Current or None, got {current!r}")
            if current.device != self.device or current.count != fleet.count:
                raise ValueError(f"Simulator: the current holds {current.count} environments on {current.device}, "
                                 f"the fleet {fleet.count} boats on {self.device}: one environment per boat")
            current.follow(self.clock)
        self.current = current
        """The water's current (a :class:`~ocean_warp.Current`), or None: still water."""
        self._hull_wrenches = hull_wrenches_kernel(
            vertex_rounds, self.block_dim, wave_points=any(t.seakeeping is not None for t in fleet.model.boat_types),
            currents=current is not None)
        self.current_field = current.field if current is not None else no_current(self.device)
        """What the force kernels read of the current (a field without rows when there is none)."""
        self.bounds = SafetyBounds()
        self.bounds.max_altitude = self.config.max_altitude
        self.bounds.max_depth = self.config.max_depth
        self.bounds.min_uprightness = math.cos(self.config.max_tilt)
        self.models = list(models)
        for model in self.models:
            if not callable(getattr(model, "substep", None)):
                raise ValueError(f"Simulator: model {model!r} has no substep(simulator) method")
        self._replayed_step = ReplayedLaunches(self.launch_step, self.device, capture=self.config.capture_graph)

    def add_model(self, model) -> None:
        """Add a force model (``substep(simulator)``, optionally ``step(simulator)``) after the others; the step
        is captured anew at its next call."""
        if not callable(getattr(model, "substep", None)):
            raise ValueError(f"Simulator.add_model: {model!r} has no substep(simulator) method")
        self.models.append(model)
        self._replayed_step = ReplayedLaunches(self.launch_step, self.device, capture=self.config.capture_graph)

    @property
    def time(self) -> float:
        """Simulated time [s] (reads the device; do not call inside a capture)."""
        return float(self.clock.numpy()[0])

    def compute_hull_wrenches(self) -> None:
        """Sample the ocean at every hull vertex and sum the water's wrench on each boat into
        ``fleet.forces.hydro_wrench``, for the fleet's current state and the ocean's current fields."""
        fleet = self.fleet
        wp.launch_tiled(self._hull_wrenches, dim=[fleet.count], block_dim=self.block_dim, device=self.device,
                        inputs=[self.ocean.surface, fleet.model.meshes, self.water, fleet.model.hull_type, fleet.model.triangle_offset,
                                fleet.state.position, fleet.state.orientation, fleet.state.velocity,
                                fleet.state.swept_rate, self.current_field],
                        outputs=[fleet.state.water_velocity, fleet.state.wave_velocity, fleet.state.wave_acceleration,
                                 fleet.forces.hydro_wrench])

    def integrate(self) -> None:
        """One substep of the rigid bodies with the wrenches computed last, then of their radiation memory."""
        fleet = self.fleet
        wp.launch(integrate_boats, dim=fleet.count, device=self.device,
                  inputs=[fleet.model.body, fleet.model.hull_type, self.ocean.config.water.gravity, self.config.substep_dt,
                          self.bounds, fleet.forces.hydro_wrench, fleet.forces.model_wrench, fleet.control.wrench_world, fleet.control.wrench_body,
                          fleet.state.water_velocity, self.radiation, fleet.state.wave_acceleration,
                          fleet.state.radiation_output],
                  outputs=[fleet.state.position, fleet.state.orientation, fleet.state.velocity, fleet.state.status])
        if fleet.model.radiation_terms:
            wp.launch(advance_radiation_terms, dim=(fleet.count, fleet.model.radiation_terms), device=self.device,
                      inputs=[self.radiation, fleet.model.hull_type, fleet.state.velocity, fleet.state.orientation,
                              fleet.state.wave_velocity, fleet.state.status],
                      outputs=[fleet.state.radiation_state, fleet.state.radiation_output])

    def substep(self, *, update_ocean: bool = True) -> None:
        """Ocean (optionally), current, water forces, force models, integration, time += dt / substeps."""
        if update_ocean:
            self.ocean.update(clock=self.clock)
        if self.current is not None:
            self.current.update()
        if self.config.hull_pressure:
            self.compute_hull_wrenches()
        else:
            self._sample_origin_water()
        self.fleet.forces.model_wrench.zero_()
        for model in self.models:
            model.substep(self)
        self.integrate()
        launch_clock_advance(self.clock, self.config.substep_dt, self.device)

    def _sample_origin_water(self) -> None:
        """Without the hull pass, still sample the water velocity at each boat's origin."""
        fleet = self.fleet
        wp.launch(sample_origin_water, dim=fleet.count, device=self.device,
                  inputs=[self.ocean.surface, fleet.state.position, fleet.state.orientation, self.current_field],
                  outputs=[fleet.state.water_velocity])

    def launch_step(self) -> None:
        """Launch one step's kernels without capturing them, e.g. inside a larger capture of the caller's
        (an environment's decision step); :meth:`step` is the usual way."""
        for update_ocean in ocean_updates_of_step(self.config.substeps, self.config.ocean_every_substep):
            self.substep(update_ocean=update_ocean)
        for model in self.models:
            if callable(getattr(model, "step", None)):
                model.step(self)

    def step(self) -> None:
        """Advance ``config.dt`` seconds (asynchronous on CUDA, ordered after torch's pending work on
        the fleet's tensors and before torch's next)."""
        with ordered_with_torch(self.device):
            self._replayed_step()

    @property
    def step_graph(self) -> wp.Graph | None:
        """The captured step (after the first :meth:`step`; None without capture), for benchmarks."""
        return self._replayed_step.graph


def ocean_updates_of_step(substeps: int, every_substep: bool) -> list[bool]:
    """Which substeps of a step update the ocean before their forces: every one with ``every_substep``,
    else the first only. The simulator's clock then advances by the substep dt after each substep."""
    return [every_substep or index == 0 for index in range(substeps)]


def launch_clock_advance(time: wp.array, substep_dt: float, device) -> None:
    """The simulator's clock: ``time`` (1,) float64 [s] += ``substep_dt`` [s], on the device (graph-safe)."""
    wp.launch(advance_time, dim=1, inputs=[time, wp.float64(substep_dt)], device=device)


def _water_model(config: HydrodynamicsConfig, water: WaterConfig, substep: float) -> WaterModel:
    return struct_from(WaterModel, config, water,
                       inverse_reference_speed=1.0 / config.reference_speed,
                       skin_friction=int(config.skin_friction), friction_factor=1.0 + config.form_factor,
                       cross_flow_only=int(config.cross_flow_only), slamming=int(config.slamming),
                       inverse_slamming_max_acceleration=1.0 / config.slamming_max_acceleration, substep=substep)
