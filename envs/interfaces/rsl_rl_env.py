"""The rsl-rl face of the batched sailing simulator: :class:`RslRlVecEnv` (``rsl_rl.env.VecEnv``).

A thin adapter over one :class:`~ocean_warp.envs.protocol.BatchedEnv` (a SailingEnv, a ShardedSailingEnv); it never
loops over environments.
Rewards, dones, time-outs and the episode counter are the env's Warp-backed torch views, handed out
as they are (zero copy). Observations are the one exception, and deliberately so: rsl-rl's PPO keeps
the observation TensorDict it acted on (``PPO.act``) and copies it into its rollout storage only in
``process_env_step``, *after* ``env.step`` has run. Handing out the Warp-backed views themselves
would make the storage record the next observation instead of the one acted on. So each call
copies the views (bound once, see :attr:`RslRlVecEnv.observation_views`) into one of two
preallocated TensorDicts, alternately: an observation returned by one call stays valid until the
call after next. The copy is (N, P + C) float32 per decision, no allocation, no host sync.
"""

from __future__ import annotations

import torch
from rsl_rl.env import VecEnv
from tensordict import TensorDict

from ..env_factory import make_env
from ..protocol import BatchedEnv

__all__ = ["RslRlVecEnv"]


class RslRlVecEnv(VecEnv):
    """A :class:`~ocean_warp.envs.protocol.BatchedEnv` presented to rsl-rl (``OnPolicyRunner``).

    Observation groups: ``"policy"`` (what the boat's sensors give, shape (N, P)) and ``"critic"``
    (privileged truth, shape (N, C)); map them in the runner config with
    ``"obs_groups": {"actor": ["policy"], "critic": ["critic"]}``.

    ``step`` returns post-reset observations for envs that ended in that step (the SailingEnv resets
    them in the same step), ``dones`` (N,) bool (= terminated or timed out), and
    ``extras = {"time_outs": (N,) bool, "log": {"/episode/...": tensor}}``; rsl-rl bootstraps the value
    of timed-out envs and averages the log tensors. The runner never calls :meth:`reset`.

    Args:
        env: the batched environment to present (a :class:`~ocean_warp.envs.protocol.BatchedEnv`: a
            SailingEnv or a ShardedSailingEnv); the adapter holds it, it does not copy it.
    """

    def __init__(self, env: BatchedEnv) -> None:
        if not isinstance(env, BatchedEnv):
            raise ValueError(f"RslRlVecEnv: env must be a BatchedEnv (SailingEnv, ShardedSailingEnv), got {env!r}")
        self.env = env
        self.num_envs = env.num_envs
        self.num_actions = env.num_actions
        self.max_episode_length = int(env.max_episode_length)
        self.device = torch.device(env.torch_device)
        self.cfg = env.task
        buffers = env.buffers
        # Bound once, outside any torch.inference_mode(): views of the Warp memory itself.
        self._views = TensorDict(
            {"policy": buffers.policy_obs, "critic": buffers.critic_obs},
            batch_size=[self.num_envs],
            device=self.device,
        )
        # Two preallocated copies, written alternately (see the module docstring).
        self._snapshots = (self._views.clone(), self._views.clone())
        self._slot = 0

    @classmethod
    def from_task(cls, task: object, num_envs: int, device: str = "cpu", seed: int = 0) -> RslRlVecEnv:
        """Build the SailingEnv for ``task`` (a task config) and wrap it.

        Args:
            task: a task config from ``ocean_warp.envs.tasks`` (e.g. ``WaypointConfig()``).
            num_envs: number of boats simulated in parallel.
            device: Warp device ("cpu", "cuda:0").
            seed: seed of the per-env random streams.
        """
        return cls(make_env(task, num_envs, device=device, seed=seed))

    @property
    def observation_views(self) -> TensorDict:
        """Zero-copy views of the current observations (groups "policy", "critic"), batch [N].

        Their memory is the simulator's: the next ``step`` overwrites them in place. Use them to
        read the state without a copy; give rsl-rl what :meth:`get_observations` returns.
        """
        return self._views

    @property
    def episode_length_buf(self) -> torch.Tensor:
        """Decisions taken in each env's current episode, (N,) int32; a view of the Warp array."""
        return self.env.buffers.episode_length

    @episode_length_buf.setter
    def episode_length_buf(self, value: torch.Tensor) -> None:
        # rsl-rl assigns a fresh tensor (init_at_random_ep_len): write it into the Warp memory,
        # which the simulator's time-out test reads; never rebind the view.
        self.env.buffers.episode_length.copy_(value)

    def _snapshot(self) -> TensorDict:
        """Copy the observation views into the current slot and return that slot's TensorDict."""
        snapshot = self._snapshots[self._slot]
        snapshot["policy"].copy_(self._views["policy"])
        snapshot["critic"].copy_(self._views["critic"])
        return snapshot

    def get_observations(self) -> TensorDict:
        """The current observations, groups "policy" (N, P) and "critic" (N, C), on :attr:`device`.

        The returned TensorDict is not overwritten by the next :meth:`step` (only by the one after).
        """
        return self._snapshot()

    def step(self, actions: torch.Tensor) -> tuple[TensorDict, torch.Tensor, torch.Tensor, dict]:
        """Run one decision for every env.

        Args:
            actions: (N, 3) in [-1, 1] (clipped by the simulator): propeller (ignored by a task without
                propeller), sheet, rudder.

        Returns:
            observations (post-reset where an env ended), rewards (N,) float32, dones (N,) bool,
            extras with "time_outs" (N,) bool and "log" (dict of "/episode/..." tensors). Rewards,
            dones and time-outs are views of the simulator's memory, valid until the next step.
        """
        self.env.step(actions)
        self._slot ^= 1
        observations = self._snapshot()
        buffers = self.env.buffers
        extras = {"time_outs": buffers.time_out, "log": self.env.episode_log()}
        return observations, buffers.reward, buffers.done, extras

    def reset(self, seed: int | None = None) -> tuple[TensorDict, dict]:
        """Redraw every env (a host call; rsl-rl's runner never needs it).

        Args:
            seed: re-seeds the per-env random streams when given.

        Returns:
            the observations and an empty extras dict.
        """
        self.env.reset(seed=seed)
        return self._snapshot(), {}

    def close(self) -> None:
        """Close the env (a ShardedSailingEnv stops its workers; a SailingEnv's memory goes with the object)."""
        self.env.close()
