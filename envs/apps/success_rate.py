"""How well a policy does on a task: the first episode of each of N seeded environments, sailed to its end.

    from ocean_warp.envs.apps.success_rate import evaluate_task
    result = evaluate_task(load_policy("policy.pt"), WaypointConfig(), episodes=256, seed=1000)
    result.success_rate, result.mean_return, result.mean_length_s

Counting only each environment's first episode (every environment starts fresh from a seeded reset)
keeps the estimate unbiased: counting "the first N episodes to end" would favour short ones, i.e.
quick successes and quick failures. The mission has its own, richer evaluation
(:mod:`ocean_warp.envs.evaluation`, ``ocean-warp eval``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch

from ..sailing_env import SailingEnv
from ..training.policy_io import Policy
from ..evaluation import observation_mismatch


@dataclass(frozen=True)
class TaskEvaluation:
    """Outcome of ``episodes`` first episodes: per-episode arrays and their means."""

    success: np.ndarray
    """(E,) bool: the episode reached its goal."""
    episode_return: np.ndarray
    """(E,) float: undiscounted sum of rewards."""
    length_s: np.ndarray
    """(E,) float: simulated duration of the episode [s]."""

    @property
    def success_rate(self) -> float:
        return float(self.success.mean())

    @property
    def mean_return(self) -> float:
        return float(self.episode_return.mean())

    @property
    def mean_length_s(self) -> float:
        return float(self.length_s.mean())


def evaluate_task(policy: Policy, task, *, episodes: int = 256, seed: int = 1000, device: str = "cpu") -> TaskEvaluation:
    """Sail ``policy`` (deterministic) in ``episodes`` environments of ``task`` until each has ended once.

    Args:
        policy: an exported policy (:func:`ocean_warp.envs.training.policy_io.load_policy`); its observation must
            be the task's.
        task: a task config (``WaypointConfig()``, ...).
        episodes: number of environments, hence of episodes.
        seed: seed of the environments' starts, winds and sea; use one the policy did not train on.
        device: Warp device of the simulator; the policy is moved there.
    """
    if episodes < 1:
        raise ValueError(f"episodes must be at least 1, got {episodes}")
    env = SailingEnv(task, episodes, device=device, seed=seed)
    problem = observation_mismatch(policy, task.observation, env.num_policy_obs)
    if problem is not None:
        raise ValueError(f"evaluate_task: {problem}")
    policy = policy.to(env.buffers.policy_obs.device)
    b = env.buffers
    ended = torch.zeros(episodes, dtype=torch.bool, device=b.done.device)
    success = torch.zeros(episodes, dtype=torch.bool, device=b.done.device)
    episode_return = torch.zeros(episodes, dtype=torch.float32, device=b.done.device)
    length = torch.zeros(episodes, dtype=torch.float32, device=b.done.device)
    with torch.inference_mode():
        for _ in range(env.max_episode_length):
            env.step(policy(b.policy_obs))
            first_end = b.done.bool() & ~ended
            success |= first_end & (b.final_success > 0.5)
            episode_return = torch.where(first_end, b.final_return, episode_return)
            length = torch.where(first_end, b.final_length.float(), length)
            ended |= first_end
            if bool(ended.all()):
                break
    if not bool(ended.all()):
        raise RuntimeError("some episodes did not end within the task's episode length (time-out not flagged)")
    return TaskEvaluation(success=success.cpu().numpy(), episode_return=episode_return.cpu().numpy(),
                          length_s=length.cpu().numpy() * task.decision_period)
