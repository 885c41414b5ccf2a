"""The WAM-V's thrusters as the classical controllers see them: from a body force and yaw moment to the actions
of two stern thrusters, fixed (A = 2: ``left_thrust``, ``right_thrust``) or azimuthing (A = 4: plus
``left_angle``, ``right_angle``), batched in torch. Body frame FLU (x bow, y port), yaw counter-clockwise."""

from __future__ import annotations

import dataclasses
import math

import torch

from ocean_warp.validation import require_in_range, require_positive

__all__ = ["ThrusterLayout", "yaw_of", "wrap_angle", "body_error", "differential_thrust", "azimuth_thrust",
           "aft_thrust", "integrate_clipped"]


@dataclasses.dataclass(frozen=True)
class ThrusterLayout:
    """Where the two thrusters are and what they give, as the controllers assume (VRX's WAM-V by default)."""

    x: float = -2.373776
    """Thrusters' position along the body x axis [m] (VRX ``wamv_aft_thrusters.xacro``)."""
    half_spacing: float = 1.027135
    """Each thruster's lateral offset: the left one at +y, the right one at -y [m] (ibid.)."""
    forward_thrust: float = 250.0
    """Thrust at action +1 [N] (VRX's classic thruster model, Bingham et al. 2019: 250 N forward)."""
    reverse_thrust: float = 100.0
    """Thrust at action -1 [N] (ibid.: 100 N astern); between, thrust proportional to the action."""
    azimuth_limit: float = math.pi / 2
    """Thrust angle at angle action +1 (to port) [rad]; must match the vessel's."""

    def __post_init__(self):
        require_in_range("ThrusterLayout", "x", self.x, -100.0, 100.0, unit=" m")
        for name in ("half_spacing", "forward_thrust", "reverse_thrust"):
            require_positive("ThrusterLayout", name, getattr(self, name))
        require_in_range("ThrusterLayout", "azimuth_limit", self.azimuth_limit, 1e-3, math.pi, unit=" rad")


def yaw_of(orientation: torch.Tensor) -> torch.Tensor:
    """Yaw [rad] of (N, 4) body -> world quaternions (x, y, z, w)."""
    x, y, z, w = orientation.unbind(-1)
    return torch.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def wrap_angle(angle: torch.Tensor) -> torch.Tensor:
    """``angle`` [rad] wrapped into [-pi, pi)."""
    return torch.remainder(angle + math.pi, 2.0 * math.pi) - math.pi


def body_error(dx: torch.Tensor, dy: torch.Tensor, yaw: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """A world-frame offset (dx, dy) [m] in the body frame of a boat heading ``yaw``: (ahead, to port)."""
    c, s = torch.cos(yaw), torch.sin(yaw)
    return c * dx + s * dy, -s * dx + c * dy


def _action_of_thrust(thrust: torch.Tensor, layout: ThrusterLayout) -> torch.Tensor:
    scaled = torch.where(thrust >= 0.0, thrust / layout.forward_thrust, thrust / layout.reverse_thrust)
    return scaled.clamp(-1.0, 1.0)


def differential_thrust(surge: torch.Tensor, yaw_moment: torch.Tensor, layout: ThrusterLayout) -> torch.Tensor:
    """(N, 2) left and right thrust actions for a surge force [N] and a yaw moment [N m] (+ to port).

    Thrusters along x at y = +-b: X = F_l + F_r, N = b (F_r - F_l), so each thruster gives the common part X / 2
    and -+ the differential part N / (2 b). The moment keeps a reserve: the differential part up to the largest
    one both thrusters can give about zero (min(forward, reverse thrust)) is kept, the common part cut to make
    room for it; beyond, the moment takes what the surge leaves. (Full yaw priority would, with a weaker
    reverse, drive the boat ahead whenever it turns hard.)"""
    f_max, f_min = layout.forward_thrust, -layout.reverse_thrust
    half_diff = yaw_moment / (2.0 * layout.half_spacing)
    reserve = half_diff.abs().clamp(max=min(f_max, -f_min))
    common = (surge / 2.0).clamp(f_min + reserve, f_max - reserve)
    room = torch.minimum(f_max - common, common - f_min)
    half_diff = torch.maximum(torch.minimum(half_diff, room), -room)
    left, right = common - half_diff, common + half_diff
    return torch.stack([_action_of_thrust(left, layout), _action_of_thrust(right, layout)], dim=-1)


def azimuth_thrust(surge: torch.Tensor, sway: torch.Tensor, yaw_moment: torch.Tensor,
                   layout: ThrusterLayout) -> torch.Tensor:
    """(N, 4) actions (left thrust, right thrust, left angle, right angle) giving body force (surge, sway) [N]
    and yaw moment [N m] with the least squared thruster forces: each thruster takes half the sway, and the
    moment the sway leaves (N - x Y) from opposite surge forces. A force pointing aft is given by reverse thrust
    (the angle kept within +-pi/2), angles beyond the layout's limit are clamped."""
    b = layout.half_spacing
    fy = sway / 2.0
    split = (yaw_moment - layout.x * sway) / (2.0 * b)
    angles, thrusts = [], []
    for fx in (surge / 2.0 - split, surge / 2.0 + split):
        thrust = torch.hypot(fx, fy)
        angle = torch.atan2(fy, fx)
        astern = angle.abs() > math.pi / 2
        angle = torch.where(astern, angle - math.pi * torch.sign(angle), angle)
        thrust = torch.where(astern, -thrust, thrust)
        angles.append(angle.clamp(-layout.azimuth_limit, layout.azimuth_limit) / layout.azimuth_limit)
        thrusts.append(_action_of_thrust(thrust, layout))
    return torch.stack(thrusts + angles, dim=-1)


def aft_thrust(surge: torch.Tensor, yaw_moment: torch.Tensor, num_actions: int, layout: ThrusterLayout) -> torch.Tensor:
    """(N, A) actions for a surge force [N] and a yaw moment [N m] with the thrust along the hulls: fixed thrusters
    (A = 2, ``differential_thrust``), or azimuth ones (A = 4) held straight aft (``azimuth_thrust`` without sway)."""
    if num_actions == 4:
        return azimuth_thrust(surge, torch.zeros_like(surge), yaw_moment, layout)
    return differential_thrust(surge, yaw_moment, layout)


def integrate_clipped(integral: torch.Tensor, error: torch.Tensor, gain: float, limit: float,
                      dt: float) -> torch.Tensor:
    """The integral of ``error`` one step of ``dt`` [s] on, clipped so that gain x integral stays within +-limit
    (anti-windup); zero where the gain is zero."""
    bound = limit / gain if gain > 0.0 else 0.0
    return (integral + error * dt).clamp(-bound, bound)
