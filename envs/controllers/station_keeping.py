"""Station keeping by PID for a batch of WAM-Vs: the classical baseline of VRX's station-keeping task.

Each boat holds the goal pose in ``buffers.target`` (world x, y [m], heading [rad]). With d the distance to
the goal, (e_x, e_y) the offset to it in the body frame (ahead, to port), and the heading error
e_psi = wrap(psi_goal - psi):

- **Transit**, until the boat arrives: the surge a PI on speed toward min(``transit_speed``, ``approach_gain``
  x the distance to go), scaled by max(cos(heading error), 0) (no way made while turning away), so that it
  tapers into the hold; the heading reference:
  - azimuth thrusters (A = 4): the bearing to the goal (line of sight); they arrive within ``arrive_radius``;
  - fixed thrusters (A = 2), which cannot push sideways and so must come in along the goal's heading: the
    bearing to the staging point ``staging_distance`` behind the goal on its axis until within
    ``staging_radius`` of it (or at once where the boat is already that far behind and near the axis), then
    a line of sight onto the axis, goal heading - atan(offset from the axis / ``axis_lookahead``), until the
    boat is within ``axis_arrive_radius`` of the goal, ``axis_capture_offset`` of its axis and
    ``axis_capture_angle`` of its heading (a boat that passes the goal without arriving goes round again).
- **Holding**, until the boat is beyond ``release_radius`` (``axis_release_radius``): the goal's heading by a
  PID, the surge by a PID on e_x; azimuth thrusters add a PID on e_y for the sway and share the force and
  moment between the two swivelling thrusters (``thrust_allocation``).

The switch is a hysteresis between the two radii, not a blend: the speed reference tapering to zero at the
goal joins the transit's surge to the hold's. A fixed-thruster boat holds against a steady push along its
heading (the surge integral takes it), not against one across it: no force of its thrusters has a sideways
component, and turning on the spot it drifts with the push.

Measured on the 3-DOF WAM-V of ``tests/envs/controllers/wamv_plant.py`` (64 boats, goals 6 to 12 m away,
any heading, calm): fixed thrusters within 0.56 m and 1.5 deg of the goal from 60 s on, azimuth within 0.02 m
and 1.0 deg; azimuth against a 20 N push from any direction within 0.03 m. Known limit: fixed thrusters coming
in from elsewhere under a 20 N push along the goal's heading settled within 60 s in about 9 runs of 10 (the
others by 100 s), some 0.9 to 1.3 m off the goal's axis: the push carries them sideways while they turn onto
the axis, and holding cannot take a sideways offset back.

The integrals run while holding (the speed's in transit), clipped to ``integral_limit`` of output, and restart
with a new goal or episode.
"""

from __future__ import annotations

import dataclasses

import torch

from ocean_warp.validation import require_non_negative, require_positive

from .thrust_allocation import (ThrusterLayout, azimuth_thrust, body_error, differential_thrust, integrate_clipped,
                                wrap_angle, yaw_of)

__all__ = ["StationKeepingConfig", "StationKeepingController", "WAMV_STATION_KEEPING"]


@dataclasses.dataclass(frozen=True)
class StationKeepingConfig:
    """Gains and limits of :class:`StationKeepingController` (tuned on a 3-DOF WAM-V model: 200 kg in surge,
    650 kg m^2 in yaw with added mass; VRX's linear and quadratic damping; 250 N / 100 N thrusters)."""

    arrive_radius: float = 5.0
    """Azimuth thrusters: transit ends within this distance of the goal [m]."""
    release_radius: float = 10.0
    """Azimuth thrusters: holding ends beyond this distance [m] (hysteresis against switching at the
    boundary)."""
    axis_arrive_radius: float = 1.5
    """Fixed thrusters: transit ends within this distance of the goal [m] (they cannot close a sideways offset
    once holding, so they come in close, along the goal's axis)."""
    axis_release_radius: float = 3.0
    """Fixed thrusters: holding ends beyond this distance [m]."""
    axis_capture_offset: float = 0.5
    """Fixed thrusters: holding starts only this close to the goal's axis [m] (else the boat goes round)."""
    axis_capture_angle: float = 1.0
    """Fixed thrusters: holding starts only this close to the goal's heading [rad]."""
    axis_lookahead: float = 4.0
    """Fixed thrusters: lookahead of the line of sight onto the goal's axis [m]."""
    staging_distance: float = 14.0
    """Fixed thrusters: a boat not behind the goal first heads for the point this far behind it on its axis
    [m]."""
    staging_radius: float = 4.0
    """Fixed thrusters: the staging point is reached within this distance [m]; a boat farther behind the goal
    than the staging point and this close to its axis goes along the axis at once."""
    transit_speed: float = 1.4
    """Surge speed asked for in transit [m/s]."""
    approach_gain: float = 0.6
    """Transit speed per metre to the goal [1/s] (slowing into the holding zone)."""
    speed_p: float = 300.0
    """Surge force per m/s of speed error [N s/m]."""
    speed_i: float = 60.0
    """Surge force per m of integrated speed error [N/m]."""
    surge_p: float = 100.0
    """Holding: surge force per metre of e_x [N/m]."""
    surge_i: float = 12.0
    """Holding: surge force per metre-second of e_x [N/(m s)]."""
    surge_d: float = 250.0
    """Holding: surge force per m/s of surge speed (damping) [N s/m]."""
    sway_p: float = 100.0
    """Holding, azimuth thrusters: sway force per metre of e_y [N/m]."""
    sway_i: float = 12.0
    """Holding, azimuth thrusters: sway force per metre-second of e_y [N/(m s)]."""
    sway_d: float = 300.0
    """Holding, azimuth thrusters: sway force per m/s of sway speed [N s/m]."""
    heading_p: float = 500.0
    """Yaw moment per radian of heading error [N m/rad]."""
    heading_i: float = 40.0
    """Holding: yaw moment per radian-second of heading error [N m/(rad s)]."""
    heading_d: float = 400.0
    """Yaw moment per rad/s of yaw rate (damping) [N m s/rad]."""
    integral_limit: float = 150.0
    """Each integral term's largest output [N or N m]."""
    thrusters: ThrusterLayout = ThrusterLayout()

    def __post_init__(self):
        owner = "StationKeepingConfig"
        for name in ("arrive_radius", "release_radius", "axis_arrive_radius", "axis_release_radius",
                     "axis_capture_offset", "axis_capture_angle", "axis_lookahead", "staging_distance",
                     "staging_radius", "transit_speed", "approach_gain", "speed_p", "surge_p", "surge_d", "sway_p",
                     "sway_d", "heading_p", "heading_d"):
            require_positive(owner, name, getattr(self, name))
        for name in ("speed_i", "surge_i", "sway_i", "heading_i", "integral_limit"):
            require_non_negative(owner, name, getattr(self, name))
        for arrive, release in (("arrive_radius", "release_radius"), ("axis_arrive_radius", "axis_release_radius")):
            if getattr(self, release) < getattr(self, arrive):
                raise ValueError(f"{owner}.{release} must be >= {arrive} ({getattr(self, arrive)}), got "
                                 f"{getattr(self, release)!r}")
        if not isinstance(self.thrusters, ThrusterLayout):
            raise ValueError(f"{owner}.thrusters must be a ThrusterLayout, got {self.thrusters!r}")


class StationKeepingController:
    """PID station keeping of every boat of a batch on its goal pose (the module's docstring gives the law);
    the evaluation's ``Controller``: reads ``env.buffers``, writes ``env.buffers.actions`` (N, A), A = 2
    (fixed thrusters) or 4 (azimuth)."""

    name = "pid-station-keeping"

    def __init__(self, config: StationKeepingConfig = StationKeepingConfig()):
        self.config = config
        self._state: dict[str, torch.Tensor] = {}

    def reset(self, env) -> None:
        if env.num_actions not in (2, 4):
            raise ValueError(f"StationKeepingController: the task's actions must be 2 (fixed thrusters) or 4 "
                             f"(azimuth thrusters), got {env.num_actions}")
        zeros = torch.zeros(env.num_envs, device=env.torch_device)
        no = torch.zeros(env.num_envs, dtype=torch.bool, device=env.torch_device)
        self._state = {"holding": no, "on_axis": no.clone(),
                       "goal": env.buffers.target[:, :3].clone(),
                       **{k: zeros.clone() for k in ("speed", "surge", "sway", "heading")}}

    def act(self, env) -> None:
        c, s, b = self.config, self._state, env.buffers
        dt = float(env.decision_period)
        goal = b.target[:, :3]
        new_goal = (goal != s["goal"]).any(dim=1) | b.done
        s["goal"].copy_(goal)
        for k in ("speed", "surge", "sway", "heading"):
            s[k].masked_fill_(new_goal, 0.0)
        s["holding"].masked_fill_(new_goal, False)
        s["on_axis"].masked_fill_(new_goal, False)

        yaw = yaw_of(b.orientation)
        dx, dy = goal[:, 0] - b.position[:, 0], goal[:, 1] - b.position[:, 1]
        distance = torch.hypot(dx, dy)
        ahead, port = body_error(dx, dy, yaw)
        u, v, r = b.velocity[:, 0], b.velocity[:, 1], b.velocity[:, 5]
        azimuth = env.num_actions == 4
        arrive, release = (c.arrive_radius, c.release_radius) if azimuth else (c.axis_arrive_radius,
                                                                                c.axis_release_radius)
        arriving = distance < arrive
        if not azimuth:
            behind, across = body_error(-dx, -dy, goal[:, 2])
            arriving = arriving & (across.abs() < c.axis_capture_offset) & (
                wrap_angle(goal[:, 2] - yaw).abs() < c.axis_capture_angle)
        holding = (s["holding"] | arriving) & (distance <= release)

        transit_heading = torch.atan2(dy, dx)
        to_go = distance
        if not azimuth:
            # first to the staging point behind the goal on its axis, then along the axis to the goal
            cg, sg = torch.cos(goal[:, 2]), torch.sin(goal[:, 2])
            sx, sy = dx - c.staging_distance * cg, dy - c.staging_distance * sg
            staged = torch.hypot(sx, sy) < c.staging_radius
            well_behind = (behind < -c.staging_distance) & (across.abs() < c.staging_radius)
            on_axis = (s["on_axis"] | staged | well_behind) & (behind < 0.0) & ~holding
            s["on_axis"].copy_(on_axis)
            axis_heading = goal[:, 2] - torch.atan(across / c.axis_lookahead)
            transit_heading = torch.where(on_axis, axis_heading, torch.atan2(sy, sx))
            to_go = torch.where(on_axis, distance, torch.hypot(sx, sy) + c.staging_distance)
        s["holding"].copy_(holding)
        heading_error = wrap_angle(torch.where(holding, goal[:, 2], transit_heading) - yaw)

        # transit: speed PI along the line of sight
        speed_ref = (c.approach_gain * to_go).clamp(max=c.transit_speed)
        speed_ref = speed_ref * torch.cos(heading_error).clamp(min=0.0)
        speed_error = speed_ref - u
        speed_integral = integrate_clipped(s["speed"], speed_error, c.speed_i, c.integral_limit, dt)
        s["speed"] = torch.where(holding, 0.0, speed_integral)
        transit_surge = c.speed_p * speed_error + c.speed_i * s["speed"]

        # holding: PID on the offset ahead (and to port)
        s["surge"] = torch.where(holding, integrate_clipped(s["surge"], ahead, c.surge_i, c.integral_limit, dt), 0.0)
        hold_surge = c.surge_p * ahead + c.surge_i * s["surge"] - c.surge_d * u
        surge = torch.where(holding, hold_surge, transit_surge)

        heading_integral = integrate_clipped(s["heading"], heading_error, c.heading_i, c.integral_limit, dt)
        s["heading"] = torch.where(holding, heading_integral, 0.0)
        moment = c.heading_p * heading_error + c.heading_i * s["heading"] - c.heading_d * r

        if azimuth:
            s["sway"] = torch.where(holding, integrate_clipped(s["sway"], port, c.sway_i, c.integral_limit, dt), 0.0)
            sway = torch.where(holding, c.sway_p * port + c.sway_i * s["sway"] - c.sway_d * v, 0.0)
            actions = azimuth_thrust(surge, sway, moment, c.thrusters)
        else:
            actions = differential_thrust(surge, moment, c.thrusters)
        b.actions[:, : actions.shape[1]].copy_(actions)


WAMV_STATION_KEEPING = StationKeepingConfig(axis_capture_offset=3.0, axis_capture_angle=2.0, axis_arrive_radius=4.0,
                                            axis_release_radius=8.0, staging_distance=8.0, surge_p=200.0,
                                            heading_p=800.0)
"""The gains ``ocean-warp eval`` gives the baseline on ``ocean_warp.wamv``'s WAM-V: a looser capture onto the goal's
axis, a nearer staging point and stiffer surge and heading holds. On 12 seeded 150 s station-keeping runs in 5 m/s
of wind on a 0.3 m sea (CPU, 2026-11-28) its VRX score is 4.25 m against 6.56 m with the defaults, which circle the
goal on this WAM-V (tuned on a 3-DOF model with VRX's newer, heavier damping)."""
