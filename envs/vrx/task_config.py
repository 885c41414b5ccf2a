"""The configs of VRX's tasks as RL tasks: which task, the vessel that sails it, the randomisation of each
episode and the reward.

VRX (the RobotX competition's simulator, ``osrf/vrx``) scores a WAM-V on station keeping (hold a goal pose),
wayfinding (visit a list of goal poses) and following a path (gates between buoys, in order). Here each is a
batched task on any :class:`~ocean_warp.vessel.Vessel` with thrusters or a propeller and rudder; the WAM-V is
the default. A goal is a pose: x, y from the environment's origin [m] and a heading [rad].
"""

from __future__ import annotations

import dataclasses
import enum
import math
from typing import Any

from ocean_warp.validation import require_int_in_range, require_positive
from ocean_warp.vessel import require_actions, require_vessel

from .path_course_config import PathCourseConfig

__all__ = ["VrxTask", "VrxRewardConfig", "VrxStartConfig", "VrxTaskConfig", "PathCourseConfig", "wamv_vessel"]


class VrxTask(str, enum.Enum):
    """VRX's task (``VrxTaskConfig.kind``)."""

    STATION_KEEPING = "station_keeping"
    """Reach and hold one goal pose for the whole episode; VRX scores the mean pose error over the run."""
    WAYFINDING = "wayfinding"
    """Visit goal poses in turn; VRX scores the mean over the goals of each one's smallest pose error."""
    FOLLOW_PATH = "follow_path"
    """Pass gates (two buoys each) in order, among obstacles; VRX counts the gates and the collisions."""


def _range(owner: str, name: str, value, low: float, high: float, unit: str = "") -> tuple[float, float]:
    try:
        a, b = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{owner}.{name} must be a (low, high) pair{unit}, got {value!r}") from None
    if not (math.isfinite(a) and math.isfinite(b) and low <= a <= b <= high):
        raise ValueError(f"{owner}.{name} must satisfy {low} <= low <= high <= {high}{unit}, got {value!r}")
    return (a, b)


def _goal_count(owner: str, value) -> int | tuple[int, int]:
    """``goals`` as an int, or as a (low, high) pair of ints in order; each within 1 to 16."""
    if isinstance(value, (tuple, list)):
        if len(value) != 2:
            raise ValueError(f"{owner}.goals must be a count or a (low, high) pair of counts, got {value!r}")
        low, high = (require_int_in_range(owner, "goals", v, 1, 16) for v in value)
        if low > high:
            raise ValueError(f"{owner}.goals must have low <= high, got {value!r}")
        return (low, high)
    return require_int_in_range(owner, "goals", value, 1, 16)


@dataclasses.dataclass(frozen=True)
class VrxRewardConfig:
    """The reward of a decision: progress in pose error, a cost of the error and of the thrust, a bonus per goal
    reached and a penalty for a flagged boat. The pose error is VRX's: d + 0.75^d |heading error| [m, rad]."""

    progress_scale: float = 1.0
    """Reward per metre of pose error removed in the decision."""
    error_cost: float = 0.05
    """Cost per metre of pose error per second."""
    action_cost: float = 0.01
    """Cost per decision of the mean squared action (thrust spent)."""
    reach_bonus: float = 2.0
    """Reward when a goal of wayfinding or a gate of the path is reached."""
    flagged_penalty: float = 10.0
    """Penalty when the simulator flags the boat (capsized, sunk, non-finite, collided)."""

    def __post_init__(self):
        for field in dataclasses.fields(self):
            value = float(getattr(self, field.name))
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"VrxRewardConfig.{field.name} must be finite and >= 0, got {value!r}")
            object.__setattr__(self, field.name, value)


@dataclasses.dataclass(frozen=True)
class VrxStartConfig:
    """How each episode starts (drawn per environment from its own random stream)."""

    goal_distance: tuple[float, float] = (5.0, 15.0)
    """Distance from the start to the first goal [m]."""
    goal_spacing: tuple[float, float] = (10.0, 20.0)
    """Distance between consecutive goals (wayfinding) or gates (the path) [m]."""
    goal_bearing_deg: tuple[float, float] = (-180.0, 180.0)
    """Direction of the first goal from the start, from the boat's start heading [deg]."""
    leg_turn_deg: tuple[float, float] = (-180.0, 180.0)
    """Change of direction from one leg to the next (goal to goal, gate to gate) [deg]."""
    wind_speed: tuple[float, float] = (0.0, 5.0)
    """Mean true wind speed [m/s]."""
    wind_direction_deg: tuple[float, float] = (-180.0, 180.0)
    """Mean wind direction, where it blows towards, from +x [deg]."""
    gust_scale: tuple[float, float] = (1.0, 1.0)
    """Factor on the configured gusts."""
    current_speed: tuple[float, float] = (0.0, 0.0)
    """Steady current [m/s]."""
    current_direction_deg: tuple[float, float] = (-180.0, 180.0)
    """Where the current flows towards, from +x [deg]."""
    sensor_noise_scale: tuple[float, float] = (1.0, 1.0)
    """Factor on the sensors' noise."""
    start_speed: tuple[float, float] = (0.0, 0.0)
    """Surge speed at the start [m/s]."""

    def __post_init__(self):
        owner = "VrxStartConfig"
        for name, low, high, unit in (("goal_distance", 0.0, 1e4, " [m]"), ("goal_spacing", 0.0, 1e4, " [m]"),
                                      ("goal_bearing_deg", -360, 360, " [deg]"), ("leg_turn_deg", -360, 360, " [deg]"),
                                      ("wind_speed", 0.0, 60.0, " [m/s]"), ("wind_direction_deg", -360, 360, " [deg]"),
                                      ("gust_scale", 0.0, 10.0, ""), ("current_speed", 0.0, 5.0, " [m/s]"),
                                      ("current_direction_deg", -360, 360, " [deg]"),
                                      ("sensor_noise_scale", 0.0, 100.0, ""), ("start_speed", -5.0, 10.0, " [m/s]")):
            object.__setattr__(self, name, _range(owner, name, getattr(self, name), low, high, unit))


def wamv_vessel(significant_wave_height: float = 0.3, *, profile: str = "vrx", thrusters: str = "fixed"):
    """The WAM-V on a JONSWAP sea of ``significant_wave_height`` [m] (peak period 3 s, a 256 m tile), with
    ``profile`` ("vrx" by default: per-triangle hydrostatics and VRX's lumped damping; "physics" resists
    surge by friction alone so far and sails too fast) and ``thrusters`` ("fixed" or "azimuth")."""
    from ocean_warp.ocean_config import OceanConfig
    from ocean_warp.wamv import Wamv, WamvConfig, WamvSimulatorConfig  # built lazily so configs stay light

    sea = OceanConfig(tile_size=256.0, resolution=64, significant_wave_height=significant_wave_height,
                      peak_period=3.0)
    return Wamv(WamvSimulatorConfig(boat=WamvConfig(profile=profile, thrusters=thrusters), ocean=sea))


@dataclasses.dataclass(frozen=True)
class VrxTaskConfig:
    """One of VRX's tasks on a vessel (see the module's docstring)."""

    kind: VrxTask = VrxTask.STATION_KEEPING
    vessel: Any = dataclasses.field(default_factory=wamv_vessel)
    """The :class:`~ocean_warp.vessel.Vessel` that sails it (default the WAM-V); its config holds the sea."""
    goals: int | tuple[int, int] = 1
    """Goal poses of an episode (station keeping: 1) or gates of the path: a count, or a (low, high) range each
    episode draws its own count from, uniformly, low and high included (VRX 2023: 3-5 waypoints, 3-9 gates)."""
    decision_period: float = 0.5
    """Simulated time of one decision [s]."""
    episode_time: float = 60.0
    """The episode's time limit [s]."""
    gate_width: float = 20.0
    """Between a gate's two buoys [m] (VRX 2023: 15.8 to 24.2 m)."""
    reach_error: float = 1.0
    """Pose error under which a wayfinding goal counts as reached and the next one is shown [m]."""
    lost_distance: float = 60.0
    """An episode ends, lost, when the boat is this far from its goal [m]."""
    position_scale: float = 10.0
    """Observations divide distances by this [m]."""
    start: VrxStartConfig = dataclasses.field(default_factory=VrxStartConfig)
    reward: VrxRewardConfig = dataclasses.field(default_factory=VrxRewardConfig)
    observation: str = "vrx"
    """The observation set's name (checked against a policy's)."""
    actions: tuple[str, ...] | None = None
    """The vessel's actions the task uses, by name (None: all); the others command their neutral value."""
    path_course: PathCourseConfig | None = dataclasses.field(default_factory=PathCourseConfig)
    """Following the path: the gates' buoys, the obstacles among them and the contact with them (None: the gates
    are lines on open water). Not used by the other tasks."""

    def __post_init__(self):
        owner = "VrxTaskConfig"
        try:
            object.__setattr__(self, "kind", VrxTask(self.kind))
        except ValueError:
            raise ValueError(f"{owner}.kind must be one of {[k.value for k in VrxTask]}, got {self.kind!r}") from None
        require_vessel(f"{owner}.vessel", self.vessel)
        if self.actions is not None:
            object.__setattr__(self, "actions", tuple(self.actions))
            require_actions(f"{owner}.actions", self.vessel, self.actions)
        object.__setattr__(self, "goals", _goal_count(owner, self.goals))
        if self.kind is VrxTask.STATION_KEEPING and self.goal_range != (1, 1):
            raise ValueError(f"{owner}.goals must be 1 for station keeping, got {self.goals}")
        for name, unit in (("decision_period", " [s]"), ("episode_time", " [s]"), ("reach_error", " [m]"),
                           ("gate_width", " [m]"),
                           ("lost_distance", " [m]"), ("position_scale", " [m]")):
            object.__setattr__(self, name, require_positive(owner, name, getattr(self, name), unit=unit))
        dt = self.simulator.dt
        steps = self.decision_period / dt
        if abs(steps - round(steps)) > 1e-6 or round(steps) < 1:
            raise ValueError(f"{owner}.decision_period ({self.decision_period} s) must be a whole number of the "
                             f"vessel's steps ({dt} s)")
        if not isinstance(self.start, VrxStartConfig):
            raise ValueError(f"{owner}.start must be a VrxStartConfig, got {self.start!r}")
        if not isinstance(self.reward, VrxRewardConfig):
            raise ValueError(f"{owner}.reward must be a VrxRewardConfig, got {self.reward!r}")
        if self.path_course is not None and not isinstance(self.path_course, PathCourseConfig):
            raise ValueError(f"{owner}.path_course must be a PathCourseConfig or None, got {self.path_course!r}")
        if self.kind is VrxTask.FOLLOW_PATH and self.path_course is not None:
            # A gate faced along a leg pointing away from the start keeps its buoys half its width off that line:
            # the draw's fallback, so the start clearance holds whatever the legs' turns.
            course = self.path_course
            if 0.5 * self.gate_width - course.gate_buoy_radius < course.start_clearance:
                raise ValueError(f"{owner}.gate_width ({self.gate_width} m) must leave its buoys' surfaces at least "
                                 f"path_course.start_clearance ({course.start_clearance} m) off the centre line: "
                                 f"gate_width / 2 - gate_buoy_radius >= start_clearance")

    @property
    def simulator(self):
        """The vessel's simulator config (its sea, wind model, time step)."""
        return self.vessel.config

    @property
    def steps_per_decision(self) -> int:
        return int(round(self.decision_period / self.simulator.dt))

    @property
    def max_episode_length(self) -> int:
        """The time limit in decisions."""
        return max(1, int(round(self.episode_time / self.decision_period)))

    @property
    def goal_range(self) -> tuple[int, int]:
        """The (fewest, most) goals or gates of an episode (equal for a fixed count)."""
        return (self.goals, self.goals) if isinstance(self.goals, int) else self.goals

    @property
    def max_goals(self) -> int:
        """The most goals or gates of an episode: the width of the route arrays."""
        return self.goal_range[1]

    @property
    def route_length(self) -> int:
        return self.max_goals

    @property
    def start_point(self) -> tuple[float, float]:
        """Where each boat starts, from its environment's origin [m]."""
        return (0.0, 0.0)

    @property
    def route(self) -> None:
        """None: every episode draws its own goals (as a task with a drawn waypoint has no fixed route)."""
        return None

    @property
    def reach_radius(self) -> float:
        """The pose error under which a goal counts as reached [m] (drawn around goals in plots)."""
        return self.reach_error

    @property
    def num_actions(self) -> int:
        return len(self.vessel.actions)

    @property
    def path_lidar(self):
        """The lidar the policy sees the path's buoys through (a ``LidarConfig``; None: none, or not the path)."""
        return self.path_course.lidar if self.kind is VrxTask.FOLLOW_PATH and self.path_course is not None else None

    @property
    def lidar_observations(self) -> int:
        """Values of the policy's observation that come from the path's lidar (after the last actions)."""
        return 0 if self.path_lidar is None else self.path_course.lidar_sectors

    def enabled_actions(self) -> list[int]:
        """1 for each of the vessel's actions the task uses, else 0, in the vessel's column order."""
        used = set(a.name for a in self.vessel.actions) if self.actions is None else set(self.actions)
        return [int(a.name in used) for a in self.vessel.actions]
