"""One door to every batched environment: the env a task config sails in, and the sizes of its buffers.

An E-Boat sailing task (a :class:`~ocean_warp.envs.tasks.TaskConfig`) sails in a
:class:`~ocean_warp.envs.sailing_env.SailingEnv`; one of VRX's tasks (a
:class:`~ocean_warp.envs.vrx.VrxTaskConfig`) in a :class:`~ocean_warp.envs.vrx.VrxEnv` on its vessel. Training,
the adapters and the sharded backend build envs here, so a new kind of task needs one line here and none there.
"""

from __future__ import annotations

from typing import NamedTuple

from .sailing_env import SailingEnv
from .tasks.task_configs import TaskConfig
from .tasks.task_kernels import PRIVILEGED_OBS, policy_observation_count
from .vrx import VrxEnv, VrxTaskConfig
from .vrx.vrx_kernels import POLICY_BASE, PRIVILEGED

__all__ = ["EnvSizes", "make_env", "env_sizes", "require_task"]


class EnvSizes(NamedTuple):
    """The sizes of an env's buffers (``ocean_warp.envs.protocol.EnvBuffers``)."""

    num_actions: int
    num_policy_obs: int
    num_critic_obs: int
    route_length: int
    obstacle_slots: int


def require_task(owner: str, task) -> TaskConfig | VrxTaskConfig:
    """``task`` if it is a task config an env sails, else ``ValueError`` naming ``owner``."""
    if not isinstance(task, (TaskConfig, VrxTaskConfig)):
        raise ValueError(f"{owner}: task must be a task config (WaypointConfig, MissionConfig, ..., or a "
                         f"VrxTaskConfig), got {type(task).__name__} {task!r:.80}")
    return task


def make_env(task, num_envs: int, *, device=None, seed: int = 0, first_env: int = 0):
    """The batched env of ``task`` with ``num_envs`` environments (see the module's docstring)."""
    require_task("make_env", task)
    kind = VrxEnv if isinstance(task, VrxTaskConfig) else SailingEnv
    return kind(task, num_envs, device=device, seed=seed, first_env=first_env)


def env_sizes(task) -> EnvSizes:
    """The buffer sizes ``make_env(task, ...)`` will have, without building it."""
    require_task("env_sizes", task)
    if isinstance(task, VrxTaskConfig):
        policy = POLICY_BASE + task.num_actions
        return EnvSizes(task.num_actions, policy, policy + PRIVILEGED, task.max_goals, 0)
    policy = policy_observation_count(task)
    return EnvSizes(SailingEnv.num_actions, policy, policy + PRIVILEGED_OBS, task.route_length, task.obstacle_slots)
