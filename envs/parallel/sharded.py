"""A :class:`SailingEnv` sharded over worker processes, for training on more than one CPU core.

Warp runs a CPU launch on one thread, so one SailingEnv uses one core. :class:`ShardedSailingEnv` splits
``num_envs`` environments into contiguous shards, one per worker process; each worker holds a CPU
SailingEnv of its own for its shard (built with ``first_env``, so its environments are the same
environments, with the same origins, random starts, mass variants, gusts and sensor noise, as in one
SailingEnv of ``num_envs``). The
actions, observations, rewards, dones and episode records live in torch tensors in shared memory; the
parent presents them as one batch with SailingEnv's face (``buffers``, ``step``, ``reset``,
``episode_log``, ...), so the rsl-rl and gymnasium adapters take it as they take a SailingEnv.

A step: the parent writes the actions into shared memory and sends one small message to every worker
through its pipe; each worker reads its rows, steps its shard and writes its rows of the results; the
parent waits for every answer. Nothing but the command and a short reply is pickled.

Same seed, same results: observations, rewards and dones equal those of one SailingEnv bit for bit,
for any number of workers (each shard numbers its random streams from its first environment's index).
The sea is the same for every worker, so the parent evaluates it once (``envs.shared_ocean``), one
decision ahead, into shared memory that every worker's ocean copies from; with a cheap per-boat model
(the four-point hull) that evaluation was most of a small shard's work. ``shared_ocean=False`` lets
each worker evaluate its own, with the same results.

Workers are started with "spawn" (Warp and torch do not survive ``fork``), ignore Ctrl-C (the parent
decides), and exit when the parent dies. A worker that dies or raises makes the parent's next call
raise RuntimeError naming it, after every other worker has been stopped. ``close()`` (also on
``with``, on Ctrl-C in the parent and at interpreter exit) stops and joins them, and kills stragglers.
"""

from __future__ import annotations

import contextlib
import logging
import os
import signal
import threading
import time
import traceback
import weakref
from multiprocessing.connection import wait
from typing import Any

import torch
import torch.multiprocessing
import warp as wp

from ocean_warp.validation import require_int_in_range

from ocean_warp.devices import init_warp
from ..protocol import EnvBuffers, episode_log
from ..env_factory import env_sizes, make_env, require_task
from .shared_ocean import SharedOcean, ocean_updates_per_decision

__all__ = ["ShardedSailingEnv", "shard_bounds"]

_PARENT_POLL_S = 1.0
"""How often an idle worker checks that its parent is alive [s]."""


def shard_bounds(num_envs: int, workers: int) -> list[tuple[int, int]]:
    """Contiguous shards (first env, count) of ``num_envs`` environments over ``workers`` workers; the
    first ``num_envs % workers`` shards hold one environment more than the others."""
    size, extra = divmod(num_envs, workers)
    bounds, first = [], 0
    for index in range(workers):
        count = size + (1 if index < extra else 0)
        bounds.append((first, count))
        first += count
    return bounds


def _buffer_layout(task) -> dict[str, tuple[tuple[int, ...], torch.dtype]]:
    """Per-environment shape and dtype of every :class:`EnvBuffers` field for ``task``."""
    sizes = env_sizes(task)
    p, c = sizes.num_policy_obs, sizes.num_critic_obs
    f32, i32 = torch.float32, torch.int32
    return {"actions": ((sizes.num_actions,), f32), "policy_obs": ((p,), f32), "critic_obs": ((c,), f32),
            "final_policy_obs": ((p,), f32), "final_critic_obs": ((c,), f32), "reward": ((), f32),
            "terminated": ((), torch.bool), "time_out": ((), torch.bool), "done": ((), torch.bool),
            "episode_length": ((), i32), "episode_return": ((), f32), "target": ((3,), f32), "origin": ((3,), f32),
            "route": ((sizes.route_length, 3), f32), "waypoint_index": ((), i32), "position": ((3,), f32),
            "orientation": ((4,), f32), "velocity": ((6,), f32), "wind_velocity": ((3,), f32),
            "wind_direction": ((), f32), "propeller_level": ((), i32), "final_position": ((3,), f32),
            "final_orientation": ((4,), f32), "final_return": ((), f32), "final_length": ((), i32),
            "final_success": ((), f32), "final_status": ((), i32), "final_waypoints": ((), i32),
            "final_score": ((), f32),
            "obstacles": ((sizes.obstacle_slots, 4), f32)}


# --- the worker side ---------------------------------------------------------------------------------
class _Shard:
    """A worker's SailingEnv for global environments [first, first + count) and its rows of shared memory."""

    def __init__(self, task, shared: dict[str, torch.Tensor], first: int, count: int, seed: int,
                 ocean_slots: torch.Tensor | None):
        self.env = make_env(task, count, device="cpu", seed=seed, first_env=first)
        self.ocean_cursor = None
        if ocean_slots is not None:
            self.updates_per_decision = ocean_updates_per_decision(task)
            self.ocean_cursor = wp.zeros(1, dtype=wp.int32, device="cpu")
            self.env.simulator.ocean.read_fields_from(wp.from_torch(ocean_slots, dtype=wp.vec2f), self.ocean_cursor)
        own = vars(self.env.buffers)
        self.rows = {name: tensor[first:first + count] for name, tensor in shared.items()}
        for name, rows in self.rows.items():
            if rows.shape != own[name].shape or rows.dtype != own[name].dtype:
                raise RuntimeError(f"shared buffer {name} is {tuple(rows.shape)} {rows.dtype}, the shard's "
                                   f"{tuple(own[name].shape)} {own[name].dtype}")
        self.pairs = [(self.rows[name], own[name]) for name in self.rows]
        self.publish()

    def publish(self) -> None:
        """Copy the shard's buffers into its rows of shared memory (the inputs too: a step advances
        ``episode_length``, and the learner reads it)."""
        for rows, own in self.pairs:
            rows.copy_(own)

    def run(self, command: str, argument: Any) -> Any:
        """Carry out one command from the parent; returns the reply's payload."""
        env = self.env
        if command == "step":
            if self.ocean_cursor is not None:  # the argument: which half of the shared ocean's slots to read
                self.ocean_cursor.fill_(argument * self.updates_per_decision)
            # The learner may have written episode lengths (rsl-rl's random episode start) since the last step.
            env.buffers.episode_length.copy_(self.rows["episode_length"])
            env.step(self.rows["actions"])
            self.publish()
            return None
        if command == "reset":
            env.reset(seed=argument)
            self.publish()
            return None
        if command == "wave_height":
            return env.set_significant_wave_height(argument)
        if command == "crash":  # for tests: an exception inside a worker
            raise RuntimeError(f"crash requested: {argument}")
        raise ValueError(f"unknown command {command!r}")


def _worker_main(conn, shared: dict[str, torch.Tensor], ocean_slots: torch.Tensor | None, task,
                 first: int, count: int, seed: int, parent_pid: int, log_level: int) -> None:
    """A worker process: build the shard, answer with its sea's wave height, then run commands until
    "close", until the parent's end of the pipe closes or until the parent dies. An exception is sent
    back as text. Warp logs at the parent's level but at least WARNING (a banner and a line per loaded
    module from every worker is noise)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    torch.set_num_threads(1)
    wp.config.log_level = max(log_level, logging.WARNING)
    init_warp()  # without Warp's no-driver warning from every worker of a machine without a GPU
    try:
        shard = _Shard(task, shared, first, count, seed, ocean_slots)
        conn.send(("ok", shard.env.significant_wave_height))
        while True:
            if not conn.poll(_PARENT_POLL_S):
                if os.getppid() != parent_pid:
                    return
                continue
            command, argument = conn.recv()
            if command == "close":
                return
            conn.send(("ok", shard.run(command, argument)))
    except (EOFError, BrokenPipeError, ConnectionResetError):
        return  # the parent is gone or closed its end: nobody to answer
    except BaseException:
        with contextlib.suppress(Exception):
            conn.send(("error", traceback.format_exc()))
        raise SystemExit(1)


# --- the parent side ---------------------------------------------------------------------------------
class _WorkerPool:
    """The worker processes and their pipes; knows nothing of environments, so a finalizer can hold it
    without keeping the env alive."""

    def __init__(self, names: list[str]):
        self.names = names
        self.processes: list[Any] = []
        self.conns: list[Any] = []
        self.closed = False

    def start(self, context, args_per_worker: list[tuple]) -> None:
        """Start one process per entry of ``args_per_worker`` (arguments after the pipe), with SIGINT
        ignored from birth (spawned children inherit an ignored signal)."""
        with _sigint_ignored():
            for args in args_per_worker:
                parent_end, child_end = context.Pipe()
                process = context.Process(target=_worker_main, args=(child_end, *args), daemon=True)
                process.start()
                child_end.close()
                self.processes.append(process)
                self.conns.append(parent_end)

    def send_all(self, message: tuple) -> None:
        for index, conn in enumerate(self.conns):
            try:
                conn.send(message)
            except (BrokenPipeError, ConnectionResetError, EOFError):
                # Most often the worker died: say how (a broken pipe alone hides the cause).
                process = self.processes[index]
                process.join(1.0)
                self._fail(index, "could not be reached" if process.is_alive() else self._death(index))

    def gather(self, timeout: float) -> list[Any]:
        """Every worker's reply payload, in order; raises RuntimeError on a death, an error or a timeout."""
        replies: list[Any] = [None] * len(self.conns)
        pending = dict(enumerate(self.conns))
        deadline = time.monotonic() + timeout
        while pending:
            sentinels = {self.processes[i].sentinel: i for i in pending}
            ready = wait(list(pending.values()) + list(sentinels), timeout=max(0.0, deadline - time.monotonic()))
            if not ready:
                self._fail(next(iter(pending)), f"did not answer within {timeout:g} s")
            for index, conn in list(pending.items()):
                if conn in ready:  # a reply, or the end of the pipe of a worker that died
                    replies[index] = self._receive(index, conn)
                    del pending[index]
            for sentinel, index in sentinels.items():
                if sentinel in ready and index in pending:
                    self._fail(index, self._death(index))
        return replies

    def _receive(self, index: int, conn) -> Any:
        try:
            status, payload = conn.recv()
        except (EOFError, ConnectionResetError, OSError):
            self.processes[index].join(1.0)
            self._fail(index, self._death(index))
        if status == "error":
            self._fail(index, f"raised an exception:\n{payload}")
        return payload

    def _death(self, index: int) -> str:
        process = self.processes[index]
        process.join(1.0)
        code = process.exitcode
        if code is not None and code < 0:
            with contextlib.suppress(ValueError):
                return f"died: killed by {signal.Signals(-code).name} (exit code {code})"
        return f"died with exit code {code}"

    def _fail(self, index: int, what: str) -> None:
        name = self.names[index]
        self.shutdown()
        raise RuntimeError(f"ShardedSailingEnv: {name} {what}; all workers have been stopped")

    def shutdown(self, timeout: float = 5.0) -> None:
        """Ask every worker to exit, join them within ``timeout`` [s] together, then terminate and, if
        need be, kill the stragglers. Idempotent."""
        if self.closed:
            return
        self.closed = True
        for conn in self.conns:
            with contextlib.suppress(Exception):
                conn.send(("close", None))
        deadline = time.monotonic() + timeout
        for process in self.processes:
            process.join(max(0.0, deadline - time.monotonic()))
        for stop in ("terminate", "kill"):
            stragglers = [p for p in self.processes if p.is_alive()]
            for process in stragglers:
                getattr(process, stop)()
            for process in stragglers:
                process.join(1.0)
        for conn in self.conns:
            conn.close()


@contextlib.contextmanager
def _sigint_ignored():
    """Ignore SIGINT in this process for the duration (only from the main thread, where Python allows it)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


class ShardedSailingEnv:
    """``num_envs`` environments of ``task`` on the CPU, sharded over ``workers`` processes.

    Implements :class:`~ocean_warp.envs.protocol.BatchedEnv`, as a SailingEnv does: ``buffers``
    (:class:`EnvBuffers` of shared-memory tensors, bound once), ``step(actions)``, ``reset(seed)``,
    ``episode_log()``, ``set_significant_wave_height``, ``close`` and the sizes and periods. Writes into
    ``buffers.actions`` and ``buffers.episode_length`` take effect at the next step, as in a SailingEnv.

    Example::

        with ShardedSailingEnv(WaypointConfig(), 256, workers=4, seed=1) as env:
            for _ in range(1000):
                env.step(policy(env.buffers.policy_obs))

    Args:
        task: the task config.
        num_envs: environments in all (>= workers).
        workers: worker processes, 1 to num_envs; shards differ in size by at most one environment.
        seed: seed of the per-env random streams, as SailingEnv's.
        timeout: longest wait for the workers' answer to one command (building included) [s].
        shared_ocean: evaluate the sea once, in this process, for every worker (False: every worker
            evaluates its own; the results are the same bit for bit).
    """

    def __init__(self, task, num_envs: int, *, workers: int, seed: int = 0, timeout: float = 300.0,
                 shared_ocean: bool = True):
        require_task("ShardedSailingEnv", task)
        self.num_envs = require_int_in_range("ShardedSailingEnv", "num_envs", num_envs, 1, 2**24)
        self.workers = require_int_in_range("ShardedSailingEnv", "workers", workers, 1, self.num_envs)
        self.seed = require_int_in_range("ShardedSailingEnv", "seed", seed, 0, 2**31 - 1)
        if not (isinstance(timeout, (int, float)) and timeout > 0):
            raise ValueError(f"ShardedSailingEnv.timeout must be a positive number of seconds, got {timeout!r}")
        self.timeout = float(timeout)
        self.task = task
        sizes = env_sizes(task)
        self.num_actions = sizes.num_actions
        self.num_policy_obs = sizes.num_policy_obs
        self.num_critic_obs = sizes.num_critic_obs
        self.max_episode_length = task.max_episode_length
        self.decision_period = task.decision_period
        self.steps_per_decision = task.steps_per_decision
        self.device = "cpu"
        self.torch_device = torch.device("cpu")
        self.shards = shard_bounds(self.num_envs, self.workers)
        shared = {name: torch.zeros((self.num_envs, *shape), dtype=dtype).share_memory_()
                  for name, (shape, dtype) in _buffer_layout(task).items()}
        self.buffers = EnvBuffers(**shared)
        """Shared-memory tensors, (N, ...) on the CPU, bound once (see :class:`EnvBuffers`)."""
        self._ocean = SharedOcean(task) if shared_ocean else None
        ocean_slots = self._ocean.slots if self._ocean is not None else None

        names = [f"worker {i} (envs {a}-{a + n - 1})" if n > 1 else f"worker {i} (env {a})"
                 for i, (a, n) in enumerate(self.shards)]
        self._pool = _WorkerPool(names)
        self._finalizer = weakref.finalize(self, self._pool.shutdown)
        context = torch.multiprocessing.get_context("spawn")
        args = [(shared, ocean_slots, task, first, count, self.seed, os.getpid(), wp.config.log_level)
                for first, count in self.shards]
        try:
            self._pool.start(context, args)
            self.pids = [process.pid for process in self._pool.processes]
            heights = self._pool.gather(self.timeout)
            if self._ocean is not None:
                self._ocean.restart(0.0)
        except BaseException:
            self.close()
            raise
        self._significant_wave_height = heights[0]

    # --- SailingEnv's face -----------------------------------------------------------------------------
    def step(self, actions: torch.Tensor | None = None) -> None:
        """One decision for every environment: ``actions`` (N, 3) in [-1, 1] (None: those already in
        ``buffers.actions``). Returns when every worker has written its results into ``buffers``."""
        if actions is not None:
            if tuple(actions.shape) != (self.num_envs, self.num_actions):
                raise ValueError(f"ShardedSailingEnv.step: actions must have shape ({self.num_envs}, "
                                 f"{self.num_actions}), got {tuple(actions.shape)}")
            self.buffers.actions.copy_(actions)
        if self._ocean is None:
            self._command("step")
            return
        self._command("step", self._ocean.parity, while_waiting=self._ocean.fill_next)
        self._ocean.advance()

    def reset(self, seed: int | None = None) -> None:
        """Start a new episode in every environment; with ``seed``, restart the batch from it (see
        :meth:`SailingEnv.reset`)."""
        if seed is not None:
            self.seed = require_int_in_range("ShardedSailingEnv.reset", "seed", seed, 0, 2**31 - 1)
        self._command("reset", seed)
        if seed is not None and self._ocean is not None:
            self._ocean.restart(0.0)  # the workers' clocks went back to zero

    @property
    def significant_wave_height(self) -> float:
        """The sea's significant wave height as the wave grid holds it [m] (every worker's is the same)."""
        return self._significant_wave_height

    def set_significant_wave_height(self, hs: float) -> float:
        """Every worker's sea (and the shared ocean's) to significant wave height ``hs`` [m] (see
        ``SailingEnv.set_significant_wave_height``); returns the wave height the grid holds."""
        if self._ocean is not None:
            self._ocean.ocean.set_significant_wave_height(hs)  # a bad hs raises here, before any worker changes
        self._significant_wave_height = self._command("wave_height", float(hs))[0]
        if self._ocean is not None:
            self._ocean.restart()
        return self._significant_wave_height

    def episode_log(self) -> dict[str, torch.Tensor]:
        """Statistics of the episodes that ended in the last step (see :func:`ocean_warp.envs.sailing_env.episode_log`)."""
        return episode_log(self.buffers)

    # --- life cycle ------------------------------------------------------------------------------------
    @property
    def closed(self) -> bool:
        return self._pool.closed

    def close(self) -> None:
        """Stop the workers and join them (terminating and killing stragglers). Idempotent."""
        self._finalizer()

    def __enter__(self) -> ShardedSailingEnv:
        return self

    def __exit__(self, *exc_info) -> None:
        self.close()

    def _command(self, command: str, argument: Any = None, while_waiting=None) -> list[Any]:
        """Send one command to every worker and wait for all of them, calling ``while_waiting()`` in
        between; on any failure, including Ctrl-C while waiting, every worker is stopped before the
        exception propagates."""
        if self._pool.closed:
            raise RuntimeError("ShardedSailingEnv is closed (its workers have been stopped)")
        try:
            self._pool.send_all((command, argument))
            if while_waiting is not None:
                while_waiting()
            return self._pool.gather(self.timeout)
        except BaseException:
            self.close()
            raise
