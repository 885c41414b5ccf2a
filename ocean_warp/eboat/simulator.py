"""Many E-Boats on one ocean in one wind: the Simulator with the rig, wind and sensor models wired in."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import warp as wp

from ..fleet import Fleet
from ..hydrodynamics_config import HydrodynamicsConfig
from ..frames import quaternion_from_roll_pitch_yaw
from ..kernels.point_buoyancy import point_buoyancy
from ..kernels.sailing_rig import reset_rig, sailing_rig, set_sheet
from ..ocean import Ocean
from ..ocean_config import OceanConfig
from ..sensors import SensorConfig, Sensors
from ..simulator import Simulator, SimulatorConfig
from ..torch_streams import ordered_with_torch
from ..validation import require_indices, require_per_item
from ..wind import Wind, WindConfig
from .eboat import EBoat, Hydrostatics

__all__ = ["EBoatSimulator", "SailingRig", "EBoatTensors"]


class SailingRig:
    """Commands and actuator state of every boat's rig, and the model that turns them, with the
    wind and the water, into sail, keel, rudder and propeller forces every substep."""

    def __init__(self, eboat: EBoat, count: int, wind: Wind, *, device):
        self.device = wp.get_device(device)
        self.count = count
        self.wind = wind
        self.parameters = eboat.rig_parameters()
        self.tables = eboat.foil_tables(self.device)
        zeros = lambda dtype=float: wp.zeros(count, dtype=dtype, device=self.device)  # noqa: E731
        self.rudder_command = zeros()
        """(N,) rudder angle to steer to [rad]; positive turns the boat to port (within +-60 deg)."""
        self.sheet_command = zeros()
        """(N,) sheet: largest boom angle either side [rad] (0 to 90 deg)."""
        self.propeller_command = zeros(int)
        """(N,) propeller level, -5 ... +5."""
        self.rudder_angle = zeros()
        """(N,) actual rudder angle [rad]."""
        self.sheet_limit = zeros()
        """(N,) actual boom limit [rad]."""
        self.boom_angle = zeros()
        """(N,) boom angle, positive to port [rad]."""
        self.boom_rate = zeros()
        """(N,) [rad/s]."""

    def substep(self, simulator) -> None:
        fleet = simulator.fleet
        wp.launch(sailing_rig, dim=self.count, device=self.device,
                  inputs=[self.parameters, self.tables, self.wind.gusts, simulator.config.substep_dt, fleet.position,
                          fleet.orientation, fleet.velocity, fleet.water_velocity, self.wind.velocity,
                          self.rudder_command, self.sheet_command, self.propeller_command],
                  outputs=[self.rudder_angle, self.sheet_limit, self.boom_angle, self.boom_rate, fleet.model_wrench,
                           fleet.status])

    def reset(self, boats: wp.array) -> None:
        wp.launch(reset_rig, dim=boats.shape[0], device=self.device, inputs=[boats],
                  outputs=[self.rudder_command, self.sheet_command, self.propeller_command, self.rudder_angle,
                           self.sheet_limit, self.boom_angle, self.boom_rate])

    def set_sheet(self, boats: wp.array, angles: np.ndarray) -> None:
        """Set the sheet command and the actual boom limit of ``boats`` to ``angles`` [rad] at once."""
        limits = np.clip(angles, 0.0, self.parameters.sheet_limit_max).astype(np.float32)
        values = wp.array(limits, dtype=float, device=self.device)
        wp.launch(set_sheet, dim=boats.shape[0], device=self.device, inputs=[boats, values],
                  outputs=[self.sheet_command, self.sheet_limit])


class _PointBuoyancyModel:
    """The original twin's four-point buoyancy, as a force model."""

    def __init__(self, eboat: EBoat, device, gravity: float):
        self.parameters = eboat.point_buoyancy(device, gravity)

    def substep(self, simulator) -> None:
        fleet = simulator.fleet
        wp.launch(point_buoyancy, dim=fleet.count, device=simulator.device,
                  inputs=[self.parameters, simulator.ocean.surface, fleet.position, fleet.orientation],
                  outputs=[fleet.model_wrench])


class EBoatTensors(NamedTuple):
    """torch views of everything an agent reads or writes (bound once, no copies)."""

    position: object
    orientation: object
    velocity: object
    status: object
    rudder_command: object
    sheet_command: object
    propeller_command: object
    rudder_angle: object
    boom_angle: object
    wind_speed: object
    """(N,) mean wind speed per environment [m/s] (writable)."""
    wind_direction: object
    """(N,) mean wind direction per environment [rad] (writable)."""
    readings: object
    """(N, 16) noisy sensor readings (``ocean_warp.sensors.CHANNEL_NAMES``)."""
    truth: object
    """(N, 16) exact sensor readings."""


class EBoatSimulator:
    """``count`` E-Boats, each in an environment of its own wind, on one ocean.

    Example::

        sim = EBoatSimulator(256, wind=WindConfig(speed=7.0), device="cuda:0")
        sim.reset(heading=0.3)
        t = sim.tensors
        t.sheet_command[:] = 0.6; t.rudder_command[:] = 0.1; t.propeller_command[:] = 0
        for _ in range(100):
            sim.step()
    """

    def __init__(self, count: int, *, eboat: EBoat | None = None, ocean: Ocean | None = None,
                 wind: WindConfig | None = None, sensors: SensorConfig | None = None, dt: float = 0.05,
                 substeps: int = 5, ocean_every_substep: bool = True, hydrodynamics: HydrodynamicsConfig | None = None,
                 device=None, **simulator_options):
        """``count`` boats; ``eboat`` (default: V-C, mesh hydrostatics); ``ocean`` (default: still water);
        ``wind`` and ``sensors`` configs; steps of ``dt`` [s] in ``substeps``; ``hydrodynamics``
        (default: the E-Boat's tuned water); other ``SimulatorConfig`` fields as keywords."""
        self.eboat = eboat if eboat is not None else EBoat()
        device = wp.get_device(device if device is not None else (ocean.device if ocean is not None else None))
        self.device = device
        if ocean is None:
            ocean = Ocean(OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.0), device=device)
        config = SimulatorConfig(dt=dt, substeps=substeps, ocean_every_substep=ocean_every_substep,
                                 hydrodynamics=hydrodynamics or self.eboat.hydrodynamics,
                                 hull_pressure=self.eboat.config.hydrostatics is Hydrostatics.MESH, **simulator_options)
        self.fleet = Fleet(self.eboat.boat_type, count, device=device)
        self.wind = Wind(wind, count, substep=config.substep_dt, device=device)
        self.rig = SailingRig(self.eboat, count, self.wind, device=device)
        self.sensors = Sensors(sensors, count, masthead=self.eboat.masthead, wind=self.wind, step=config.dt,
                               gravity=config.hydrodynamics.gravity, device=device)
        models = [self.wind]
        if self.eboat.config.hydrostatics is Hydrostatics.POINTS:
            models.append(_PointBuoyancyModel(self.eboat, device, config.hydrodynamics.gravity))
        models += [self.rig, self.sensors]
        self.simulator = Simulator(ocean, self.fleet, config, models=models)
        self._tensors = None

    @property
    def count(self) -> int:
        return self.fleet.count

    @property
    def time(self) -> float:
        return self.simulator.time

    def reset(self, boats=None, *, position=(0.0, 0.0, 0.0), heading=0.0, velocity=None, wind_speed=None,
              wind_direction=None, sheet=None) -> None:
        """Put the chosen boats (None: all) upright at ``position`` [m] with ``heading`` [rad, yaw from
        +x]; centre their rudder and boom, stop the propeller, and sheet in, or set the sheet (command
        and actual limit) to ``sheet`` [rad, clipped to 0-90 deg]; optionally set their environments'
        mean wind. Scalars and single rows broadcast."""
        indices = require_indices("EBoatSimulator.reset", "boats", boats, self.count)
        headings = require_per_item("EBoatSimulator.reset", "heading", heading, len(indices))
        sheets = None if sheet is None else require_per_item("EBoatSimulator.reset", "sheet", sheet, len(indices))
        angles = np.column_stack([np.zeros(len(indices)), np.zeros(len(indices)), headings])
        self.fleet.reset(indices, position=position, orientation=quaternion_from_roll_pitch_yaw(angles),
                         velocity=velocity)
        if wind_speed is not None or wind_direction is not None:
            speed = self.wind.mean_speed.numpy()[indices] if wind_speed is None else wind_speed
            direction = self.wind.mean_direction.numpy()[indices] if wind_direction is None else wind_direction
            self.wind.set(indices, speed=speed, direction=direction)
        boats_wp = wp.array(indices, dtype=int, device=self.device)
        with ordered_with_torch(self.device):
            self.rig.reset(boats_wp)
            if sheets is not None:
                self.rig.set_sheet(boats_wp, sheets)
        self.sensors.reset(indices, self.fleet)

    def step(self) -> None:
        """Advance ``dt``: ocean, hull, wind, rig and integration every substep, sensors once."""
        self.simulator.step()

    @property
    def tensors(self) -> EBoatTensors:
        if self._tensors is None:
            fleet = self.fleet.tensors
            self._tensors = EBoatTensors(
                fleet.position, fleet.orientation, fleet.velocity, fleet.status,
                *(wp.to_torch(a) for a in (self.rig.rudder_command, self.rig.sheet_command, self.rig.propeller_command,
                                           self.rig.rudder_angle, self.rig.boom_angle, self.wind.mean_speed,
                                           self.wind.mean_direction, self.sensors.readings, self.sensors.truth)))
        return self._tensors

