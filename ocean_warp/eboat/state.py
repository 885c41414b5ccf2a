"""Named views of what moves (state), what is commanded (control) and where a reset puts a boat (start).

Each is a frozen dataclass of arrays: an :class:`~ocean_warp.eboat.EBoatSimulator` holds one of Warp
arrays (``sim.state``, ``sim.control``, ``sim.start``) and one of torch views of the same memory
(``sim.tensors.state``, ...), bound once in its constructor. The arrays belong to the simulator's
parts (fleet, rig, wind, sensors); these views only name them. N is the number of boats; boat i sails
in environment i.
"""

from __future__ import annotations

import dataclasses
from typing import Any, Callable, NamedTuple, TypeVar

import numpy as np
import warp as wp

from ..kernels.spatial import vec6

__all__ = ["EBoatState", "EBoatControl", "EBoatStart", "EBoatTensors"]

View = TypeVar("View")


class _Named:
    def map(self: View, convert: Callable[[Any], Any]) -> View:
        """The same view with every array passed through ``convert`` (e.g. ``wp.to_torch``)."""
        return type(self)(**{field.name: convert(getattr(self, field.name)) for field in dataclasses.fields(self)})

    def names(self) -> tuple[str, ...]:
        return tuple(field.name for field in dataclasses.fields(self))


@dataclasses.dataclass(frozen=True)
class EBoatState(_Named):
    """What moves: read it; write it only through a reset (writes between steps are honoured, but the
    sensors and the episode bookkeeping of an environment would not know)."""

    position: Any
    """(N,) vec3: body origin in the world frame (ENU, still water at z = 0) [m]."""
    orientation: Any
    """(N,) quat (x, y, z, w): body (FLU) -> world."""
    velocity: Any
    """(N,) vec6: Fossen's nu, body-frame velocity of the origin [m/s] and angular velocity [rad/s]."""
    status: Any
    """(N,) int32: ``BoatStatus`` bits; 0 is a healthy boat. Flags stay until a reset."""
    water_velocity: Any
    """(N,) vec3: the water's velocity at the boat's origin, body frame [m/s]: the waves' orbital velocity and
    the current (the boat's velocity through the water is ``velocity`` minus it)."""
    rudder_angle: Any
    """(N,) actual rudder angle [rad]; positive turns the boat to port."""
    sheet_limit: Any
    """(N,) actual largest boom angle either side [rad] (follows the sheet command at 0.5 rad/s)."""
    boom_angle: Any
    """(N,) boom angle, positive with the boom to port [rad]."""
    boom_rate: Any
    """(N,) [rad/s]"""
    wind_mean_speed: Any
    """(N,) mean true wind speed of each environment at the reference height [m/s]."""
    wind_mean_direction: Any
    """(N,) mean direction the true wind blows towards, from +x counter-clockwise [rad]."""
    wind_speed: Any
    """(N,) current true wind speed, gusts included [m/s]."""
    wind_direction: Any
    """(N,) current true wind direction, gusts included [rad]."""
    wind_velocity: Any
    """(N,) vec3: current true wind at the reference height, world frame [m/s]."""
    gust_scale: Any
    """(N,) factor on the wind config's gust standard deviations per environment."""
    current_speed: Any
    """(N,) steady speed of each environment's current at the surface [m/s] (its tide comes on top)."""
    current_direction: Any
    """(N,) where each environment's current sets toward, from +x counter-clockwise [rad]."""
    current_velocity: Any
    """(N,) vec3: the current at the surface now, tide included, world frame [m/s]."""
    foil_scale: Any
    """(N,) vec3: factors on the lift and drag coefficients of each boat's (sail, keel, rudder) this
    episode (1: as tabulated)."""
    reef_level: Any
    """(N,) int32: each boat's reef level this episode (0: the full sail; k: ``EBoatConfig.reef_areas[k - 1]``,
    the sail scaled by ``EBoatConfig.reef_scales[k]`` about its tack)."""
    noise_scale: Any
    """(N,) factor on every sensor channel's noise and on the IMU bias of each boat this episode (1: as
    configured, 0: exact readings)."""
    readings: Any
    """(N, 16) noisy sensor readings, held between refreshes (columns: ``ocean_warp.CHANNEL_NAMES``)."""
    truth: Any
    """(N, 16) the same channels without noise, read every step."""
    time: Any
    """(1,) float64: simulated time [s]."""


@dataclasses.dataclass(frozen=True)
class EBoatControl(_Named):
    """What is commanded: write it before a step (from torch through ``sim.tensors.control``)."""

    rudder: Any
    """(N,) rudder angle to steer to [rad], positive turns to port; clamped to +-60 deg."""
    sheet: Any
    """(N,) sheet: largest boom angle either side [rad]; clamped to 0-90 deg."""
    propeller: Any
    """(N,) int32 propeller level, -5 ... +5 (24.02 N a level ahead, x 0.4 astern)."""
    wrench_world: Any
    """(N,) vec6: external force at the centre of mass [N] and couple [N m], world frame."""
    wrench_body: Any
    """(N,) vec6: the same in the body frame."""


@dataclasses.dataclass(frozen=True)
class EBoatStart(_Named):
    """Where a reset puts each boat; rows of boats not being reset are ignored."""

    position: Any
    """(N,) vec3: body origin, world frame [m]."""
    orientation: Any
    """(N,) quat (x, y, z, w), normalised by the reset."""
    velocity: Any
    """(N,) vec6: Fossen's nu [m/s, rad/s]."""
    sheet: Any
    """(N,) sheet command and actual boom limit [rad] (0: sheeted in)."""
    wind_speed: Any
    """(N,) new mean true wind speed [m/s]."""
    wind_direction: Any
    """(N,) new mean true wind direction (towards) [rad]."""
    gust_scale: Any
    """(N,) factor on the wind config's gust standard deviations (1: as configured)."""
    current_speed: Any
    """(N,) new steady speed of the current [m/s]."""
    current_direction: Any
    """(N,) new direction the current sets toward [rad]."""
    foil_scale: Any
    """(N,) vec3: factors on the lift and drag coefficients of the (sail, keel, rudder) (1: as tabulated)."""
    reef_level: Any
    """(N,) int32: reef level of the sail (0: the full sail)."""
    noise_scale: Any
    """(N,) factor on the sensor noise and the IMU bias drawn at the reset (1: as configured)."""

    @classmethod
    def allocate(cls, count: int, device) -> "EBoatStart":
        """Upright boats at rest at the world origin, sheeted in, in calm air and still water, full sail, foils
        and sensors as configured."""
        upright = np.tile(np.array([0.0, 0.0, 0.0, 1.0], dtype=np.float32), (count, 1))
        return cls(position=wp.zeros(count, dtype=wp.vec3, device=device),
                   orientation=wp.array(upright, dtype=wp.quat, device=device),
                   velocity=wp.zeros(count, dtype=vec6, device=device),
                   sheet=wp.zeros(count, dtype=float, device=device),
                   wind_speed=wp.zeros(count, dtype=float, device=device),
                   wind_direction=wp.zeros(count, dtype=float, device=device),
                   gust_scale=wp.ones(count, dtype=float, device=device),
                   current_speed=wp.zeros(count, dtype=float, device=device),
                   current_direction=wp.zeros(count, dtype=float, device=device),
                   foil_scale=wp.full(count, wp.vec3(1.0, 1.0, 1.0), dtype=wp.vec3, device=device),
                   reef_level=wp.zeros(count, dtype=wp.int32, device=device),
                   noise_scale=wp.ones(count, dtype=float, device=device))


class EBoatTensors(NamedTuple):
    """torch views (no copies) of a simulator's state, control and start arrays."""

    state: EBoatState
    control: EBoatControl
    start: EBoatStart
