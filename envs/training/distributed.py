"""Training one policy in several processes (ranks) with torch.distributed, the way torchrun starts them.

    torchrun --standalone --nproc_per_node=2 -m ocean_warp.envs.training.train --device cuda ...   # 2 GPUs
    torchrun --standalone --nproc_per_node=2 -m ocean_warp.envs.training.train --device cpu ...    # 2 CPU processes

torchrun tells each process who it is through the environment: ``RANK`` (0 .. W-1 over every host),
``LOCAL_RANK`` (its index on this host, which picks its GPU: ``cuda:LOCAL_RANK``), ``WORLD_SIZE`` (W),
``LOCAL_WORLD_SIZE`` (ranks on this host) and ``GROUP_RANK`` (this host's index). Several hosts run the same
command and meet at a rendezvous (``ocean-warp train --nnodes N --rdzv-endpoint HOST:PORT``, :mod:`.rendezvous`);
nothing else changes: the seed and the environments follow the global rank, the GPU the local one.
Each rank simulates its own batch of ``num_envs`` environments; rsl-rl's PPO averages the gradients
and the observation normalisers over the ranks (NCCL on GPUs, gloo on the CPU), so every rank holds
the same networks after each update.

What this module gives the trainer:

- :class:`RankContext`: rank, local rank and world size, read from torchrun's variables.
- :func:`rank_device`, :func:`rank_seed`, :meth:`RankContext.first_env`: each rank's device, torch seed
  and first environment index. Rank r's batch is environments [r N, (r + 1) N) of one batch of W N
  with the same environment seed (``SailingEnv(first_env=...)``: distinct random streams, starts and
  mass variants per rank); its torch seed (action sampling, minibatch order) is :func:`rank_seed`.
- :class:`Ranks`: the process groups and the few collectives the trainer adds to rsl-rl's (startup
  checks, the resumed checkpoint, per-iteration statistics and failures, random states for checkpoints,
  the end-of-training parameter check), each bounded by a timeout. A rank that fails between
  collectives is reported on every rank as a :class:`RankFailure` naming it.
- :class:`DistributedRunner`: rsl-rl's ``OnPolicyRunner`` configured from a :class:`RankContext`
  (any device, a timeout) instead of rsl-rl's own environment reading (CUDA and NCCL only, no timeout).

A world of one (no torchrun, or ``--nproc_per_node=1``) creates no process group and behaves exactly
as a plain single-process run.
"""

from __future__ import annotations

import dataclasses
import datetime
import hashlib
import os
import re
import signal
import socket
import time
from collections.abc import Mapping
from typing import Any

import numpy as np
import torch
from rsl_rl.runners import OnPolicyRunner

from .train_options import DEFAULT_TIMEOUT_S

__all__ = ["RankContext", "RankFailure", "Ranks", "DistributedRunner", "DEFAULT_TIMEOUT_S", "rank_device",
           "rank_seed", "derived_seed", "backend_for", "parameter_checksum", "inject_fault", "FAULT_VARIABLE"]


FAULT_VARIABLE = "OCEAN_WARP_FAULT"
"""Fault injection for tests: ``"<rank>:<iteration>:<kind>"`` makes that rank fail after collecting that
iteration; kind ``nan`` writes NaN into its rewards, ``kill`` sends itself SIGKILL, ``hang`` sleeps forever."""


class RankFailure(RuntimeError):
    """A rank failed, or lost contact with the others. ``everywhere``: every rank raises the same message
    (it came through a collective), so rank 0's copy is enough to show; else only this rank knows it."""

    def __init__(self, message: str, *, everywhere: bool = True):
        super().__init__(message)
        self.everywhere = everywhere


@dataclasses.dataclass(frozen=True)
class RankContext:
    """Who this process is among the ranks of one training job."""

    rank: int = 0
    """Global rank, 0 .. world_size - 1; rank 0 writes every file."""
    local_rank: int = 0
    """Index on this host: rank r uses ``cuda:local_rank``."""
    world_size: int = 1
    node_rank: int = 0
    """Index of this rank's host in the job (torchrun's ``GROUP_RANK``), 0 on a single host."""

    def __post_init__(self):
        for name in ("rank", "local_rank", "world_size", "node_rank"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int):
                raise ValueError(f"RankContext.{name} must be a whole number, got {value!r}")
        if self.world_size < 1:
            raise ValueError(f"WORLD_SIZE must be >= 1, got {self.world_size}")
        if not 0 <= self.rank < self.world_size:
            raise ValueError(f"RANK must be in 0..{self.world_size - 1} (WORLD_SIZE {self.world_size}), got {self.rank}")
        if not 0 <= self.local_rank < self.world_size:
            raise ValueError(f"LOCAL_RANK must be in 0..{self.world_size - 1} (WORLD_SIZE {self.world_size}), "
                             f"got {self.local_rank}")
        if not 0 <= self.node_rank < self.world_size:
            raise ValueError(f"GROUP_RANK (the host's index) must be in 0..{self.world_size - 1} "
                             f"(WORLD_SIZE {self.world_size}), got {self.node_rank}")

    @classmethod
    def from_env(cls, environ: Mapping[str, str] | None = None) -> RankContext:
        """The context torchrun describes in ``environ`` (default ``os.environ``); rank 0 of 1 without it.

        Raises:
            ValueError: a variable that is not a whole number, a rank outside the world, or RANK and
                LOCAL_RANK missing where WORLD_SIZE says there are several ranks.
        """
        environ = os.environ if environ is None else environ
        world_size = int_variable(environ, "WORLD_SIZE", 1)
        if world_size > 1:
            missing = [name for name in ("RANK", "LOCAL_RANK") if name not in environ]
            if missing:
                raise ValueError(f"WORLD_SIZE is {world_size} but {' and '.join(missing)} is not set: start the "
                                 "ranks with torchrun (it sets RANK, LOCAL_RANK and WORLD_SIZE)")
        context = cls(rank=int_variable(environ, "RANK", 0), local_rank=int_variable(environ, "LOCAL_RANK", 0),
                      world_size=world_size, node_rank=int_variable(environ, "GROUP_RANK", 0))
        local_world = environ.get("LOCAL_WORLD_SIZE")
        if local_world is not None and context.local_rank >= int_variable(environ, "LOCAL_WORLD_SIZE", 1):
            raise ValueError(f"LOCAL_RANK {context.local_rank} must be below LOCAL_WORLD_SIZE {local_world}")
        return context

    @property
    def distributed(self) -> bool:
        return self.world_size > 1

    @property
    def is_main(self) -> bool:
        """Rank 0: the one that logs, shows progress and writes files."""
        return self.rank == 0

    def first_env(self, num_envs: int) -> int:
        """Global index of this rank's first environment when every rank simulates ``num_envs``."""
        return self.rank * int(num_envs)


def int_variable(environ: Mapping[str, str], name: str, default: int) -> int:
    text = environ.get(name)
    if text is None:
        return default
    try:
        return int(text.strip())
    except ValueError:
        raise ValueError(f"environment variable {name}={text!r} is not a whole number (torchrun sets it; "
                         "check how the job was started)") from None


def rank_seed(seed: int, rank: int) -> int:
    """The torch seed of ``rank`` in a job seeded with ``seed``: ``seed`` itself on rank 0 (so a world of
    one seeds as a plain run does), else 31 bits of ``numpy.random.SeedSequence([seed, rank])``."""
    if rank == 0:
        return int(seed)
    return int(np.random.SeedSequence([int(seed), int(rank)]).generate_state(1)[0]) & 0x7FFFFFFF


def derived_seed(rank0_state: torch.Tensor, rank: int) -> int:
    """A torch seed for ``rank`` from rank 0's saved random state (a checkpoint resumed by a different number
    of ranks than trained it): :func:`rank_seed` of the state's SHA-256, so different per rank and
    reproducible."""
    digest = hashlib.sha256(rank0_state.cpu().numpy().tobytes()).digest()
    return rank_seed(int.from_bytes(digest[:4], "little"), rank)


def rank_device(context: RankContext, device: str) -> str:
    """This rank's device for a requested ``device``: "cpu" stays; with several ranks, "cuda" becomes
    ``cuda:LOCAL_RANK``, and "cuda:N" must be that device. One rank: ``device`` unchanged.

    Raises:
        ValueError: "cuda:N" that is not this rank's GPU.
    """
    device = str(device)
    if not context.distributed or not device.startswith("cuda"):
        return device
    expected = f"cuda:{context.local_rank}"
    if device not in ("cuda", expected):
        raise ValueError(f"rank {context.rank} (local rank {context.local_rank}) trains on {expected}, not {device}: "
                         "pass --device cuda and let each rank take its own GPU")
    return expected


def backend_for(device: str) -> str:
    """torch.distributed backend for the ranks' device: NCCL between GPUs, gloo between CPU processes."""
    return "nccl" if str(device).startswith("cuda") else "gloo"


def parameter_checksum(*state_dicts: Mapping[str, torch.Tensor]) -> str:
    """SHA-256 of state dicts (parameters and buffers: normaliser statistics too), in key order."""
    digest = hashlib.sha256()
    for state in state_dicts:
        for name, tensor in sorted(state.items()):
            digest.update(name.encode())
            digest.update(tensor.detach().cpu().contiguous().numpy().tobytes())
    return digest.hexdigest()


class Ranks:
    """The ranks of a job, seen from one of them: its :class:`RankContext` and the collectives the
    trainer needs. Start with :meth:`start`; every method is a collective (each rank calls it at the same
    point) except :meth:`close`. With one rank nothing is communicated."""

    def __init__(self, context: RankContext, backend: str | None = None, timeout_s: float = DEFAULT_TIMEOUT_S,
                 control=None):
        self.context = context
        self.backend = backend
        """"nccl" or "gloo"; None for one rank."""
        self.timeout_s = timeout_s
        self._control = control

    @classmethod
    def start(cls, context: RankContext, device: str, timeout_s: float = DEFAULT_TIMEOUT_S) -> Ranks:
        """Join the job's process group (none for one rank): backend :func:`backend_for` ``device``, every
        collective bounded by ``timeout_s``; a gloo group beside an NCCL one carries the trainer's own small
        messages (they are host objects, and a rank whose GPU is unusable can still report it).

        NCCL errors and timeouts abort the communicator and the process (TORCH_NCCL_ASYNC_ERROR_HANDLING=1,
        unless set otherwise), so a rank never waits forever on a dead peer.
        """
        if not (isinstance(timeout_s, (int, float)) and np.isfinite(timeout_s) and timeout_s > 0):
            raise ValueError(f"the distributed timeout must be a positive number of seconds, got {timeout_s!r}")
        if not context.distributed:
            return cls(context, None, timeout_s)
        backend = backend_for(device)
        if backend == "nccl" and not (torch.cuda.is_available() and torch.distributed.is_nccl_available()):
            raise ValueError(f"device {device!r} with {context.world_size} ranks needs a CUDA build of torch with "
                             f"NCCL; this one is {torch.__version__} and sees {torch.cuda.device_count()} GPU(s)")
        os.environ.setdefault("TORCH_NCCL_ASYNC_ERROR_HANDLING", "1")
        timeout = datetime.timedelta(seconds=float(timeout_s))
        dist = torch.distributed
        if not dist.is_initialized():
            dist.init_process_group(backend=backend, rank=context.rank, world_size=context.world_size,
                                    timeout=timeout)
        control = dist.new_group(backend="gloo", timeout=timeout) if backend == "nccl" else dist.group.WORLD
        return cls(context, backend, timeout_s, control)

    @property
    def distributed(self) -> bool:
        return self.context.distributed

    def gather(self, value: Any) -> list[Any]:
        """Every rank's ``value`` (picklable), in rank order, on every rank."""
        if not self.distributed:
            return [value]
        values: list[Any] = [None] * self.context.world_size
        self._collective(torch.distributed.all_gather_object, values, value, group=self._control)
        return values

    def broadcast(self, value: Any) -> Any:
        """Rank 0's ``value`` (picklable), on every rank."""
        if not self.distributed:
            return value
        box = [value if self.context.is_main else None]
        self._collective(torch.distributed.broadcast_object_list, box, src=0, group=self._control)
        return box[0]

    def check(self, error: BaseException | str | None, when: str) -> None:
        """Raise :class:`RankFailure` on every rank if any rank passes an ``error`` (what it caught, or a
        message); ``when`` says where, e.g. "at startup". With one rank, its own error is raised as it is."""
        if not self.distributed and error is not None:
            raise error if isinstance(error, BaseException) else RankFailure(f"failed {when}: {error}")
        message = None if error is None else (error if isinstance(error, str) else _describe(error))
        failures = [(rank, text) for rank, text in enumerate(self.gather(message)) if text is not None]
        if failures:
            raise RankFailure(_failure_message(failures, when))

    def gather_iteration(self, error: BaseException | None, values: list[float], when: str) -> list[float]:
        """One collective per iteration: raise :class:`RankFailure` if any rank failed, else the sums of
        ``values`` over the ranks (added in rank order, so every rank gets the same floats)."""
        if not self.distributed:
            if error is not None:
                raise error
            return list(values)
        gathered = self.gather((None if error is None else _describe(error), [float(v) for v in values]))
        failures = [(rank, text) for rank, (text, _) in enumerate(gathered) if text is not None]
        if failures:
            raise RankFailure(_failure_message(failures, when))
        totals = [0.0] * len(values)
        for _, numbers in gathered:
            totals = [total + number for total, number in zip(totals, numbers)]
        return totals

    def close(self) -> None:
        """Leave the process group (after a successful run; a failed one exits and torchrun cleans up)."""
        if self.distributed and torch.distributed.is_initialized():
            torch.distributed.destroy_process_group()

    def _collective(self, function, *args, **kwargs) -> None:
        try:
            function(*args, **kwargs)
        except RuntimeError as error:  # gloo: peer closed the connection, or the timeout passed
            first_line = re.sub(r"^\[[^\]]*\]\s*", "", (str(error).strip().splitlines() or [type(error).__name__])[0])
            first_line = first_line.split(". This is typically")[0]  # gloo's generic advice
            raise RankFailure(f"rank {self.context.rank} lost contact with the other ranks (one failed, was killed "
                              f"or is stuck for more than the {self.timeout_s:g} s timeout): {first_line}",
                              everywhere=False) from error


def _failure_message(failures: list[tuple[int, str]], when: str) -> str:
    """"rank 1 failed at iteration 3: ..." (ranks with the same message named together)."""
    by_text: dict[str, list[int]] = {}
    for rank, text in failures:
        by_text.setdefault(text, []).append(rank)
    parts = []
    for text, ranks in by_text.items():
        who = f"rank {ranks[0]}" if len(ranks) == 1 else f"ranks {', '.join(map(str, ranks))}"
        parts.append(f"{who} failed {when}: {text}")
    return "; ".join(parts)


def _describe(error: BaseException) -> str:
    first_line = (str(error).strip().splitlines() or [""])[0]
    return f"{type(error).__name__}: {first_line}" if first_line else type(error).__name__


class DistributedRunner(OnPolicyRunner):
    """rsl-rl's ``OnPolicyRunner`` for the ranks of :class:`RankContext` ``context``: any device (CUDA
    with NCCL, the CPU with gloo), the process group joined with a timeout if the caller has not done so
    (:meth:`Ranks.start`), and rsl-rl's multi-GPU settings (gradient and normaliser averaging, logging on
    rank 0 only) from the context rather than from the environment."""

    def __init__(self, env, train_cfg: dict, log_dir: str | None = None, device: str = "cpu", *,
                 context: RankContext, timeout_s: float = DEFAULT_TIMEOUT_S):
        self._context = context
        self._timeout_s = timeout_s
        super().__init__(env, train_cfg, log_dir=log_dir, device=device)

    def _configure_multi_gpu(self) -> None:
        context = self._context
        self.gpu_world_size = context.world_size
        self.is_distributed = context.distributed
        self.gpu_local_rank = context.local_rank
        self.gpu_global_rank = context.rank
        if not context.distributed:
            self.cfg["multi_gpu"] = None
            return
        self.cfg["multi_gpu"] = {"global_rank": context.rank, "local_rank": context.local_rank,
                                 "world_size": context.world_size}
        device = rank_device(context, self.device)
        if device != self.device:
            raise ValueError(f"rank {context.rank}: runner device {self.device!r}, expected {device!r}")
        Ranks.start(context, device, self._timeout_s)  # joins only if not joined yet
        if device.startswith("cuda"):
            torch.cuda.set_device(torch.device(device))


def _parse_fault(text: str) -> tuple[int, int, str]:
    try:
        rank, iteration, kind = text.split(":")
        parsed = int(rank), int(iteration), kind.strip()
    except ValueError:
        parsed = None
    if parsed is None or parsed[2] not in ("nan", "kill", "hang"):
        raise ValueError(f"{FAULT_VARIABLE}={text!r}: expected <rank>:<iteration>:nan|kill|hang")
    return parsed


def inject_fault(context: RankContext, iteration: int, rewards: torch.Tensor) -> None:
    """Test hook (fault injection), a no-op unless :data:`FAULT_VARIABLE` names this rank and ``iteration``:
    then "nan" fills ``rewards`` (the rollout's) with NaN, "kill" sends this process SIGKILL, "hang"
    sleeps until killed."""
    text = os.environ.get(FAULT_VARIABLE)
    if not text:
        return
    rank, when, kind = _parse_fault(text)
    if rank != context.rank or when != iteration:
        return
    if kind == "nan":
        rewards.fill_(float("nan"))
    elif kind == "kill":
        os.kill(os.getpid(), signal.SIGKILL)
    else:
        while True:
            time.sleep(3600)


def host_name() -> str:
    """This host's name (recorded per rank: ranks may run on several hosts)."""
    return socket.gethostname()
