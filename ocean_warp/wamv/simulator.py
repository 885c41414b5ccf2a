"""Many WAM-Vs on one ocean, each in a wind and a current of its own: the Simulator with the thrusters, wind,
current and sensors wired in, and named views of its state, controls and resets."""

from __future__ import annotations

import numpy as np
import warp as wp

from ..current import Current
from ..fleet import Fleet
from ..frames import quaternion_from_roll_pitch_yaw
from ..hull_form import floating_waterline
from ..masks import mask_of, rows_at
from ..ocean import Ocean
from ..sensors import Sensors
from ..simulator import Simulator
from ..torch_streams import ordered_with_torch
from ..validation import require_indices, require_int_in_range, require_per_item, require_rows
from ..wind import Wind
from . import figures

from .boat import wamv_boat_type
from .config import ThrusterLayout
from .simulator_config import WamvSimulatorConfig
from .state import WamvControl, WamvStart, WamvState, WamvTensors
from .thrusters import Thrusters
from .windage import Windage

__all__ = ["WamvSimulator"]


class WamvSimulator:
    """``count`` WAM-Vs on one ocean, boat i in environment i with a wind and a current of its own (an
    ``ocean_warp.vessel.VesselSimulator``).

    Example::

        sim = WamvSimulator(WamvSimulatorConfig(boat=WamvConfig(profile="vrx")), 64)
        sim.tensors.control.thrust_command[:] = 0.5     # both thrusters half ahead
        for _ in range(100):
            sim.step()

    ``state``, ``control`` and ``start`` name the Warp arrays (:class:`WamvState`...), ``tensors`` torch views of
    them, bound here. The sensors' GNSS and IMU read the body origin's motion (``ocean_warp.sensors``); their wind
    vane and anemometer sit at VRX's GPS mount (``figures.GPS_MOUNT``).
    """

    def __init__(self, config: WamvSimulatorConfig | None = None, count: int = 1, *, device=None,
                 ocean: Ocean | None = None, first_boat: int = 0):
        """``config`` (default: still water, the physics profile, fixed thrusters); ``count`` boats; ``ocean``: an
        existing :class:`Ocean` to share (its water must be ``config.water``); ``first_boat``: this batch is boats
        [first_boat, first_boat + count) of a larger one (their gust and sensor-noise random streams)."""
        self.config = config if config is not None else WamvSimulatorConfig()
        if not isinstance(self.config, WamvSimulatorConfig):
            raise ValueError(f"WamvSimulator: config must be a WamvSimulatorConfig, got {self.config!r}")
        count = require_int_in_range("WamvSimulator", "count", count, 1, 2**24)
        config = self.config
        self.device = wp.get_device(device if device is not None else (ocean.device if ocean is not None else None))
        device = self.device
        if ocean is None:
            ocean = Ocean(config.ocean, device=device, depth_fields=True)
        elif ocean.config.water != config.water:
            raise ValueError(f"WamvSimulator: the ocean given holds {ocean.config.water}, the config "
                             f"{config.water}; the boats float in the water of the ocean they are on")
        self.first_boat = require_int_in_range("WamvSimulator", "first_boat", first_boat, 0, 2**30)
        self.boat_type = wamv_boat_type(config.boat)
        self.fleet = Fleet(self.boat_type, count, device=device)
        self.wind = Wind(config.wind, count, substep=config.substep_dt, device=device, first_index=self.first_boat)
        self.current = Current(config.current, count, device=device)
        self.thrusters = Thrusters(config.boat, count, device=device)
        self.windage = Windage(config.boat.wind_coefficients, self.wind, count, device=device)
        self.sensors = Sensors(config.sensors, count, masthead=figures.GPS_MOUNT, wind=self.wind, step=config.dt,
                               gravity=config.water.gravity, device=device, first_index=self.first_boat)
        self.simulator = Simulator(ocean, self.fleet, config.simulator_config(),
                                   models=[self.wind, self.windage, self.thrusters, self.sensors], current=self.current)
        self.ocean = ocean

        fleet, thrusters, wind, sensors = self.fleet, self.thrusters, self.wind, self.sensors
        current = self.current.state
        self.state = WamvState(
            position=fleet.state.position, orientation=fleet.state.orientation, velocity=fleet.state.velocity,
            status=fleet.state.status, water_velocity=fleet.state.water_velocity, thrust=thrusters.thrust,
            thruster_angle=thrusters.thruster_angle, wind_mean_speed=wind.state.mean_speed,
            wind_mean_direction=wind.state.mean_direction, wind_speed=wind.state.speed,
            wind_direction=wind.state.direction, wind_velocity=wind.state.velocity, gust_scale=wind.state.gust_scale,
            current_speed=current.speed, current_direction=current.direction, current_velocity=current.velocity,
            noise_scale=sensors.noise_scale, readings=sensors.readings, truth=sensors.truth, time=self.simulator.clock)
        """What moves (Warp arrays; see :class:`WamvState` for units)."""
        self.control = WamvControl(thrust_command=thrusters.thrust_command, angle_command=thrusters.angle_command,
                                   wrench_world=fleet.control.wrench_world, wrench_body=fleet.control.wrench_body)
        """What is commanded (Warp arrays; see :class:`WamvControl`)."""
        self.start = WamvStart.allocate(count, device)
        """Where :meth:`reset_masked` puts each boat (Warp arrays; see :class:`WamvStart`)."""
        self.tensors = WamvTensors(self.state.map(wp.to_torch), self.control.map(wp.to_torch),
                                   self.start.map(wp.to_torch))
        """torch views of ``state``, ``control`` and ``start``, bound once."""
        self.reset()

    @property
    def count(self) -> int:
        return self.fleet.count

    @property
    def action_count(self) -> int:
        """Columns of the actions :meth:`launch_actions` takes: 2 (fixed thrusters) or 4 (azimuth)."""
        return 4 if self.config.boat.thrusters is ThrusterLayout.AZIMUTH else 2

    @property
    def time(self) -> float:
        """Simulated time [s] (reads the device)."""
        return self.simulator.time

    def reset(self, boats=None, *, position=(0.0, 0.0, 0.0), heading=0.0, velocity=None, wind_speed=None,
              wind_direction=None, current_speed=None, current_direction=None, noise_scale=None) -> None:
        """Host path of :meth:`reset_masked`. Put the chosen boats (None: all) upright at ``position`` [m] (the body
        origin, between the pontoons' axes) with ``heading`` [rad, yaw from +x] and ``velocity``
        (Fossen nu, default at rest), thrusters stopped and centred; optionally set their environments' mean wind
        [m/s, rad] and steady current [m/s, rad] (default: keep them); ``noise_scale`` (default 1) each chosen
        boat's factor on its sensor noise. Scalars and single rows broadcast."""
        owner = "WamvSimulator.reset"
        indices = require_indices(owner, "boats", boats, self.count)
        k = len(indices)
        headings = require_per_item(owner, "heading", heading, k)
        positions = require_rows(owner, "position", position, k, 3)
        velocities = require_rows(owner, "velocity", np.zeros(6) if velocity is None else velocity, k, 6)
        with ordered_with_torch(self.device):
            old = {name: array.numpy()[indices] for name, array in (
                ("wind_speed", self.wind.state.mean_speed), ("wind_direction", self.wind.state.mean_direction),
                ("gust_scale", self.wind.state.gust_scale), ("current_speed", self.current.state.speed),
                ("current_direction", self.current.state.direction))}
        given = {"wind_speed": wind_speed, "wind_direction": wind_direction, "current_speed": current_speed,
                 "current_direction": current_direction}
        values = {name: old[name] if value is None else require_per_item(owner, name, value, k)
                  for name, value in given.items()}
        for name in ("wind_speed", "current_speed"):
            if np.any(values[name] < 0.0):
                raise ValueError(f"{owner}.{name} must be >= 0 [m/s], got {given[name]!r}")
        noise_scales = require_per_item(owner, "noise_scale", 1.0 if noise_scale is None else noise_scale, k)
        if np.any(noise_scales < 0.0):
            raise ValueError(f"{owner}.noise_scale must be >= 0, got {noise_scale!r}")
        if k == 0:
            return
        orientations = quaternion_from_roll_pitch_yaw(np.column_stack([np.zeros(k), np.zeros(k), headings]))
        rows = dict(values, position=positions, orientation=orientations, velocity=velocities,
                    gust_scale=old["gust_scale"], noise_scale=noise_scales)
        for name, value in rows.items():
            getattr(self.start, name).assign(rows_at(indices, value, self.count))
        with ordered_with_torch(self.device):
            self.reset_masked(mask_of(indices, self.count, self.device))

    def rest_height(self) -> float:
        """Height [m] of the body origin above still water when the boat floats upright at rest (the waterline of
        its hull mesh holding its mass in the config's water)."""
        return -floating_waterline(self.boat_type.hull, self.boat_type.mass, self.config.water.density)

    def reset_masked(self, mask: wp.array, start: WamvStart | None = None) -> None:
        """Device path of every reset: each boat whose ``mask`` (N,) int32 is non-zero goes to its row of ``start``
        (default ``self.start``): pose, velocity, its environment's mean wind and steady current, with flags,
        external wrenches and thrusters cleared, its sensor-noise factor set, a new IMU bias drawn and every sensor
        channel read at once. Launches only (graph-safe); outside a capture, wrap it in ``ordered_with_torch``."""
        start = start if start is not None else self.start
        self.fleet.reset_masked(mask, start.position, start.orientation, start.velocity)
        self.wind.reset_masked(mask, start.wind_speed, start.wind_direction, start.gust_scale)
        self.current.reset_masked(mask, start.current_speed, start.current_direction)
        self.thrusters.reset_masked(mask)
        self.sensors.reset_masked(mask, self.fleet, start.noise_scale)

    def launch_actions(self, actions, enabled: wp.array | None = None) -> None:
        """``actions`` (N, A) float32 in [-1, 1] (a Warp array or a torch tensor on the device; columns as
        ``Wamv.actions``) -> thrust commands and, with azimuth thrusters, angles (action x ``max_thruster_angle``);
        ``enabled`` (A,) int32: a zero switches that column off (None: all on). Launches only (graph-safe)."""
        if not isinstance(actions, wp.array):
            actions = wp.from_torch(actions, dtype=wp.float32)
        if actions.ndim != 2 or actions.shape[0] != self.count or actions.shape[1] < self.action_count:
            raise ValueError(f"WamvSimulator.launch_actions: actions must be ({self.count}, {self.action_count}) "
                             f"float32, got shape {actions.shape}")
        self.thrusters.launch_actions(actions, enabled)

    def rewind(self) -> None:
        """Time and the wind's and sensors' random streams back to their start; launches only."""
        self.simulator.clock.zero_()
        self.wind.restart_stream()
        self.sensors.restart_stream()

    def step(self) -> None:
        """Advance ``config.dt`` (a captured graph after the first call; ordered with torch's work)."""
        self.simulator.step()

    def launch_step(self) -> None:
        """The launches of :meth:`step` without capture or torch ordering, to embed in a larger graph."""
        self.simulator.launch_step()
