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
from ocean_warp.validation import require_int_in_range

from .components import EnvComponent
from .decision_hook import DecisionHook, HookChain
from .protocol import EnvBuffers, episode_log

__all__ = ["BatchedVesselEnv"]


class BatchedVesselEnv:
    """The decision loop shared by the environments (see the module's docstring). A subclass sets ``task``,
    ``simulator`` (a :class:`~ocean_warp.vessel.VesselSimulator`), ``num_envs``, ``num_actions``,
    ``num_policy_obs``, ``num_critic_obs``, ``steps_per_decision`` and ``device``, calls
    :meth:`_allocate_decision_arrays`, sets ``origin``, ``route`` and ``propeller_level``, and binds ``buffers``
    with :meth:`_bind_buffers`."""

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

    def _allocate_decision_arrays(self) -> None:
        """The arrays of a decision every env has (N = ``num_envs``): actions, observations, rewards, episode
        ends, the episode's bookkeeping and the last ended episode's results, and ``final_score`` at NaN (a task
        without a competition score leaves it there)."""
        n, device = self.num_envs, self.device
        zeros = lambda shape, dtype=float: wp.zeros(shape, dtype=dtype, device=device)  # noqa: E731
        self.actions = zeros((n, self.num_actions))
        self.policy_obs = zeros((n, self.num_policy_obs))
        self.critic_obs = zeros((n, self.num_critic_obs))
        self.final_policy_obs = zeros((n, self.num_policy_obs))
        self.final_critic_obs = zeros((n, self.num_critic_obs))
        self.reward = zeros(n)
        self.terminated = zeros(n, wp.bool)
        self.time_out = zeros(n, wp.bool)
        self.done = zeros(n, wp.bool)
        self.reset_mask = zeros(n, wp.int32)
        self.episode_length = zeros(n, wp.int32)
        self.episode_return = zeros(n)
        self.episode_count = zeros(n, int)
        self.target_index = zeros(n, int)
        self.target_world = zeros(n, wp.vec3)
        self.final_return = zeros(n)
        self.final_length = zeros(n, wp.int32)
        self.final_success = zeros(n)
        self.final_status = zeros(n, int)
        self.final_waypoints = zeros(n, int)
        self.final_score = wp.full(n, float("nan"), dtype=float, device=device)
        """(N,) the competition score of each environment's last ended episode (NaN: the task has none)."""
        self.final_position = zeros(n, wp.vec3)
        """(N,) the boats' positions after the last decision's physics, before any reset [m]."""
        self.final_orientation = zeros(n, wp.quat)
        self._everyone = wp.ones(n, dtype=wp.int32, device=device)

    def _bind_buffers(self, obstacles) -> EnvBuffers:
        """torch views of the decision's arrays, the course's and the boats' state, bound once (``obstacles``: the
        (N, K, 4) tensor of the obstacle table)."""
        view, state = wp.to_torch, self.simulator.state
        return EnvBuffers(
            actions=view(self.actions), policy_obs=view(self.policy_obs), critic_obs=view(self.critic_obs),
            final_policy_obs=view(self.final_policy_obs), final_critic_obs=view(self.final_critic_obs),
            reward=view(self.reward), terminated=view(self.terminated), time_out=view(self.time_out),
            done=view(self.done), episode_length=view(self.episode_length), episode_return=view(self.episode_return),
            target=view(self.target_world), origin=view(self.origin), route=view(self.route),
            waypoint_index=view(self.target_index), position=view(state.position),
            orientation=view(state.orientation), velocity=view(state.velocity),
            wind_velocity=view(state.wind_velocity), wind_direction=view(state.wind_mean_direction),
            propeller_level=view(self.propeller_level), final_position=view(self.final_position),
            final_orientation=view(self.final_orientation), final_return=view(self.final_return),
            final_length=view(self.final_length), final_success=view(self.final_success),
            final_status=view(self.final_status), final_waypoints=view(self.final_waypoints),
            final_score=view(self.final_score), obstacles=obstacles)

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
            self._after_physics_step()
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

    def reset(self, seed: int | None = None) -> None:
        """Start a new episode in every environment; with ``seed``, restart the whole batch from it: every
        environment's random stream, the simulated time (the waves) and the gusts' and sensors' noise
        (one seed, one sequence of episodes)."""
        with ordered_with_torch(self.device):
            if seed is not None:
                self.seed = require_int_in_range(f"{type(self).__name__}.reset", "seed", seed, 0, 2**31 - 1)
                self._seed.fill_(self.seed)
                self.episode_count.zero_()
                self.simulator.rewind()
                self._restart_component_streams()
            self.terminated.zero_()
            self.time_out.zero_()
            self.done.zero_()
            self._start_episodes(self._everyone)
            self._sense_components()
            self._observe(self.policy_obs, self.critic_obs)
            wp.copy(self.final_policy_obs, self.policy_obs)
            wp.copy(self.final_critic_obs, self.critic_obs)
            wp.copy(self.final_position, self.simulator.state.position)
            wp.copy(self.final_orientation, self.simulator.state.orientation)
            self._after_reset()

    def _after_reset(self) -> None:
        """What a subclass adds at the end of :meth:`reset` (launches only); nothing by default."""

    def _after_physics_step(self) -> None:
        """What a subclass samples after every physics step of a decision, before the hooks' (launches only);
        nothing by default."""

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
