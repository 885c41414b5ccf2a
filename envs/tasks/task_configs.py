"""Sailing tasks as configs: the seed paper's waypoint task, our Waypoint+, the BCDACA mission, the
mission under sail alone, and the avoidance task (a waypoint through a field of buoys and piles, seen with
a lidar), with and without the propeller.

A task is this config plus the kernels of ``ocean_warp.envs.tasks.task_kernels``; ``SailingEnv`` runs any of
them. Every task has the same three actions, each in [-1, 1] (the seed's):

    a0  propeller level int(5 a0), truncated toward zero (-5 ... +5); ignored (level 0) by a task
        without propeller (``TaskConfig.propeller`` False), which keeps a0 so that every task has
        the same action space
    a1  sheet, the largest boom angle either side: (a1 + 1) 45 deg
    a2  rudder angle: 60 deg a2, positive turns to port

Geometry is relative to each environment's origin on the periodic ocean; angles in configs are in
degrees (written by people), radians inside.
"""

from __future__ import annotations

import dataclasses
import enum
import math

from ocean_warp.contact import ContactConfig
from ocean_warp.eboat import EBoatConfig, EBoatSimulatorConfig, Profile
from ocean_warp.ocean_config import OceanConfig
from ocean_warp.perception.lidar_config import LidarConfig
from ocean_warp.sensors import SensorConfig
from ocean_warp.validation import (
    require_choice,
    require_in_range,
    require_non_negative,
    require_positive,
    require_range_pair,
)
from ocean_warp.water_config import WaterConfig
from ocean_warp.wind import WindConfig

from .obstacle_layout import ObstacleLayoutConfig

__all__ = ["ObservationSet", "StartConfig", "RewardConfig", "ReefRule", "TaskConfig", "WaypointConfig",
           "WaypointPlusConfig", "MissionConfig", "MissionSailConfig", "AvoidConfig", "AvoidSailConfig",
           "ObstacleLayoutConfig",
           "avoid_lidar", "BCDACA_ROUTE", "MISSION_WAYPOINTS", "mission_waypoint_name",
           "mission_sea", "mission_simulator", "waypoint_plus_sea"]

MISSION_WAYPOINTS = {"A": (0.0, 0.0), "B": (70.71, -70.71), "C": (141.42, 0.0), "D": (70.71, 70.71)}
"""The seed paper's waypoints [m]: a 100 m square turned 45 degrees."""
BCDACA_ROUTE = tuple(MISSION_WAYPOINTS[name] for name in "BCDACA")
"""The six legs of the mission, in order, starting from A."""


def mission_waypoint_name(point, tolerance: float = 1e-3) -> str | None:
    """The letter of the MISSION_WAYPOINTS entry within ``tolerance`` [m] of ``point`` (x, y) [m], or None."""
    for name, where in MISSION_WAYPOINTS.items():
        if math.dist(where, tuple(map(float, point))) < tolerance:
            return name
    return None


class ObservationSet(str, enum.Enum):
    """What the policy sees (``observation_blocks`` names every column with its scale and unit)."""

    SEED = "seed"
    """The seed paper's 5 values from exact state, each scaled to [-1, 1] and clipped: 2 d / d_lost - 1;
    bearing to the waypoint from the bow [deg] / 180; u / 5 - 1 [m/s]; apparent wind speed / 15 - 1
    [m/s]; apparent wind angle [deg] / 180."""
    PLUS = "plus"
    """15 values from the noisy sensors: distance / d_lost; sin, cos of the bearing (GNSS and compass);
    speed through the water / 2; sin, cos of the apparent wind angle and its speed / 10 (vane and
    anemometer); heel from the accelerometer [rad]; yaw rate / 0.5 (gyro); rudder / 60 deg, boom /
    90 deg and sheet limit / 90 deg (actuator feedback); the last action (3)."""


@dataclasses.dataclass(frozen=True)
class StartConfig:
    """Where and how each episode starts, drawn per environment from its own random stream.

    A ``*_step_deg`` of 0 draws continuously from the range; otherwise from the grid low, low + step, ...
    that stays below high (a full circle counts its end once)."""

    heading_deg: tuple[float, float] = (-180.0, 180.0)
    """Range of the boat's heading [deg, yaw from +x counter-clockwise]; relative to the bearing of the
    first waypoint when ``heading_toward_waypoint``."""
    heading_step_deg: float = 20.0
    """Grid of headings [deg] (the seed: 20); 0: continuous."""
    heading_toward_waypoint: bool = False
    """Headings are offsets from the bearing of the first waypoint (False: absolute)."""
    wind_speed: tuple[float, float] = (0.0, 12.0)
    """Range of the mean true wind speed [m/s] (the seed: 0-12)."""
    wind_direction_deg: tuple[float, float] = (-180.0, 180.0)
    """Range of the direction the wind blows towards [deg]."""
    wind_direction_step_deg: float = 10.0
    """Grid of wind directions [deg] (the seed: 10); 0: continuous."""
    gust_scale: tuple[float, float] = (1.0, 1.0)
    """Range of the factor on the wind config's gust standard deviations."""
    waypoint_distance: tuple[float, float] = (100.0, 100.0)
    """Range of the first waypoint's distance from the start [m] (waypoint tasks; the seed: 100)."""
    waypoint_bearing_deg: tuple[float, float] = (0.0, 0.0)
    """Range of its bearing from the start [deg, from +x counter-clockwise] (the seed: fixed)."""
    position_jitter: float = 0.0
    """Half-width of the square around the start point the boat is placed in [m]."""
    surge_speed: tuple[float, float] = (0.0, 0.0)
    """Range of the initial speed ahead [m/s]."""
    sheet_deg: tuple[float, float] = (0.0, 0.0)
    """Range of the initial sheet (boom limit) [deg]."""
    foil_variation: float = 0.0
    """Domain randomisation of the foils, a fraction (0 to 0.5): each episode the factors on the lift and
    drag coefficients of the sail, the keel and the rudder are drawn independently, uniform in
    [1 - v, 1 + v] (0: exactly 1, as tabulated)."""
    sensor_noise_scale: tuple[float, float] = (1.0, 1.0)
    """Range of the per-episode factor on every sensor's noise and the IMU bias (0 to 10; (1, 1): the
    sensor config's noise exactly)."""
    current_speed: tuple[float, float] | None = None
    """Range of the steady speed of the water's current [m/s] (0 to 5), drawn per episode with its direction
    (the tide and depth profile stay the simulator config's); None (every task's default): the simulator
    config's current every episode (``EBoatSimulatorConfig.current``: none by default)."""
    current_direction_deg: tuple[float, float] = (-180.0, 180.0)
    """Range of the direction the current sets toward [deg, from +x counter-clockwise], with ``current_speed``."""

    def __post_init__(self):
        owner = "StartConfig"
        for name, low, high in (("heading_deg", -360.0, 360.0), ("wind_speed", 0.0, 40.0),
                                ("wind_direction_deg", -360.0, 360.0), ("gust_scale", 0.0, 10.0),
                                ("waypoint_distance", 0.0, 10_000.0), ("waypoint_bearing_deg", -360.0, 360.0),
                                ("surge_speed", -2.0, 5.0), ("sheet_deg", 0.0, 90.0),
                                ("sensor_noise_scale", 0.0, 10.0), ("current_direction_deg", -360.0, 360.0)):
            object.__setattr__(self, name, require_range_pair(owner, name, getattr(self, name), low, high))
        if self.current_speed is not None:
            object.__setattr__(self, "current_speed", require_range_pair(owner, "current_speed", self.current_speed,
                                                                         0.0, 5.0))
        for name in ("heading_step_deg", "wind_direction_step_deg"):
            object.__setattr__(self, name, require_in_range(owner, name, getattr(self, name), 0.0, 360.0))
        object.__setattr__(self, "position_jitter", require_non_negative(owner, "position_jitter",
                                                                         self.position_jitter, unit=" [m]"))
        object.__setattr__(self, "foil_variation", require_in_range(owner, "foil_variation", self.foil_variation,
                                                                    0.0, 0.5))
        if not isinstance(self.heading_toward_waypoint, bool):
            raise ValueError(f"{owner}.heading_toward_waypoint must be True or False, got "
                             f"{self.heading_toward_waypoint!r}")


@dataclasses.dataclass(frozen=True)
class RewardConfig:
    """Reward per decision. Progress: r = (d_prev - d) / progress_scale towards the current waypoint;
    then the seed's propeller term: if r > 0, r *= 1 - propeller_gain |level| / 5, else r -= propeller_cost
    |level|. Plus ``reach_bonus`` per waypoint reached, minus ``lost_penalty`` when the boat is lost,
    minus ``flagged_penalty`` when the simulator flags it (capsized, non-finite, sunk, flying, bad
    input) or, instead, ``collision_penalty`` when the flag is a collision; minus ``smoothness``
    sum((a - a_prev)^2), ``time_cost`` and the motor's energy ``energy_cost`` (|level| / 5)^1.5
    ``decision_period`` every decision; and on a task with obstacles, minus the
    proximity cost ``proximity_cost`` max(0, 1 - g / ``proximity_range``) every decision the boat's
    capsule is a gap g [m] from the nearest obstacle. The progress and proximity terms count only on
    decisions that end unflagged. The level is the one commanded: 0 on a task without propeller
    (``TaskConfig.propeller`` False), whatever a0 is."""

    progress_scale: float = 125.0
    """[m] (the seed: 125)."""
    propeller_gain: float = 0.9
    """The seed: 0.9."""
    propeller_cost: float = 0.01
    """The seed: 0.01."""
    reach_bonus: float = 1.0
    lost_penalty: float = 1.0
    flagged_penalty: float = 1.0
    smoothness: float = 0.0
    """Weight of the squared change of the action (0 in the seed)."""
    time_cost: float = 0.0
    """Per decision (0 in the seed)."""
    collision_penalty: float = 1.0
    """When the boat touches an obstacle or another boat (``BoatStatus.COLLIDED``), in place of
    ``flagged_penalty``; the episode ends."""
    proximity_cost: float = 0.0
    """Cost per decision of sailing at a gap of 0 from an obstacle (falls linearly to 0 at
    ``proximity_range``); 0 in the tasks without obstacles."""
    proximity_range: float = 5.0
    """Gap [m] beyond which an obstacle costs nothing."""
    energy_cost: float = 0.0
    """The battery's price: cost per second of the motor at full thrust, whatever the boat gains by it; at a
    lower level (|level| / 5)^1.5 of it (a propeller's power goes about as thrust^1.5, momentum theory).
    0 in the seed's reward (whose propeller terms price the motor only against progress)."""

    def __post_init__(self):
        owner = "RewardConfig"
        for name, unit in (("progress_scale", " [m]"), ("proximity_range", " [m]")):
            object.__setattr__(self, name, require_positive(owner, name, getattr(self, name), unit=unit))
        for field in dataclasses.fields(self):
            if field.name not in ("progress_scale", "proximity_range"):
                object.__setattr__(self, field.name, require_non_negative(owner, field.name,
                                                                          getattr(self, field.name)))


@dataclasses.dataclass(frozen=True)
class ReefRule:
    """How each episode's reef level is chosen, as a crew sets the rig for the forecast: by the episode's
    drawn mean true wind speed (before gusts), at its start, from a random stream of its own. Level k sails
    the boat's sail ``EBoatConfig.sail_areas[k]`` (the E-Boat: 3.188, about 2.0 and 1.15 m^2), and the policy
    of a task with a rule sees it (one value, level / (levels - 1), after the observation set's)."""

    thresholds: tuple[float, ...] = (6.0, 8.0)
    """True wind speeds [m/s] at which the rule reefs one level deeper, increasing: the default sails the full
    sail below 6 m/s, reef 1 from 6 to 8 and reef 2 from 8 (a speed on a threshold takes the deeper reef).
    At most one fewer than the boat's levels."""
    level: int | None = None
    """A fixed reef level for every episode in place of the rule (None: the rule)."""
    random_level: float = 0.0
    """Probability (0 to 1) that an episode's level is drawn uniformly from the boat's levels instead of the
    rule's (or ``level``'s): domain randomisation for training (0: never)."""

    def __post_init__(self):
        owner = "ReefRule"
        try:
            thresholds = tuple(float(t) for t in self.thresholds)
        except (TypeError, ValueError):
            raise ValueError(f"{owner}.thresholds must be a sequence of true wind speeds [m/s], got "
                             f"{self.thresholds!r}") from None
        if not all(math.isfinite(t) and t >= 0.0 for t in thresholds):
            raise ValueError(f"{owner}.thresholds must be finite wind speeds >= 0 [m/s], got {self.thresholds!r}")
        if any(b <= a for a, b in zip(thresholds, thresholds[1:])):
            raise ValueError(f"{owner}.thresholds must increase, got {self.thresholds!r}")
        object.__setattr__(self, "thresholds", thresholds)
        if self.level is not None and (isinstance(self.level, bool) or not isinstance(self.level, int)
                                       or self.level < 0):
            raise ValueError(f"{owner}.level must be None or a reef level >= 0, got {self.level!r}")
        object.__setattr__(self, "random_level", require_in_range(owner, "random_level", self.random_level, 0.0, 1.0))

    def level_for(self, wind_speed: float) -> int:
        """The rule's level at a mean true wind of ``wind_speed`` [m/s] (``level`` where fixed; not the random
        draw): the number of thresholds at or below it."""
        if self.level is not None:
            return self.level
        return sum(1 for t in self.thresholds if t <= wind_speed)

    def require_levels(self, owner: str, levels: int) -> None:
        """``ValueError`` naming the field unless this rule fits a boat of ``levels`` reef levels."""
        if len(self.thresholds) > levels - 1:
            raise ValueError(f"{owner}.reef: ReefRule.thresholds {self.thresholds} reef {len(self.thresholds)} "
                             f"levels deep; the boat has {levels - 1} reef levels after its full sail "
                             "(EBoatConfig.reef_areas)")
        if self.level is not None and self.level >= levels:
            raise ValueError(f"{owner}.reef: ReefRule.level {self.level} is outside the boat's reef levels "
                             f"0-{levels - 1}")


FRESH_WATER = WaterConfig(density=997.0)
"""The Gazebo twin's water (the seed's tasks); every other task sails sea water."""


def _seed_sea() -> OceanConfig:
    """Gentle waves, as the seed's (three small Pierson-Moskowitz components): Hs 0.3 m, Tp 3 s."""
    return OceanConfig(tile_size=256.0, resolution=64, significant_wave_height=0.3, peak_period=3.0)


def waypoint_plus_sea() -> OceanConfig:
    """A livelier sea than the seed's, choppy: Hs 0.5 m, Tp 3.5 s, choppiness 0.5."""
    return OceanConfig(tile_size=256.0, resolution=64, significant_wave_height=0.5, peak_period=3.5, choppiness=0.5)


def mission_sea() -> OceanConfig:
    """The mission's default JONSWAP sea: Hs 0.3 m, Tp 3 s."""
    return OceanConfig(tile_size=256.0, resolution=64, significant_wave_height=0.3, peak_period=3.0)


@dataclasses.dataclass(frozen=True)
class TaskConfig:
    """A sailing task: the simulation, the route, the start distribution, the observation and the reward."""

    simulator: EBoatSimulatorConfig = dataclasses.field(default_factory=lambda: EBoatSimulatorConfig(
        boat=EBoatConfig(), ocean=_seed_sea(), sensors=SensorConfig.noise_free()))
    """Boat, sea, wind gusts, sensors, water and time step (dt, substeps)."""
    decision_period: float = 1.0
    """Simulated time per decision [s] (the seed: 1-5 s); a whole number of ``simulator.dt``."""
    episode_time: float = 600.0
    """Time limit [s]; an episode that reaches it is reported as a time-out, not a termination."""
    route: tuple[tuple[float, float], ...] | None = None
    """Fixed waypoints (x, y) [m] from the origin, sailed in order; None: one waypoint drawn per episode
    (``start.waypoint_distance``, ``start.waypoint_bearing_deg``)."""
    start_point: tuple[float, float] = (0.0, 0.0)
    """Where episodes start, from the origin [m]."""
    reach_radius: float = 5.0
    """A waypoint counts as reached within this distance [m]."""
    lost_margin: float = 25.0
    """The boat is lost when farther from its waypoint than the leg's length plus this [m] (the seed:
    100 + 25 = 125 m)."""
    observation: ObservationSet | str = ObservationSet.SEED
    start: StartConfig = dataclasses.field(default_factory=StartConfig)
    reward: RewardConfig = dataclasses.field(default_factory=RewardConfig)
    ocean_spacing: bool = True
    """Give each environment its own origin, spread over the periodic ocean tile, so that neighbours
    meet different waves (False: every origin at (0, 0))."""
    start_height: float | None = None
    """Height of the base frame at the start [m]; None: the boat's rest height in still water."""
    propeller: bool = True
    """The boat may use its propeller (a0 sets the level). False: sail only; a0 is ignored, the level
    commanded (and seen by the reward's propeller term) is 0 at every decision; the action space stays
    3-D, as every task's."""
    obstacles: ObstacleLayoutConfig | None = None
    """Buoys and piles drawn for every environment at every reset, between the start and the first waypoint
    (None: open water). Needs ``contact``."""
    contact: ContactConfig | None = None
    """Contact of the boats with their environment's obstacles: a touch flags ``BoatStatus.COLLIDED``, which
    ends the episode with ``reward.collision_penalty``, and the penalty force pushes the boat off."""
    lidar: LidarConfig | None = None
    """A lidar on every boat, scanned when the observation is made (at the end of each decision, and again
    after a reset; its ``rate`` is not used); the policy sees ``lidar_sectors`` values after the observation
    set's: the nearest return of each sector over the lidar's max range, in [0, 1] (None: no lidar)."""
    lidar_sectors: int = 24
    """Equal sectors the lidar's beams are pooled into (a whole divisor of its beams per channel)."""
    reef: ReefRule | None = dataclasses.field(default_factory=ReefRule)
    """How each episode's reef level is chosen (:class:`ReefRule`); the policy sees the level (one value after
    the observation set's, before the lidar's). None: the full sail always, and no such value (the seed's
    waypoint task, as published)."""

    def __post_init__(self):
        owner = type(self).__name__
        if not isinstance(self.simulator, EBoatSimulatorConfig):
            raise ValueError(f"{owner}.simulator must be an EBoatSimulatorConfig, got {self.simulator!r}")
        period = require_positive(owner, "decision_period", self.decision_period, unit=" [s]")
        steps = period / self.simulator.dt
        if abs(steps - round(steps)) > 1e-6 * max(1.0, steps) or round(steps) < 1:
            raise ValueError(f"{owner}.decision_period {period} s must be a whole number (>= 1) of simulator.dt "
                             f"{self.simulator.dt} s")
        object.__setattr__(self, "decision_period", period)
        episode = require_positive(owner, "episode_time", self.episode_time, unit=" [s]")
        if episode < period:
            raise ValueError(f"{owner}.episode_time {episode} s must be at least one decision_period ({period} s)")
        object.__setattr__(self, "episode_time", episode)
        if self.route is not None:
            route = tuple(tuple(float(v) for v in point) for point in self.route)
            if not route or any(len(point) != 2 or not all(math.isfinite(v) for v in point) for point in route):
                raise ValueError(f"{owner}.route must be a non-empty sequence of finite (x, y) pairs [m], got "
                                 f"{self.route!r}")
            object.__setattr__(self, "route", route)
        object.__setattr__(self, "reach_radius", require_positive(owner, "reach_radius", self.reach_radius,
                                                                  unit=" [m]"))
        object.__setattr__(self, "lost_margin", require_non_negative(owner, "lost_margin", self.lost_margin,
                                                                     unit=" [m]"))
        object.__setattr__(self, "observation", require_choice(owner, "observation", self.observation,
                                                               ObservationSet))
        for name, kind in (("start", StartConfig), ("reward", RewardConfig)):
            if not isinstance(getattr(self, name), kind):
                raise ValueError(f"{owner}.{name} must be a {kind.__name__}, got {getattr(self, name)!r}")
        if self.start_height is not None:
            object.__setattr__(self, "start_height", require_in_range(owner, "start_height", self.start_height,
                                                                      -1.0, 1.0, unit=" [m]"))
        if not isinstance(self.propeller, bool):
            raise ValueError(f"{owner}.propeller must be True or False, got {self.propeller!r}")
        for name, kind in (("obstacles", ObstacleLayoutConfig), ("contact", ContactConfig), ("lidar", LidarConfig)):
            if getattr(self, name) is not None and not isinstance(getattr(self, name), kind):
                raise ValueError(f"{owner}.{name} must be a {kind.__name__} or None, got {getattr(self, name)!r}")
        if self.obstacles is not None and self.contact is None:
            raise ValueError(f"{owner}.contact must be a ContactConfig when obstacles are drawn (else nothing "
                             "detects a collision), got None")
        if self.reef is not None:
            if not isinstance(self.reef, ReefRule):
                raise ValueError(f"{owner}.reef must be a ReefRule or None, got {self.reef!r}")
            self.reef.require_levels(owner, self.simulator.boat.reef_levels)
        if self.lidar is not None:
            beams = self.lidar.beams
            sectors = self.lidar_sectors
            if isinstance(sectors, bool) or not isinstance(sectors, int) or not 1 <= sectors <= beams \
                    or beams % sectors:
                raise ValueError(f"{owner}.lidar_sectors must be a whole divisor of the lidar's {beams} beams, "
                                 f"got {sectors!r}")

    @property
    def steps_per_decision(self) -> int:
        return int(round(self.decision_period / self.simulator.dt))

    @property
    def max_episode_length(self) -> int:
        """Decisions before a time-out."""
        return max(1, int(round(self.episode_time / self.decision_period)))

    @property
    def route_length(self) -> int:
        return 1 if self.route is None else len(self.route)

    @property
    def reef_observations(self) -> int:
        """Values of the policy's observation that give the reef level: 1 with a ``reef`` rule, else 0."""
        return 0 if self.reef is None else 1

    @property
    def lidar_observations(self) -> int:
        """Values of the policy's observation that come from the lidar (after the observation set's)."""
        return 0 if self.lidar is None else self.lidar_sectors

    @property
    def obstacle_slots(self) -> int:
        """The most obstacles an environment holds (0 without ``obstacles``)."""
        return 0 if self.obstacles is None else self.obstacles.slots


@dataclasses.dataclass(frozen=True)
class WaypointConfig(TaskConfig):
    """The seed paper's task on the seed's twin: the boat at the origin, a waypoint 100 m away (toward
    +x), heading on a 20 deg grid, wind 0-12 m/s from a 10 deg grid, gentle waves, exact observations
    (5), the seed's reward; reached within 5 m, lost beyond 125 m. The boat floats on the original
    twin's four-point buoyancy in fresh water (997 kg/m^3), as in Gazebo, and the sea is evaluated once
    per 0.05 s step (its waves are 3 s long): about 30 times cheaper than the mesh hull, which is what
    lets this task train on a laptop's CPU. The seed gave no time limit; ours is 600 s. No reef rule: the
    full sail in every wind, as published (``reef`` None)."""

    simulator: EBoatSimulatorConfig = dataclasses.field(default_factory=lambda: EBoatSimulatorConfig(
        boat=EBoatConfig(profile=Profile.SEED), ocean=dataclasses.replace(_seed_sea(), water=FRESH_WATER),
        sensors=SensorConfig.noise_free(), ocean_every_substep=False))
    reef: ReefRule | None = None


@dataclasses.dataclass(frozen=True)
class WaypointPlusConfig(TaskConfig):
    """Ours: noisy-sensor observations with sin/cos angles, heel, yaw rate, actuator feedback and the last
    action; continuous randomisation of start, wind (2-12 m/s), gusts (0-1.5 x 1 m/s and 0.1 rad) and
    the waypoint (50-150 m, any bearing); a choppy sea; a 300 s time limit; a penalty on jerky actuation. The
    sail is reefed by the default :class:`ReefRule` (full sail below 6 m/s of true wind, reef 1 to 8, reef 2
    above), and the policy sees its level (16 values)."""

    simulator: EBoatSimulatorConfig = dataclasses.field(default_factory=lambda: EBoatSimulatorConfig(
        boat=EBoatConfig(), ocean=waypoint_plus_sea(),
        wind=WindConfig(gust_speed_std=1.0, gust_direction_std=0.1)))
    episode_time: float = 300.0
    observation: ObservationSet | str = ObservationSet.PLUS
    start: StartConfig = dataclasses.field(default_factory=lambda: StartConfig(
        heading_deg=(-180.0, 180.0), heading_step_deg=0.0, wind_speed=(2.0, 12.0), wind_direction_step_deg=0.0,
        gust_scale=(0.0, 1.5), waypoint_distance=(50.0, 150.0), waypoint_bearing_deg=(-180.0, 180.0),
        position_jitter=2.0, surge_speed=(0.0, 1.0), sheet_deg=(0.0, 60.0)))
    reward: RewardConfig = dataclasses.field(default_factory=lambda: RewardConfig(smoothness=0.05))


def mission_simulator(boat: EBoatConfig) -> EBoatSimulatorConfig:
    """The mission's simulation with ``boat``: its JONSWAP sea, a true wind of 10 m/s toward +x with gusts
    (1 m/s and 0.1 rad standard deviations), noise-free sensors."""
    return EBoatSimulatorConfig(boat=boat, ocean=mission_sea(),
                                wind=WindConfig(speed=10.0, direction=0.0, gust_speed_std=1.0, gust_direction_std=0.1),
                                sensors=SensorConfig.noise_free())


@dataclasses.dataclass(frozen=True)
class MissionConfig(TaskConfig):
    """The seed paper's six-waypoint mission "BCDACA": from A (0, 0) to B, C, D, A, C, A, each reached within
    5 m; true wind 10 m/s blowing toward +x with gusts, so A->C runs dead downwind and C->A beats dead
    upwind; a JONSWAP sea; the boat starts with its sheet eased to 60 deg (sheeted hard in on the broad reach
    to B, the full-sail E-Boat capsized in 10 m/s before the sheet could ease; kept with the reef). Observations
    and reward as the waypoint task's, toward the current waypoint;
    lost beyond the leg's length + 25 m; ends at the last waypoint or after 1800 s. The boat is the physics
    profile's (``EBoatConfig()``: mesh hull, ITTC friction and residuary resistance, keel and rudder as
    lifting surfaces), its sail reefed by the default :class:`ReefRule` (full sail below 6 m/s of true wind,
    reef 1 to 8, reef 2 above): reef 2 (1.15 m^2) in the mission's 10 m/s; the policy sees its level (6
    values)."""

    simulator: EBoatSimulatorConfig = dataclasses.field(default_factory=lambda: mission_simulator(EBoatConfig()))
    episode_time: float = 1800.0
    route: tuple[tuple[float, float], ...] | None = BCDACA_ROUTE
    start: StartConfig = dataclasses.field(default_factory=lambda: StartConfig(
        heading_deg=(-10.0, 10.0), heading_step_deg=0.0, heading_toward_waypoint=True, wind_speed=(10.0, 10.0),
        wind_direction_deg=(0.0, 0.0), wind_direction_step_deg=0.0, position_jitter=1.0, sheet_deg=(60.0, 60.0)))


@dataclasses.dataclass(frozen=True)
class MissionSailConfig(MissionConfig):
    """The BCDACA mission under sail alone: as :class:`MissionConfig` (route, sea, gusty 10 m/s wind, start,
    reward, 1800 s, the physics profile's boat), with the propeller off (a0 ignored, level 0 at every
    decision) and the ``plus`` observation: under sail alone the policy must see its heel, yaw rate, boom
    and rudder, which the seed's five values lack (trained the same 8 minutes on an H100, the seed's
    observation completes 0 of 20 missions in 10 m/s, this one 6-9 of 20 and 18-19 of 20 in 7 m/s;
    ``benchmarks/RESULTS.md``, "Sailing fidelity"; before the reef). The reef rule is the mission's (reef 2 in
    10 m/s; the policy sees its level: 16 values). Its shipped policy is ``eboat_mission_sail.pt`` (7.3 minutes
    on one GPU; 19-20 of 20 in 3, 5, 7 and 10 m/s at Hs 0.3 and 0.5 m: RESULTS, issue 34)."""

    propeller: bool = False
    observation: ObservationSet | str = ObservationSet.PLUS


def avoid_lidar(**changes) -> LidarConfig:
    """The avoidance task's lidar: a level 2D scan of 360 beams (1 deg) from the bow mount, 0.2-50 m, exact,
    with the sea's returns filtered out (on a heeling boat the level beams meet the waves within a few
    metres; a marine lidar's clutter filter removes them), then ``changes``."""
    return LidarConfig(**({"beams": 360, "max_range": 50.0, "rate": 1.0, "water_returns": False} | changes))


def avoid_simulator() -> EBoatSimulatorConfig:
    """The avoidance task's simulation: the physics profile's boat, the mission's JONSWAP sea (Hs 0.3 m,
    Tp 3 s), light gusts (0.5 m/s and 0.05 rad standard deviations), noise-free sensors."""
    return EBoatSimulatorConfig(boat=EBoatConfig(), ocean=mission_sea(),
                                wind=WindConfig(gust_speed_std=0.5, gust_direction_std=0.05),
                                sensors=SensorConfig.noise_free())


@dataclasses.dataclass(frozen=True)
class AvoidConfig(TaskConfig):
    """Obstacle avoidance: a waypoint 100-200 m away at any bearing through a field of 6-12 buoys and piles
    (``ObstacleLayoutConfig()``, drawn anew at every reset, clear of the start and the waypoint); the boat
    starts heading within 45 deg of it; true wind 3-8 m/s from any direction. The policy sees the seed's
    five values and the lidar's 24 sectors (15 deg each, nearest return / 50 m). The seed's reward, plus a
    collision penalty of 2 (the episode ends on a touch) and a proximity cost of up to 0.02 per decision
    within 5 m of an obstacle. Reached within 5 m; lost beyond the leg's length + 25 m; 400 s. The physics
    profile's boat (mesh hull), its sail reefed by the default :class:`ReefRule` (full sail below 6 m/s of true
    wind, reef 1 to 8, reef 2 above): full or reef 1 in this task's winds; the policy sees its level after the
    seed's five values and before the lidar's sectors (30 values)."""

    simulator: EBoatSimulatorConfig = dataclasses.field(default_factory=avoid_simulator)
    episode_time: float = 400.0
    start: StartConfig = dataclasses.field(default_factory=lambda: StartConfig(
        heading_deg=(-45.0, 45.0), heading_step_deg=0.0, heading_toward_waypoint=True, wind_speed=(3.0, 8.0),
        wind_direction_step_deg=0.0, waypoint_distance=(100.0, 200.0), waypoint_bearing_deg=(-180.0, 180.0),
        position_jitter=1.0, sheet_deg=(30.0, 60.0)))
    reward: RewardConfig = dataclasses.field(default_factory=lambda: RewardConfig(
        collision_penalty=2.0, proximity_cost=0.02, proximity_range=5.0))
    obstacles: ObstacleLayoutConfig | None = dataclasses.field(default_factory=ObstacleLayoutConfig)
    contact: ContactConfig | None = dataclasses.field(default_factory=ContactConfig)
    lidar: LidarConfig | None = dataclasses.field(default_factory=avoid_lidar)


@dataclasses.dataclass(frozen=True)
class AvoidSailConfig(AvoidConfig):
    """The avoidance task under sail alone: as :class:`AvoidConfig`, with the propeller off (a0 ignored, level
    0), wind 4-8 m/s and 800 s (a 200 m beat to windward takes the boat about 5 minutes); the reef rule is
    the avoidance task's (the default :class:`ReefRule`)."""

    propeller: bool = False
    episode_time: float = 800.0
    start: StartConfig = dataclasses.field(default_factory=lambda: StartConfig(
        heading_deg=(-45.0, 45.0), heading_step_deg=0.0, heading_toward_waypoint=True, wind_speed=(4.0, 8.0),
        wind_direction_step_deg=0.0, waypoint_distance=(100.0, 200.0), waypoint_bearing_deg=(-180.0, 180.0),
        position_jitter=1.0, sheet_deg=(30.0, 60.0)))
