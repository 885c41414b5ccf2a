"""VRX's score of every episode of a :class:`~ocean_warp.envs.vrx.VrxEnv`, kept on the device: the rule of its task
(``ocean_warp.envs.tasks.vrx_scoring``) sampled after every physics step as VRX's plugins sample every update (once
a decision, the station-keeping mean came out 1.6 % low: the boat's approach to its goal was sampled at the end of
each half second), over the episode's own goals or gates (``env.goal_count``), written into ``final_score`` when
the episode ends."""

from __future__ import annotations

import warp as wp

from ..tasks.vrx_scoring import FollowPathScore, StationKeepingScore, WayfindingScore
from .task_config import VrxTask
from .vrx_kernels import vrx_contact, vrx_gate_buoys

__all__ = ["VrxScorer"]


class VrxScorer:
    """The score of ``env``'s task: ``launch_sample`` after every physics step, ``launch_finish`` after each
    decision's rewards (before the same-step reset; it writes the ended episodes' scores and starts their next),
    ``launch_courses`` once new episodes drew their goals, ``launch_reset`` when every episode restarts without a
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

    def launch_sample(self, env) -> None:
        """The rule's running state after a physics step of ``env`` (its pose, the path's gates and contact)."""
        state = env.simulator.state
        if self.kind is VrxTask.STATION_KEEPING:
            self.rule.update(state.position, state.orientation, env.target_world)
        elif self.kind is VrxTask.WAYFINDING:
            self.rule.update(state.position, state.orientation, env.origin, env.route)
        else:
            wp.launch(vrx_contact, dim=env.num_envs, device=env.device, inputs=[state.status], outputs=[self.contact])
            self.rule.update(state.position, env.origin, self.gates, self.contact,
                             env.decision_period / env.steps_per_decision)

    def launch_courses(self, env) -> None:
        """The path's gates from ``env.route`` (after the goals of new episodes were drawn); nothing for the other
        tasks."""
        if self.kind is VrxTask.FOLLOW_PATH:
            wp.launch(vrx_gate_buoys, dim=self.gates.shape, device=env.device,
                      inputs=[env.route, self.half_width], outputs=[self.gates])

    def launch_finish(self, env) -> None:
        """The scores of the episodes that ended in the decision (``env.done``) into ``env.final_score``."""
        self.rule.finish(env.done, env.final_score)

    def launch_reset(self, env) -> None:
        self.rule.reset_masked(self._everyone)
