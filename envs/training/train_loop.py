"""``ocean-warp train``: rsl-rl PPO on a sailing task, with a progress bar, TensorBoard logs, atomic
checkpoints that resume bit for bit, a sea-state curriculum, and the exported policy at the end.

    ocean-warp train --task EBoatWaypoint-v0 --device cpu --minutes 20
    ocean-warp train --task EBoatWaypoint-v0 --device cpu --workers 8 --num-envs 512
    ocean-warp train --task EBoatMission-v0 --device cuda --iterations 250 --run-name h100
    ocean-warp train --task EBoatMission-v0 --resume out/train/EBoatMission-v0/<date>_<name>/model_99.pt
    ocean-warp train --task EBoatMission-v0 --gpus 2 --minutes 5          # 2 GPUs, 4096 envs on each
    ocean-warp train --gpus 4 --nnodes 2 --rdzv-endpoint node01:29500     # on each of 2 hosts: 8 GPUs
    torchrun --standalone --nproc_per_node=2 -m ocean_warp.envs.training.train --device cpu ...   # 2 CPU processes

A run writes into ``out/train/<task>/<date>_<name>/`` (``--runs-root``, default ``out/train``):
``config.json`` (the resolved config), rsl-rl's TensorBoard events, ``progress.csv`` (one row per iteration,
rewritten after each), ``model_<it>.pt`` every ``save_interval`` iterations and at the end, and ``policy.pt``
(the actor alone, kilobytes).

The loop is rsl-rl's ``OnPolicyRunner.learn`` with three additions between iterations: the
curriculum's sea state, a seeded reset of every environment at each multiple of ``save_interval``
(so a run resumed from a checkpoint meets exactly the environments the uninterrupted run met), and the
checkpoint, which holds the torch random state and the curriculum beside the networks.

Several ranks (torchrun; ``--gpus G`` starts it): each rank simulates ``--num-envs`` environments of its
own (rank r's are environments [r N, (r + 1) N) of one batch), rsl-rl averages the gradients and the
normalisers, and one small collective per iteration sums the episode statistics (the curriculum moves
on all ranks' episodes, alike everywhere) and stops every rank when one failed. Rank 0 alone writes, and
adds ``distributed.json`` (every rank's host, node rank and checksum of its networks at the end, checked
equal). Several hosts: the same command on each with ``--nnodes N --rdzv-endpoint HOST:PORT`` (see
``ocean_warp.envs.training.distributed`` and ``ocean_warp.envs.training.rendezvous``).

Resuming with another number of ranks (hosts or GPUs) than wrote the checkpoint: the networks, optimiser,
normalisers, curriculum and history are the job's, one copy (rank 0's, equal on every rank), and carry over
whole. What belongs to a rank does not: ``--num-envs`` is per rank and taken from the command line, so the
batch becomes (ranks now) x N environments, rank r's being environments [r N, (r + 1) N) of the one seeded
batch restarted at the resumed iteration (the first ranks meet exactly the environments they would have met,
added ranks new ones of the same batch, and the history's samples count on at the new size); rank 0 continues
the saved random stream, and every other rank continues its own where as many ranks wrote the checkpoint, else
takes a seed derived from rank 0's saved state and its rank (``distributed.derived_seed``): reproducible, but
not the stream the uninterrupted run would have drawn.
"""

from __future__ import annotations

import argparse
import ast
import contextlib
import copy
import csv
import dataclasses
import datetime
import enum
import hashlib
import io
import json
import math
import numbers
import os
import sys
import time
import traceback
from typing import Any

import numpy as np
import torch

from ocean_warp.atomic_files import atomic_output
from ocean_warp.cli_support import (checked_output_folder, finite_above, option_problem, plural, report_error)
from ocean_warp.devices import resolve_device
from ocean_warp.termination import Terminated
from ocean_warp.vessel import Vessel

from .agents import TrainConfig, agent_config
from ..env_factory import make_env
from .distributed import (
    DEFAULT_TIMEOUT_S,
    DistributedRunner,
    RankContext,
    RankFailure,
    Ranks,
    derived_seed,
    host_name,
    inject_fault,
    parameter_checksum,
    rank_device,
    rank_seed,
)
from .distributed_launch import gpus_problem, hosts_problem, job_label, launch, torchrun_command, visible_gpus
from .policy_io import CheckpointError, export_policy, read_checkpoint, save_checkpoint
from .rendezvous import rendezvous_from_options
from .train_options import RUNS_ROOT, parser as _parser
from ..interfaces.rsl_rl_env import RslRlVecEnv
from ..parallel.sharded import ShardedSailingEnv
from ..protocol import BatchedEnv
from ..registration import task_name

__all__ = ["train", "Training", "TrainLength", "RunOutput", "Placement", "TrainResult", "apply_overrides", "main"]


@dataclasses.dataclass
class TrainResult:
    run_dir: str
    checkpoint: str
    """The last training checkpoint written."""
    policy: str
    """The exported policy (actor only)."""
    iterations: int
    """Iterations done in this call."""
    wall_time: float
    """[s] from the start of this call."""
    history: list[dict[str, float]]
    """One row per iteration (this call and, resumed, the ones before): see ``progress.csv``."""
    world_size: int = 1
    """Ranks that trained it (processes, one per GPU)."""
    parameter_checksums: list[str] | None = None
    """Several ranks: each rank's SHA-256 of its networks at the end, checked equal (also in the run's
    ``distributed.json``); None for one rank."""


class _Curriculum:
    """The sea-state level and the success rates it moves on (its state goes into the checkpoint)."""

    def __init__(self, config, state: dict | None = None):
        self.config = config
        self.level = 0
        self.window: list[float] = []
        if state:
            self.level = int(state["level"])
            self.window = [float(v) for v in state["window"]]

    @property
    def active(self) -> bool:
        return self.config.levels > 0

    def sea_state(self, seed: int, iteration: int) -> float | None:
        """Hs [m] for this iteration (None: no curriculum); drawn from (seed, iteration), not from a stream,
        so a resumed run draws the same."""
        if not self.config.sea_states:
            return None
        top = self.config.sea_states[self.level]
        if not self.config.randomize:
            return top
        return float(np.random.default_rng([seed, iteration, 0x5EA]).uniform(0.0, top))

    def record(self, success_rate: float) -> None:
        if not self.active or math.isnan(success_rate):
            return
        self.window = (self.window + [success_rate])[-self.config.window:]
        full = len(self.window) == self.config.window
        if full and np.mean(self.window) >= self.config.promote_success and self.level + 1 < self.config.levels:
            self.level += 1
            self.window = []

    def state(self) -> dict:
        return {"level": self.level, "window": list(self.window)}


def _jsonable(value: Any) -> Any:
    if dataclasses.is_dataclass(value):
        return {field.name: _jsonable(getattr(value, field.name)) for field in dataclasses.fields(value)}
    if isinstance(value, enum.Enum):
        return value.value
    if isinstance(value, (tuple, list)):
        return [_jsonable(v) for v in value]
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if isinstance(value, Vessel):
        return {"vessel": value.name, "config": _jsonable(value.config)}
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value


def _write_json(path: str, data: Any) -> None:
    with atomic_output(path) as temporary, open(temporary, "w") as stream:
        json.dump(data, stream, indent=2)


def _write_history(path: str, history: list[dict[str, float]]) -> None:
    if not history:
        return
    with atomic_output(path) as temporary, open(temporary, "w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=list(history[0]))
        writer.writeheader()
        writer.writerows(history)


def _segment_seed(seed: int, iteration: int) -> int:
    return int(np.random.default_rng([seed, iteration, 0x5E6]).integers(0, 2**31 - 1))


def _restart_segment(vec: RslRlVecEnv, config: TrainConfig, seed: int, iteration: int,
                     full_budget: torch.Tensor, first_env: int = 0) -> None:
    """Every environment from a reset seeded by (seed, iteration), episode lengths spread at random
    (drawn for environments 0 .. first_env + N - 1, this batch taking its own: a rank's share of them).

    ``full_budget`` (N,) bool is set to whether each env's current episode has its whole time budget:
    an episode whose clock was started part-way ends early by construction, and counting it would
    show a failure the policy did not make.
    """
    vec.reset(seed=_segment_seed(seed, iteration))
    full_budget.fill_(not config.random_episode_start)
    if config.random_episode_start:
        generator = torch.Generator().manual_seed(_segment_seed(seed, iteration) + 1)
        lengths = torch.randint(0, int(vec.max_episode_length), (first_env + vec.num_envs,), generator=generator)
        vec.episode_length_buf = lengths[first_env:].to(device=vec.device, dtype=vec.episode_length_buf.dtype)


def _default_run_dir(task: str, run_name: str | None, root: str) -> str:
    stamp = datetime.datetime.now().strftime("%Y-%m-%d_%H-%M-%S")
    return os.path.join(root, task, f"{stamp}_{run_name}" if run_name else stamp)


@dataclasses.dataclass(frozen=True)
class TrainLength:
    """How long :func:`train` runs: the first limit reached ends it."""

    iterations: int | None = None
    """PPO iterations in this call (default: the config's)."""
    minutes: float | None = None
    """Stop after the iteration that passes this much wall time [min] (rank 0's clock decides for every rank)."""


@dataclasses.dataclass(frozen=True)
class RunOutput:
    """Where :func:`train` writes (rank 0 only) and what it shows."""

    run_dir: str | None = None
    """The run folder (default ``runs_root/<task>/<date>_<run_name>``; resumed: the checkpoint's folder)."""
    run_name: str | None = None
    """Suffix of the default run folder's name."""
    runs_root: str = RUNS_ROOT
    """Folder that holds ``<task>/<date>_<name>/``."""
    progress: bool = True
    """Show a progress bar."""


@dataclasses.dataclass(frozen=True)
class Placement:
    """Where :func:`train` runs: its device, environments and ranks."""

    device: str = "cpu"
    """"cpu", "cuda" or "cuda:N": the simulator and the networks both live there. With several ranks,
    "cuda" is each rank's ``cuda:LOCAL_RANK``."""
    num_envs: int | None = None
    """Environments of this rank (default: the config's for this device); W ranks simulate W times as many,
    rank r's being environments [r num_envs, (r + 1) num_envs) of one batch."""
    workers: int = 1
    """Processes that simulate the environments, each a shard on a core of its own (a
    :class:`ShardedSailingEnv`, CPU only, one rank only; the same results as 1 for the same seed)."""
    rank: RankContext | None = None
    """Which rank this is (default: from torchrun's RANK, LOCAL_RANK, WORLD_SIZE; rank 0 of 1 without them)."""
    dist_timeout: float = DEFAULT_TIMEOUT_S
    """[s] the longest any rank waits for the others (several ranks only)."""


def train(config: TrainConfig, *, seed: int = 0, length: TrainLength = TrainLength(), output: RunOutput = RunOutput(),
          placement: Placement = Placement(), resume: str | None = None) -> TrainResult:
    """Train a policy with rsl-rl PPO, in this process or as one rank of several (torchrun).

    Example::

        train(agent_config("EBoatMission-v0"), seed=1, length=TrainLength(minutes=5),
              placement=Placement(device="cuda"), output=RunOutput(run_name="h100"))

    Args:
        config: the task's training config (``agents.agent_config(task)``, changed as wished).
        seed: seeds the environments' random streams, the networks' initialisation and PPO's sampling
            (rank r's torch seed: ``distributed.rank_seed(seed, r)``).
        length: iterations and wall-time limit (:class:`TrainLength`).
        output: run folder and progress bar (:class:`RunOutput`).
        placement: device, environments, worker processes and ranks (:class:`Placement`).
        resume: a training checkpoint (``model_<it>.pt``) to continue from: networks, optimiser, torch
            random state, curriculum; the next iteration is the one after it. Rank 0 reads it and sends it
            to the others; it may come from a run with another number of ranks.

    Only rank 0 writes files (run folder, config.json, progress.csv, TensorBoard, checkpoints,
    policy.pt) and shows progress; every rank returns the same iterations and history.

    Returns:
        a :class:`TrainResult`.

    Raises:
        RankFailure: (several ranks) a rank failed or lost contact with the others; every rank raises.
    """
    context = RankContext.from_env() if placement.rank is None else placement.rank
    device = placement.device if context.distributed else resolve_device(placement.device)
    ranks = Ranks.start(context, device, placement.dist_timeout)
    training = Training(config, ranks, seed=seed, length=length, output=output,
                        placement=dataclasses.replace(placement, device=device), resume=resume)
    try:
        training.setup()
        result = training.run()
    finally:
        training.close()
    ranks.close()  # only after success: a failed rank exits, and torchrun stops the others
    return result


@dataclasses.dataclass
class _Rollout:
    """What one iteration's collection counted over the episodes with their whole time budget."""

    ended: torch.Tensor
    successes: torch.Tensor
    returns: torch.Tensor


class Training:
    """One training run on one rank, in the steps of its life: :meth:`setup` (run folder, environments,
    networks, a resumed checkpoint), then per iteration :meth:`prepare` (a seeded restart at each checkpoint
    boundary, the curriculum's sea), :meth:`collect` (the rollout), :meth:`update` (PPO) and :meth:`record` (history, logs,
    progress), with :meth:`checkpoint` every ``save_interval`` iterations and at the end, and :meth:`close`
    (workers, progress bar, log writer). :meth:`run` does all of it; :func:`train` is the usual entry."""

    def __init__(self, config: TrainConfig, ranks: Ranks, *, seed: int, length: TrainLength, output: RunOutput,
                 placement: Placement, resume: str | None):
        self.config, self.ranks, self.seed, self.output, self.resume = config, ranks, seed, output, resume
        self.context = context = ranks.context
        error = None
        try:
            device = resolve_device(rank_device(context, placement.device)) if context.distributed \
                else placement.device
            num_envs = config.num_envs(device.startswith("cuda")) if placement.num_envs is None \
                else placement.num_envs
            if isinstance(num_envs, bool) or not isinstance(num_envs, numbers.Integral) or num_envs < 1:
                raise ValueError(f"num_envs must be a whole number >= 1, got {num_envs!r}")
            iterations = config.iterations if length.iterations is None else int(length.iterations)
            if iterations < 1:
                raise ValueError(f"iterations must be >= 1, got {iterations}")
            minutes = length.minutes
            if minutes is not None and not (math.isfinite(minutes) and minutes > 0):
                raise ValueError(f"minutes must be a positive number, got {minutes}")
            _check_workers(placement.workers, device, int(num_envs))
            if placement.workers > 1 and context.distributed:
                raise ValueError(f"workers {placement.workers} with {context.world_size} ranks: a ShardedSailingEnv "
                                 "cannot be one rank's share yet; start more ranks instead (one per core)")
        except ValueError as caught:
            error = caught
        ranks.check(error, "at startup")
        self.device, self.num_envs, self.workers = device, int(num_envs), placement.workers
        self.iterations, self.minutes = iterations, minutes
        if context.distributed:
            _check_same_settings(ranks, config, device, seed, self.num_envs, iterations, minutes, resume, self.workers)
        if device.startswith("cuda") and context.distributed:
            torch.cuda.set_device(torch.device(device))
        self.env = self.vec = self.runner = self.bar = None
        self.history: list[dict[str, float]] = []
        self.start_iteration = 0
        self.last_checkpoint = resume or ""

    # --- setup ------------------------------------------------------------------------------------
    def setup(self) -> None:
        """The run folder and config.json (rank 0), the resumed checkpoint, the environments (this rank's
        share), rsl-rl's runner and networks, the curriculum, the logs and the progress bar."""
        config, ranks, context = self.config, self.ranks, self.context
        checkpoint = _read_resumed(ranks, self.resume, config) if self.resume is not None else None
        self.run_dir = ranks.broadcast(self._make_run_dir() if context.is_main else None)
        error = None
        try:
            torch.manual_seed(rank_seed(self.seed, context.rank))
            if self.workers > 1:
                self.env = ShardedSailingEnv(config.train_task, self.num_envs, workers=self.workers, seed=self.seed)
            else:
                self.env = make_env(config.train_task, self.num_envs, device=self.device, seed=self.seed,
                                    first_env=context.first_env(self.num_envs))
            self.vec = RslRlVecEnv(self.env)
            self.full_budget = torch.zeros(self.num_envs, dtype=torch.bool, device=self.vec.device)
            runner_config = config.ppo.runner_config(config.steps_per_env)
            with contextlib.redirect_stdout(io.StringIO()):  # rsl-rl prints the networks; the bar says enough
                self.runner = DistributedRunner(self.vec, runner_config,
                                                log_dir=self.run_dir if context.is_main else None,
                                                device=str(self.vec.device), context=context,
                                                timeout_s=ranks.timeout_s)
        except Exception as caught:
            if not context.distributed:
                raise
            _print_own_failure(context, caught)
            error = caught
        ranks.check(error, "building its environments and networks")
        self.alg = self.runner.alg
        self.curriculum = _Curriculum(config.curriculum, checkpoint["curriculum"] if checkpoint else None)
        if checkpoint is not None:
            self.alg.load(checkpoint, None, strict=True)
            _restore_random_state(checkpoint, context, self.device)
            self.start_iteration = int(checkpoint["iteration"]) + 1
            self.history = [dict(row) for row in checkpoint.get("history", [])]
        if context.distributed:
            self.alg.broadcast_parameters()  # rank 0's fresh networks (a checkpoint gave every rank the same already)
        self.base_sea_state = self.env.significant_wave_height
        self.start_level = None
        """The curriculum level whose wind and leg ranges the environments draw from (None: the task's)."""
        curriculum = config.curriculum
        if (curriculum.wind_speeds or curriculum.waypoint_distances) and not hasattr(self.env, "set_start"):
            raise ValueError("a curriculum over wind or legs needs environments that take a new start "
                             f"distribution (SailingEnv.set_start); {type(self.env).__name__} does not")
        self.runner.logger.git_status_repos = []  # rsl-rl would store its own repository's git diff in the run
        with contextlib.redirect_stdout(io.StringIO()):
            self.runner.logger.init_logging_writer()
        if context.is_main:
            with contextlib.suppress(OSError):
                os.rmdir(os.path.join(self.run_dir, "git"))  # left empty by rsl-rl when it stores no repository
        self.alg.train_mode()
        self.decisions_per_iteration = self.num_envs * config.steps_per_env * context.world_size
        label = config.task if not context.distributed else f"{config.task} x{context.world_size}"
        self.bar = _progress_bar(self.output.progress and context.is_main,
                                 self.iterations if self.iterations < 10**8 else None, label)
        self.started = time.perf_counter()
        """When this call's training began (after the setup; ``time.perf_counter`` [s])."""
        self.wall_before = self.history[-1]["wall_time_s"] if self.history else 0.0
        """Training wall time of the run before this call (a resumed run's) [s]."""

    def _make_run_dir(self) -> str:
        """Rank 0's run folder, made, with the resolved config written into it."""
        output, config = self.output, self.config
        run_dir = output.run_dir
        if run_dir is None and self.resume is not None:
            run_dir = os.path.dirname(os.path.abspath(self.resume))
        run_dir = run_dir or _default_run_dir(config.task, output.run_name, output.runs_root)
        os.makedirs(run_dir, exist_ok=True)
        resolved = {"task": config.task, "device": self.device, "seed": self.seed, "num_envs": self.num_envs,
                    "workers": self.workers, "world_size": self.context.world_size, "train_config": _jsonable(config)}
        _write_json(os.path.join(run_dir, "config.json"), resolved)
        return run_dir

    # --- one iteration ------------------------------------------------------------------------------
    def prepare(self, iteration: int) -> None:
        """The seeded restart that opens each segment of ``save_interval`` iterations (and a resumed run),
        and the curriculum's sea state for the iteration."""
        config = self.config
        if iteration % config.save_interval == 0 or iteration == self.start_iteration:
            _restart_segment(self.vec, config, self.seed, iteration - iteration % config.save_interval,
                             self.full_budget, first_env=self.context.first_env(self.num_envs))
        self.sea_state = self.curriculum.sea_state(self.seed, iteration)
        if self.sea_state is not None:
            self.env.set_significant_wave_height(self.sea_state)
        curriculum = config.curriculum
        if (curriculum.wind_speeds or curriculum.waypoint_distances) and self.start_level != self.curriculum.level:
            self.env.set_start(curriculum.start(config.train_task.start, self.curriculum.level))
            self.start_level = self.curriculum.level

    def collect(self, iteration: int) -> tuple[_Rollout | None, Exception | None]:
        """The iteration's rollout into PPO's storage and its returns. Returns the counts of the episodes
        that ended with their whole budget, or (several ranks) the failure to share."""
        config, vec, alg, buffers = self.config, self.vec, self.alg, self.env.buffers
        rollout = _Rollout(*(torch.zeros((), device=vec.device) for _ in range(3)))
        try:
            with torch.inference_mode():
                obs = vec.get_observations()
                for _ in range(config.steps_per_env):
                    actions = alg.act(obs)
                    obs, rewards, dones, extras = vec.step(actions)
                    alg.process_env_step(obs, rewards, dones, extras)
                    self.runner.logger.process_env_step(rewards, dones, extras, None)
                    counted = dones.bool() & self.full_budget
                    rollout.ended += counted.sum()
                    rollout.successes += (buffers.final_success * counted).sum()
                    rollout.returns += (buffers.final_return * counted).sum()
                    self.full_budget |= dones.bool()
                inject_fault(self.context, iteration, alg.storage.rewards)
                _check_finite(alg.storage, iteration)
                alg.compute_returns(obs)
        except Exception as caught:
            if not self.context.distributed:
                raise
            if not isinstance(caught, NonFiniteBatch):
                _print_own_failure(self.context, caught)
            return None, caught
        return rollout, None

    def update(self, iteration: int, rollout: _Rollout | None, failure: Exception | None) -> tuple[dict, list[float]]:
        """Every rank's episode counts (or its failure) gathered, then PPO's update; returns the losses and
        the gathered (episodes, success sum, return sum)."""
        local = [0.0, 0.0, 0.0] if rollout is None else \
            [float(rollout.ended.item()), float(rollout.successes.item()), float(rollout.returns.item())]
        # Every rank's statistics, or every rank's failure, before the update's collectives.
        gathered = self.ranks.gather_iteration(failure, local, f"at iteration {iteration}")
        return self.alg.update(), gathered

    def record(self, iteration: int, losses: dict, gathered: list[float], collect_time: float,
               learn_time: float) -> dict[str, float]:
        """The iteration's row of the history (times [s]), rsl-rl's and our TensorBoard scalars, the
        curriculum's move and the progress bar; returns the row."""
        alg, runner = self.alg, self.runner
        runner.current_learning_iteration = iteration
        with contextlib.redirect_stdout(io.StringIO()):
            runner.logger.log(it=iteration, start_it=self.start_iteration,
                              total_it=self.start_iteration + self.iterations, collect_time=collect_time,
                              learn_time=learn_time, loss_dict=losses, learning_rate=alg.learning_rate,
                              action_std=alg.get_policy().output_std, rnd_weight=None)
        count, success_sum, return_sum = gathered
        success_rate = success_sum / count if count else float("nan")
        mean_return = return_sum / count if count else float("nan")
        self.curriculum.record(success_rate)  # the same sums on every rank: the same level everywhere
        decisions_per_second = self.decisions_per_iteration / (collect_time + learn_time)
        history = self.history
        row = {"iteration": iteration,
               "samples": (history[-1]["samples"] if history else 0) + self.decisions_per_iteration,
               "wall_time_s": self.wall_before + time.perf_counter() - self.started, "episodes": count,
               "mean_return": mean_return, "success_rate": success_rate, "decisions_per_s": decisions_per_second,
               "real_time_factor": decisions_per_second * self.env.decision_period,
               "sea_state_m": self.base_sea_state if self.sea_state is None else self.sea_state,
               "curriculum_level": self.curriculum.level, "learning_rate": alg.learning_rate,
               "collect_s": collect_time, "learn_s": learn_time}
        history.append(row)
        if writer := runner.logger.writer:
            writer.add_scalar("Episode/success_rate", success_rate if count else 0.0, iteration)
            writer.add_scalar("Curriculum/sea_state_m", row["sea_state_m"], iteration)
            writer.add_scalar("Perf/real_time_factor", row["real_time_factor"], iteration)
        _update_bar(self.bar, row)
        return row

    def checkpoint(self, iteration: int) -> str:
        """``model_<iteration>.pt`` in the run folder (written by rank 0, with every rank's random state)."""
        self.last_checkpoint = _save(self.run_dir, iteration, self.alg, self.config, self.env, self.curriculum,
                                     self.history, self.device, self.ranks)
        return self.last_checkpoint

    # --- the whole run ------------------------------------------------------------------------------
    def run(self) -> TrainResult:
        """The iterations (until ``iterations`` or ``minutes``), then the exported policy and, with several
        ranks, the check that every rank holds the same networks."""
        config, context, ranks = self.config, self.context, self.ranks
        started = self.started
        iteration = self.start_iteration - 1
        completed = None  # rank 0: the last completed iteration's checkpoint, kept in memory for an interruption
        try:
            for iteration in range(self.start_iteration, self.start_iteration + self.iterations):
                self.prepare(iteration)
                tic = time.perf_counter()
                rollout, failure = self.collect(iteration)
                collect_time = time.perf_counter() - tic
                tic = time.perf_counter()
                losses, gathered = self.update(iteration, rollout, failure)
                learn_time = time.perf_counter() - tic
                self.record(iteration, losses, gathered, collect_time, learn_time)
                if context.is_main:
                    completed = self._snapshot(iteration)
                last = iteration == self.start_iteration + self.iterations - 1
                out_of_time = self.minutes is not None and time.perf_counter() - started >= 60.0 * self.minutes
                if self.minutes is not None and context.distributed:
                    out_of_time = ranks.broadcast(out_of_time)  # rank 0's clock, or the ranks would part ways
                if (iteration + 1) % config.save_interval == 0 or last or out_of_time:
                    self.checkpoint(iteration)
                if context.is_main:
                    _write_history(os.path.join(self.run_dir, "progress.csv"), self.history)
                if out_of_time:
                    break
        except (KeyboardInterrupt, Terminated):
            if context.is_main:
                self._save_interrupted(completed)
            raise
        self.close()
        policy_path = os.path.join(self.run_dir, "policy.pt")
        if context.is_main:
            export_policy(read_checkpoint(self.last_checkpoint), policy_path)
        checksums = _check_identical_parameters(ranks, self.alg, self.run_dir, self.device, self.num_envs)
        return TrainResult(run_dir=self.run_dir, checkpoint=self.last_checkpoint, policy=policy_path,
                           iterations=iteration - self.start_iteration + 1, wall_time=time.perf_counter() - started,
                           history=self.history, world_size=context.world_size, parameter_checksums=checksums)

    def _snapshot(self, iteration: int) -> dict:
        """Rank 0: a copy of the checkpoint ``iteration`` would write (its own random state only: an
        interruption may reach the ranks at different moments, so it gathers nothing)."""
        payload = copy.deepcopy(_checkpoint_payload(iteration, self.alg, self.config, self.env, self.curriculum, [],
                                                    [_random_state(self.device)], self.context.world_size))
        payload["history"] = list(self.history)  # rows are never changed once appended
        return payload

    def _save_interrupted(self, completed: dict | None) -> None:
        """Ctrl-C or SIGTERM: write ``model_<it>.pt`` and ``policy.pt`` of the last completed iteration (the
        networks of an iteration cut short are half updated) unless its checkpoint exists, and say so."""
        if self.bar is not None:
            self.bar.close()
            self.bar = None
        prog = "ocean-warp train"
        if completed is None:
            print(f"{prog}: interrupted before the first iteration ended: no checkpoint written", file=sys.stderr)
            return
        iteration = int(completed["iteration"])
        path = os.path.join(self.run_dir, f"model_{iteration}.pt")
        if self.last_checkpoint != path:
            save_checkpoint(path, completed)
            self.last_checkpoint = path
        export_policy(completed, os.path.join(self.run_dir, "policy.pt"))
        _write_history(os.path.join(self.run_dir, "progress.csv"), completed["history"])
        print(f"{prog}: interrupted; iteration {iteration} saved as {path} (and policy.pt beside it); "
              f"--resume {path} continues", file=sys.stderr, flush=True)

    def close(self) -> None:
        """Stop a ShardedSailingEnv's workers (also on Ctrl-C), close the progress bar and the log writer.
        Idempotent."""
        if self.vec is not None:
            self.vec.close()
            self.vec = None
        if self.bar is not None:
            self.bar.close()
            self.bar = None
        if self.runner is not None:
            with contextlib.redirect_stdout(io.StringIO()):
                self.runner.logger.stop_logging_writer()
            self.runner = None


class NonFiniteBatch(ValueError):
    """NaN or infinity in a rank's collected batch (observations or rewards)."""


def _check_finite(storage, iteration: int) -> None:
    """Raise :class:`NonFiniteBatch` if the rollout holds NaN or infinity: caught before the update, it
    never reaches the gradients or the normalisers (on any rank)."""
    groups = [(f"observations[{name!r}]", tensor) for name, tensor in storage.observations.items()]
    bad = [name for name, tensor in groups + [("rewards", storage.rewards)] if not bool(torch.isfinite(tensor).all())]
    if bad:
        raise NonFiniteBatch(f"NaN or infinity in the batch collected at iteration {iteration}: {', '.join(bad)}")


def _print_own_failure(context: RankContext, error: BaseException) -> None:
    """The failing rank's traceback on its own stderr (every rank then reports the failure in one line)."""
    print(f"rank {context.rank}: {type(error).__name__} (traceback follows; every rank stops)", file=sys.stderr)
    traceback.print_exception(error, file=sys.stderr)


def _check_same_settings(ranks: Ranks, config: TrainConfig, device: str, seed: int, num_envs: int, iterations: int,
                         minutes: float | None, resume: str | None, workers: int) -> None:
    """Every rank must train the same thing (a launch across hosts can give them different arguments)."""
    settings = json.dumps({"config": _jsonable(config), "seed": seed, "num_envs": num_envs, "iterations": iterations,
                           "minutes": minutes, "resume": resume, "workers": workers,
                           "device_type": device.split(":")[0]}, sort_keys=True)
    digests = ranks.gather(hashlib.sha256(settings.encode()).hexdigest()[:12])
    if len(set(digests)) > 1:
        raise RankFailure("the ranks were started with different settings (settings digests by rank: "
                          f"{', '.join(digests)}): give every rank the same arguments")


def _read_resumed(ranks: Ranks, path: str, config: TrainConfig) -> dict:
    """The checkpoint to resume from, read and checked by rank 0 and sent to every rank."""
    if not ranks.distributed:
        checkpoint = read_checkpoint(path)
        _check_resumable(checkpoint, config, path)
        return checkpoint
    checkpoint, message = None, None
    if ranks.context.is_main:
        try:
            checkpoint = read_checkpoint(path)
            _check_resumable(checkpoint, config, path)
        except CheckpointError as error:
            message = str(error)
    checkpoint, message = ranks.broadcast((checkpoint, message))
    if message is not None:
        raise CheckpointError(message)
    return checkpoint


def _random_state(device: str) -> dict[str, torch.Tensor]:
    state = {"torch": torch.get_rng_state()}
    if device.startswith("cuda"):
        state["cuda"] = torch.cuda.get_rng_state(torch.device(device))
    return state


def _restore_random_state(checkpoint: dict, context: RankContext, device: str) -> None:
    """Rank 0 takes the saved state; another rank its own, saved beside it when as many ranks trained the
    checkpoint, else a seed derived from rank 0's state and its rank."""
    saved = checkpoint.get("rank_rng_states", [])
    if context.rank == 0:
        state = {"torch": checkpoint["torch_rng_state"]}
        if "cuda_rng_state" in checkpoint:
            state["cuda"] = checkpoint["cuda_rng_state"]
    elif int(checkpoint.get("world_size", 1)) == context.world_size and len(saved) == context.world_size - 1:
        state = saved[context.rank - 1]
    else:
        torch.manual_seed(derived_seed(checkpoint["torch_rng_state"], context.rank))
        return
    torch.set_rng_state(state["torch"])
    if device.startswith("cuda") and "cuda" in state:
        torch.cuda.set_rng_state(state["cuda"], device=torch.device(device))


def _check_identical_parameters(ranks: Ranks, alg, run_dir: str, device: str, num_envs: int) -> list[str] | None:
    """Several ranks: every rank's checksum of its networks (normalisers included) and, on rank 0,
    ``distributed.json`` recording them; :class:`RankFailure` on every rank if they differ."""
    if not ranks.distributed:
        return None
    saved = alg.save()
    mine = parameter_checksum(saved["actor_state_dict"], saved["critic_state_dict"])
    context = ranks.context
    gathered = ranks.gather((mine, {"device": device, "host": host_name(), "node_rank": context.node_rank,
                                    "local_rank": context.local_rank}))
    checksums = [checksum for checksum, _ in gathered]
    where = [place for _, place in gathered]
    identical = len(set(checksums)) == 1
    if context.is_main:
        _write_json(os.path.join(run_dir, "distributed.json"),
                    {"world_size": context.world_size, "nodes": len({place["node_rank"] for place in where}),
                     "backend": ranks.backend, "num_envs_per_rank": num_envs, "ranks": where,
                     "parameter_checksums": checksums, "identical_parameters": identical})
    if not identical:
        raise RankFailure(f"the ranks ended with different networks (checksums by rank: {', '.join(checksums)}); "
                          "they did not start alike or their updates were not averaged alike")
    return checksums


def _save(run_dir: str, iteration: int, alg, config: TrainConfig, env: BatchedEnv, curriculum: _Curriculum,
          history: list[dict[str, float]], device: str, ranks: Ranks) -> str:
    """Write ``model_<iteration>.pt`` (rank 0; every rank gives its random state, so a resume by as many
    ranks continues each rank's stream). Returns its path on every rank."""
    path = os.path.join(run_dir, f"model_{iteration}.pt")
    states = ranks.gather(_random_state(device))
    if not ranks.context.is_main:
        return path
    save_checkpoint(path, _checkpoint_payload(iteration, alg, config, env, curriculum, history, states,
                                              ranks.context.world_size))
    return path


def _checkpoint_payload(iteration: int, alg, config: TrainConfig, env: BatchedEnv, curriculum: _Curriculum,
                        history: list[dict[str, float]], states: list[dict], world_size: int) -> dict:
    """What ``model_<iteration>.pt`` holds: networks, optimiser, what describes them, the random states
    (``states``: rank 0's, then the other ranks' where known), the curriculum and the history."""
    payload = dict(alg.save())
    payload.update({
        "task": config.task, "observation": env.task.observation.value if hasattr(env.task.observation, "value")
        else str(env.task.observation), "num_obs": env.num_policy_obs, "num_actions": env.num_actions,
        "actor_config": config.ppo.actor_config(), "critic_config": config.ppo.critic_config(),
        "iteration": iteration, "torch_rng_state": states[0]["torch"], "curriculum": curriculum.state(),
        "history": history, "train_config": json.dumps(_jsonable(config)), "world_size": world_size,
    })
    if "cuda" in states[0]:
        payload["cuda_rng_state"] = states[0]["cuda"]
    if len(states) > 1:
        payload["rank_rng_states"] = states[1:]
    return payload


def _check_resumable(checkpoint: dict, config: TrainConfig, path: str) -> None:
    if "optimizer_state_dict" not in checkpoint or "iteration" not in checkpoint:
        raise CheckpointError(f"checkpoint {path!r} is an exported policy, not a training checkpoint: it has no "
                              "optimiser state to resume from (use a model_<it>.pt of the run)")
    if checkpoint["task"].removeprefix("ocean_warp/") != config.task:
        raise CheckpointError(f"checkpoint {path!r} was trained for {checkpoint['task']}, not {config.task}")
    if checkpoint["actor_config"] != config.ppo.actor_config():
        raise CheckpointError(f"checkpoint {path!r} has actor {checkpoint['actor_config']}, but this run builds "
                              f"{config.ppo.actor_config()}")


def _check_workers(workers: int, device: str, num_envs: int) -> None:
    """``workers`` must be a whole number from 1 to ``num_envs``, and 1 on a CUDA device (one GPU
    simulates every environment in one process)."""
    if isinstance(workers, bool) or not isinstance(workers, int) or not 1 <= workers <= num_envs:
        raise ValueError(f"workers must be a whole number from 1 to num_envs ({num_envs}), got {workers!r}")
    if workers > 1 and device != "cpu":
        raise ValueError(f"workers {workers} shards the environments over CPU processes; on {device} use "
                         "workers 1 (the GPU simulates every environment in one process)")


def _progress_bar(enabled: bool, total: int, task: str):
    if not enabled:
        return None
    from tqdm.auto import tqdm

    return tqdm(total=total, desc=task, unit="it", dynamic_ncols=True, file=sys.stderr)


def _episode_summary(row: dict[str, float]) -> str:
    """Return and success of an iteration's ended episodes, or a note that none ended in it."""
    if not math.isfinite(row.get("success_rate", math.nan)):
        return "no episode ended"
    return f"return {row['mean_return']:.2f}  success {100 * row['success_rate']:.0f}%"


def _update_bar(bar, row: dict[str, float]) -> None:
    if bar is None:
        return
    bar.set_postfix_str(f"{_episode_summary(row)}  {row['decisions_per_s'] / 1e3:.1f}k dec/s  RTF {row['real_time_factor']:.0f}  "
                        f"Hs {row['sea_state_m']:.2f} m", refresh=False)
    bar.update(1)


# --- command line ----------------------------------------------------------------------------------

def apply_overrides(config: Any, assignments: list[str]) -> Any:
    """``config`` with fields replaced by ``"a.b=value"`` assignments (value as a Python literal, else a
    string); each nested dataclass is rebuilt with ``dataclasses.replace``, so its validation runs."""
    for assignment in assignments:
        if "=" not in assignment:
            raise ValueError(f"--set {assignment!r}: expected field=value, e.g. ppo.learning_rate=3e-4")
        path, text = assignment.split("=", 1)
        try:
            value = ast.literal_eval(text)
        except (ValueError, SyntaxError):
            value = text
        config = _replace_path(config, path.strip().split("."), value, path)
    return config


def _replace_path(obj: Any, names: list[str], value: Any, full: str) -> Any:
    if not dataclasses.is_dataclass(obj):
        raise ValueError(f"--set {full}: {type(obj).__name__} has no fields")
    fields = {field.name for field in dataclasses.fields(obj)}
    if names[0] not in fields:
        raise ValueError(f"--set {full}: {type(obj).__name__} has no field {names[0]!r}; fields: "
                         f"{', '.join(sorted(fields))}")
    if len(names) > 1:
        value = _replace_path(getattr(obj, names[0]), names[1:], value, full)
    return dataclasses.replace(obj, **{names[0]: value})


def _option_problem(args: argparse.Namespace) -> str | None:
    """What is wrong with the options' values, in one line; None when nothing is."""
    return option_problem((
        ("--num-envs", args.num_envs, args.num_envs is None or args.num_envs >= 1, "a whole number >= 1"),
        ("--iterations", args.iterations, args.iterations is None or args.iterations >= 1, "a whole number >= 1"),
        ("--minutes", args.minutes, args.minutes is None or finite_above(args.minutes, 0.0), "a number > 0"),
        ("--workers", args.workers, args.workers >= 1, "a whole number >= 1"),
        ("--torch-threads", args.torch_threads, args.torch_threads is None or args.torch_threads >= 1,
         "a whole number >= 1"),
        ("--dist-timeout", args.dist_timeout, finite_above(args.dist_timeout, 0.0), "a number of seconds > 0"),
    ))


def main(argv: list[str] | None = None) -> int:
    """``ocean-warp train``: 0 on success, 2 for bad options or checkpoints, 1 when a rank failed (the
    launcher: torchrun's status)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = _parser()
    args = parser.parse_args(argv)
    problem = _option_problem(args)
    if problem is not None:
        return report_error(parser.prog, problem)
    try:
        task = task_name(args.task)
    except ValueError as error:
        return report_error(parser.prog, f"--task: {error}")
    if args.resume is None:
        checked_output_folder(parser, args.runs_root, "--runs-root")
    device = None if args.device == "auto" else args.device  # None: Warp's preferred device
    try:
        rendezvous = rendezvous_from_options(args.nnodes, args.node_rank, args.rdzv_endpoint, args.rdzv_id)
    except ValueError as error:
        return report_error(parser.prog, str(error))
    if rendezvous is not None and (problem := hosts_problem(device, args.gpus)) is not None:
        return report_error(parser.prog, problem)
    if args.gpus is not None:
        problem = gpus_problem(args.gpus, device, visible_gpus())
        if problem is not None:
            return report_error(parser.prog, problem)
        if int(args.gpus) > 1 or rendezvous is not None:
            gpus = int(args.gpus)
            return launch(torchrun_command(argv, gpus, rendezvous=rendezvous), job_label(gpus, True, rendezvous))
        device = "cuda"
    elif rendezvous is not None:  # one rank on this host, on --device
        return launch(torchrun_command(argv, 1, rendezvous=rendezvous, on_gpus=False), job_label(1, False, rendezvous))
    try:
        context = RankContext.from_env()
    except ValueError as error:
        return report_error(parser.prog, str(error))
    try:
        if not context.distributed:
            device = resolve_device(device, name="--device")  # None ("auto"): Warp's preferred device
        elif device is None:  # each rank on its own GPU where there are GPUs
            device = "cuda" if resolve_device(None).startswith("cuda") else "cpu"
        threads = _torch_threads(args.torch_threads, device)
        if context.is_main:
            print(f"{parser.prog}: {task} on {device}, torch threads {threads}")
        config = apply_overrides(agent_config(task), args.overrides)
        if args.minutes is not None and args.iterations is None:
            iterations = 10**9
        else:
            iterations = args.iterations
        result = train(config, seed=args.seed, length=TrainLength(iterations, args.minutes),
                       output=RunOutput(run_name=args.run_name, runs_root=args.runs_root, progress=not args.no_progress),
                       placement=Placement(device=device, num_envs=args.num_envs, workers=args.workers,
                                           rank=context, dist_timeout=args.dist_timeout),
                       resume=args.resume)
    except RankFailure as error:
        if context.is_main or not error.everywhere:  # the others hold the same message as rank 0
            print(f"{parser.prog}: {error}", file=sys.stderr)
        return 1
    except (CheckpointError, ValueError) as error:
        return report_error(parser.prog, f"{_rank_prefix(context)}{error}")
    if not context.is_main:
        return 0
    ended = [row for row in result.history if math.isfinite(row.get("success_rate", math.nan))]
    last = (f"last iteration with ended episodes ({ended[-1]['iteration']}): {_episode_summary(ended[-1])}"
            if ended else "no episode ended")
    print(f"{plural(result.iterations, 'iteration')} in {result.wall_time:.0f} s; {last}")
    print(f"checkpoint {result.checkpoint}\npolicy     {result.policy}")
    if result.parameter_checksums:
        print(f"{result.world_size} ranks ended with identical networks (sha256 {result.parameter_checksums[0][:16]}...)")
    return 0


def _torch_threads(requested: int | None, device: str) -> int:
    """Set torch's CPU threads in this process: ``requested`` (--torch-threads), else 1 on the CPU (the small
    networks gain nothing from more, and more threads contend with Warp's: 10 times slower on a busy two-core
    machine) and torch's own default on a GPU. Returns the count in use. ``--workers`` processes set one
    each themselves (``ocean_warp.envs.parallel.sharded``)."""
    if requested is None and device.startswith("cuda"):
        return torch.get_num_threads()
    torch.set_num_threads(requested or 1)
    return torch.get_num_threads()


def _rank_prefix(context: RankContext) -> str:
    return f"rank {context.rank}: " if context.distributed else ""
