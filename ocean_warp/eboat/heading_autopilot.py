"""A heading autopilot for a fleet of E-Boats: a PID rudder on the heading error (host side)."""

from __future__ import annotations

import math

import numpy as np
import warp as wp

from ocean_warp.kernels.heading_hold import HeadingGains, hold_heading
from ocean_warp.validation import require_per_item

__all__ = ["HeadingAutopilot"]


class HeadingAutopilot:
    """Steers every boat of an :class:`EBoatSimulator` to its ``target`` heading [rad, yaw from +x];
    call :meth:`steer` before each step (it writes the rudder commands on the device)."""

    def __init__(self, simulator, *, proportional: float = 2.0, integral: float = 0.5, damping: float = 1.0,
                 rudder_limit: float = math.radians(30.0)):
        self.simulator = simulator
        device = simulator.device
        self.target = wp.zeros(simulator.count, dtype=float, device=device)
        """(N,) heading to hold per boat [rad]."""
        self._integral = wp.zeros(simulator.count, dtype=float, device=device)
        self.gains = HeadingGains()
        self.gains.proportional = proportional
        self.gains.integral = integral
        self.gains.damping = damping
        self.gains.rudder_limit = rudder_limit
        self.gains.dt = simulator.config.dt

    def set_target(self, headings) -> None:
        """Headings [rad] for every boat (or one for all); clears the integrators."""
        values = require_per_item("HeadingAutopilot.set_target", "headings", headings, self.simulator.count)
        self.target.assign(values.astype(np.float32))
        self._integral.zero_()

    def steer(self) -> None:
        sim = self.simulator
        wp.launch(hold_heading, dim=sim.count, device=sim.device,
                  inputs=[self.target, self.gains, sim.state.orientation, sim.state.velocity, self._integral],
                  outputs=[sim.control.rudder])
