"""Line following for a batch of sailing boats: the controller of Jaulin and Le Bars, the default baseline.

L. Jaulin and F. Le Bars, "A simple controller for line following of sailboats", 5th International
Robotic Sailing Conference, Cardiff, 2012 (the law the VAIMOS robot sailed across the Bay of Biscay).
Each boat follows the line from its last waypoint a to its next one b; at each decision, with m its
position, theta its heading and psi the direction the true wind blows toward:

- e = det((b - a) / |b - a|, m - a), its signed distance to the line (positive to the left), and
  phi = atan2(b - a), the line's direction;
- the nominal heading theta* = phi - (2 gamma / pi) atan(e / r), which meets the line at up to the
  incidence angle gamma (``incidence_angle``) from afar and runs along it as e goes to 0;
- the tack q = sign(e) once |e| > r, kept inside the corridor of half-width r (``corridor_half_width``);
- where theta* lies within zeta (``close_hauled_angle``) of the wind's source, or the line does and the
  boat is inside the corridor, the desired heading is close-hauled on tack q: theta_bar = pi + psi - q zeta
  (the boat beats across the corridor, tacking at its edges); else theta_bar = theta*;
- the rudder (the paper's law, its sign reversed: here a positive rudder turns the boat to port)
  delta_r_max sin(theta_bar - theta) while the error is under 90 deg, else the full delta_r_max toward
  theta_bar; delta_r_max (``rudder_limit``) is held below the rudder's stall;
- the sheet (boom limit) (pi / 2) ((cos(psi - theta_bar) + 1) / 2)^(log(pi / (2 beta)) / log 2): sheeted in
  head to wind, beta (``beam_reach_sheet``) on a beam reach, let out dead downwind. Here it is evaluated at
  the boat's heading theta rather than theta_bar: at the start of the mission (BCDACA, 5 m/s) a boat that
  had rounded up to a beam reach, 55 deg above its desired broad reach, had its boom let out to 80 deg for
  the broad reach, luffed, lay at 0.1 m/s with its rudder hard over, and drifted 1500 s without steerage;
  trimmed for its own heading, it gathered way and bore away in 20 s. While the bow lies inside the no-go
  zone (within zeta of the wind's source: through a tack, or in irons) the sheet is the law's at theta_bar
  again: the law at the heading sheets hard in there, which held a boat in irons for 200 s. Neither gets
  the E-Boat out of irons every time (see "Known limits" below).

Known limits (BCDACA under sail, 5 m/s, Hs 0.3 m, CPU, seed 0, 2 runs: 1 completed in 572 s; the other lay
in irons from its start at rest, 45 deg off the wind, backing and filling at +-0.3 m/s): with little way on,
the rudder cannot bear the E-Boat away from the wind against its weather helm, and neither the sheet at
the close-hauled trim, nor let fly, nor the rudder reversed astern freed it within 100 s in trials.

The paper's rudder sign: its boat turns with theta' = omega and omega' carrying -cos(delta_r) times the
rudder's force, itself proportional to sin(delta_r), so a positive delta_r turns the boat clockwise, and
its law sets delta_r > 0 when theta is counter-clockwise of theta_bar. Here (``kernels.sailing_rig``) a
positive rudder turns the boat counter-clockwise, so the law's rudder is negated:
rudder = delta_r_max sin(theta_bar - theta).

What this controller adds to the law, each for the E-Boat and each documented at its field:

- ``yaw_rate_gain``: rudder against the yaw rate (damping), within +-delta_r_max;
- ``heel_limit``, ``heel_ease``: the sheet eased in proportion to the heel past a limit, never sheeted in
  (the idea of ArduPilot's sailboat mode, which lets the main out as the heel passes its maximum);
- ``tack_timeout``, ``turn_release_angle``: a tack that does not come through in time (the E-Boat can
  stall head to wind) turns the other way round with the full rudder, bearing away through the run (a wear);
- ``approach_corridor``: the corridor narrows near b (r = clamp(this x the distance to go along the line,
  1 m, ``corridor_half_width``)) so that a beating boat crosses the line within the task's reach radius of b;
  a boat past b's abeam follows the line mirrored about b, back to it;
- ``run_angle``: an optional no-go zone downwind, with the same corridor hysteresis (off at pi);
- the rudder reversed when the boat moves astern faster than ``astern_speed``;
- ``assist_level``, ``assist_speed``: the motor on beats, through forced turns and below a speed, on a
  task that allows a motor (``LineFollowingConfig.sail_only`` and ``AutopilotController`` set it to 0 where
  the task has none).

The line: a boat's line starts where it stands at its first decision after a reset and, each time its
target moves on, at the target it had (the waypoint reached): the same line as the task's leg
(``Course.leg_start`` to ``Course.target_world``), tracked here so that any
:class:`~ocean_warp.envs.protocol.BatchedEnv` (and a bare simulator) can be sailed.

Obstacles: where the boats carry a lidar (``for_env`` on a task with a ``lidar``), the legacy autopilot's
collision-cone avoidance (``autopilot_kernels.steer_clear``, law in ``SailingAutopilot``'s docstring) runs
first, with this controller's sailing angles; where it turns the course, the boat follows the line from
itself to the steering target it gives instead of its leg.

It reads the boats' truth (position, orientation, velocity, current true wind), as ``SailingAutopilot``.

Example::

    follower = LineFollower(sim.state)
    follower.reset()
    follower.act(targets, actions)        # targets (N,) vec3 world [m]; actions (N, 3) float
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import warp as wp

from ocean_warp.device_structs import struct_from
from ocean_warp.validation import require_in_range, require_int_in_range

from .autopilot_kernels import NO_RETURN_AGE, forget_returns, steer_clear
from .line_following_kernels import LineFollowingParameters, follow_lines, reset_line_following
from .sailing_autopilot import AutopilotConfig, LidarSectors, env_boats

__all__ = ["LineFollowingConfig", "LineFollower"]

_OWNER = "LineFollowingConfig"
_DEGREE = math.pi / 180.0


@dataclasses.dataclass(frozen=True)
class LineFollowingConfig:
    """Gains and sailing angles of :class:`LineFollower` (radians, SI units). Invalid values raise
    ``ValueError`` naming the field."""

    decision_period: float = 1.0
    """Sim time between calls of ``act`` [s], in (0, 60]: the step of the tack timer."""
    corridor_half_width: float = 15.0
    """r [m], in [1, 1000]: the boat beats within this of the line (the paper's cutoff distance)."""
    approach_corridor: float = 0.5
    """Corridor half-width per metre still to go along the line toward b, in (0, 10]: the corridor narrows
    to clamp(this x distance, 1 m, r) near the target, so a beating boat crosses the line near b."""
    incidence_angle: float = 45.0 * _DEGREE
    """gamma [rad], in (0, 90 deg]: the angle at which the nominal heading meets the line from afar."""
    close_hauled_angle: float = 50.0 * _DEGREE
    """zeta [rad], in (0, 90 deg): the close-hauled heading's angle off the true wind's source, and the
    half-width of the no-go zone the law beats through."""
    run_angle: float = math.pi
    """Deepest true wind angle sailed downwind [rad], in (90, 180] deg: a nominal heading deeper than this
    (or a line deeper than this, inside the corridor) is sailed as a broad reach at this angle on gybe q.
    pi: no such zone (the paper's law: a dead run where the line runs dead downwind)."""
    rudder_limit: float = 25.0 * _DEGREE
    """delta_r_max [rad], in (0, 60 deg]: the largest rudder. The real E-Boat's rudder (a lifting surface,
    ``ocean_warp.lifting_surface``) reaches its largest attached lift at 15.0 deg of attack, but a turning
    boat's rudder meets the flow at less than its angle (at 1 m/s and 0.2 rad/s of yaw, 12 deg less: the
    stock is 1.09 m aft), so 25 deg keeps it near stall through a turn. 15 deg could not bear the E-Boat away
    out of irons in 5 m/s (BCDACA, seed 0, run 0: 400 s in irons, lost); 25 deg completed that run."""
    rudder_gain: float = 2.5
    """k, in (0, 100]: the rudder is delta_r_max clamp(k sin(theta_bar - theta), -1, 1) while the error is
    under 90 deg (the paper's law: k = 1). With k = 1 the E-Boat held a broad reach 10 deg off its desired
    heading against its weather helm (still water, 5 m/s); k > 1 reaches the full rudder at asin(1 / k)."""
    yaw_rate_gain: float = 0.3
    """Rudder per yaw rate [rad / (rad/s)], >= 0: damps the turn (the law alone is proportional)."""
    beam_reach_sheet: float = 50.0 * _DEGREE
    """beta [rad], in (0, 90 deg): the boom limit on a beam reach (the paper's sheet law)."""
    min_sheet: float = 0.0
    """Smallest boom limit [rad], in [0, 90 deg]."""
    max_sheet: float = 90.0 * _DEGREE
    """Largest boom limit [rad], in [min_sheet, 90 deg]."""
    heel_limit: float = 20.0 * _DEGREE
    """Heel [rad], in [0, 90 deg], past which the sheet is eased."""
    heel_ease: float = 2.0
    """Boom limit let out per heel past ``heel_limit`` [rad/rad], >= 0 (never sheeted in)."""
    tack_timeout: float = 15.0
    """How long [s] (>= 0, <= 3600) a turn through the wind may take before the boat turns the other way
    round (a wear)."""
    turn_release_angle: float = 30.0 * _DEGREE
    """A turn forced the other way round ends this close to the desired heading [rad], in (0, 90 deg)."""
    assist_level: int = 0
    """Propeller level 0 ... 5 on beats, through forced turns and below ``assist_speed``; 0: sail only.
    ``AutopilotController`` sets it to ``MOTOR_ASSIST_LEVEL`` on tasks with a propeller."""
    assist_speed: float = 0.5
    """Speed ahead [m/s] (>= 0, <= 100) below which the motor assists."""
    astern_speed: float = 0.2
    """Speed astern [m/s] (>= 0, <= 100) beyond which the rudder is reversed. Not 0: a boat in irons rocks
    between +-0.1 m/s, and reversing at every sign change held its rudder flapping from side to side for
    200 s (BCDACA, 5 m/s)."""
    avoidance: bool = True
    """Steer clear of the lidar's returns where the boats carry a lidar (the legacy autopilot's collision
    cones, with its default ranges); False: follow the lines regardless."""

    def __post_init__(self):
        checks = (
            ("decision_period", 1.0e-6, 60.0, "(", "]"),
            ("corridor_half_width", 1.0, 1000.0, "[", "]"),
            ("approach_corridor", 0.0, 10.0, "(", "]"),
            ("incidence_angle", 0.0, 90.0 * _DEGREE, "(", "]"),
            ("close_hauled_angle", 0.0, 90.0 * _DEGREE, "(", ")"),
            ("run_angle", 90.0 * _DEGREE, math.pi, "(", "]"),
            ("rudder_limit", 0.0, 60.0 * _DEGREE, "(", "]"),
            ("rudder_gain", 0.0, 100.0, "(", "]"),
            ("yaw_rate_gain", 0.0, 100.0, "[", "]"),
            ("beam_reach_sheet", 0.0, 90.0 * _DEGREE, "(", ")"),
            ("min_sheet", 0.0, 90.0 * _DEGREE, "[", "]"),
            ("max_sheet", 0.0, 90.0 * _DEGREE, "[", "]"),
            ("heel_limit", 0.0, 90.0 * _DEGREE, "[", "]"),
            ("heel_ease", 0.0, 100.0, "[", "]"),
            ("tack_timeout", 0.0, 3600.0, "[", "]"),
            ("turn_release_angle", 0.0, 90.0 * _DEGREE, "(", ")"),
            ("assist_speed", 0.0, 100.0, "[", "]"),
            ("astern_speed", 0.0, 100.0, "[", "]"),
        )
        for name, low, high, left, right in checks:
            value = require_in_range(_OWNER, name, getattr(self, name), low, high)
            if (left == "(" and value <= low) or (right == ")" and value >= high):
                raise ValueError(f"{_OWNER}.{name} must be in {left}{low!r}, {high!r}{right}, got {value!r}")
            object.__setattr__(self, name, value)
        if self.max_sheet < self.min_sheet:
            raise ValueError(f"{_OWNER}.max_sheet must be >= min_sheet ({self.min_sheet!r} rad), "
                             f"got {self.max_sheet!r}")
        object.__setattr__(self, "assist_level", require_int_in_range(_OWNER, "assist_level", self.assist_level, 0, 5))
        if not isinstance(self.avoidance, bool):
            raise ValueError(f"{_OWNER}.avoidance must be True or False, got {self.avoidance!r}")

    @classmethod
    def sail_only(cls, **overrides) -> "LineFollowingConfig":
        """The defaults with the motor off (``overrides`` replace fields)."""
        return cls(**{"assist_level": 0, **overrides})

    def parameters(self) -> LineFollowingParameters:
        """The kernel's view of this config."""
        return struct_from(LineFollowingParameters, self)

    def avoidance_config(self) -> AutopilotConfig:
        """The legacy autopilot's config whose course logic the avoidance kernel runs: its defaults (ranges,
        clearance, memory), with this controller's decision period and sailing angles (no-go zone = the
        close-hauled angle; the run angle)."""
        return AutopilotConfig(decision_period=self.decision_period, close_hauled_angle=self.close_hauled_angle,
                               no_go_angle=self.close_hauled_angle, run_angle=self.run_angle)


class LineFollower:
    """Line following (the module's law) for a batch of boats whose truth ``boats`` holds: an
    :class:`~ocean_warp.eboat.EBoatState` or any object with the Warp arrays ``position`` (N,) vec3 [m],
    ``orientation`` (N,) quat, ``velocity`` (N,) vec6 (Fossen's nu) and ``wind_velocity`` (N,) vec3 [m/s],
    world frame; read at each call, nothing copied. With ``lidar`` (:class:`LidarSectors`) and
    ``config.avoidance``, each decision first steers clear of the lidar's returns.

    Per-boat memory on the device: ``tack`` (q: +1, -1; 0 after a reset), ``line_start`` and ``line_end``
    (the line followed, world [m]), ``turn`` and ``stalled`` (a forced turn's direction, the time spent trying
    to tack [s]), ``tacks`` and ``gybes`` (q's flips while close-hauled / on a broad reach since the boat's
    reset); after each decision ``course`` (theta_bar [rad]) and ``cross_track`` (e [m])."""

    def __init__(self, boats, config: LineFollowingConfig | None = None, lidar: LidarSectors | None = None):
        self.boats = boats
        self.config = config if config is not None else LineFollowingConfig()
        if not isinstance(self.config, LineFollowingConfig):
            raise ValueError(f"LineFollower: config must be a LineFollowingConfig, got {self.config!r}")
        if lidar is not None and not isinstance(lidar, LidarSectors):
            raise ValueError(f"LineFollower: lidar must be LidarSectors or None, got {lidar!r}")
        self.device = boats.position.device
        self.count = boats.position.shape[0]
        if lidar is not None and lidar.values.shape[0] != self.count:
            raise ValueError(f"LineFollower: lidar.values has {lidar.values.shape[0]} rows for {self.count} boats")
        self.parameters = self.config.parameters()
        zeros = lambda dtype: wp.zeros(self.count, dtype=dtype, device=self.device)  # noqa: E731
        self.fresh = wp.ones(self.count, dtype=wp.int32, device=self.device)
        self.line_start = zeros(wp.vec3)
        self.line_end = zeros(wp.vec3)
        self.tack = zeros(wp.int32)
        self.side = zeros(wp.int32)
        """(N,) -q: the legacy autopilot's side (+1 starboard tack), which its avoidance kernel reads."""
        self.turn = zeros(wp.int32)
        self.stalled = zeros(float)
        self.tacks = zeros(wp.int32)
        self.gybes = zeros(wp.int32)
        self.course = zeros(float)
        self.cross_track = zeros(float)
        self.steering = zeros(wp.vec3)
        """(N,) the steering targets of the last decision's avoidance, world [m] (unused without a lidar)."""
        self.deflection = zeros(float)
        """(N,) the avoidance's turn of the course [rad]; 0: the boat follows its line."""
        self._everyone = wp.ones(self.count, dtype=wp.int32, device=self.device)
        self.lidar = lidar if self.config.avoidance else None
        if self.lidar is not None:
            legacy = self.config.avoidance_config()
            self._legacy_parameters = legacy.parameters()
            self._avoidance_parameters = legacy.avoidance_parameters(self.lidar)
            self._azimuth = wp.array(np.asarray(self.lidar.azimuth, dtype=np.float32), dtype=float, device=self.device)
            none = np.tile(np.array([0.0, 0.0, NO_RETURN_AGE], np.float32), (self.count, len(self.lidar.azimuth), 1))
            self.returns = wp.array(none, dtype=wp.vec3, device=self.device)
            """(N, S) each sector's last return: world x, y [m] and its age [s]."""

    @classmethod
    def for_env(cls, env, config: LineFollowingConfig | None = None) -> LineFollower:
        """The controller for every boat of ``env`` (a :class:`~ocean_warp.envs.protocol.BatchedEnv`), reading the
        truth from its buffers (Warp views, bound here); on a task with a ``lidar`` its sectors are read from
        the policy's observation, as :meth:`SailingAutopilot.for_env` does."""
        boats, lidar = env_boats(env)
        return cls(boats, config, lidar)

    def act(self, targets: wp.array, actions: wp.array) -> None:
        """One decision: ``targets`` (N,) vec3, each boat's next waypoint b, world [m]; writes ``actions``
        (N, 3) in [-1, 1]. Launches only (no allocation, no host copy): safe inside a CUDA graph capture."""
        boats = self.boats
        if self.lidar is not None:
            wp.launch(steer_clear, dim=self.count, device=self.device,
                      inputs=[self._legacy_parameters, self._avoidance_parameters, self.lidar.values, self.lidar.first,
                              self._azimuth, targets, boats.position, boats.orientation, boats.wind_velocity,
                              self.side],
                      outputs=[self.returns, self.steering, self.deflection])
        wp.launch(follow_lines, dim=self.count, device=self.device,
                  inputs=[self.parameters, targets, self.steering, self.deflection, boats.position, boats.orientation,
                          boats.velocity, boats.wind_velocity],
                  outputs=[self.fresh, self.line_start, self.line_end, self.tack, self.side, self.turn, self.stalled,
                           self.tacks, self.gybes, self.course, self.cross_track, actions])

    def reset(self, mask: wp.array | None = None) -> None:
        """Forget the line, tack, forced turn, counts (and remembered lidar returns) of boats whose ``mask``
        (N,) int32 is non-zero (all if None): their next decision starts a line where they stand. Launches only."""
        mask = self._everyone if mask is None else mask
        wp.launch(reset_line_following, dim=self.count, device=self.device,
                  inputs=[mask, self.fresh, self.tack, self.side, self.turn, self.stalled, self.tacks, self.gybes])
        if self.lidar is not None:
            wp.launch(forget_returns, dim=self.returns.shape, device=self.device, inputs=[mask, self.returns])
