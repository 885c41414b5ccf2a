"""The seed paper's own recipe: Stable-Baselines3 PPO on the seed waypoint task, for comparison.

    python -m benchmarks.studies.sb3_seed_recipe                            # the seed: 1 boat, 512 000 steps, CPU
    python -m benchmarks.studies.sb3_seed_recipe --device cuda:0 --num-envs 16 --out out/sb3_seed_16

PPO exactly as the seed paper trained it (README of the E-Boat twin, "The reinforcement-learning task
of the seed paper"): ``MlpPolicy`` with separate policy and value MLPs [32, 32], ReLU; learning rate
3e-4, n_steps 2048, batch 64, 10 epochs, gamma 0.99, GAE lambda 0.95, clip 0.2, entropy 0.001;
512 000 steps of one boat. The task is ``WaypointConfig()`` (id "EBoatWaypoint-v0") through
``Sb3VecEnv``. With ``--num-envs`` N > 1 each rollout keeps the seed's 2048 steps: n_steps = 2048 // N.
The Warp simulator runs on ``--device``; SB3's torch stays on the CPU (the networks are tiny).

After training, the deterministic policy sails ``--eval-episodes`` episodes of the same task in a fresh
environment seeded ``seed + 1000``; an episode is a success when the boat reached its waypoint. The
script prints a one-line JSON summary and writes it to OUT/summary.json; the model goes to
OUT/model.zip (both atomically).
"""

from __future__ import annotations

import argparse
import collections
import json
import logging
import math
import os
import time
from typing import Any

import numpy as np
import torch
import warp as wp


from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.vec_env import VecEnv, VecEnvWrapper
from tqdm import tqdm

from ocean_warp.atomic_files import atomic_output
from ocean_warp.envs.interfaces.sb3_env import Sb3VecEnv

TASK_ID = "EBoatWaypoint-v0"
"""The seed paper's waypoint task (``WaypointConfig()``)."""
SEED_TOTAL_STEPS = 512_000
SEED_ROLLOUT_STEPS = 2048
"""Steps per PPO rollout, summed over the environments (the seed: n_steps 2048 of one boat)."""
SEED_PPO = dict(learning_rate=3e-4, batch_size=64, n_epochs=10, gamma=0.99, gae_lambda=0.95, clip_range=0.2,
                ent_coef=0.001)
"""The seed's PPO hyperparameters besides n_steps (the rest are SB3's defaults, as in the seed)."""
SEED_POLICY_KWARGS = dict(net_arch=dict(pi=[32, 32], vf=[32, 32]), activation_fn=torch.nn.ReLU)
"""The seed's networks: separate policy and value MLPs of two 32-unit ReLU layers."""
EVAL_SEED_OFFSET = 1000
"""The evaluation environment is seeded ``seed + EVAL_SEED_OFFSET``: episodes training never saw."""
RECENT_EPISODES = 100
"""Episodes the progress bar averages over (SB3's own statistics window)."""


def seed_n_steps(num_envs: int) -> int:
    """n_steps per environment that keeps the seed's rollout of 2048 steps (2048 // num_envs)."""
    if not 1 <= num_envs <= SEED_ROLLOUT_STEPS // 2:
        raise ValueError(f"num_envs must be in [1, {SEED_ROLLOUT_STEPS // 2}] (n_steps = 2048 // num_envs >= 2), "
                         f"got {num_envs}")
    return SEED_ROLLOUT_STEPS // num_envs


def build_model(env: VecEnv, seed: int, n_steps: int | None = None, verbose: int = 0) -> PPO:
    """SB3 PPO with the seed's hyperparameters on ``env``, torch on the CPU.

    Args:
        env: the training environments (e.g. an :class:`Sb3VecEnv`).
        seed: seed of torch, numpy and the environments (SB3 seeds ``env`` at the first reset).
        n_steps: steps per environment per rollout; None: the seed's 2048 // env.num_envs.
        verbose: SB3's verbosity.
    """
    n_steps = seed_n_steps(env.num_envs) if n_steps is None else int(n_steps)
    if n_steps * env.num_envs < 2:
        raise ValueError(f"a rollout needs at least 2 steps, got n_steps {n_steps} x {env.num_envs} envs")
    return PPO("MlpPolicy", env, n_steps=n_steps, policy_kwargs=dict(SEED_POLICY_KWARGS), seed=seed, device="cpu",
               verbose=verbose, **SEED_PPO)


def _sailing_env(vec_env: VecEnv):
    """The SailingEnv under ``vec_env`` (through any SB3 VecEnv wrappers)."""
    while isinstance(vec_env, VecEnvWrapper):
        vec_env = vec_env.venv
    return vec_env.env


def ended_episodes(vec_env: VecEnv, dones: np.ndarray, infos: list[dict[str, Any]]) -> list[tuple[int, float, bool]]:
    """(env index, return, success) of each episode that ended in the last step of ``vec_env``.

    The return is ``info["episode"]["r"]`` (Sb3VecEnv reports it as SB3's Monitor does). Success is
    ``info["is_success"]`` where the adapter gives it, else the SailingEnv's ``final_success`` buffer
    (1 when the boat reached its last waypoint), read before the next step overwrites it.
    """
    indices = np.flatnonzero(dones)
    if indices.size == 0:
        return []
    success = None
    if not all("is_success" in infos[index] for index in indices):
        success = _sailing_env(vec_env).buffers.final_success.detach().cpu().numpy()
    return [(int(index), float(infos[index]["episode"]["r"]),
             bool(infos[index]["is_success"]) if success is None else bool(success[index] > 0.5))
            for index in indices]


class EpisodeProgress(BaseCallback):
    """A tqdm bar over training steps showing the mean return and success rate of recent episodes.

    Args:
        total: steps the bar runs to.
        show: draw the bar (False: only count the episodes).
    """

    def __init__(self, total: int, show: bool = True):
        super().__init__()
        self.total, self.show = total, show
        self.returns: collections.deque[float] = collections.deque(maxlen=RECENT_EPISODES)
        self.successes: collections.deque[bool] = collections.deque(maxlen=RECENT_EPISODES)
        self.episodes = 0
        self.bar: tqdm | None = None

    def _on_training_start(self) -> None:
        self.bar = tqdm(total=self.total, unit="step", dynamic_ncols=True, disable=not self.show,
                        desc="PPO (seed recipe)")

    def _on_step(self) -> bool:
        ended = ended_episodes(self.training_env, self.locals["dones"], self.locals["infos"])
        for _, episode_return, success in ended:
            self.returns.append(episode_return)
            self.successes.append(success)
        self.episodes += len(ended)
        if ended and self.show:
            self.bar.set_postfix(ret=f"{np.mean(self.returns):.3f}", success=f"{np.mean(self.successes):.2f}",
                                 episodes=self.episodes, refresh=False)
        self.bar.update(self.training_env.num_envs)
        return True

    def _on_training_end(self) -> None:
        if self.bar is not None:
            self.bar.close()


def evaluate(model: PPO, task: Any, num_envs: int, device: str, seed: int, episodes: int) -> dict[str, Any]:
    """Sail ``episodes`` episodes of ``task`` with the model's deterministic policy.

    A fresh :class:`Sb3VecEnv` of ``num_envs`` boats seeded ``seed``; env i sails
    (episodes + i) // num_envs episodes (as SB3's ``evaluate_policy``), so the short episodes of some
    envs do not crowd out the long ones of others. Returns the episodes, successes, success rate, mean
    return and the wall time of the sailing [s].
    """
    if episodes < 1:
        raise ValueError(f"episodes must be >= 1, got {episodes}")
    env = Sb3VecEnv(task, num_envs=num_envs, device=device, seed=seed)
    env.seed(seed)
    targets = np.array([(episodes + index) // num_envs for index in range(num_envs)])
    counts = np.zeros(num_envs, dtype=int)
    returns, successes = [], []
    start = time.perf_counter()
    observations = env.reset()
    while (counts < targets).any():
        actions, _ = model.predict(observations, deterministic=True)
        observations, _, dones, infos = env.step(actions)
        for index, episode_return, success in ended_episodes(env, dones, infos):
            if counts[index] < targets[index]:
                counts[index] += 1
                returns.append(episode_return)
                successes.append(success)
    wall = time.perf_counter() - start
    env.close()
    return {"episodes": len(returns), "successes": int(np.sum(successes)),
            "success_rate": float(np.mean(successes)), "mean_return": float(np.mean(returns)), "eval_wall_s": wall}


def _readable(path: str) -> None:
    """Give a temporary file (created 0600) the usual permissions of a new file (0666 less the umask)."""
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(path, 0o666 & ~umask)


def run(steps: int = SEED_TOTAL_STEPS, num_envs: int = 1, device: str = "cpu", seed: int = 0,
        out: str = "out/sb3_seed", eval_episodes: int = 100, progress: bool = True, *, task: Any = TASK_ID,
        n_steps: int | None = None) -> dict[str, Any]:
    """Train PPO with the seed's recipe, evaluate it, and save the model and the summary.

    Args:
        steps: training steps (boat decisions summed over the envs); SB3 finishes the last rollout, so
            the count trained is the next multiple of the rollout size.
        num_envs: boats simulated together (1: the seed).
        device: Warp device of the simulator ("cpu", "cuda:0"); torch stays on the CPU.
        seed: seed of training; evaluation uses ``seed + 1000``.
        out: folder for model.zip and summary.json.
        eval_episodes: episodes of the deterministic policy to evaluate.
        progress: show the tqdm bar.
        task: task id or config (default: the seed's waypoint task).
        n_steps: steps per env per rollout; None: 2048 // num_envs (the seed's rollout). For tests.

    Returns:
        the summary: steps, num_envs, train_wall_s, success_rate, mean_return, episodes, device, and
        n_steps, seed, task, successes, eval_wall_s, train_episodes.
    """
    if steps < 1 or eval_episodes < 1:
        raise ValueError(f"steps and eval_episodes must be >= 1, got {steps} and {eval_episodes}")
    env = Sb3VecEnv(task, num_envs=num_envs, device=device, seed=seed)
    model = build_model(env, seed, n_steps)
    rollout = model.n_steps * env.num_envs
    callback = EpisodeProgress(total=math.ceil(steps / rollout) * rollout, show=progress)
    start = time.perf_counter()
    model.learn(total_timesteps=steps, callback=callback)
    train_wall = time.perf_counter() - start

    evaluation = evaluate(model, task, num_envs, device, seed + EVAL_SEED_OFFSET, eval_episodes)
    os.makedirs(out, exist_ok=True)
    with atomic_output(os.path.join(out, "model.zip")) as temporary:
        model.save(temporary)
        _readable(temporary)
    summary = {
        "steps": int(model.num_timesteps), "num_envs": int(env.num_envs), "train_wall_s": round(train_wall, 3),
        "success_rate": evaluation["success_rate"], "mean_return": evaluation["mean_return"],
        "episodes": evaluation["episodes"], "device": str(device),
        "n_steps": int(model.n_steps), "seed": int(seed),
        "task": task if isinstance(task, str) else type(task).__name__,
        "successes": evaluation["successes"], "eval_wall_s": round(evaluation["eval_wall_s"], 3),
        "train_episodes": callback.episodes,
    }
    with atomic_output(os.path.join(out, "summary.json")) as temporary, open(temporary, "w") as handle:
        json.dump(summary, handle, indent=2)
        handle.write("\n")
        _readable(temporary)
    return summary


def main(argv: list[str] | None = None) -> dict[str, Any]:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--steps", type=int, default=SEED_TOTAL_STEPS,
                        help="training steps, boat decisions over all envs (default: the seed's 512000)")
    parser.add_argument("--num-envs", type=int, default=1,
                        help="boats simulated together (default 1: the seed's single boat); with N > 1 the "
                             "rollout keeps the seed's 2048 steps: n_steps = 2048 // N per env")
    parser.add_argument("--device", default="cpu", help="Warp device of the simulator: cpu, cuda:0 (default cpu); "
                                                        "SB3's torch always runs on the CPU")
    parser.add_argument("--seed", type=int, default=0, help="training seed; evaluation uses seed + 1000 (default 0)")
    parser.add_argument("--out", default="out/sb3_seed", help="folder for model.zip and summary.json "
                                                               "(default out/sb3_seed)")
    parser.add_argument("--eval-episodes", type=int, default=100,
                        help="episodes of the deterministic policy to evaluate (default 100)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING  # no module-load chatter
    torch.set_num_threads(1)  # 32-unit MLPs: more threads only contend with the simulator
    summary = run(args.steps, args.num_envs, args.device, args.seed, args.out, args.eval_episodes,
                  progress=not args.no_progress)
    print(json.dumps(summary), flush=True)
    return summary


if __name__ == "__main__":
    main()
