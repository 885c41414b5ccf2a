"""A classical sailing autopilot for a batch of E-Boats: a baseline that runs in place of a policy.

Each call of :meth:`SailingAutopilot.act` makes one decision per boat and writes the same normalised
actions a policy would (a0 propeller, a1 sheet, a2 rudder, each in [-1, 1]; see the action map in
``ocean_warp.envs``): line-of-sight guidance to each boat's target, a close-hauled beat with tacks at
the laylines (with hysteresis) when the target lies upwind in the no-go zone (turning the long way
round, a wear, when a tack does not come through), broad reaches with
gybes when it lies dead downwind (deeper than ``run_angle``), the sheet trimmed from the apparent
wind angle (eased when the boat heels), and the rudder from a PI heading controller with yaw-rate
damping; the motor assists on beats, through turns and when the boat has too little way on. The
kernels are in ``ocean_warp.envs.controllers.autopilot_kernels``. The defaults were tuned on the BCDACA mission
(mesh hull, 10 m/s gusty wind, 0.3 m sea; ``benchmarks/studies/autopilot_mission.py``): under sail alone the
E-Boat makes 0.2-0.3 m/s to windward there and fails most tacks (lee helm, little way on), and it
completed none of 20 missions; with the motor assisting on beats it completes them.

It reads the boats' truth (position, orientation, velocity, current true wind): a baseline, not a
sensor-driven controller. It takes them from a simulator's state, or from an environment's buffers
(:meth:`SailingAutopilot.for_env`, any :class:`~ocean_warp.envs.protocol.BatchedEnv`).

Obstacle avoidance: where the boats carry a lidar (:class:`LidarSectors`: ``for_env`` reads them from the
policy's observation of a task with a ``lidar``, as EBoatAvoid-v0), the autopilot first turns each target
into a steering target that keeps its course out of the collision cones of the lidar's nearest return per
sector, then sails to it as above (``AutopilotConfig.avoidance``; the law is in :class:`SailingAutopilot`'s
docstring). Without a lidar, nothing of this runs and the autopilot sails exactly as it did before
avoidance existed.

Example::

    autopilot = SailingAutopilot(sim.state)
    autopilot.reset()
    autopilot.act(targets, actions)        # targets (N,) vec3 world [m]; actions (N, 3) float
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import warp as wp

from ocean_warp.device_structs import struct_from
from ocean_warp.validation import require_in_range, require_int_in_range, require_non_negative, require_positive

from ocean_warp.kernels.spatial import vec6

from .autopilot_kernels import (AutopilotParameters, AvoidanceParameters, NO_RETURN_AGE, forget_returns,
                                reset_autopilot, sail_to_targets, steer_clear)

__all__ = ["AutopilotConfig", "LidarSectors", "SailingAutopilot", "env_boats"]

_OWNER = "AutopilotConfig"


@dataclasses.dataclass(frozen=True)
class AutopilotConfig:
    """Gains and sailing angles of :class:`SailingAutopilot` (radians, SI units). Invalid values raise
    ``ValueError`` naming the field."""

    decision_period: float = 1.0
    """Sim time between calls of ``act`` [s]: the step of the heading integrator. In (0, 60]."""
    close_hauled_angle: float = math.radians(50.0)
    """Heading off the true wind's source while beating [rad], in (0, 90 deg). With the motor assisting
    (``assist_level``) the E-Boat points higher than under sail alone (65 deg measured best there)."""
    no_go_angle: float = math.radians(60.0)
    """Half-width of the no-go zone around the true wind's source [rad], in [close_hauled_angle, 90 deg):
    targets whose bearing is closer to the wind than this are reached by beating. The track made good
    close-hauled, leeway (about 10 deg) included."""
    run_angle: float = math.radians(150.0)
    """Deepest true wind angle sailed downwind [rad], in (90, 180] deg: targets deeper than this are
    reached on broad reaches at this angle, gybing. A dead run (180 deg) is a little faster for the
    E-Boat, but in 10 m/s gusts it rolled boats over after the rounding at A (1-4 capsizes in 20
    missions; 0 at 150 deg, Hs 0.3 m, seeds 0 and 1)."""
    tack_hysteresis: float = math.radians(70.0)
    """How far past the wind axis the target's bearing must swing [rad], in [0, 90 deg), before the boat
    tacks (or gybes) to the other side: the larger, the fewer tacks. Capped at the zone's half-width,
    where the boat tacks on the layline. The default, near the layline, keeps the E-Boat's costly
    wears (about 25 s and 15-20 m to leeward each) to one or two a beat."""
    lane_half_width: float = 10.0
    """Cross-track room kept near the target [m] (>= 0): the tack margin widens to atan(this / distance)
    so tacks do not crowd together as the target nears."""
    heading_gain: float = 0.7
    """Rudder per heading error [rad/rad] (> 0)."""
    heading_integral_gain: float = 0.1
    """Rudder per accumulated heading error [rad/(rad s)] (>= 0): trims out weather helm."""
    yaw_rate_gain: float = 1.5
    """Rudder per yaw rate [rad/(rad/s)] (>= 0): damps the turn."""
    rudder_limit: float = math.radians(30.0)
    """Largest rudder angle commanded [rad], in (0, 60 deg]."""
    attack_angle: float = math.radians(20.0)
    """Angle of attack the sheet aims the sail at [rad], in [0, 90 deg]: sheet = |apparent wind angle| - this."""
    min_sheet: float = 0.0
    """Smallest sheet (boom limit) [rad], in [0, 90 deg]."""
    max_sheet: float = math.radians(90.0)
    """Largest sheet (boom limit) [rad], in [min_sheet, 90 deg]."""
    heel_limit: float = math.radians(15.0)
    """Heel [rad], in [0, 90 deg], past which the sheet is eased."""
    heel_ease: float = 3.0
    """Sheet eased per heel past ``heel_limit`` [rad/rad] (>= 0)."""
    propeller_level: int = 0
    """Propeller level -5 ... 5 written as a0 at all times (0: the autopilot sails)."""
    assist_level: int = 5
    """Propeller level 0 ... 5 used on beats, through turns and below ``assist_speed``: in 10 m/s of wind
    the E-Boat under sail alone makes 0.2-0.3 m/s to windward and fails most tacks (lee helm, little way
    on), so the mission needs the motor there. 0: sail only."""
    assist_speed: float = 0.5
    """Speed ahead [m/s] (>= 0) below which the motor assists."""
    tack_timeout: float = 15.0
    """How long the boat tries to turn through the wind [s] (>= 0) before it turns the other way round,
    bearing away through the run (a wear). Under sail alone the E-Boat's lee helm defeats most tacks in
    10 m/s; with the motor assisting they mostly succeed."""
    turn_release_angle: float = math.radians(30.0)
    """A turn forced the long way round ends when the heading is this close to the course [rad], in (0, 90 deg)."""
    bear_away_ease: float = 1.5
    """Sheet eased per heading error while bearing away [rad/rad] (>= 0): a heeled E-Boat rounds up
    against full rudder unless the sail is let out."""
    approach_radius: float = 5.0
    """Within this distance of its target [m] (>= 0), a boat that has the target behind it (overshot)
    holds its last course until it is this far away, then comes back, rather than circling the target."""
    avoidance: bool = True
    """Steer clear of the lidar's returns where the boats carry a lidar (:class:`LidarSectors`; for an env:
    a task with a ``lidar``): the collision cones of :class:`SailingAutopilot`. False, or without a lidar:
    sail straight to the targets."""
    avoidance_range: float = 20.0
    """Range R [m] (> 0) within which returns are avoided; farther ones are ignored."""
    avoidance_clearance: float = 3.0
    """Gap c [m] (> 0) the course keeps from a return: the boat's half beam (0.5 m), the rest of the obstacle
    beyond its nearest point (a pile or buoy is up to 1.2 m in radius) and a margin. A return at range r
    blocks the courses within min(asin(min(1, c / r)), ``avoidance_cone``) of it, plus half a sector."""
    avoidance_cone: float = math.radians(45.0)
    """The widest [rad], in (0, 90 deg], that a return's cone spreads for the clearance (beyond half a
    sector): asin(c / r) grows to 90 deg as a return closes to c, which would turn a boat hard away from a
    buoy it is passing 2 m off; capped, a near return only blocks the courses that head at it."""
    avoidance_lookahead: float = 20.0
    """Distance from the boat [m] (> 0) of the steering target put on the clear course while the course to
    the target is blocked."""
    avoidance_memory: float = 3.0
    """How long [s] (>= 0) a sector's last return is still avoided, where it lies in the world, after the
    sector stops seeing anything: the avoidance task's level lidar, 0.8 m above the water, catches a buoy
    (0.4-1 m in radius, floating half out) in only about a third of its scans within 25 m, as the boat
    pitches and the buoy rides the waves (piles: nine in ten). 0: this scan's returns alone. On
    EBoatAvoid-v0 (192 runs, seeds 0-5) 3 s left 7 collisions where 0 s left 17."""
    avoidance_turn_cost: float = 1.0
    """Weight (>= 0, dimensionless) of the turn from the boat's heading against the departure from the
    intended course in choosing among the clear courses: a clear course costs |course - intended| + this
    |course - heading| [rad]. 0: the clear course nearest the intended one, however far the boat must turn;
    above 0, the boat keeps turning the way it turned (fewer flips from side to side)."""

    def __post_init__(self):
        degree = math.pi / 180.0
        checks = (
            ("decision_period", lambda v: require_in_range(_OWNER, "decision_period",
                                                           require_positive(_OWNER, "decision_period", v, unit=" [s]"),
                                                           0.0, 60.0, unit=" [s]")),
            ("close_hauled_angle", lambda v: _open_range("close_hauled_angle", v, 0.0, 90.0 * degree)),
            ("no_go_angle", lambda v: _right_open_range("no_go_angle", v, 0.0, 90.0 * degree)),
            ("run_angle", lambda v: _half_open_range("run_angle", v, 90.0 * degree, math.pi)),
            ("tack_hysteresis", lambda v: _right_open_range("tack_hysteresis", v, 0.0, 90.0 * degree)),
            ("lane_half_width", lambda v: require_non_negative(_OWNER, "lane_half_width", v, unit=" [m]")),
            ("heading_gain", lambda v: require_positive(_OWNER, "heading_gain", v)),
            ("heading_integral_gain", lambda v: require_non_negative(_OWNER, "heading_integral_gain", v)),
            ("yaw_rate_gain", lambda v: require_non_negative(_OWNER, "yaw_rate_gain", v)),
            ("rudder_limit", lambda v: _half_open_range("rudder_limit", v, 0.0, 60.0 * degree)),
            ("attack_angle", lambda v: require_in_range(_OWNER, "attack_angle", v, 0.0, 90.0 * degree, unit=" [rad]")),
            ("min_sheet", lambda v: require_in_range(_OWNER, "min_sheet", v, 0.0, 90.0 * degree, unit=" [rad]")),
            ("max_sheet", lambda v: require_in_range(_OWNER, "max_sheet", v, 0.0, 90.0 * degree, unit=" [rad]")),
            ("heel_limit", lambda v: require_in_range(_OWNER, "heel_limit", v, 0.0, 90.0 * degree, unit=" [rad]")),
            ("heel_ease", lambda v: require_non_negative(_OWNER, "heel_ease", v)),
            ("bear_away_ease", lambda v: require_non_negative(_OWNER, "bear_away_ease", v)),
            ("approach_radius", lambda v: require_non_negative(_OWNER, "approach_radius", v, unit=" [m]")),
            ("tack_timeout", lambda v: require_non_negative(_OWNER, "tack_timeout", v, unit=" [s]")),
            ("turn_release_angle", lambda v: _open_range("turn_release_angle", v, 0.0, 90.0 * degree)),
            ("assist_speed", lambda v: require_non_negative(_OWNER, "assist_speed", v, unit=" [m/s]")),
            ("avoidance_range", lambda v: require_in_range(
                _OWNER, "avoidance_range", require_positive(_OWNER, "avoidance_range", v, unit=" [m]"), 0.0, 1.0e4,
                unit=" [m]")),
            ("avoidance_clearance", lambda v: require_in_range(
                _OWNER, "avoidance_clearance", require_positive(_OWNER, "avoidance_clearance", v, unit=" [m]"),
                0.0, 1.0e3, unit=" [m]")),
            ("avoidance_cone", lambda v: _half_open_range("avoidance_cone", v, 0.0, 90.0 * degree)),
            ("avoidance_lookahead", lambda v: require_in_range(
                _OWNER, "avoidance_lookahead", require_positive(_OWNER, "avoidance_lookahead", v, unit=" [m]"),
                0.0, 1.0e4, unit=" [m]")),
            ("avoidance_memory", lambda v: require_in_range(_OWNER, "avoidance_memory", v, 0.0, 3600.0, unit=" [s]")),
            ("avoidance_turn_cost", lambda v: require_in_range(_OWNER, "avoidance_turn_cost", v, 0.0, 1.0e3)),
        )
        for name, check in checks:
            object.__setattr__(self, name, check(getattr(self, name)))
        if self.no_go_angle < self.close_hauled_angle:
            raise ValueError(f"{_OWNER}.no_go_angle must be >= close_hauled_angle ({self.close_hauled_angle!r} rad), "
                             f"got {self.no_go_angle!r}")
        if self.max_sheet < self.min_sheet:
            raise ValueError(f"{_OWNER}.max_sheet must be >= min_sheet ({self.min_sheet!r} rad), "
                             f"got {self.max_sheet!r}")
        object.__setattr__(self, "assist_level", require_int_in_range(_OWNER, "assist_level", self.assist_level, 0, 5))
        object.__setattr__(self, "propeller_level",
                           require_int_in_range(_OWNER, "propeller_level", self.propeller_level, -5, 5))
        if not isinstance(self.avoidance, bool):
            raise ValueError(f"{_OWNER}.avoidance must be True or False, got {self.avoidance!r}")

    @classmethod
    def sail_only(cls, **overrides) -> "AutopilotConfig":
        """Settings for the physics-profile E-Boat with the propeller off (``overrides`` replace fields): the
        sail aimed at 20 deg of attack (the ORC main's lift is near its top there and it luffs below 8),
        the rudder held to 18 deg (the lifting-surface rudder stalls at 17.7 deg of attack, which a turning
        boat's rudder meets at a larger angle), dead runs rather than broad
        reaches (on a broad reach with the boom at 90 deg the boat rounds up against its rudder in 10 m/s)
        and the boom let out no further than 80 deg. Swept on the sail-only BCDACA mission, 5 m/s, Hs 0.3 m,
        20 runs (H100, 2026-11-24): 20 of 20 completed; the defaults with the motor off: 10 of 20."""
        degree = math.pi / 180.0
        settings = dict(attack_angle=20.0 * degree, rudder_limit=18.0 * degree, run_angle=180.0 * degree,
                        max_sheet=80.0 * degree, assist_level=0, propeller_level=0)
        return cls(**{**settings, **overrides})

    def parameters(self) -> AutopilotParameters:
        """The kernels' view of this config."""
        return struct_from(AutopilotParameters, self)

    def avoidance_parameters(self, lidar: "LidarSectors") -> AvoidanceParameters:
        """The avoidance kernel's view of this config and of ``lidar``."""
        return struct_from(AvoidanceParameters, self, sector_range=lidar.max_range,
                           sector_half_width=lidar.half_width, mount=wp.vec3(*lidar.mount))


def _open_range(name: str, value, low: float, high: float) -> float:
    value = require_in_range(_OWNER, name, value, low, high, unit=" [rad]")
    if value <= low or value >= high:
        raise ValueError(f"{_OWNER}.{name} must be in ({low!r}, {high!r}) [rad], got {value!r}")
    return value


def _half_open_range(name: str, value, low: float, high: float) -> float:
    value = require_in_range(_OWNER, name, value, low, high, unit=" [rad]")
    if value <= low:
        raise ValueError(f"{_OWNER}.{name} must be in ({low!r}, {high!r}] [rad], got {value!r}")
    return value


def _right_open_range(name: str, value, low: float, high: float) -> float:
    value = require_in_range(_OWNER, name, value, low, high, unit=" [rad]")
    if value >= high:
        raise ValueError(f"{_OWNER}.{name} must be in [{low!r}, {high!r}) [rad], got {value!r}")
    return value


@dataclasses.dataclass(frozen=True)
class LidarSectors:
    """Where :class:`SailingAutopilot` reads a lidar's nearest return per sector (read at each call, nothing
    is copied), and the lidar's geometry. :meth:`from_lidar` builds one from a ``LidarConfig``."""

    values: wp.array
    """(N, P) float32: columns ``first`` .. ``first + len(azimuth) - 1`` hold each sector's nearest return
    over ``max_range``, in [0, 1] (1: nothing within range), as ``kernels.lidar.sector_minimum`` writes them."""
    first: int
    """Column of sector 0 in ``values``."""
    azimuth: tuple[float, ...]
    """(S,) each sector's centre [rad]: azimuth in the boat's frame, counter-clockwise from the bow."""
    max_range: float
    """The lidar's max range [m]."""
    half_width: float
    """Half a sector's angular width [rad] (a return lies within this of its sector's centre)."""
    mount: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """The lidar's origin in the body frame [m]."""

    def __post_init__(self):
        owner = "LidarSectors"
        values = self.values
        if not isinstance(values, wp.array) or values.ndim != 2 or values.dtype != wp.float32:
            raise ValueError(f"{owner}.values must be a 2-D float32 Warp array, got {values!r}")
        azimuth = tuple(float(a) for a in np.asarray(self.azimuth, dtype=np.float64).reshape(-1))
        if not azimuth or not all(math.isfinite(a) for a in azimuth):
            raise ValueError(f"{owner}.azimuth must be one or more finite angles [rad], got {self.azimuth!r}")
        object.__setattr__(self, "azimuth", azimuth)
        object.__setattr__(self, "first", require_int_in_range(owner, "first", self.first, 0,
                                                               values.shape[1] - len(azimuth)))
        object.__setattr__(self, "max_range", require_positive(owner, "max_range", self.max_range, unit=" [m]"))
        object.__setattr__(self, "half_width", require_in_range(owner, "half_width", self.half_width, 0.0, math.pi,
                                                                unit=" [rad]"))
        mount = tuple(float(v) for v in np.asarray(self.mount, dtype=np.float64).reshape(-1))
        if len(mount) != 3 or not all(math.isfinite(v) for v in mount):
            raise ValueError(f"{owner}.mount must be three finite numbers [m], got {self.mount!r}")
        object.__setattr__(self, "mount", mount)

    @classmethod
    def from_lidar(cls, values: wp.array, first: int, lidar, sectors: int) -> "LidarSectors":
        """The sectors of ``lidar`` (a :class:`~ocean_warp.perception.lidar_config.LidarConfig`) pooled into
        ``sectors`` equal runs of consecutive beams (as ``Lidar.downsampled``) and held in ``values`` from
        column ``first``: each sector centred on the mean azimuth of its beams, turned by the mount's yaw
        (the mount's roll and pitch are taken as level), half as wide as its beams span plus one beam's
        spacing."""
        beams = np.asarray(lidar.azimuths(), dtype=np.float64)
        if isinstance(sectors, bool) or not isinstance(sectors, int) or sectors < 1 or beams.size % sectors:
            raise ValueError(f"LidarSectors.from_lidar: sectors must be a whole divisor of the lidar's "
                             f"{beams.size} beams, got {sectors!r}")
        runs = beams.reshape(sectors, -1)
        centres = runs.mean(axis=1) + float(lidar.mount_rpy[2])
        spacing = 2.0 * math.pi / beams.size if lidar.horizontal_fov >= 2.0 * math.pi \
            else (lidar.horizontal_fov / (beams.size - 1) if beams.size > 1 else 0.0)
        half_width = 0.5 * (runs[0, -1] - runs[0, 0] + spacing)
        return cls(values=values, first=first, azimuth=tuple(centres), max_range=lidar.max_range,
                   half_width=half_width, mount=lidar.mount)


@dataclasses.dataclass(frozen=True)
class EnvBoats:
    """Warp views of the boats' truth in an environment's buffers (what :class:`SailingAutopilot` reads)."""

    position: wp.array
    orientation: wp.array
    velocity: wp.array
    wind_velocity: wp.array


def env_boats(env) -> tuple[EnvBoats, LidarSectors | None]:
    """Warp views of the boats' truth in ``env``'s buffers (a :class:`~ocean_warp.envs.protocol.BatchedEnv`), bound
    here, and on a task with a ``lidar`` its sectors, read from the policy's observation (its last
    ``task.lidar_observations`` values); None without one."""
    b = env.buffers
    boats = EnvBoats(position=wp.from_torch(b.position, dtype=wp.vec3),
                     orientation=wp.from_torch(b.orientation, dtype=wp.quat),
                     velocity=wp.from_torch(b.velocity, dtype=vec6),
                     wind_velocity=wp.from_torch(b.wind_velocity, dtype=wp.vec3))
    lidar = None
    task = getattr(env, "task", None)
    if getattr(task, "lidar", None) is not None:
        sectors = task.lidar_observations
        lidar = LidarSectors.from_lidar(wp.from_torch(b.policy_obs, dtype=wp.float32),
                                        env.num_policy_obs - sectors, task.lidar, sectors)
    return boats, lidar


class SailingAutopilot:
    """The autopilot for a batch of boats whose truth ``boats`` holds: an
    :class:`~ocean_warp.eboat.EBoatState` (``simulator.state``) or any object with the Warp arrays
    ``position`` (N,) vec3 [m], ``orientation`` (N,) quat, ``velocity`` (N,) vec6 (Fossen's nu) and
    ``wind_velocity`` (N,) vec3 [m/s], world frame; they are read at each call, nothing is copied.
    Per-boat memory on the device: ``side`` (+1 starboard tack, -1 port, 0 unset), ``integral`` (heading
    integrator [rad s]), ``tacks`` and ``gybes`` (counts since the boat's last reset) and ``course`` (the
    course steered at the last decision [rad]).

    With ``lidar`` (:class:`LidarSectors`) and ``config.avoidance``, each decision first steers clear of the
    lidar's returns (velocity obstacles for still obstacles: collision cones), in the horizontal plane, for
    each boat:

    - Returns: sector s's nearest return, at range r_s (its value times the lidar's max range) on the
      sector's centre azimuth, put into the world from the lidar's pose; a sector that sees nothing keeps its
      last return for ``avoidance_memory`` seconds (``returns``).
    - Cones: a return at distance d < R (``avoidance_range``) from the lidar, at world bearing phi, blocks
      the courses within w + min(asin(min(1, c / d)), a) of phi: w half a sector (where in its sector the
      return lies is unknown), c ``avoidance_clearance`` (the gap kept), a ``avoidance_cone``.
    - Course: the intended course, the one the autopilot would steer to its target (line of sight, or
      close-hauled / broad reach on its side, as without avoidance). If no cone holds it, the boat sails to
      its target unchanged. Else it steers to the point ``avoidance_lookahead`` from it on a clear bearing:
      among the cones' edges and the zones' edges (the no-go and dead-run zones), the one whose course (the
      course logic's for a target on that bearing: the bearing itself, or close-hauled / a broad reach on
      the boat's side for one inside a zone) costs least: |course - intended| + ``avoidance_turn_cost``
      |course - heading| [rad], plus 10 if that course heads into a cone, plus 20 if the bow would sweep
      across another cone on the short turn to it (after leaving the cones it heads into now). Boxed in
      (no clear bearing): straight away from the nearest return. ``steering``: the targets steered to;
      ``deflection``: the course steered's angle off the intended one [rad].

    It is a baseline, reactive and local: it turns as little as keeps the course out of the cones, and does
    not plan around a field of obstacles. (A potential field, attraction to the target plus repulsion
    k (R / r - 1) from every return within R, turned the boats hard off course, sometimes astern, and
    capsized more of them.)"""

    def __init__(self, boats, config: AutopilotConfig | None = None, lidar: LidarSectors | None = None):
        self.boats = boats
        self.config = config if config is not None else AutopilotConfig()
        if not isinstance(self.config, AutopilotConfig):
            raise ValueError(f"SailingAutopilot: config must be an AutopilotConfig, got {self.config!r}")
        self.device = boats.position.device
        self.count = boats.position.shape[0]
        self.parameters = self.config.parameters()
        zeros = lambda dtype: wp.zeros(self.count, dtype=dtype, device=self.device)  # noqa: E731
        self.side = zeros(wp.int32)
        """(N,) int32: +1 starboard tack (wind over the starboard side), -1 port, 0 not chosen yet."""
        self.integral = zeros(float)
        """(N,) heading error integrated over decisions [rad s]."""
        self.tacks = zeros(wp.int32)
        """(N,) tacks since the boat's last reset."""
        self.gybes = zeros(wp.int32)
        """(N,) gybes since the boat's last reset."""
        self.turn = zeros(wp.int32)
        """(N,) int32: direction of a turn forced the long way round (+1 to port), 0 none."""
        self.stalled = zeros(float)
        """(N,) time spent trying to turn through the wind [s]."""
        self._everyone = wp.ones(self.count, dtype=wp.int32, device=self.device)
        self.course = zeros(float)
        """(N,) course steered at the last decision [rad, yaw from +x]."""
        if lidar is not None and not isinstance(lidar, LidarSectors):
            raise ValueError(f"SailingAutopilot: lidar must be LidarSectors or None, got {lidar!r}")
        if lidar is not None and lidar.values.shape[0] != self.count:
            raise ValueError(f"SailingAutopilot: lidar.values has {lidar.values.shape[0]} rows for {self.count} boats")
        self.lidar = lidar if self.config.avoidance else None
        """The lidar's sectors the autopilot steers clear of (None: it sails straight to the targets)."""
        if self.lidar is not None:
            sectors = len(self.lidar.azimuth)
            self.avoidance_parameters = self.config.avoidance_parameters(self.lidar)
            self._azimuth = wp.array(np.asarray(self.lidar.azimuth, dtype=np.float32), dtype=float, device=self.device)
            self.returns = wp.array(np.tile(np.array([0.0, 0.0, NO_RETURN_AGE], np.float32), (self.count, sectors, 1)),
                                    dtype=wp.vec3, device=self.device)
            """(N, S) each sector's last return: world x, y [m] and its age [s] (z; huge: none)."""
            self.steering = zeros(wp.vec3)
            """(N,) the steering targets of the last decision, world [m]."""
            self.deflection = zeros(float)
            """(N,) the clear course's angle off the intended one at the last decision [rad] (0: clear)."""

    @classmethod
    def for_env(cls, env, config: AutopilotConfig | None = None) -> SailingAutopilot:
        """The autopilot for every boat of ``env`` (a :class:`~ocean_warp.envs.protocol.BatchedEnv`), reading
        the truth from its buffers (Warp views of them, bound here). On a task with a ``lidar``, the lidar's
        sectors are read from the policy's observation (its last ``task.lidar_sectors`` values), so the
        autopilot steers clear of obstacles as ``config.avoidance`` says."""
        boats, lidar = env_boats(env)
        return cls(boats, config, lidar)

    def act(self, targets: wp.array, actions: wp.array) -> None:
        """One decision: ``targets`` (N,) vec3 world positions [m] to sail to (steering clear of the lidar's
        returns on the way, where there is a lidar); writes ``actions`` (N, 3) in [-1, 1]. Launches only (no
        allocation, no host copy): safe inside a CUDA graph capture."""
        boats = self.boats
        if self.lidar is not None:
            wp.launch(steer_clear, dim=self.count, device=self.device,
                      inputs=[self.parameters, self.avoidance_parameters, self.lidar.values, self.lidar.first,
                              self._azimuth, targets, boats.position, boats.orientation, boats.wind_velocity,
                              self.side],
                      outputs=[self.returns, self.steering, self.deflection])
            targets = self.steering
        wp.launch(sail_to_targets, dim=self.count, device=self.device,
                  inputs=[self.parameters, targets, boats.position, boats.orientation, boats.velocity,
                          boats.wind_velocity],
                  outputs=[self.side, self.integral, self.tacks, self.gybes, self.turn, self.stalled, self.course,
                           actions])

    def reset(self, mask: wp.array | None = None) -> None:
        """Forget the side, integrator, counts (and remembered lidar returns) of boats whose ``mask`` (N,)
        int32 is non-zero (all if None). Launches only."""
        wp.launch(reset_autopilot, dim=self.count, device=self.device,
                  inputs=[self._everyone if mask is None else mask, self.side, self.integral, self.tacks, self.gybes,
                          self.turn, self.stalled])
        if self.lidar is not None:
            wp.launch(forget_returns, dim=self.returns.shape, device=self.device,
                      inputs=[self._everyone if mask is None else mask, self.returns])
