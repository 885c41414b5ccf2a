"""The Stable-Baselines3 face of the batched sailing simulator: :class:`Sb3VecEnv`.

SB3 is an optional extra (``pip install -e ".[sb3]"``); ``import ocean_warp.envs`` works without it
and only importing this module needs it.

One SailingEnv stands for all of SB3's sub-environments: no loop over envs, no subprocesses. The
simulator resets an env in the step it ends; as SB3 expects, that step's observation is the new
episode's first and ``infos[i]["terminal_observation"]`` the old episode's last, with
``infos[i]["TimeLimit.truncated"]`` True when the episode was cut by the time limit (so SB3
bootstraps its value). ``infos[i]["episode"] = {"r": return, "l": length [decisions], "t": wall time
[s]}`` is added as SB3's Monitor would, so ``rollout/ep_rew_mean`` is logged without a wrapper.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import Any

import numpy as np
import torch

try:
    from stable_baselines3.common.vec_env import VecEnv
    from stable_baselines3.common.vec_env.base_vec_env import VecEnvIndices, VecEnvObs, VecEnvStepReturn
except ImportError as error:  # pragma: no cover - depends on the installed extras
    raise ImportError(
        "ocean_warp.envs.interfaces.sb3_env needs Stable-Baselines3, an optional extra: "
        'pip install -e ".[sb3]"  (or: pip install stable-baselines3)'
    ) from error

from ..protocol import BatchedEnv
from .gym_env import as_actions, build_sailing_env, action_space, observation_space, to_numpy

__all__ = ["Sb3VecEnv"]


class Sb3VecEnv(VecEnv):
    """A fleet of boats behind SB3's ``VecEnv`` API.

    Args:
        task: task id ("EBoatWaypoint-v0", ...) or task config, or a BatchedEnv (SailingEnv, ShardedSailingEnv)
            to present as it is.
        num_envs: number of boats (ignored when ``task`` is an env).
        device: Warp device of the simulator; SB3 gets numpy either way.
        seed: seed of the per-env random streams (``seed()`` then ``reset()`` re-seeds them).
        max_episode_steps: episode length limit [decisions]; None keeps the task's.
        **task_overrides: task config fields to replace.

    Attribute access (``get_attr``, ``set_attr``, ``env_method``) goes to the one SailingEnv (or, for
    names it lacks, to this adapter) and is shared by all sub-environments: it answers with one value
    per index asked for, and refuses to set or call for a subset of the envs.
    """

    def __init__(self, task: Any = "EBoatWaypoint-v0", num_envs: int = 1, device: str = "cpu", seed: int = 0,
                 max_episode_steps: int | None = None, **task_overrides: Any) -> None:
        if isinstance(task, BatchedEnv):
            self.env = task
        else:
            self.env = build_sailing_env(task, num_envs, device, seed, max_episode_steps, task_overrides)
        self.render_mode = None  # read by VecEnv.__init__ through get_attr
        super().__init__(self.env.num_envs, observation_space(self.env.num_policy_obs),
                         action_space(self.env.num_actions))
        self._device = torch.device(self.env.torch_device)
        self._actions: torch.Tensor | None = None
        self._start_time = time.time()

    def reset(self) -> VecEnvObs:
        """Redraw every env (re-seeded if ``seed()`` was called since the last reset).

        Returns:
            observations (N, P) float32.
        """
        seed = self._seeds[0]
        self.env.reset(seed=seed)
        self._reset_seeds()
        self._reset_options()
        return to_numpy(self.env.buffers.policy_obs)

    def step_async(self, actions: np.ndarray) -> None:
        """Stage the actions (N, 3) in [-1, 1] for :meth:`step_wait`."""
        self._actions = as_actions(actions, self.num_envs, self._device, self.env.num_actions)

    def step_wait(self) -> VecEnvStepReturn:
        """Run one decision with the staged actions.

        Returns:
            observations (N, P) float32, rewards (N,) float32, dones (N,) bool, one info dict per env.
        """
        if self._actions is None:
            raise RuntimeError("step_wait() without step_async()")
        self.env.step(self._actions)
        self._actions = None
        buffers = self.env.buffers
        observations = to_numpy(buffers.policy_obs)
        rewards = to_numpy(buffers.reward).astype(np.float32, copy=False)
        terminated = to_numpy(buffers.terminated)
        truncated = to_numpy(buffers.time_out)
        dones = terminated | truncated
        infos: list[dict[str, Any]] = [{} for _ in range(self.num_envs)]
        if dones.any():
            final = to_numpy(buffers.final_policy_obs)
            returns, lengths = to_numpy(buffers.final_return), to_numpy(buffers.final_length)
            elapsed = round(time.time() - self._start_time, 6)
            for index in np.flatnonzero(dones):
                infos[index] = {
                    "terminal_observation": final[index],
                    "TimeLimit.truncated": bool(truncated[index] and not terminated[index]),
                    "episode": {"r": float(returns[index]), "l": int(lengths[index]), "t": elapsed},
                }
        return observations, rewards, dones, infos

    def close(self) -> None:
        """Close the env (a ShardedSailingEnv stops its workers; a SailingEnv's memory goes with the object)."""
        self.env.close()

    def _all_indices(self, indices: VecEnvIndices) -> list[int]:
        return list(self._get_indices(indices))

    def _owner(self, name: str) -> object:
        """The object that holds attribute ``name``: the SailingEnv, else this adapter."""
        if hasattr(self.env, name):
            return self.env
        if name in self.__dict__ or hasattr(type(self), name):
            return self
        raise AttributeError(f"neither the SailingEnv nor Sb3VecEnv has an attribute {name!r}")

    def _require_all(self, indices: VecEnvIndices, what: str) -> list[int]:
        selected = self._all_indices(indices)
        if sorted(selected) != list(range(self.num_envs)):
            raise ValueError(f"{what} acts on the one shared simulator: pass indices=None (all envs), "
                             f"got {selected}")
        return selected

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        """The attribute's value, once per index asked for (shared by all envs)."""
        value = getattr(self._owner(attr_name), attr_name)
        return [value for _ in self._all_indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        """Set the attribute on the shared simulator (all envs, or raises ValueError)."""
        self._require_all(indices, "set_attr")
        setattr(self._owner(attr_name), attr_name, value)

    def env_method(self, method_name: str, *method_args: Any, indices: VecEnvIndices = None,
                   **method_kwargs: Any) -> list[Any]:
        """Call the method once on the shared simulator (all envs, or raises ValueError); its result
        is returned once per env."""
        selected = self._require_all(indices, "env_method")
        result = getattr(self._owner(method_name), method_name)(*method_args, **method_kwargs)
        return [result for _ in selected]

    def env_is_wrapped(self, wrapper_class: type, indices: VecEnvIndices = None) -> list[bool]:
        """Always False: the envs are not gymnasium envs and carry no wrappers."""
        return [False for _ in self._all_indices(indices)]

    def seed(self, seed: int | None = None) -> Sequence[int | None]:
        """Seed the per-env streams at the next :meth:`reset` (SB3 semantics; one seed for the batch).

        Returns:
            the seed per env, as SB3 reports it (``seed + index``); the simulator uses ``seed``.
        """
        return super().seed(seed)
