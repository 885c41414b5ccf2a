"""VRX's score of every episode of a :class:`~ocean_warp.envs.vrx.VrxEnv`, kept on the device: the rule of its task
(``ocean_warp.envs.tasks.vrx_scoring``) sampled once per decision at the boat's pose after the physics, over the
episode's own goals or gates (``env.goal_count``), written into ``final_score`` when the episode ends."""

from __future__ import annotations

import warp as wp

from ..tasks.vrx_scoring import FollowPathScore, StationKeepingScore, WayfindingScore
from .task_config import VrxTask
from .vrx_kernels import vrx_path_inputs

__all__ = ["VrxScorer"]


class VrxScorer:
    """The score of ``env``'s task: ``launch_update`` after each decision's rewards (before the same-step reset; it
    writes the ended episodes' scores and starts their next), ``launch_reset`` when every episode restarts without a
    score (``env.reset``). Launches only (graph-safe)."""

    def __init__(self, env, gate_half_width: float):
        n, device, task = env.num_envs, env.device, env.task
        goals = task.max_goals
        self.kind = task.kind
        self._everyone = wp.ones(n, dtype=wp.bool, device=device)
        if self.kind is VrxTask.STATION_KEEPING:
            self.rule = StationKeepingScore(n, device)
        elif self.kind is VrxTask.WAYFINDING:
            self.rule = WayfindingScore(n, goals, device, count=env.goal_count)
        else:
            self.rule = FollowPathScore(n, goals, device, count=env.goal_count)
            self.gates = wp.zeros((n, goals), dtype=wp.vec4, device=device)
            """(N, G) each gate's red and green buoy x, y from the environment's origin [m]."""
            self.contact = wp.zeros(n, dtype=wp.bool, device=device)
            self.half_width = float(gate_half_width)

    def launch_update(self, env) -> None:
        state = env.simulator.state
        if self.kind is VrxTask.STATION_KEEPING:
            self.rule.update(state.position, state.orientation, env.target_world)
        elif self.kind is VrxTask.WAYFINDING:
            self.rule.update(state.position, state.orientation, env.origin, env.route)
        else:
            wp.launch(vrx_path_inputs, dim=self.gates.shape, device=env.device,
                      inputs=[env.route, self.half_width, state.status], outputs=[self.gates, self.contact])
            self.rule.update(state.position, env.origin, self.gates, self.contact, env.decision_period)
        self.rule.finish(env.done, env.final_score)

    def launch_reset(self, env) -> None:
        self.rule.reset_masked(self._everyone)
