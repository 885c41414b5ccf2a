"""The actuator commands of every decision, kept for a log: a :class:`~ocean_warp.envs.decision_hook.DecisionHook`
that copies, right after the actions became commands, the rudder and sheet commands, the propeller level and
the simulated time of the decision's start into arrays of its own (the simulator's command arrays are cleared
when an environment restarts, so after ``env.step()`` they no longer hold what steered an episode's last
decision)."""

from __future__ import annotations

import numpy as np
import warp as wp

from ocean_warp.envs.decision_hook import DecisionHook

__all__ = ["CommandTap"]


class CommandTap(DecisionHook):
    """Copies of the last decision's commands of a :class:`~ocean_warp.envs.SailingEnv`'s N boats; attach it
    with ``env.attach(tap)``. Device copies only (graph-safe)."""

    def __init__(self, env):
        n, device = env.num_envs, env.device
        control = env.simulator.control
        self.rudder = wp.zeros(n, dtype=control.rudder.dtype, device=device)
        """(N,) rudder commands [rad], positive turns to port."""
        self.sheet = wp.zeros(n, dtype=control.sheet.dtype, device=device)
        """(N,) sheet commands: largest boom angle either side [rad]."""
        self.propeller = wp.zeros(n, dtype=control.propeller.dtype, device=device)
        """(N,) propeller levels, -5 ... 5."""
        self.time = wp.full(1, float("nan"), dtype=wp.float64, device=device)
        """(1,) simulated time at the decision's start [s]; NaN before the first decision seen."""

    def after_actions(self, env) -> None:
        control = env.simulator.control
        for source, target in ((control.rudder, self.rudder), (control.sheet, self.sheet),
                               (control.propeller, self.propeller), (env.simulator.state.time, self.time)):
            wp.copy(target, source)

    def read(self) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
        """On the host: the decision's start time [s] (NaN: none yet), rudder and sheet [rad], levels."""
        return float(self.time.numpy()[0]), self.rudder.numpy(), self.sheet.numpy(), self.propeller.numpy()
