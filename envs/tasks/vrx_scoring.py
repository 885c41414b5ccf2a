"""VRX's scoring rules for station keeping, wayfinding and following the path, as VRX's scoring plugins compute
them (osrf/vrx, ``vrx_gz/src``, the 2023 competition's code), each on the device for a batch of environments
and as a plain numpy function of one whole trajectory (for people and tests).

The pose error (``StationkeepingScoringPlugin.cc``, ``WayfindingScoringPlugin.cc``): for a boat at distance d
[m] from a goal pose, heading error h = |goal yaw - yaw| wrapped into [0, pi] [rad],

    e = d + 0.75^d h,

so the heading counts fully on the goal and fades away from it (at 3 m off with 0.5 rad: 3 + 0.42 x 0.5).
VRX wraps the heading error as pi - | |goal yaw - yaw| - pi |, the same for yaws in [-pi, pi].

- Station keeping (``StationkeepingScoringPlugin::PreUpdate``): the score is the mean of e over the task's
  running time, one sample per update (VRX: per physics step; here too); lower is better.
- Wayfinding (``WayfindingScoringPlugin::PreUpdate``): each waypoint keeps the least e the boat reached to it
  over the run, in any order; the score is the mean of those minima over the waypoints; lower is better.
- Following the path (``NavigationScoringPlugin.cc``, the task "follow_path" on the worlds
  ``vrx_gz/worlds/2023_phase2/phase2_2023_follow_path*.sdf``): a gate is the segment between a red buoy
  (VRX's ``left_marker``) and a green one (``right_marker``); its forward direction is z x (red - green), so
  that crossing forward the red buoy lies to starboard. A boat between the buoys' lines is before or after the
  gate; a gate goes from before to after (crossed: 10 points, ``points_per_gate_crossed``; 1 more,
  ``bonus``, where it is the gate after the last one scored, and 1 more for the last gate, which ends the
  course) or from after to before (crossed backwards: invalid, the consecutive run broken, and the course
  ends if it was the last gate). Only the gates after the last one crossed or invalidated are watched, and
  none but the first until the first is crossed: a gate skipped is lost (out of order does not count), and
  the first gate crossed backwards is not invalidated (it can be crossed forward after). At most one gate
  changes per update. Each collision of the boat with an obstacle costs 3 points (``obstacle_penalty``),
  the score floored at 0 when the penalty is taken; contacts within ``collision_buffer`` (10 s in the
  follow-path worlds, 3 s VRX's default, ``ScoringPlugin::OnContacts``) of the last counted one are not
  counted again. Higher is better.

  Not reproduced: VRX sets a follow-path run that times out to a score of 200 (``SetTimeoutScore(200)`` in
  ``NavigationScoringPlugin::Configure``, applied by ``ScoringPlugin::OnFinished``), which would rank a run
  that times out above one that finishes; here a run keeps its points. VRX counts time since the simulation
  started for the collision buffer (its first 20 s are the task's initial and ready states); here the first
  contact of an episode always counts.

Device use: each host class below owns its (N,)-shaped running arrays; ``update`` launches one kernel (no
allocation: graph-safe) with the env's Warp arrays (``position`` (N,) vec3, ``orientation`` (N,) quat, ...;
torch views through ``wp.from_torch(t, dtype=wp.vec3)``), ``finish(done, final_score)`` writes each ended
episode's score into the env's ``final_score`` and clears its state, and ``reset_masked(mask)`` clears
without writing. The kernels are in ``vrx_scoring_kernels``.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import warp as wp

from ocean_warp.validation import require_non_negative, require_positive

from . import vrx_scoring_kernels as k

__all__ = [
    "HEADING_WEIGHT_BASE",
    "FollowPathRules",
    "pose_error",
    "station_keeping_score",
    "wayfinding_score",
    "follow_path_score",
    "StationKeepingScore",
    "WayfindingScore",
    "FollowPathScore",
]

HEADING_WEIGHT_BASE = 0.75
"""k of VRX's pose error d + k^d |heading error| (``double k = 0.75`` in both plugins)."""


@dataclasses.dataclass(frozen=True)
class FollowPathRules:
    """VRX's navigation scoring figures (``NavigationScoringPlugin.cc`` and the follow-path worlds)."""

    points_per_gate: float = 10.0
    """Points for each gate crossed forward, in order (``points_per_gate_crossed``)."""
    bonus: float = 1.0
    """Points for a gate crossed right after the last one scored, and again for the last gate (``bonus``)."""
    obstacle_penalty: float = 3.0
    """Points taken for each counted collision (``obstacle_penalty``)."""
    collision_buffer: float = 10.0
    """Contacts within this time of the last counted collision are not counted [s] (``collision_buffer``:
    10 in the 2023 follow-path worlds, 3 VRX's default)."""

    def __post_init__(self):
        for name in ("points_per_gate", "bonus", "obstacle_penalty", "collision_buffer"):
            require_non_negative("FollowPathRules", name, getattr(self, name))

    def parameters(self) -> k.FollowPathRulesParameters:
        p = k.FollowPathRulesParameters()
        p.points_per_gate = self.points_per_gate
        p.bonus = self.bonus
        p.obstacle_penalty = self.obstacle_penalty
        p.collision_buffer = self.collision_buffer
        return p


# --- whole trajectories, numpy ---


def pose_error(positions, yaws, goal) -> np.ndarray:
    """VRX's pose error (T,) of the poses ``positions`` (T, >=2) [m], ``yaws`` (T,) [rad] to ``goal`` (x, y,
    yaw)."""
    positions = np.asarray(positions, dtype=np.float64)
    goal = np.asarray(goal, dtype=np.float64)
    d = np.hypot(goal[0] - positions[:, 0], goal[1] - positions[:, 1])
    heading_error = np.abs(np.remainder(goal[2] - np.asarray(yaws, dtype=np.float64) + np.pi, 2 * np.pi) - np.pi)
    return d + HEADING_WEIGHT_BASE**d * heading_error


def station_keeping_score(positions, yaws, goal) -> float:
    """VRX's station-keeping score of one run sampled at even times: the mean pose error [m-ish, lower is
    better] of ``positions`` (T, >=2), ``yaws`` (T,) to ``goal`` (x, y, yaw)."""
    errors = pose_error(positions, yaws, goal)
    if errors.size == 0:
        raise ValueError("station_keeping_score: the trajectory has no sample")
    return float(errors.mean())


def wayfinding_score(positions, yaws, waypoints) -> float:
    """VRX's wayfinding score of one run: the mean over ``waypoints`` (W, 3: x, y, yaw) of the least pose error
    the run reached to each (lower is better)."""
    waypoints = np.asarray(waypoints, dtype=np.float64).reshape(-1, 3)
    if waypoints.shape[0] == 0 or len(positions) == 0:
        raise ValueError("wayfinding_score: needs at least one waypoint and one sample")
    return float(np.mean([pose_error(positions, yaws, w).min() for w in waypoints]))


def _gate_side(x: float, y: float, gate) -> int:
    red, green = np.asarray(gate[:2], dtype=np.float64), np.asarray(gate[2:4], dtype=np.float64)
    width = float(np.linalg.norm(red - green))
    u = (red - green) / width
    forward = np.array([-u[1], u[0]])
    rel = np.array([x, y]) - 0.5 * (red + green)
    if abs(rel @ u) > 0.5 * width:
        return int(k.GATE_OUTSIDE)
    return int(k.GATE_AFTER) if rel @ forward >= 0.0 else int(k.GATE_BEFORE)


def follow_path_score(positions, gates, contacts=None, dt: float = 1.0, rules: FollowPathRules = FollowPathRules()
                      ) -> float:
    """VRX's follow-path points of one run (higher is better): ``positions`` (T, >=2) [m] sampled every ``dt``
    [s], ``gates`` (G, 4) red x, y, green x, y [m] in order, ``contacts`` (T,) bool: the boat touches an
    obstacle at that sample (None: never). See the module's docstring for the rules."""
    positions = np.asarray(positions, dtype=np.float64)
    gates = np.asarray(gates, dtype=np.float64).reshape(-1, 4)
    contacts = np.zeros(len(positions), bool) if contacts is None else np.asarray(contacts, dtype=bool)
    n = gates.shape[0]
    state = [int(k.GATE_OUTSIDE)] * n
    last_crossed, last_scored = -1, None
    since_collision, score = math.inf, 0.0
    for (x, y), touching in zip(positions[:, :2], contacts):
        since_collision += dt
        if touching and since_collision > rules.collision_buffer:
            since_collision = 0.0
            score = max(0.0, score - rules.obstacle_penalty)
        for g in range(last_crossed + 1, n):
            if g != 0 and state[0] != k.GATE_CROSSED:
                break
            side = _gate_side(x, y, gates[g])
            if side == k.GATE_AFTER and state[g] == k.GATE_BEFORE:
                state[g] = int(k.GATE_CROSSED)
                score += rules.points_per_gate
                if g != 0 and last_scored is not None and g == last_scored + 1:
                    score += rules.bonus
                last_crossed = last_scored = g
                if g == n - 1:
                    return score + rules.bonus
                break
            if g != 0 and side == k.GATE_BEFORE and state[g] == k.GATE_AFTER:
                state[g] = int(k.GATE_INVALID)
                last_scored, last_crossed = None, g
                if g == n - 1:
                    return score
                break
            state[g] = side
    return score


# --- batches on the device ---


def _launch_finish(kernel, mask, write: bool, inputs, device):
    wp.launch(kernel, dim=mask.shape[0], inputs=[mask, int(write), *inputs], device=device)


class StationKeepingScore:
    """The running mean pose error of N environments' episodes to each one's goal pose (``buffers.target``)."""

    def __init__(self, num_envs: int, device):
        self.device = wp.get_device(device)
        self.error_sum = wp.zeros(num_envs, dtype=float, device=self.device)
        """(N,) the episode's summed pose errors."""
        self.samples = wp.zeros(num_envs, dtype=wp.int32, device=self.device)
        """(N,) samples in the sum."""
        self._placeholder = wp.zeros(num_envs, dtype=float, device=self.device)

    def update(self, position: wp.array, orientation: wp.array, target: wp.array) -> None:
        """One sample: ``position`` (N,) vec3 world [m], ``orientation`` (N,) quat, ``target`` (N,) vec3 the goal's
        world x, y [m] and yaw [rad]."""
        wp.launch(k.station_keeping_update, dim=self.samples.shape[0],
                  inputs=[position, orientation, target, self.error_sum, self.samples], device=self.device)

    def finish(self, done: wp.array, final_score: wp.array) -> None:
        """Where ``done`` (N,) bool: the episode's mean pose error into ``final_score`` (N,) float32 (NaN with no
        sample), and a new episode."""
        _launch_finish(k.station_keeping_finish, done, True, [self.error_sum, self.samples, final_score],
                       self.device)

    def reset_masked(self, mask: wp.array) -> None:
        """A new episode where ``mask`` (N,) bool, no score written."""
        _launch_finish(k.station_keeping_finish, mask, False, [self.error_sum, self.samples, self._placeholder],
                       self.device)


def _counts(num_envs: int, most: int, count: wp.array | None, device) -> wp.array:
    """``count`` checked to be an (N,) int32 array on ``device``, or a new one holding ``most`` everywhere."""
    if count is None:
        return wp.full(num_envs, most, dtype=wp.int32, device=device)
    if count.dtype != wp.int32 or count.shape != (num_envs,) or count.device != device:
        raise ValueError(f"count must be a ({num_envs},) int32 array on {device}, got {count.dtype.__name__} "
                         f"{count.shape} on {count.device}")
    return count


class WayfindingScore:
    """Each of N environments' least pose error to each waypoint of its route over the episode."""

    def __init__(self, num_envs: int, max_waypoints: int, device, count: wp.array | None = None):
        self.device = wp.get_device(device)
        self.min_error = wp.zeros((num_envs, max_waypoints), dtype=float, device=self.device)
        """(N, R) the least pose error reached to each waypoint (valid once ``samples`` > 0)."""
        self.samples = wp.zeros(num_envs, dtype=wp.int32, device=self.device)
        self.count = _counts(num_envs, max_waypoints, count, self.device)
        """(N,) int32 waypoints of each episode's route that count, 1 to R: ``count`` where given (the caller's
        array, read at every update and finish: an env's own count per episode), else all R."""
        self._placeholder = wp.zeros(num_envs, dtype=float, device=self.device)

    def update(self, position: wp.array, orientation: wp.array, origin: wp.array, route: wp.array) -> None:
        """One sample: ``position`` (N,) vec3 world [m], ``orientation`` (N,) quat, ``origin`` (N,) vec3 [m],
        ``route`` (N, R) vec3: waypoints' x, y from the origin [m] and yaw [rad]."""
        wp.launch(k.wayfinding_update, dim=self.samples.shape[0],
                  inputs=[position, orientation, origin, route, self.count, self.min_error, self.samples],
                  device=self.device)

    def finish(self, done: wp.array, final_score: wp.array) -> None:
        """Where ``done``: the mean of the least errors into ``final_score`` (NaN with no sample), and a new
        episode."""
        _launch_finish(k.wayfinding_finish, done, True, [self.count, self.min_error, self.samples, final_score],
                       self.device)

    def reset_masked(self, mask: wp.array) -> None:
        _launch_finish(k.wayfinding_finish, mask, False,
                       [self.count, self.min_error, self.samples, self._placeholder], self.device)


class FollowPathScore:
    """VRX's follow-path points of N environments' episodes (the module's docstring gives the rules)."""

    def __init__(self, num_envs: int, max_gates: int, device, rules: FollowPathRules = FollowPathRules(),
                 count: wp.array | None = None):
        require_positive("FollowPathScore", "max_gates", max_gates)
        self.device = wp.get_device(device)
        self.rules = rules
        self._rules = rules.parameters()
        n = num_envs
        self.gate_state = wp.zeros((n, max_gates), dtype=wp.int32, device=self.device)
        """(N, G) each gate's ``vrx_scoring_kernels.GATE_*`` state."""
        self.last_crossed = wp.full(n, -1, dtype=wp.int32, device=self.device)
        """(N,) the last gate crossed or invalidated (-1: none)."""
        self.last_scored = wp.full(n, int(k.NO_GATE), dtype=wp.int32, device=self.device)
        self.since_collision = wp.full(n, rules.collision_buffer + 1.0, dtype=float, device=self.device)
        """(N,) time since the last counted collision [s]."""
        self.collisions = wp.zeros(n, dtype=wp.int32, device=self.device)
        """(N,) collisions counted this episode."""
        self.score = wp.zeros(n, dtype=float, device=self.device)
        """(N,) the episode's points so far."""
        self.finished = wp.zeros(n, dtype=wp.int32, device=self.device)
        """(N,) 1 once the last gate was crossed or invalidated (the course is over: VRX ends the task)."""
        self.count = _counts(n, max_gates, count, self.device)
        """(N,) int32 gates of each episode's course, 1 to G: ``count`` where given (as ``WayfindingScore``'s),
        else all G; the last of them ends the course."""
        self._placeholder = wp.zeros(n, dtype=float, device=self.device)

    def _state(self):
        return [self.gate_state, self.last_crossed, self.last_scored, self.since_collision, self.collisions,
                self.score, self.finished]

    def update(self, position: wp.array, origin: wp.array, gates: wp.array, contact: wp.array, dt: float) -> None:
        """One decision of ``dt`` [s]: ``position`` (N,) vec3 world, ``origin`` (N,) vec3, ``gates`` (N, G) vec4
        (red x, y, green x, y from the origin [m]), ``contact`` (N,) bool (touching an obstacle now)."""
        wp.launch(k.follow_path_update, dim=self.score.shape[0],
                  inputs=[self._rules, position, origin, gates, self.count, contact, float(dt), *self._state()],
                  device=self.device)

    def finish(self, done: wp.array, final_score: wp.array) -> None:
        """Where ``done``: the episode's points into ``final_score``, and a new course."""
        _launch_finish(k.follow_path_finish, done, True, [self._rules, *self._state(), final_score], self.device)

    def reset_masked(self, mask: wp.array) -> None:
        _launch_finish(k.follow_path_finish, mask, False, [self._rules, *self._state(), self._placeholder],
                       self.device)
