"""The ranges VRX draws its station-keeping, wayfinding and follow-path tasks from, for randomising the WAM-V's
tasks: wind, waves, current, the goals and the course.

Source: osrf/vrx (commit 93ae8d0, May 2025), the 2023 phase-2 worlds of each task
(``vrx_gz/worlds/2023_phase2/phase2_2023_{stationkeeping,wayfinding,follow_path}{0..5}.sdf``), the follow-path
courses they load (``vrx_gz/models/short_navigation_course_{0..5}/model.sdf``), the WAM-V's spawn pose
(``vrx_gz/launch/competition.launch.py``: x -532, y 162, yaw 1 rad) and the wind and wave plugins
(``vrx_gz/src/USVWind.cc``, ``vrx_gz/src/Wavefield.cc``). Goals given in latitude and longitude were turned into
local east/north metres about the worlds' origin (-33.724223, 150.679736; WGS84 tangent plane).

- Wind (``USVWind``): the mean speed ``wind_mean_velocity``, toward ``wind_direction`` (degrees from east,
  counter-clockwise: the direction it blows toward, as ``EnvBuffers.wind_direction``), and gusts of a
  first-order filter of white noise with time constant ``var_wind_time_constants`` (2 s) and filter gain
  ``var_wind_gain_constants`` x sqrt(2 tau): its stationary standard deviation is ``var_wind_gain_constants``
  [m/s].
- Waves (``Wavefield``, model "PMS"): three components at omega_p x 1.1^n (n = -1, 0, 1), omega_p = 2 pi /
  ``period``, amplitudes ``gain`` x sqrt(2 S(omega) d_omega) under the Pierson-Moskowitz spectrum
  S = 0.0081 g^2 / omega^5 exp(-5/4 (omega_p / omega)^4) (:func:`vrx_significant_wave_height` gives their
  significant height 4 sqrt(sum a^2 / 2)). The worlds set (gain, period): (0, 4 s) calm, (0.6, 6 s) Hs 0.54 m,
  (0.8, 6 s) Hs 0.72 m, (2.0, 2 s) Hs 0.20 m.
- Current: none. VRX's worlds and hydrodynamics plugins have no water current.
- Every task runs 300 s (``running_state_duration``).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ocean_warp.validation import require_int_in_range, require_positive, require_range_pair

__all__ = ["VrxConditions", "vrx_significant_wave_height"]

_PM_ALPHA = 0.0081
"""Phillips' constant of VRX's Pierson-Moskowitz spectrum (``WavefieldPrivate::Pm``)."""
_PMS_SCALE = 1.1
"""Ratio of neighbouring component frequencies in VRX's "PMS" wave field (``Wavefield``'s default ``scale``)."""
_GRAVITY = 9.81


def vrx_significant_wave_height(gain: float, period: float) -> float:
    """The significant wave height [m] of VRX's three-component "PMS" wave field of ``gain`` and peak ``period``
    [s] (``WavefieldPrivate::RecalculatePms``): 4 sqrt(sum a_i^2 / 2) of its component amplitudes a_i."""
    require_positive("vrx_significant_wave_height", "period", period, unit=" s")
    if not (math.isfinite(gain) and gain >= 0.0):
        raise ValueError(f"vrx_significant_wave_height.gain must be a finite number >= 0, got {gain!r}")
    wp_ = 2.0 * math.pi / period
    s = _PMS_SCALE
    spacing = np.array([1.0 - 1.0 / s, (s - 1.0 / s) / 2.0, s - 1.0]) * wp_
    omega = wp_ * s ** np.array([-1.0, 0.0, 1.0])
    spectrum = _PM_ALPHA * _GRAVITY**2 / omega**5 * np.exp(-1.25 * (wp_ / omega) ** 4)
    amplitude = gain * np.sqrt(2.0 * spectrum * spacing)
    return float(4.0 * np.sqrt(np.sum(amplitude**2) / 2.0))


_RANGES = {
    # field: (lowest, highest) a range's ends may take
    "wind_speed": (0.0, 40.0),
    "wind_gust_std": (0.0, 20.0),
    "wind_direction": (-math.pi, math.pi),
    "wave_height": (0.0, 10.0),
    "wave_period": (0.5, 30.0),
    "wave_direction": (-math.pi, math.pi),
    "current_speed": (0.0, 5.0),
    "goal_distance": (0.0, 1000.0),
    "goal_bearing": (-math.pi, math.pi),
    "goal_heading": (-math.pi, math.pi),
    "gate_width": (1.0, 200.0),
    "gate_spacing": (1.0, 1000.0),
    "gate_turn": (0.0, math.pi),
}


@dataclasses.dataclass(frozen=True)
class VrxConditions:
    """The (low, high) ranges a WAM-V task draws each episode's conditions from (uniformly), VRX's by default
    through :meth:`station_keeping`, :meth:`wayfinding` and :meth:`follow_path` (the module's docstring names
    the sources). Angles [rad], lengths [m], speeds [m/s], times [s]. Fields a task does not use keep their
    defaults (no gates outside following the path)."""

    wind_speed: tuple[float, float] = (0.0, 0.0)
    """The episode's mean wind speed [m/s]."""
    wind_gust_std: tuple[float, float] = (0.0, 0.0)
    """Standard deviation of the gusts about the mean [m/s] (VRX's ``var_wind_gain_constants``)."""
    wind_gust_time_constant: float = 2.0
    """Time constant of the gusts' filter [s] (VRX's ``var_wind_time_constants``: 2 in every world)."""
    wind_direction: tuple[float, float] = (-math.pi, math.pi)
    """Where the mean wind blows toward, from +x (east) counter-clockwise [rad]."""
    wave_height: tuple[float, float] = (0.0, 0.0)
    """Significant wave height [m] (:func:`vrx_significant_wave_height` of VRX's gain and period)."""
    wave_period: tuple[float, float] = (6.0, 6.0)
    """Peak period [s]."""
    wave_direction: tuple[float, float] = (0.0, 0.0)
    """Where the waves travel toward, from +x counter-clockwise [rad]."""
    current_speed: tuple[float, float] = (0.0, 0.0)
    """Water current speed [m/s] (VRX has none)."""
    goal_distance: tuple[float, float] = (5.0, 12.0)
    """From the start to the (first) goal, and between consecutive waypoints [m]."""
    goal_bearing: tuple[float, float] = (-1.0, 1.0)
    """Direction of the goal from the start, from the boat's start heading [rad]."""
    goal_heading: tuple[float, float] = (-math.pi, math.pi)
    """Each goal's heading, from the boat's start heading [rad]."""
    waypoints: tuple[int, int] = (1, 1)
    """Goals (waypoints, or gates when following the path) per episode."""
    gate_width: tuple[float, float] = (16.0, 24.0)
    """Distance between a gate's red and green buoys [m]."""
    gate_spacing: tuple[float, float] = (25.0, 66.0)
    """Distance between consecutive gates' centres [m]."""
    gate_turn: tuple[float, float] = (0.0, 0.0)
    """The course's turn at a gate, either way (|change of direction| between consecutive legs) [rad]."""
    obstacles: tuple[int, int] = (0, 0)
    """Obstacle buoys on the course."""
    duration: float = 300.0
    """The task's scored time [s] (VRX's ``running_state_duration``)."""

    def __post_init__(self):
        owner = "VrxConditions"
        for name, (low, high) in _RANGES.items():
            object.__setattr__(self, name, require_range_pair(owner, name, getattr(self, name), low, high))
        for name, low, high in (("waypoints", 1, 100), ("obstacles", 0, 1000)):
            pair = getattr(self, name)
            if not (isinstance(pair, (tuple, list)) and len(pair) == 2):
                raise ValueError(f"{owner}.{name} must be a (low, high) pair of integers, got {pair!r}")
            a, b = (require_int_in_range(owner, name, v, low, high) for v in pair)
            if a > b:
                raise ValueError(f"{owner}.{name} must have low <= high, got {pair!r}")
            object.__setattr__(self, name, (a, b))
        require_positive(owner, "wind_gust_time_constant", self.wind_gust_time_constant, unit=" s")
        require_positive(owner, "duration", self.duration, unit=" s")

    @classmethod
    def station_keeping(cls, **overrides) -> "VrxConditions":
        """VRX 2023 station keeping (``phase2_2023_stationkeeping0..5``): wind 0, 5 or 7 m/s with gusts of 0, 2
        or 1.5 m/s, toward 120, 240 or 265 deg (any direction here); waves calm, Hs 0.54 m or 0.72 m (gain 0.6
        or 0.8 at 6 s) toward 0, 45 or 90 deg; the goal 5.9 to 11.9 m from the WAM-V's spawn, -0.47 to +0.97 rad
        off its spawn heading (+-1 rad here), its heading -2.0 to +1.25 rad from the spawn heading (any here)."""
        base = dict(wind_speed=(0.0, 7.0), wind_gust_std=(0.0, 2.0), wave_height=(0.0, 0.72), wave_period=(6.0, 6.0),
                    wave_direction=(0.0, math.pi / 2), goal_distance=(5.0, 12.0), goal_bearing=(-1.0, 1.0),
                    waypoints=(1, 1))
        return cls(**{**base, **overrides})

    @classmethod
    def wayfinding(cls, **overrides) -> "VrxConditions":
        """VRX 2023 wayfinding (``phase2_2023_wayfinding0..5``): wind 0, 4 or 8 m/s with gusts of 0 or 2 m/s,
        toward 240, 244 or 315 deg (any here); waves calm, Hs 0.54 or 0.72 m (6 s) toward 45 deg (0 to 45 deg
        here); 3 to 5 waypoints, legs (the spawn to the first, then between waypoints) of 11 to 60 m, the first
        waypoint in any direction from the spawn heading, the waypoints' headings anywhere in [-3, 2.5] rad."""
        base = dict(wind_speed=(0.0, 8.0), wind_gust_std=(0.0, 2.0), wave_height=(0.0, 0.72), wave_period=(6.0, 6.0),
                    wave_direction=(0.0, math.pi / 4), goal_distance=(11.0, 60.0), goal_bearing=(-math.pi, math.pi),
                    waypoints=(3, 5))
        return cls(**{**base, **overrides})

    @classmethod
    def follow_path(cls, **overrides) -> "VrxConditions":
        """VRX 2023 follow the path (``phase2_2023_follow_path0..5`` and ``short_navigation_course_0..5``):
        wind 0, 5 or 9 m/s with gusts of 0, 4 or 5 m/s, toward 72, 240 or 355 deg (any here); waves calm, Hs 0.54
        m (gain 0.6, 6 s, toward 45 deg) or Hs 0.20 m (gain 2, 2 s, toward 0 deg); 3, 6 or 9 gates 15.8 to 24.2 m
        wide, their centres 25 to 66 m apart, the course turning up to 97 deg at a gate, 1 to 17 obstacle buoys.
        The first gate's centre lies 19.6 to 30.3 m from the spawn, -0.02 to +0.65 rad off its heading (+-0.7 rad
        here): ``goal_distance`` and ``goal_bearing`` place it."""
        base = dict(wind_speed=(0.0, 9.0), wind_gust_std=(0.0, 5.0), wave_height=(0.0, 0.54), wave_period=(2.0, 6.0),
                    wave_direction=(0.0, math.pi / 4), goal_distance=(19.0, 31.0), goal_bearing=(-0.7, 0.7),
                    waypoints=(3, 9), gate_width=(16.0, 24.0), gate_spacing=(25.0, 66.0),
                    gate_turn=(0.0, math.radians(97.0)), obstacles=(1, 17))
        return cls(**{**base, **overrides})
