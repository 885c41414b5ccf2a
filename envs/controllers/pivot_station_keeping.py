"""Station keeping for a batch of WAM-Vs with fixed thrusters (no sideways force), in three modes: the baseline of
VRX's station-keeping and wayfinding tasks.

A boat with two fixed stern thrusters is underactuated: it controls surge and yaw, not sway, so a holonomic PID
cannot take back an offset across its heading (``station_keeping``'s known limit). This controller closes the
position first and turns to the goal heading only once on the goal, the usual scheme for underactuated dynamic
positioning (Fossen, "Handbook of Marine Craft Hydrodynamics and Motion Control", 2011, ch. 12: the position is
held by pointing the thrust at it, the heading is what is left free or held where the position allows). With d
the distance to the goal, beta the bearing to it and psi the boat's heading:

- **Transit** (mode 0), far from the goal: line of sight on the goal point (heading reference beta), the surge a
  PI on speed toward min(``transit_speed``, ``approach_gain`` x d) x max(cos(heading error), 0), so the boat
  turns to the goal before it makes way and slows as it nears it. Until d < ``near_radius``.
- **Back and fill** (mode 1), near the goal: the heading reference is beta, or beta + pi (stern first) where
  the goal lies within ``astern_sector`` of dead astern; the surge a P on speed toward +-min(``near_speed``,
  ``approach_gain`` x d) x max(cos(heading error), 0): an offset across the heading turns the boat on the spot
  (differential thrust) until it points at the goal, then it drives (or backs) onto it. Back to transit beyond
  ``far_radius``; on to holding within ``hold_radius``.
- **Holding** (mode 2), on the goal: the goal's heading by a PID, the surge a PID on the offset ahead. Back to
  back and fill beyond ``reposition_radius`` (a push across the heading moves the boat off, it comes back).

Every switch is a hysteresis between two radii. A new goal or episode restarts the integrals and the mode
(transit). Actions by ``thrust_allocation.aft_thrust``: fixed thrusters (A = 2), or azimuth thrusters (A = 4)
held straight aft, as fixed ones.

Measured (``benchmarks/studies/wamv_baselines.py``, 12 seeded 300 s runs on the CPU, 2026-11-28): VRX's score
1.51 m on WamvStationKeeping-v0 (PID: 4.18 m) and 1.16 m on WamvWayfinding-v0 (PID: 9.57 m). Known limit: holding,
the wind pushes the boat across its heading until it repositions, so it keeps about 1 m off the goal in 5 m/s.
"""

from __future__ import annotations

import dataclasses
import math

import torch

from ocean_warp.validation import require_in_range, require_non_negative, require_positive

from .thrust_allocation import ThrusterLayout, aft_thrust, body_error, integrate_clipped, wrap_angle, yaw_of

__all__ = ["PivotStationKeepingConfig", "PivotStationKeepingController", "TRANSIT", "BACK_AND_FILL", "HOLDING"]

TRANSIT, BACK_AND_FILL, HOLDING = 0, 1, 2
"""The modes of :class:`PivotStationKeepingController` (its ``mode`` tensor)."""


@dataclasses.dataclass(frozen=True)
class PivotStationKeepingConfig:
    """Radii, speeds and gains of :class:`PivotStationKeepingController` (tuned on ``ocean_warp.wamv``'s WAM-V with
    VRX's damping; 250 N / 100 N thrusters)."""

    near_radius: float = 6.0
    """Transit ends within this distance of the goal [m]."""
    far_radius: float = 10.0
    """Back and fill returns to transit beyond this distance [m]."""
    hold_radius: float = 0.5
    """Back and fill ends, holding starts, within this distance [m]."""
    reposition_radius: float = 1.5
    """Holding returns to back and fill beyond this distance [m]."""
    astern_sector: float = math.radians(60.0)
    """Back and fill goes stern first where the goal lies within this angle of dead astern [rad]."""
    transit_speed: float = 1.5
    """Surge speed asked for in transit [m/s]."""
    near_speed: float = 0.6
    """Largest speed asked for in back and fill [m/s]."""
    approach_gain: float = 0.4
    """Speed asked for per metre to the goal [1/s]."""
    speed_p: float = 300.0
    """Surge force per m/s of speed error [N s/m]."""
    speed_i: float = 60.0
    """Transit: surge force per m of integrated speed error [N/m]."""
    surge_p: float = 200.0
    """Holding: surge force per metre of offset ahead [N/m]."""
    surge_i: float = 20.0
    """Holding: surge force per metre-second of offset ahead [N/(m s)]."""
    surge_d: float = 250.0
    """Holding: surge force per m/s of surge speed (damping) [N s/m]."""
    heading_p: float = 800.0
    """Yaw moment per radian of heading error [N m/rad]."""
    heading_i: float = 40.0
    """Holding: yaw moment per radian-second of heading error [N m/(rad s)]."""
    heading_d: float = 400.0
    """Yaw moment per rad/s of yaw rate (damping) [N m s/rad]."""
    integral_limit: float = 150.0
    """Each integral term's largest output [N or N m]."""
    thrusters: ThrusterLayout = ThrusterLayout()

    def __post_init__(self):
        owner = "PivotStationKeepingConfig"
        for name in ("near_radius", "far_radius", "hold_radius", "reposition_radius", "transit_speed", "near_speed",
                     "approach_gain", "speed_p", "surge_p", "surge_d", "heading_p", "heading_d"):
            require_positive(owner, name, getattr(self, name))
        for name in ("speed_i", "surge_i", "heading_i", "integral_limit"):
            require_non_negative(owner, name, getattr(self, name))
        require_in_range(owner, "astern_sector", self.astern_sector, 0.0, math.pi / 2, unit=" rad")
        for inner, outer in (("near_radius", "far_radius"), ("hold_radius", "reposition_radius"),
                             ("reposition_radius", "near_radius")):
            if getattr(self, outer) < getattr(self, inner):
                raise ValueError(f"{owner}.{outer} must be >= {inner} ({getattr(self, inner)}), got "
                                 f"{getattr(self, outer)!r}")
        if not isinstance(self.thrusters, ThrusterLayout):
            raise ValueError(f"{owner}.thrusters must be a ThrusterLayout, got {self.thrusters!r}")


def next_mode(mode: torch.Tensor, distance: torch.Tensor, c: PivotStationKeepingConfig) -> torch.Tensor:
    """Each boat's mode after this decision's switches, from its mode before and its distance to the goal [m]."""
    mode = torch.where((mode == TRANSIT) & (distance < c.near_radius), BACK_AND_FILL, mode)
    mode = torch.where((mode == BACK_AND_FILL) & (distance > c.far_radius), TRANSIT, mode)
    mode = torch.where((mode == BACK_AND_FILL) & (distance < c.hold_radius), HOLDING, mode)
    return torch.where((mode == HOLDING) & (distance > c.reposition_radius), BACK_AND_FILL, mode)


class PivotStationKeepingController:
    """Station keeping of every boat of a batch on its goal pose (``buffers.target``: world x, y [m], heading
    [rad]) in transit, back-and-fill and holding modes (the module's docstring gives the law); the evaluation's
    ``Controller``: reads ``env.buffers``, writes ``env.buffers.actions`` (N, A), A = 2 or 4. ``mode`` holds each
    boat's mode after the last :meth:`act`."""

    name = "pivot-station-keeping"

    def __init__(self, config: PivotStationKeepingConfig = PivotStationKeepingConfig()):
        if not isinstance(config, PivotStationKeepingConfig):
            raise ValueError(f"PivotStationKeepingController: config must be a PivotStationKeepingConfig, got "
                             f"{config!r}")
        self.config = config
        self.mode: torch.Tensor | None = None
        self._state: dict[str, torch.Tensor] = {}

    def reset(self, env) -> None:
        if env.num_actions not in (2, 4):
            raise ValueError(f"PivotStationKeepingController: the task's actions must be 2 (fixed thrusters) or 4 "
                             f"(azimuth thrusters), got {env.num_actions}")
        zeros = torch.zeros(env.num_envs, device=env.torch_device)
        self.mode = torch.full((env.num_envs,), TRANSIT, dtype=torch.int64, device=env.torch_device)
        self._state = {"goal": env.buffers.target[:, :3].clone(), "speed": zeros.clone(), "surge": zeros.clone(),
                       "heading": zeros.clone()}

    def act(self, env) -> None:
        c, s, b = self.config, self._state, env.buffers
        dt = float(env.decision_period)
        goal = b.target[:, :3]
        restart = (goal != s["goal"]).any(dim=1) | b.done
        s["goal"].copy_(goal)
        for key in ("speed", "surge", "heading"):
            s[key].masked_fill_(restart, 0.0)
        self.mode.masked_fill_(restart, TRANSIT)

        yaw = yaw_of(b.orientation)
        dx, dy = goal[:, 0] - b.position[:, 0], goal[:, 1] - b.position[:, 1]
        distance = torch.hypot(dx, dy)
        ahead, _ = body_error(dx, dy, yaw)
        u, r = b.velocity[:, 0], b.velocity[:, 5]
        self.mode = next_mode(self.mode, distance, c)
        transit, holding = self.mode == TRANSIT, self.mode == HOLDING

        bearing = torch.atan2(dy, dx)
        astern = ~transit & (wrap_angle(bearing - yaw).abs() > math.pi - c.astern_sector)
        reference = torch.where(holding, goal[:, 2], torch.where(astern, bearing + math.pi, bearing))
        heading_error = wrap_angle(reference - yaw)

        # transit and back and fill: a speed toward the goal, made only once pointing at it
        top = torch.where(transit, c.transit_speed, c.near_speed)
        speed_ref = torch.minimum(c.approach_gain * distance, top) * torch.cos(heading_error).clamp(min=0.0)
        speed_ref = torch.where(astern, -speed_ref, speed_ref)
        speed_error = speed_ref - u
        speed_integral = integrate_clipped(s["speed"], speed_error, c.speed_i, c.integral_limit, dt)
        s["speed"] = torch.where(transit, speed_integral, 0.0)
        approach_surge = c.speed_p * speed_error + c.speed_i * s["speed"]

        # holding: PID on the offset ahead and on the goal's heading
        s["surge"] = torch.where(holding, integrate_clipped(s["surge"], ahead, c.surge_i, c.integral_limit, dt), 0.0)
        hold_surge = c.surge_p * ahead + c.surge_i * s["surge"] - c.surge_d * u
        surge = torch.where(holding, hold_surge, approach_surge)
        heading_integral = integrate_clipped(s["heading"], heading_error, c.heading_i, c.integral_limit, dt)
        s["heading"] = torch.where(holding, heading_integral, 0.0)
        moment = c.heading_p * heading_error + c.heading_i * s["heading"] - c.heading_d * r

        actions = aft_thrust(surge, moment, env.num_actions, c.thrusters)
        b.actions[:, : actions.shape[1]].copy_(actions)
