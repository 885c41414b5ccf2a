"""Line-of-sight guidance for a batch of WAM-Vs: the classical baseline of VRX's wayfinding and follow-path
tasks (Fossen, "Handbook of Marine Craft Hydrodynamics and Motion Control", 2011, ch. 10: lookahead-based
steering).

Each boat follows the leg from its previous goal a to its current one b (``buffers.target``): a is the route's
previous waypoint (``buffers.route[waypoint_index - 1]`` from ``buffers.origin``), or where the boat stood when
its episode started for the first leg. With pi_p = atan2(b - a) the leg's direction and
e = -sin(pi_p) (x - x_a) + cos(pi_p) (y - y_a) the cross-track error (positive to port of the leg):

- the heading reference chi = pi_p - atan(e / lookahead), which meets the leg at up to 90 deg from afar and
  runs along it as e goes to 0;
- a PD on the heading error (and the yaw rate) for the yaw moment;
- a PI on the surge speed toward ``cruise_speed`` x max(cos(heading error), 0) (no way made while turning),
  slowing as min(cruise_speed, ``approach_gain`` x the distance) on the route's last leg;
- the thrust allocated to the fixed (A = 2) or azimuth (A = 4, thrust straight aft) thrusters
  (``thrust_allocation``).
"""

from __future__ import annotations

import dataclasses

import torch

from ocean_warp.validation import require_non_negative, require_positive

from .thrust_allocation import ThrusterLayout, aft_thrust, integrate_clipped, wrap_angle, yaw_of

__all__ = ["LosGuidanceConfig", "LosGuidanceController"]


@dataclasses.dataclass(frozen=True)
class LosGuidanceConfig:
    """Gains and limits of :class:`LosGuidanceController` (tuned on a 3-DOF WAM-V model with VRX's damping)."""

    lookahead: float = 5.0
    """Lookahead distance along the leg [m]; about twice the boat's turning radius at cruise speed or more."""
    cruise_speed: float = 1.2
    """Surge speed along the legs [m/s]."""
    approach_gain: float = 0.5
    """Speed per metre to the last waypoint [1/s]."""
    speed_p: float = 300.0
    """Surge force per m/s of speed error [N s/m]."""
    speed_i: float = 60.0
    """Surge force per m of integrated speed error [N/m]."""
    heading_p: float = 500.0
    """Yaw moment per radian of heading error [N m/rad]."""
    heading_d: float = 400.0
    """Yaw moment per rad/s of yaw rate [N m s/rad]."""
    integral_limit: float = 150.0
    """The speed integral's largest output [N]."""
    thrusters: ThrusterLayout = ThrusterLayout()

    def __post_init__(self):
        owner = "LosGuidanceConfig"
        for name in ("lookahead", "cruise_speed", "approach_gain", "speed_p", "heading_p", "heading_d"):
            require_positive(owner, name, getattr(self, name))
        for name in ("speed_i", "integral_limit"):
            require_non_negative(owner, name, getattr(self, name))
        if not isinstance(self.thrusters, ThrusterLayout):
            raise ValueError(f"{owner}.thrusters must be a ThrusterLayout, got {self.thrusters!r}")


class LosGuidanceController:
    """Line-of-sight guidance of every boat of a batch along its route (the module's docstring gives the law);
    the evaluation's ``Controller``: reads ``env.buffers``, writes ``env.buffers.actions`` (N, A), A = 2 or 4."""

    name = "los-guidance"

    def __init__(self, config: LosGuidanceConfig = LosGuidanceConfig()):
        self.config = config
        self._start = None
        self._index = None
        self._speed_integral = None

    def reset(self, env) -> None:
        if env.num_actions not in (2, 4):
            raise ValueError(f"LosGuidanceController: the task's actions must be 2 (fixed thrusters) or 4 "
                             f"(azimuth thrusters), got {env.num_actions}")
        b = env.buffers
        self._start = b.position[:, :2].clone()
        self._index = b.waypoint_index.clone()
        self._speed_integral = torch.zeros(env.num_envs, device=env.torch_device)

    def act(self, env) -> None:
        c, b = self.config, env.buffers
        dt = float(env.decision_period)
        index = b.waypoint_index.long()
        new_episode = b.done | (index < self._index)
        self._start = torch.where(new_episode[:, None], b.position[:, :2], self._start)
        self._speed_integral.masked_fill_(new_episode, 0.0)
        self._index.copy_(b.waypoint_index)

        previous = b.route.gather(1, (index - 1).clamp(min=0)[:, None, None].expand(-1, 1, b.route.shape[2]))[:, 0]
        leg_start = torch.where((index > 0)[:, None], b.origin[:, :2] + previous[:, :2], self._start)
        target = b.target[:, :2]
        leg = target - leg_start
        leg_angle = torch.atan2(leg[:, 1], leg[:, 0])
        rel = b.position[:, :2] - leg_start
        cross_track = -torch.sin(leg_angle) * rel[:, 0] + torch.cos(leg_angle) * rel[:, 1]
        to_target = target - b.position[:, :2]
        distance = torch.linalg.vector_norm(to_target, dim=1)
        # a leg too short to have a direction: straight for the target
        reference = torch.where(torch.linalg.vector_norm(leg, dim=1) > 1e-3,
                                leg_angle - torch.atan(cross_track / c.lookahead),
                                torch.atan2(to_target[:, 1], to_target[:, 0]))

        yaw = yaw_of(b.orientation)
        heading_error = wrap_angle(reference - yaw)
        u, r = b.velocity[:, 0], b.velocity[:, 5]
        moment = c.heading_p * heading_error - c.heading_d * r

        speed = torch.full_like(u, c.cruise_speed)
        last = index >= b.route.shape[1] - 1
        speed = torch.where(last, (c.approach_gain * distance).clamp(max=c.cruise_speed), speed)
        speed_error = speed * torch.cos(heading_error).clamp(min=0.0) - u
        self._speed_integral = integrate_clipped(self._speed_integral, speed_error, c.speed_i, c.integral_limit, dt)
        surge = c.speed_p * speed_error + c.speed_i * self._speed_integral

        actions = aft_thrust(surge, moment, env.num_actions, c.thrusters)
        b.actions[:, : actions.shape[1]].copy_(actions)
