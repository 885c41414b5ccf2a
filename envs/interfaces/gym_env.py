"""The gymnasium faces of the batched sailing simulator.

* :class:`SailingVectorEnv` (``gymnasium.vector.VectorEnv``): all boats in one SailingEnv, numpy in
  and out, same-step autoreset (``AutoresetMode.SAME_STEP``): an env that ends in a step is reset in
  that step; its observation is the post-reset one and ``info["final_obs"]`` holds the last one.
* :class:`SailingEnvSingle` (``gymnasium.Env``): one boat, for tools that want the single-env API
  (``gymnasium.make``, ``check_env``). After an episode ends it returns the final observation and
  the caller calls ``reset()``.

Both build their SailingEnv from a task id ("EBoatWaypoint-v0", with or without the "ocean_warp/"
namespace) or a task config, see :func:`ocean_warp.envs.registration.make_task_config`.
Every array handed out is a fresh copy: callers keep what they are given.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import torch
from gymnasium.vector import AutoresetMode
from gymnasium.vector.utils import batch_space

from ..env_factory import make_env
from ..protocol import BatchedEnv
from ..registration import make_task_config

__all__ = ["SailingVectorEnv", "SailingEnvSingle", "action_space", "observation_space", "to_numpy", "as_actions",
           "build_sailing_env"]


def action_space(size: int = 3) -> gym.spaces.Box:
    """One boat's action space: Box(-1, 1, (size,), float32); the E-Boat's 3 = propeller, sheet, rudder (each
    scaled; see
    ``ocean_warp.envs.tasks``). The same for every task: one without propeller ignores the first."""
    return gym.spaces.Box(-1.0, 1.0, shape=(size,), dtype=np.float32)


def observation_space(size: int) -> gym.spaces.Box:
    """One boat's policy observation space: unbounded float32 vector of ``size`` entries."""
    return gym.spaces.Box(-np.inf, np.inf, shape=(size,), dtype=np.float32)


def to_numpy(tensor: torch.Tensor) -> np.ndarray:
    """A numpy copy of ``tensor`` on the host (never a view of the simulator's memory)."""
    return tensor.detach().to("cpu", copy=True).numpy()


def as_actions(actions: Any, num_envs: int, device: torch.device, num_actions: int = 3) -> torch.Tensor:
    """Actions as a (num_envs, num_actions) float32 tensor on ``device``; raises ValueError on a wrong shape."""
    tensor = torch.as_tensor(np.asarray(actions, dtype=np.float32), device=device)
    if tensor.numel() != num_envs * num_actions:
        raise ValueError(f"actions must have shape ({num_envs}, {num_actions}), got {tuple(tensor.shape)}")
    return tensor.reshape(num_envs, num_actions)


def build_sailing_env(task: Any, num_envs: int, device: str, seed: int, max_episode_steps: int | None,
                      overrides: dict[str, Any]):
    """The env (``make_env``) for a task id or config, with ``max_episode_steps`` [decisions] and overrides."""
    config = make_task_config(task, max_episode_steps=max_episode_steps, **overrides)
    return make_env(config, num_envs, device=device, seed=seed)


class SailingVectorEnv(gym.vector.VectorEnv):
    """A fleet of boats behind the ``gymnasium.vector.VectorEnv`` API, natively batched.

    Args:
        task: task id ("EBoatWaypoint-v0", "EBoatWaypointPlus-v0", "EBoatMission-v0",
            "EBoatMissionSail-v0", optionally prefixed "ocean_warp/") or a task config object.
        num_envs: number of boats simulated together.
        device: Warp device ("cpu", "cuda:0"); observations come back as numpy either way.
        seed: seed of the per-env random streams (``reset(seed=...)`` re-seeds them).
        max_episode_steps: episode length limit [decisions]; None keeps the task's.
        **task_overrides: fields of the task config to replace (dataclasses.replace).

    ``step`` returns (obs (N, P) float32, rewards (N,) float32, terminations (N,) bool,
    truncations (N,) bool, infos). Where an env ended, ``infos["final_obs"][i]`` is its last
    observation (None elsewhere; mask ``infos["_final_obs"]``) and ``obs[i]`` is its first
    observation of the next episode.
    """

    def __init__(self, task: Any = "EBoatWaypoint-v0", num_envs: int = 1, device: str = "cpu", seed: int = 0,
                 max_episode_steps: int | None = None, **task_overrides: Any) -> None:
        self._attach(build_sailing_env(task, num_envs, device, seed, max_episode_steps, task_overrides))

    @classmethod
    def from_env(cls, env: BatchedEnv) -> SailingVectorEnv:
        """Present an existing :class:`~ocean_warp.envs.protocol.BatchedEnv` (a SailingEnv, a
        ShardedSailingEnv) as a vector env (not copied); :meth:`close` closes it."""
        if not isinstance(env, BatchedEnv):
            raise ValueError(f"SailingVectorEnv.from_env: env must be a BatchedEnv (SailingEnv, ShardedSailingEnv), "
                             f"got {env!r}")
        vector_env = cls.__new__(cls)
        vector_env._attach(env)
        return vector_env

    def _attach(self, env: BatchedEnv) -> None:
        self.env = env
        self.num_envs = env.num_envs
        self.metadata = {"autoreset_mode": AutoresetMode.SAME_STEP, "render_modes": []}
        self.render_mode = None
        self.single_observation_space = observation_space(env.num_policy_obs)
        self.single_action_space = action_space(env.num_actions)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._device = torch.device(env.torch_device)

    def close_extras(self, **kwargs: Any) -> None:
        """Close the env (a ShardedSailingEnv stops its workers)."""
        self.env.close()

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None
              ) -> tuple[np.ndarray, dict[str, Any]]:
        """Redraw every env; ``seed`` re-seeds the per-env streams. No options are understood.

        Returns:
            observations (N, P) float32 and an empty info dict.
        """
        if options:
            raise ValueError(f"SailingVectorEnv.reset understands no options, got {sorted(options)}; "
                             "envs that end are reset in the same step (AutoresetMode.SAME_STEP)")
        super().reset(seed=seed)
        self.env.reset(seed=seed)
        return to_numpy(self.env.buffers.policy_obs), {}

    def step(self, actions: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """Run one decision for all envs; see the class docstring for what comes back."""
        self.env.step(as_actions(actions, self.num_envs, self._device, self.env.num_actions))
        buffers = self.env.buffers
        observations = to_numpy(buffers.policy_obs)
        rewards = to_numpy(buffers.reward)
        terminations = to_numpy(buffers.terminated)
        truncations = to_numpy(buffers.time_out)
        ended = terminations | truncations
        infos: dict[str, Any] = {}
        if ended.any():
            final = to_numpy(buffers.final_policy_obs)
            final_obs = np.full(self.num_envs, None, dtype=object)
            for index in np.flatnonzero(ended):
                final_obs[index] = final[index]
            infos = {"final_obs": final_obs, "_final_obs": ended,
                     "final_info": {}, "_final_info": ended.copy()}
        return observations, rewards, terminations, truncations, infos


class SailingEnvSingle(gym.Env):
    """One boat behind the ``gymnasium.Env`` API (a SailingEnv of one env).

    Args:
        task: task id or task config, as for :class:`SailingVectorEnv`.
        device: Warp device.
        seed: seed of the random stream until the first ``reset(seed=...)``.
        max_episode_steps: episode length limit [decisions] enforced by the simulator; None keeps the
            task's (``gymnasium.make(..., max_episode_steps=k)`` adds a TimeLimit wrapper instead).
        render_mode: only None (no rendering).
        **task_overrides: fields of the task config to replace.

    ``step`` returns (obs (P,) float32, reward float, terminated bool, truncated bool, {}). When the
    episode ends the observation is the final one (before the simulator's own reset); call
    :meth:`reset` to start the next episode.
    """

    metadata = {"render_modes": []}

    def __init__(self, task: Any = "EBoatWaypoint-v0", device: str = "cpu", seed: int = 0,
                 max_episode_steps: int | None = None, render_mode: str | None = None,
                 **task_overrides: Any) -> None:
        if render_mode is not None:
            raise ValueError(f"render_mode must be None (no rendering), got {render_mode!r}")
        self.render_mode = None
        self.env = build_sailing_env(task, 1, device, seed, max_episode_steps, task_overrides)
        self.observation_space = observation_space(self.env.num_policy_obs)
        self.action_space = action_space(self.env.num_actions)
        self._device = torch.device(self.env.torch_device)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None
              ) -> tuple[np.ndarray, dict[str, Any]]:
        """Start a new episode. ``seed`` seeds ``np_random``; without one, the episode's seed is drawn
        from ``np_random``, so a seeded reset followed by unseeded ones repeats exactly."""
        super().reset(seed=seed)
        episode_seed = seed if seed is not None else int(self.np_random.integers(0, 2**31 - 1))
        self.env.reset(seed=episode_seed)
        return to_numpy(self.env.buffers.policy_obs[0]), {}

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """Run one decision; returns the final observation when the episode ends."""
        self.env.step(as_actions(action, 1, self._device, self.env.num_actions))
        buffers = self.env.buffers
        terminated = bool(buffers.terminated[0])
        truncated = bool(buffers.time_out[0])
        source = buffers.final_policy_obs if terminated or truncated else buffers.policy_obs
        return to_numpy(source[0]), float(buffers.reward[0]), terminated, truncated, {}
