"""Named views of a WAM-V simulator's state, control and start (Warp arrays, or torch views of them).

As ``ocean_warp.eboat.state``: frozen dataclasses that only name arrays owned by the simulator's parts (fleet,
thrusters, wind, current, sensors). N is the number of boats; boat i is in environment i.
"""

from __future__ import annotations

import dataclasses
from typing import Any, NamedTuple

import numpy as np
import warp as wp

from ..eboat.state import _Named
from ..kernels.spatial import vec6

__all__ = ["WamvState", "WamvControl", "WamvStart", "WamvTensors"]


@dataclasses.dataclass(frozen=True)
class WamvState(_Named):
    """What moves: read it; write it only through a reset."""

    position: Any
    """(N,) vec3: body origin (midway between the pontoons' axes), world frame (ENU, still water at z = 0) [m]."""
    orientation: Any
    """(N,) quat (x, y, z, w): body (FLU) -> world."""
    velocity: Any
    """(N,) vec6: Fossen's nu, body-frame velocity of the origin [m/s] and angular velocity [rad/s]."""
    status: Any
    """(N,) int32: ``BoatStatus`` bits; 0 is a healthy boat."""
    water_velocity: Any
    """(N,) vec3: the water's velocity at the origin (waves and current), body frame [m/s]."""
    thrust: Any
    """(N, 2) actual thrust of the (left, right) thruster [N], + ahead; 0 with the propeller out of the water."""
    thruster_angle: Any
    """(N, 2) actual angle of each thruster [rad], + turns the boat to port (0 for fixed thrusters)."""
    wind_mean_speed: Any
    """(N,) mean true wind speed of each environment [m/s]."""
    wind_mean_direction: Any
    """(N,) mean direction the true wind blows towards, from +x counter-clockwise [rad]."""
    wind_speed: Any
    """(N,) true wind speed now, gusts included [m/s]."""
    wind_direction: Any
    """(N,) true wind direction now, gusts included [rad]."""
    wind_velocity: Any
    """(N,) vec3: true wind now at the reference height, world frame [m/s]."""
    gust_scale: Any
    """(N,) factor on the wind config's gust standard deviations per environment."""
    current_speed: Any
    """(N,) steady speed of each environment's current at the surface [m/s]."""
    current_direction: Any
    """(N,) where each environment's current sets toward, from +x counter-clockwise [rad]."""
    current_velocity: Any
    """(N,) vec3: the current at the surface now, tide included, world frame [m/s]."""
    noise_scale: Any
    """(N,) factor on every sensor channel's noise and the IMU bias this episode (1: as configured)."""
    readings: Any
    """(N, 16) noisy sensor readings (columns: ``ocean_warp.CHANNEL_NAMES``)."""
    truth: Any
    """(N, 16) the same channels without noise."""
    time: Any
    """(1,) float64: simulated time [s]."""


@dataclasses.dataclass(frozen=True)
class WamvControl(_Named):
    """What is commanded: write it before a step."""

    thrust_command: Any
    """(N, 2) (left, right) thrust commands in [-1, 1] (VRX's mapping: 242.6 N at +1, -100 N at -1)."""
    angle_command: Any
    """(N, 2) (left, right) thruster angles to take [rad], + turns the boat to port; clamped to the limit (azimuth
    thrusters), ignored by fixed ones."""
    wrench_world: Any
    """(N,) vec6: external force at the centre of mass [N] and couple [N m], world frame."""
    wrench_body: Any
    """(N,) vec6: the same in the body frame."""


@dataclasses.dataclass(frozen=True)
class WamvStart(_Named):
    """Where a reset puts each boat; rows of boats not being reset are ignored."""

    position: Any
    """(N,) vec3: body origin, world frame [m]."""
    orientation: Any
    """(N,) quat (x, y, z, w), normalised by the reset."""
    velocity: Any
    """(N,) vec6: Fossen's nu [m/s, rad/s]."""
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
    noise_scale: Any
    """(N,) factor on the sensor noise and the IMU bias drawn at the reset (1: as configured)."""

    @classmethod
    def allocate(cls, count: int, device) -> "WamvStart":
        """Upright boats at rest at the world origin, in calm air and still water, sensors as configured."""
        upright = np.tile(np.array([0.0, 0.0, 0.0, 1.0], dtype=np.float32), (count, 1))
        zeros = lambda: wp.zeros(count, dtype=float, device=device)  # noqa: E731
        return cls(position=wp.zeros(count, dtype=wp.vec3, device=device),
                   orientation=wp.array(upright, dtype=wp.quat, device=device),
                   velocity=wp.zeros(count, dtype=vec6, device=device), wind_speed=zeros(), wind_direction=zeros(),
                   gust_scale=wp.ones(count, dtype=float, device=device), current_speed=zeros(),
                   current_direction=zeros(), noise_scale=wp.ones(count, dtype=float, device=device))


class WamvTensors(NamedTuple):
    """torch views (no copies) of a simulator's state, control and start arrays."""

    state: WamvState
    control: WamvControl
    start: WamvStart
