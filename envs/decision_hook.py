"""The hook a recorder or a sensor adds to every decision of a :class:`~ocean_warp.envs.SailingEnv`
(``SailingEnv.attach``, ``SailingEnv.launch_decision``). A module of its own, so that sensors
(``ocean_warp.perception``) can subclass it without importing the environment."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

__all__ = ["DecisionHook", "HookChain"]

if TYPE_CHECKING:
    from .sailing_env import SailingEnv


class DecisionHook:
    """Launches a recorder adds at fixed points of a decision (:meth:`SailingEnv.launch_decision`): after the
    actions kernel, after each physics step and after the last one, before the task's kernels restart the
    environments that ended. They run inside the decision's graph, so they must be device work only (copies
    into arrays allocated once). The defaults launch nothing."""

    def after_actions(self, env: SailingEnv) -> None:
        """After actions became actuator commands (``env.simulator.control``)."""

    def after_physics_step(self, env: SailingEnv, step: int) -> None:
        """After physics step ``step`` (0 ... ``env.steps_per_decision`` - 1) of the decision."""

    def after_physics(self, env: SailingEnv) -> None:
        """After the decision's physics, before rewards, episode ends and resets."""


@dataclasses.dataclass
class HookChain(DecisionHook):
    """Several hooks as one, in order."""

    hooks: list

    def after_actions(self, env: SailingEnv) -> None:
        for hook in self.hooks:
            hook.after_actions(env)

    def after_physics_step(self, env: SailingEnv, step: int) -> None:
        for hook in self.hooks:
            hook.after_physics_step(env, step)

    def after_physics(self, env: SailingEnv) -> None:
        for hook in self.hooks:
            hook.after_physics(env)
