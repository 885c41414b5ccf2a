"""Line-of-sight guidance through gates, clear of buoys, for a batch of WAM-Vs: the baseline of VRX's follow-path
task.

The current gate is ``buffers.target``: its centre's world x, y [m] and the heading h it is passed in [rad]; its
axis is the line through its centre along h, square to the line between its buoys. With (along, across) the
boat's offset from the centre along the axis and to port of it:

- **Approach along the axis** (lookahead-based LOS, Fossen, "Handbook of Marine Craft Hydrodynamics and Motion
  Control", 2011, ch. 10): course chi = h - atan(across / ``lookahead``), which meets the axis at up to 90 deg
  and runs along it, so the boat crosses the gate square to its line, at its middle. A boat beside the gate or
  past its line outside it (along > -``lookahead`` and |across| beyond ``gate_margin`` x half the task's
  ``gate_width``) first heads for the point ``lookahead`` before the centre on the axis.
- **Clear of the buoys** (collision cones, the velocity-obstacle idea for a boat that keeps its speed): each buoy
  of ``buffers.obstacles`` within ``detection_range``, grown by ``clearance`` to a circle of radius R, blocks the
  courses within asin(R / D) of its bearing (D its distance; within the circle, pi/2 (1 + (R - D) / R)). Of the
  LOS course and the cones' edges, the boat takes the one clear of every cone nearest the LOS course, each radian
  of turn from its heading counting ``turn_weight`` more (so it keeps to the side it chose); where every one is
  blocked, straight away from the nearest buoy.
- The heading reference is the course less the drift angle atan(v / u) (Fossen's crab-angle compensation: the
  course is over ground), a PD on its error for the yaw moment, a PI on the surge speed toward ``cruise_speed`` x
  max(cos(heading error), 0); the thrust allocated to fixed (A = 2) or azimuth (A = 4, straight aft) thrusters.

Measured (``benchmarks/studies/wamv_baselines.py``, 12 seeded 300 s runs of WamvFollowPath-v0 on the CPU,
2026-11-28): 37.8 points, 9 runs of 12 through every gate, 2 collisions; the LOS guidance along the legs 0.6
points, 12 collisions.
"""

from __future__ import annotations

import dataclasses
import math

import torch

from ocean_warp.validation import require_non_negative, require_positive

from .thrust_allocation import ThrusterLayout, aft_thrust, integrate_clipped, wrap_angle, yaw_of

__all__ = ["GateGuidanceConfig", "GateGuidanceController", "clear_course"]


@dataclasses.dataclass(frozen=True)
class GateGuidanceConfig:
    """Gains and distances of :class:`GateGuidanceController` (tuned on ``ocean_warp.wamv``'s WAM-V)."""

    lookahead: float = 8.0
    """Lookahead distance along the gate's axis [m]."""
    clearance: float = 4.5
    """Gap kept between a buoy's surface and the boat's centre [m]: the WAM-V's contact capsule reaches 3.7 m
    ahead and astern of it, and wind pushes it aside while it turns."""
    detection_range: float = 20.0
    """Buoys farther than this are not avoided [m]."""
    gate_margin: float = 0.7
    """A boat beyond this fraction of the gate's half width off its axis, near or past its line, goes round to
    the axis first."""
    turn_weight: float = 0.5
    """Of the courses clear of every cone, the one nearest the LOS course is taken, each radian of turn from the
    heading counting this much more (the boat keeps the side it turned to)."""
    cruise_speed: float = 1.0
    """Surge speed [m/s]."""
    speed_p: float = 300.0
    """Surge force per m/s of speed error [N s/m]."""
    speed_i: float = 60.0
    """Surge force per m of integrated speed error [N/m]."""
    heading_p: float = 800.0
    """Yaw moment per radian of heading error [N m/rad]."""
    heading_d: float = 400.0
    """Yaw moment per rad/s of yaw rate [N m s/rad]."""
    integral_limit: float = 150.0
    """The speed integral's largest output [N]."""
    drift_speed: float = 0.5
    """The drift angle atan(v / u) is taken with u at least this [m/s] (it means nothing at rest)."""
    drift_limit: float = 0.6
    """Largest drift angle the heading makes up for [rad]."""
    thrusters: ThrusterLayout = ThrusterLayout()

    def __post_init__(self):
        owner = "GateGuidanceConfig"
        for name in ("lookahead", "detection_range", "gate_margin", "cruise_speed", "speed_p", "heading_p",
                     "heading_d", "drift_speed", "drift_limit"):
            require_positive(owner, name, getattr(self, name))
        for name in ("clearance", "speed_i", "integral_limit", "turn_weight"):
            require_non_negative(owner, name, getattr(self, name))
        if not isinstance(self.thrusters, ThrusterLayout):
            raise ValueError(f"{owner}.thrusters must be a ThrusterLayout, got {self.thrusters!r}")


def clear_course(course: torch.Tensor, position: torch.Tensor, buoys: torch.Tensor, clearance: float,
                 detection_range: float, heading: torch.Tensor | None = None, turn_weight: float = 0.0) -> torch.Tensor:
    """``course`` (N,) [rad] moved out of every buoy's collision cone (the module's docstring): of the course and
    the cones' edges, the one outside every cone that minimises |its angle to ``course``| + ``turn_weight`` x |its
    angle to ``heading``| [rad]; where none is outside, straight away from the nearest buoy.

    Args:
        position: (N, 2) the boats' world x, y [m].
        buoys: (N, K, 4) each boat's buoys: world x, y [m], radius [m], kind (0: an empty row, skipped).
        clearance: gap kept from a buoy's surface [m]; detection_range: buoys farther are skipped [m].
        heading: (N,) the boats' headings [rad] (None: ``course``, no cost of turning).
    """
    rel = buoys[:, :, :2] - position[:, None, :]
    distance = torch.linalg.vector_norm(rel, dim=2)
    bearing = torch.atan2(rel[:, :, 1], rel[:, :, 0])
    grown = buoys[:, :, 2] + clearance
    # inside the grown circle the cone widens past 90 deg, to 180 deg at the centre: the course leads away
    half_angle = torch.asin((grown / distance.clamp(min=1e-6)).clamp(max=1.0)) + \
        (0.5 * math.pi) * ((grown - distance) / grown.clamp(min=1e-6)).clamp(min=0.0)
    active = (buoys[:, :, 3] > 0.0) & (distance < detection_range)
    half_angle = torch.where(active, half_angle, 0.0)
    # candidates: the course itself and both edges of every cone, nudged just outside it
    edge = half_angle + 1e-4
    candidates = torch.cat([course[:, None], bearing + edge, bearing - edge], dim=1)
    inside = (wrap_angle(candidates[:, :, None] - bearing[:, None, :]).abs() < half_angle[:, None, :]).any(dim=2)
    heading = course if heading is None else heading
    cost = wrap_angle(candidates - course[:, None]).abs() + turn_weight * wrap_angle(
        candidates - heading[:, None]).abs()
    best = torch.argmin(torch.where(inside, float("inf"), cost), dim=1, keepdim=True)
    chosen = candidates.gather(1, best)[:, 0]
    nearest = torch.argmin(torch.where(active, distance, float("inf")), dim=1, keepdim=True)
    away = bearing.gather(1, nearest)[:, 0] + math.pi
    return wrap_angle(torch.where(inside.all(dim=1), away, chosen))


class GateGuidanceController:
    """LOS guidance of every boat of a batch through its current gate, clear of the buoys (the module's docstring
    gives the law); the evaluation's ``Controller``: reads ``env.buffers`` (``target``, ``obstacles``, the
    boats' state) and the task's ``gate_width`` [m], writes ``env.buffers.actions`` (N, A), A = 2 or 4.
    ``course`` holds each boat's course after the last :meth:`act` [rad]."""

    name = "gate-guidance"

    def __init__(self, config: GateGuidanceConfig = GateGuidanceConfig()):
        if not isinstance(config, GateGuidanceConfig):
            raise ValueError(f"GateGuidanceController: config must be a GateGuidanceConfig, got {config!r}")
        self.config = config
        self.course: torch.Tensor | None = None
        self._speed_integral: torch.Tensor | None = None

    def reset(self, env) -> None:
        if env.num_actions not in (2, 4):
            raise ValueError(f"GateGuidanceController: the task's actions must be 2 (fixed thrusters) or 4 "
                             f"(azimuth thrusters), got {env.num_actions}")
        self._speed_integral = torch.zeros(env.num_envs, device=env.torch_device)
        self.course = torch.zeros(env.num_envs, device=env.torch_device)

    def guidance(self, env) -> torch.Tensor:
        """(N,) each boat's course [rad]: along its gate's axis, then clear of its buoys."""
        c, b = self.config, env.buffers
        gate = b.target[:, :3]
        position = b.position[:, :2]
        cos_h, sin_h = torch.cos(gate[:, 2]), torch.sin(gate[:, 2])
        rel = position - gate[:, :2]
        along = cos_h * rel[:, 0] + sin_h * rel[:, 1]
        across = -sin_h * rel[:, 0] + cos_h * rel[:, 1]
        course = gate[:, 2] - torch.atan(across / c.lookahead)
        stage = gate[:, :2] - c.lookahead * torch.stack([cos_h, sin_h], dim=1) - position
        outside = (along > -c.lookahead) & (across.abs() > c.gate_margin * 0.5 * float(env.task.gate_width))
        course = torch.where(outside, torch.atan2(stage[:, 1], stage[:, 0]), course)
        buoys = b.obstacles
        if buoys.shape[1] == 0:
            return wrap_angle(course)
        world = torch.cat([buoys[:, :, :2] + b.origin[:, None, :2], buoys[:, :, 2:]], dim=2)
        return clear_course(course, position, world, c.clearance, c.detection_range, yaw_of(b.orientation),
                            c.turn_weight)

    def act(self, env) -> None:
        c, b = self.config, env.buffers
        dt = float(env.decision_period)
        self._speed_integral.masked_fill_(b.done, 0.0)
        self.course = self.guidance(env)
        yaw = yaw_of(b.orientation)
        u, v, r = b.velocity[:, 0], b.velocity[:, 1], b.velocity[:, 5]
        # the course is over ground: the heading leads it by the drift angle (wind and waves push the boat aside)
        drift = torch.atan2(v, u.clamp(min=c.drift_speed)).clamp(-c.drift_limit, c.drift_limit)
        heading_error = wrap_angle(self.course - drift - yaw)
        moment = c.heading_p * heading_error - c.heading_d * r
        speed_error = c.cruise_speed * torch.cos(heading_error).clamp(min=0.0) - u
        self._speed_integral = integrate_clipped(self._speed_integral, speed_error, c.speed_i, c.integral_limit, dt)
        surge = c.speed_p * speed_error + c.speed_i * self._speed_integral
        actions = aft_thrust(surge, moment, env.num_actions, c.thrusters)
        b.actions[:, : actions.shape[1]].copy_(actions)
