"""Many E-Boats on one ocean, each in a wind and a current of its own: the Simulator with the rig, wind, current
and sensor models wired in, and named views of its state, controls and resets."""

from __future__ import annotations

import dataclasses

import numpy as np
import warp as wp

from ocean_warp.current import Current
from ocean_warp.fleet import Fleet
from ocean_warp.frames import quaternion_from_roll_pitch_yaw
from ocean_warp.kernels.appendage_buoyancy import appendage_buoyancy
from ocean_warp.kernels.eboat_actions import apply_eboat_actions
from ocean_warp.kernels.point_buoyancy import point_buoyancy
from ocean_warp.device_structs import struct_from
from ocean_warp.kernels.sailing_rig import RigControl, RigState, RigSurroundings, reset_rig, sailing_rig
from ocean_warp.masks import mask_of, rows_at
from ocean_warp.ocean import Ocean
from ocean_warp.sensors import Sensors
from ocean_warp.simulator import Simulator
from ocean_warp.torch_streams import ordered_with_torch
from ocean_warp.validation import require_indices, require_int_in_range, require_per_item, require_rows
from ocean_warp.wind import Wind
from .eboat import EBoat, Hydrostatics
from .reef import require_reef_levels
from .simulator_config import EBoatSimulatorConfig
from .state import EBoatControl, EBoatStart, EBoatState, EBoatTensors

__all__ = ["EBoatSimulator", "SailingRig"]


class SailingRig:
    """Every boat's rig: its model (``parameters``, ``tables``: the E-Boat's sail, keel, rudder and
    propeller, the water's density), its ``state`` (actuators, boom, foil factors) and its ``control`` (the
    commands), and the force model that turns them, with the wind and the water, into sail, keel, rudder,
    windage and propeller forces every substep (keel and rudder in the water's flow at their depth, current
    included), the sail at each boat's reef level. ``state`` and ``control`` are Warp structs of (N,) arrays
    (``RigState``, ``RigControl`` in ``ocean_warp.kernels.sailing_rig``: names, units)."""

    def __init__(self, eboat: EBoat, count: int, wind: Wind, *, water_density: float, device):
        self.device = wp.get_device(device)
        self.count = count
        self.wind = wind
        self.parameters = eboat.rig_parameters(water_density, self.device)
        self.tables = eboat.foil_tables(self.device)
        zeros = lambda dtype=float: wp.zeros(count, dtype=dtype, device=self.device)  # noqa: E731
        self.control = struct_from(RigControl, rudder=zeros(), sheet=zeros(), propeller=zeros(int))
        """What is commanded: rudder [rad], sheet [rad], propeller level."""
        self.state = struct_from(RigState, rudder_angle=zeros(), sheet_limit=zeros(), boom_angle=zeros(),
                                 boom_rate=zeros(),
                                 foil_scale=wp.full(count, wp.vec3(1.0, 1.0, 1.0), dtype=wp.vec3, device=self.device),
                                 reef_level=zeros(int))
        """What moves (rudder and boom angles [rad], boom rate [rad/s]), the foil factors and the reef level of
        the episode (set by :meth:`reset_masked`)."""
        self._around: RigSurroundings | None = None

    def substep(self, simulator) -> None:
        if self._around is None:  # the fleet's, the wind's and the current's arrays, bound once
            fleet = simulator.fleet
            self._around = struct_from(RigSurroundings, fleet.state, wind_velocity=self.wind.state.velocity,
                                       current=simulator.current_field)
        wp.launch(sailing_rig, dim=self.count, device=self.device,
                  inputs=[self.parameters, self.tables, self.wind.gusts, simulator.config.substep_dt, self._around,
                          self.control, self.state],
                  outputs=[simulator.fleet.forces.model_wrench, simulator.fleet.state.status])

    def reset_masked(self, mask: wp.array, sheet: wp.array, foil_scale: wp.array | None = None,
                     reef_level: wp.array | None = None) -> None:
        """Boats whose ``mask`` is non-zero: rudder and boom centred, propeller stopped, sheet (command and
        actual limit) at their row of ``sheet`` [rad], their foil factors at their row of ``foil_scale`` (N,)
        vec3 and their reef level at their row of ``reef_level`` (N,) int32 (None: kept). Launches only
        (graph-safe)."""
        wp.launch(reset_rig, dim=self.count, device=self.device,
                  inputs=[mask, sheet, self.state.foil_scale if foil_scale is None else foil_scale,
                          self.state.reef_level if reef_level is None else reef_level,
                          self.parameters.sheet_limit_max, self.control, self.state])


class _PointBuoyancyModel:
    """The original twin's four-point buoyancy, as a force model."""

    def __init__(self, eboat: EBoat, device, water):
        self.parameters = eboat.point_buoyancy(device, water)

    def substep(self, simulator) -> None:
        fleet = simulator.fleet
        wp.launch(point_buoyancy, dim=fleet.count, device=simulator.device,
                  inputs=[self.parameters, simulator.ocean.surface, fleet.state.position, fleet.state.orientation],
                  outputs=[fleet.forces.model_wrench])


class _AppendageBuoyancyModel:
    """The buoyancy of keel, bulb and rudder, which the hull mesh leaves out, as a force model."""

    def __init__(self, parameters):
        self.parameters = parameters

    def substep(self, simulator) -> None:
        fleet = simulator.fleet
        wp.launch(appendage_buoyancy, dim=fleet.count, device=simulator.device,
                  inputs=[self.parameters, simulator.ocean.surface, fleet.state.position, fleet.state.orientation],
                  outputs=[fleet.forces.model_wrench])


def _fleet(eboat: EBoat, config: EBoatSimulatorConfig, count: int, device,
           first_boat: int = 0) -> tuple[Fleet, np.ndarray]:
    """The fleet, and each boat's factor on mass and inertia: one boat type without mass variation, else
    ``config.mass_variants`` types (mass and inertia about the centre of mass scaled; centre of mass,
    added mass, damping and the hull shared), boat i of type (first_boat + i) % K."""
    factors = config.mass_factors()
    if len(factors) == 1:
        return Fleet(eboat.boat_type, count, device=device), np.ones(count)
    base = eboat.boat_type
    variants = [dataclasses.replace(base, mass=base.mass * float(f), inertia=base.inertia * float(f),
                                    name=f"{base.name} x{f:.4g} mass") for f in factors]
    types = (first_boat + np.arange(count)) % len(factors)
    return Fleet(variants, types=types, device=device), factors[types]


class EBoatSimulator:
    """``count`` E-Boats on one ocean, boat i in environment i with a wind and a current of its own.

    Example::

        config = EBoatSimulatorConfig(ocean=OceanConfig(significant_wave_height=0.5),
                                      wind=WindConfig(speed=7.0, gust_speed_std=1.0))
        sim = EBoatSimulator(config, 256, device="cuda:0")
        sim.reset(heading=0.3, sheet=0.6)
        control = sim.tensors.control          # torch views, no copies
        control.rudder[:] = 0.1                # rad
        for _ in range(100):
            sim.step()
        sim.tensors.state.readings             # (256, 16) noisy sensor readings

    ``sim.state`` (what moves), ``sim.control`` (what is commanded) and ``sim.start`` (where a reset
    puts a boat) name the Warp arrays; ``sim.tensors`` holds torch views of all three, bound here.
    Resets: :meth:`reset` on the host (indices, numpy), :meth:`reset_masked` on the device.
    """

    def __init__(self, config: EBoatSimulatorConfig | None = None, count: int = 1, *, device=None,
                 ocean: Ocean | None = None, first_boat: int = 0):
        """``config`` (default: still water, 5 m/s steady wind, the V-C boat); ``count`` boats; ``ocean``: an
        existing :class:`Ocean` to share instead of building ``config.ocean`` (its water must be ``config.water``);
        ``first_boat``: this batch is boats [first_boat, first_boat + count) of a larger one with the same
        config: each boat gets that boat's mass variant and its gust and sensor-noise random streams (a
        shard of a batch, as ``ocean_warp.envs.parallel.sharded`` runs one per process, sails like the batch)."""
        self.config = config if config is not None else EBoatSimulatorConfig()
        if not isinstance(self.config, EBoatSimulatorConfig):
            raise ValueError(f"EBoatSimulator: config must be an EBoatSimulatorConfig, got {self.config!r}")
        count = require_int_in_range("EBoatSimulator", "count", count, 1, 2**24)
        config = self.config
        self.device = wp.get_device(device if device is not None else (ocean.device if ocean is not None else None))
        device = self.device
        self.eboat = EBoat(config.boat)
        if ocean is None:
            # The four-point hull reads only the surface: the pressure at depth would cost it most of its step.
            ocean = Ocean(config.ocean, device=device, depth_fields=config.boat.hydrostatics is Hydrostatics.MESH)
        elif ocean.config.water != config.water:
            raise ValueError(f"EBoatSimulator: the ocean given holds {ocean.config.water}, the config "
                             f"{config.water}; the boats sail in the water of the ocean they float on")
        self.first_boat = require_int_in_range("EBoatSimulator", "first_boat", first_boat, 0, 2**30)
        self.fleet, mass_scale = _fleet(self.eboat, config, count, device, self.first_boat)
        self.mass_scale = mass_scale
        """(N,) float64 numpy: each boat's factor on the E-Boat's mass and inertia about its centre of mass,
        fixed for the simulator's life: all 1 without ``config.mass_variation``, else boat i has
        ``config.mass_factors()[(first_boat + i) % K]`` (its BoatType: ``fleet.model.boat_types[(first_boat + i) % K]``)."""
        self.wind = Wind(config.wind, count, substep=config.substep_dt, device=device, first_index=self.first_boat)
        self.current = Current(config.current, count, device=device)
        self.rig = SailingRig(self.eboat, count, self.wind, water_density=config.water.density, device=device)
        self.sensors = Sensors(config.sensors, count, masthead=self.eboat.masthead, wind=self.wind, step=config.dt,
                               gravity=config.water.gravity, device=device, first_index=self.first_boat)
        models = [self.wind]
        if config.boat.hydrostatics is Hydrostatics.POINTS:
            models.append(_PointBuoyancyModel(self.eboat, device, config.water))
        elif (appendages := self.eboat.appendage_buoyancy(config.water)) is not None:
            models.append(_AppendageBuoyancyModel(appendages))
        models += [self.rig, self.sensors]
        self.simulator = Simulator(ocean, self.fleet, config.simulator_config(), models=models, current=self.current)
        self.ocean = ocean

        fleet, rig, wind, sensors, current = self.fleet, self.rig, self.wind, self.sensors, self.current.state
        self.state = EBoatState(
            position=fleet.state.position, orientation=fleet.state.orientation, velocity=fleet.state.velocity, status=fleet.state.status,
            water_velocity=fleet.state.water_velocity, rudder_angle=rig.state.rudder_angle,
            sheet_limit=rig.state.sheet_limit, boom_angle=rig.state.boom_angle, boom_rate=rig.state.boom_rate,
            wind_mean_speed=wind.state.mean_speed, wind_mean_direction=wind.state.mean_direction,
            wind_speed=wind.state.speed, wind_direction=wind.state.direction, wind_velocity=wind.state.velocity,
            gust_scale=wind.state.gust_scale, current_speed=current.speed, current_direction=current.direction,
            current_velocity=current.velocity, foil_scale=rig.state.foil_scale, reef_level=rig.state.reef_level,
            noise_scale=sensors.noise_scale, readings=sensors.readings, truth=sensors.truth, time=self.simulator.clock)
        """What moves (Warp arrays; see :class:`EBoatState` for units)."""
        self.control = EBoatControl(rudder=rig.control.rudder, sheet=rig.control.sheet,
                                    propeller=rig.control.propeller, wrench_world=fleet.control.wrench_world,
                                    wrench_body=fleet.control.wrench_body)
        """What is commanded (Warp arrays; see :class:`EBoatControl`)."""
        self.start = EBoatStart.allocate(count, device)
        """Where :meth:`reset_masked` puts each boat (Warp arrays; see :class:`EBoatStart`)."""
        self.tensors = EBoatTensors(self.state.map(wp.to_torch), self.control.map(wp.to_torch),
                                    self.start.map(wp.to_torch))
        """torch views of ``state``, ``control`` and ``start``, bound once."""
        self._all_actions = wp.ones(3, dtype=wp.int32, device=device)
        self.reset()

    @property
    def count(self) -> int:
        return self.fleet.count

    def sail_scales(self) -> np.ndarray:
        """(N,) float64: each boat's sail scale at its reef level now, the linear factor on the full sail about
        its tack (``config.boat.reef_scales``; reads the device), for drawings."""
        with ordered_with_torch(self.device):
            levels = self.state.reef_level.numpy()
        return np.asarray(self.config.boat.reef_scales, dtype=np.float64)[levels]

    @property
    def time(self) -> float:
        """Simulated time [s] (reads the device)."""
        return self.simulator.time

    def reset(self, boats=None, *, position=(0.0, 0.0, 0.0), heading=0.0, velocity=None, wind_speed=None,
              wind_direction=None, sheet=None, foil_scale=None, noise_scale=None, current_speed=None,
              current_direction=None, reef_level=None) -> None:
        """Host path of :meth:`reset_masked`. Put the chosen boats (None: all) upright at ``position`` [m]
        with ``heading`` [rad, yaw from +x] and ``velocity`` (Fossen nu, default at rest); centre their
        rudder and boom, stop the propeller, and sheet in, or set the sheet (command and actual limit) to
        ``sheet`` [rad, clipped to 0-90 deg]; optionally set their environments' mean wind [m/s, rad] and
        steady current (``current_speed`` [m/s] toward ``current_direction`` [rad]) (default: keep them).
        ``foil_scale``, factors on the (sail, keel, rudder) lift and drag coefficients (a row of 3 per chosen
        boat), and ``noise_scale``, a factor on each chosen boat's sensor noise, default to 1 (as configured),
        whatever they were; ``reef_level``, each chosen boat's reef level (a whole number in [0,
        ``config.boat.reef_levels``)), to 0, the full sail. Scalars and single rows broadcast."""
        owner = "EBoatSimulator.reset"
        indices = require_indices(owner, "boats", boats, self.count)
        k = len(indices)
        headings = require_per_item(owner, "heading", heading, k)
        sheets = require_per_item(owner, "sheet", 0.0 if sheet is None else sheet, k)
        positions = require_rows(owner, "position", position, k, 3)
        velocities = require_rows(owner, "velocity", np.zeros(6) if velocity is None else velocity, k, 6)
        with ordered_with_torch(self.device):
            old_speed = self.wind.state.mean_speed.numpy()[indices]
            old_direction = self.wind.state.mean_direction.numpy()[indices]
            gust_scales = self.wind.state.gust_scale.numpy()[indices]
            old_current_speed = self.current.state.speed.numpy()[indices]
            old_current_direction = self.current.state.direction.numpy()[indices]
        speeds = old_speed if wind_speed is None else require_per_item(owner, "wind_speed", wind_speed, k)
        directions = old_direction if wind_direction is None else require_per_item(owner, "wind_direction",
                                                                                    wind_direction, k)
        if np.any(speeds < 0.0):
            raise ValueError(f"{owner}.wind_speed must be >= 0 [m/s]")
        current_speeds = old_current_speed if current_speed is None else require_per_item(
            owner, "current_speed", current_speed, k)
        current_directions = old_current_direction if current_direction is None else require_per_item(
            owner, "current_direction", current_direction, k)
        if np.any(current_speeds < 0.0):
            raise ValueError(f"{owner}.current_speed must be >= 0 [m/s], got {current_speed!r}")
        foil_scales = require_rows(owner, "foil_scale", np.ones(3) if foil_scale is None else foil_scale, k, 3)
        if np.any(foil_scales < 0.0):
            raise ValueError(f"{owner}.foil_scale must be >= 0, got {foil_scale!r}")
        noise_scales = require_per_item(owner, "noise_scale", 1.0 if noise_scale is None else noise_scale, k)
        if np.any(noise_scales < 0.0):
            raise ValueError(f"{owner}.noise_scale must be >= 0, got {noise_scale!r}")
        reef_levels = require_reef_levels(owner, "reef_level", 0 if reef_level is None else reef_level, k,
                                          self.config.boat.reef_levels)
        if k == 0:
            return
        orientations = quaternion_from_roll_pitch_yaw(np.column_stack([np.zeros(k), np.zeros(k), headings]))
        n = self.count
        for name, values in (("position", positions), ("orientation", orientations), ("velocity", velocities),
                             ("sheet", sheets), ("wind_speed", speeds), ("wind_direction", directions),
                             ("gust_scale", gust_scales), ("current_speed", current_speeds),
                             ("current_direction", current_directions), ("foil_scale", foil_scales),
                             ("noise_scale", noise_scales), ("reef_level", reef_levels)):
            getattr(self.start, name).assign(rows_at(indices, values, n))
        with ordered_with_torch(self.device):
            self.reset_masked(mask_of(indices, n, self.device))

    def reset_masked(self, mask: wp.array, start: EBoatStart | None = None) -> None:
        """Device path of every reset: each boat whose ``mask`` (N,) int32 is non-zero goes to its row of
        ``start`` (default ``self.start``): pose, velocity, sheet, its environment's mean wind and steady
        current (evaluated, tide included, at the simulator's time), with
        flags, external wrenches, slamming history, rudder, boom, propeller and gusts cleared, its foil
        factors, reef level and sensor-noise factor set, a new IMU bias drawn (with that noise factor), and every
        sensor channel read at once from the new state. Boats not in the mask are
        untouched. It only launches kernels (no allocation, no host copy), so it can run inside a captured
        graph; outside one, wrap it in ``ocean_warp.torch_streams.ordered_with_torch``."""
        start = start if start is not None else self.start
        self.fleet.reset_masked(mask, start.position, start.orientation, start.velocity)
        self.wind.reset_masked(mask, start.wind_speed, start.wind_direction, start.gust_scale)
        self.current.reset_masked(mask, start.current_speed, start.current_direction)
        self.rig.reset_masked(mask, start.sheet, start.foil_scale, start.reef_level)
        self.sensors.reset_masked(mask, self.fleet, start.noise_scale)

    def launch_actions(self, actions: wp.array, enabled: wp.array | None = None) -> None:
        """The vessel's actions (N, 3) in [-1, 1] to the rig's commands (``ocean_warp.kernels.eboat_actions``:
        propeller int(5 a0), sheet (a1 + 1) 45 deg, rudder 60 deg a2); ``enabled`` (3,) int32 on the device:
        a zero switches its column off (the propeller of a task under sail alone); None: all on. Launches only."""
        wp.launch(apply_eboat_actions, dim=self.count, device=self.device,
                  inputs=[actions, self._all_actions if enabled is None else enabled],
                  outputs=[self.control.rudder, self.control.sheet, self.control.propeller])

    def rewind(self) -> None:
        """Set the simulated time (and so the waves) and the wind's and sensors' random streams back to
        their start, for a seeded restart of the whole batch; launches only."""
        self.simulator.clock.zero_()
        self.wind.restart_stream()
        self.sensors.restart_stream()

    def step(self) -> None:
        """Advance ``config.dt``: ocean, current, hull, wind, rig and integration every substep, sensors once (a
        CUDA graph after the first call; ordered with torch's work on the device)."""
        self.simulator.step()

    def launch_step(self) -> None:
        """The launches of :meth:`step` without capture or torch ordering, to embed in a larger graph."""
        self.simulator.launch_step()

