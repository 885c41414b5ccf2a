"""What every batched environment of a vessel does the same way: one decision as one replayed graph (actions to
commands, the physics steps, the task's kernels), hooks inside it, the sea's height, the episode log.

A subclass (:class:`~ocean_warp.envs.sailing_env.SailingEnv`, the E-Boat's sailing tasks;
:class:`~ocean_warp.envs.vrx.vrx_env.VrxEnv`, VRX's tasks on any vessel) builds its simulator, arrays and
``buffers`` and its components (``envs/components.py``: obstacles, sensors, recorders; :meth:`_hold`) and then
calls :meth:`BatchedVesselEnv._start_replay`; it supplies ``launch_actions`` (before the physics) and
``launch_task`` (after it), which call the components' hooks through :meth:`_sense_components`,
:meth:`_append_component_observations` and :meth:`_draw_components`.
"""

from __future__ import annotations

import torch
import warp as wp

from ocean_warp.replay import ReplayedLaunches
from ocean_warp.torch_streams import ordered_with_torch

from .components import EnvComponent
from .decision_hook import DecisionHook, HookChain
from .protocol import episode_log

__all__ = ["BatchedVesselEnv"]


class BatchedVesselEnv:
    """The decision loop shared by the environments (see the module's docstring). A subclass sets ``task``,
    ``simulator`` (a :class:`~ocean_warp.vessel.VesselSimulator`), ``num_envs``, ``num_actions``,
    ``steps_per_decision``, ``device``, ``buffers``, ``final_position`` and ``final_orientation``."""

    components: list[EnvComponent] = []
    """What lives inside the decision besides the task, hooks called in this order (:meth:`_hold`)."""

    def _hold(self, components) -> None:
        """Hold ``components`` (:class:`~ocean_warp.envs.components.EnvComponent`) and add their force models to
        the simulator, in order."""
        self.components = list(components)
        for component in self.components:
            if not isinstance(component, EnvComponent):
                raise ValueError(f"{type(self).__name__}: a component must be an EnvComponent, got {component!r}")
            for model in component.force_models:
                self.simulator.simulator.add_model(model)

    def _sense_components(self) -> None:
        for component in self.components:
            component.sense()

    def _append_component_observations(self, policy: wp.array, critic: wp.array) -> None:
        for component in self.components:
            component.append_observation(policy, critic)

    def _draw_components(self, mask: wp.array, course) -> None:
        for component in self.components:
            component.draw(self._seed, self.first_env, mask, course)

    def _restart_component_streams(self) -> None:
        for component in self.components:
            component.restart_streams()

    def _start_replay(self) -> None:
        """Start with no hooks and the decision's graph to be captured at the first step."""
        self._hooks = HookChain([])
        """The hooks :meth:`attach` added to every step."""
        self._recapture()

    def _recapture(self) -> None:
        self._replayed_decision = ReplayedLaunches(self._launch_decision, self.device,
                                                   capture=self.task.simulator.capture_graph)

    def step(self, actions: torch.Tensor | None = None) -> None:
        """One decision: ``actions`` (N, A) in [-1, 1] (None: the ones already in ``buffers.actions``),
        ``decision_period`` of simulated time, rewards and episode ends, and the same-step reset of the
        environments that ended. Results are in ``buffers``; asynchronous on CUDA, ordered with torch."""
        if actions is not None:
            if tuple(actions.shape) != (self.num_envs, self.num_actions):
                raise ValueError(f"{type(self).__name__}.step: actions must have shape ({self.num_envs}, "
                                 f"{self.num_actions}), got {tuple(actions.shape)}")
            self.buffers.actions.copy_(actions)
        with ordered_with_torch(self.device):
            self._replayed_decision()

    def _launch_decision(self) -> None:
        self.launch_decision()

    def add_force_model(self, model) -> None:
        """Add a force model to the simulator (``Simulator.add_model``: e.g. ``ocean_warp.contact.Contact``); the
        decision's graph is captured anew at the next step."""
        self.simulator.simulator.add_model(model)
        self._recapture()

    def attach(self, hook: DecisionHook) -> None:
        """Run ``hook``'s launches inside every :meth:`step` from now on (a sensor that scans during the
        decision, a recorder); hooks run in the order attached. The decision's graph is captured anew at the
        next step."""
        if not isinstance(hook, DecisionHook):
            raise ValueError(f"{type(self).__name__}.attach: hook must be a DecisionHook, got {hook!r}")
        self._hooks.hooks.append(hook)
        self._recapture()

    def launch_decision(self, hook: DecisionHook | None = None) -> None:
        """The launches of one decision (what :meth:`step` replays): actions to commands, the physics steps
        and the task's kernels, with the attached hooks' launches (:meth:`attach`) and then ``hook``'s at
        their three points (launch only; graph-safe when the hooks' are)."""
        hook = self._hooks if hook is None else HookChain(self._hooks.hooks + [hook])
        state = self.simulator.state
        self.launch_actions()
        if hook is not None:
            hook.after_actions(self)
        for step in range(self.steps_per_decision):
            self.simulator.launch_step()
            if hook is not None:
                hook.after_physics_step(self, step)
        wp.copy(self.final_position, state.position)
        wp.copy(self.final_orientation, state.orientation)
        if hook is not None:
            hook.after_physics(self)
        self.launch_task()

    def launch_actions(self) -> None:
        """The environment layer before the physics (launch only)."""
        raise NotImplementedError

    def launch_task(self) -> None:
        """The environment layer after the physics (launch only)."""
        raise NotImplementedError

    def episode_log(self) -> dict[str, torch.Tensor]:
        """Statistics of the episodes that ended in the last step, see :func:`~ocean_warp.envs.protocol.episode_log`."""
        return episode_log(self.buffers)

    @property
    def significant_wave_height(self) -> float:
        """The sea's significant wave height as the wave grid holds it [m] (``Ocean.significant_wave_height``)."""
        return self.simulator.ocean.significant_wave_height

    def set_significant_wave_height(self, hs: float) -> float:
        """Rescale the sea to significant wave height ``hs`` [m] (``Ocean.set_significant_wave_height``: the
        same spectrum shape, directions and phases); returns the height the grid holds."""
        self.simulator.ocean.set_significant_wave_height(hs)
        return self.significant_wave_height

    def close(self) -> None:
        """Nothing to release (the protocol's ``close``: Warp frees the arrays with the env)."""
