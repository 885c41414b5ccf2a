"""``ocean-warp train --gpus G`` (and ``--nnodes N``): start torchrun with G ranks on this host's GPUs (and join
the other hosts' at the rendezvous, :mod:`.rendezvous`), pass its output through, forward Ctrl-C, and say in one
line which rank failed (see :mod:`.distributed` for what each rank does)."""

from __future__ import annotations

import collections
import os
import re
import signal
import subprocess
import sys
import threading
from collections.abc import Mapping

import torch

from ocean_warp.termination import Terminated

from .distributed import int_variable
from .rendezvous import Rendezvous
from .train_options import parser as _parser

__all__ = ["visible_gpus", "gpus_problem", "hosts_problem", "torchrun_command", "job_label", "describe_failure",
           "launch"]

LAUNCHER_OPTIONS = ("--gpus", "--nnodes", "--node-rank", "--rdzv-endpoint", "--rdzv-id")
"""The options the launcher consumes: the ranks it starts never see them."""


def visible_gpus() -> int:
    """GPUs torch can use here (after CUDA_VISIBLE_DEVICES); 0 with a CPU build of torch."""
    return torch.cuda.device_count() if torch.cuda.is_available() else 0


def gpus_problem(gpus: str, device: str | None, visible: int, environ: Mapping[str, str] | None = None) -> str | None:
    """Why ``--gpus gpus`` cannot run with ``--device device`` (None: not given) when ``visible`` GPUs are
    visible, in one line; None when it can."""
    environ = os.environ if environ is None else environ
    try:
        count = int(str(gpus).strip())
    except ValueError:
        return f"--gpus must be a whole number of GPUs >= 1, got {gpus!r}"
    if count < 1:
        return f"--gpus must be a whole number of GPUs >= 1, got {count}"
    if _under_torchrun(environ):
        return "--gpus starts torchrun itself: leave it out when torchrun starts the ranks"
    if device is not None and device != "cuda":
        if device.startswith("cuda"):
            return f"--gpus gives each rank a GPU of its own: use --device cuda (or leave --device out), not {device}"
        return (f"--gpus trains on GPUs: use --device cuda (or leave --device out), not {device}; for several CPU "
                "processes start torchrun yourself: torchrun --standalone --nproc_per_node=N "
                "-m ocean_warp.envs.training.train --device cpu ...")
    if count > visible:
        return f"--gpus {count}: only {visible} GPU(s) visible to torch here (CUDA_VISIBLE_DEVICES, drivers?)"
    return None


def hosts_problem(device: str | None, gpus: str | None, environ: Mapping[str, str] | None = None) -> str | None:
    """Why ``--nnodes`` cannot start with ``--device device`` and ``--gpus gpus`` (None: not given), in one line;
    None when it can (``--gpus`` itself is checked by :func:`gpus_problem`)."""
    environ = os.environ if environ is None else environ
    if _under_torchrun(environ):
        return "--nnodes starts torchrun itself: leave it out when torchrun starts the ranks"
    if gpus is None and device is not None and device.startswith("cuda:"):
        return f"--nnodes: each rank takes the GPU of its local rank: use --device cuda, not {device}"
    return None


def _under_torchrun(environ: Mapping[str, str]) -> bool:
    return int_variable(environ, "WORLD_SIZE", 1) > 1 or "TORCHELASTIC_RUN_ID" in environ


def torchrun_command(argv: list[str], ranks_per_node: int, executable: str | None = None, *,
                     rendezvous: Rendezvous | None = None, on_gpus: bool = True) -> list[str]:
    """The command that trains ``argv`` (``ocean-warp train``'s arguments) with ``ranks_per_node`` ranks on this
    host: ``python -m torch.distributed.run --standalone --nproc_per_node=G -m ocean_warp.envs.training.train
    <argv without the launcher's options>``; with a ``rendezvous``, its arguments
    (:meth:`Rendezvous.torchrun_arguments`) instead of ``--standalone``. ``on_gpus``: ``--device cuda`` is added
    where ``argv`` names no device."""
    options = [option for action in _parser()._actions for option in action.option_strings]
    rest, skip = [], False
    for token in argv:
        if skip:
            skip = False
            continue
        name = _option_name(token, options)
        if name in LAUNCHER_OPTIONS:
            skip = "=" not in token
            continue
        rest.append(token)
    if on_gpus and not any(_option_name(token, options) == "--device" for token in rest):
        rest += ["--device", "cuda"]
    meeting = ["--standalone"] if rendezvous is None else rendezvous.torchrun_arguments()
    return [executable or sys.executable, "-m", "torch.distributed.run", *meeting,
            f"--nproc_per_node={int(ranks_per_node)}", "-m", "ocean_warp.envs.training.train", *rest]


def _option_name(token: str, options: list[str]) -> str | None:
    """The option argparse reads ``token`` as (``--name``, ``--name=value`` or an unambiguous prefix of a long
    option, as argparse accepts); None for a value."""
    name = token.split("=", 1)[0]
    if not name.startswith("--"):
        return None
    if name in options:
        return name
    matches = [option for option in options if option.startswith("--") and option.startswith(name)]
    return matches[0] if len(matches) == 1 else None


def job_label(ranks_per_node: int, on_gpus: bool, rendezvous: Rendezvous | None = None) -> str:
    """What a launch trains on, for its failure line: "training on 2 GPUs", "training on 2 hosts (4 GPUs on
    this one)"."""
    here = f"{ranks_per_node} GPU{'s' if ranks_per_node != 1 else ''}" if on_gpus else \
        f"{ranks_per_node} rank{'s' if ranks_per_node != 1 else ''}"
    if rendezvous is None:
        return f"training on {here}"
    return f"training on {rendezvous.nnodes} hosts ({here} on this one)"


def describe_failure(output: str, status: int, job: str) -> str:
    """One line for a failed torchrun ``job`` (:func:`job_label`), from the tail of its output (torchrun's failure
    summary names the first rank that failed) and its exit ``status``."""
    found = re.search(r"Root Cause.*?rank\s*:\s*(\d+).*?exitcode\s*:\s*(-?\d+)", output, re.S)
    if found is None:
        return f"{job} failed: torchrun exited with status {status}; the messages above say why"
    rank, code = int(found.group(1)), int(found.group(2))
    how = f"with status {code}"
    if code < 0:
        names = {s.value: s.name for s in signal.Signals}
        how = f"killed by signal {-code} ({names.get(-code, 'unknown')})"
    return (f"{job} failed: rank {rank} exited first, {how}, and torchrun stopped the others; "
            "the messages above say why")


def launch(command: list[str], job: str, *, grace_s: float = 60.0) -> int:
    """Run ``command`` (:func:`torchrun_command`), its output passed through; on a non-zero exit print one
    line (:func:`describe_failure`) to stderr. Ctrl-C (SIGTERM) is forwarded to torchrun as SIGINT (SIGTERM),
    which stops the ranks (rank 0 saves its last iteration), then re-raised once it has exited (after ``grace_s``
    it is terminated). Returns torchrun's status."""
    env = dict(os.environ)
    env.setdefault("OMP_NUM_THREADS", "1")  # what torchrun would set, without its warning banner
    # Its own session: a terminal's Ctrl-C reaches this process only, which forwards it exactly once.
    process = subprocess.Popen(command, stderr=subprocess.PIPE, env=env, start_new_session=True)
    tail: collections.deque[bytes] = collections.deque(maxlen=256)

    def pump() -> None:
        sink = getattr(sys.stderr, "buffer", None)
        while chunk := os.read(process.stderr.fileno(), 4096):
            tail.append(chunk)
            if sink is not None:
                sink.write(chunk)
                sink.flush()
            else:
                sys.stderr.write(chunk.decode(errors="replace"))

    reader = threading.Thread(target=pump, daemon=True)
    reader.start()
    try:
        status = process.wait()
    except (KeyboardInterrupt, Terminated) as stop:
        process.send_signal(signal.SIGINT if isinstance(stop, KeyboardInterrupt) else signal.SIGTERM)
        try:
            process.wait(grace_s)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
        reader.join(5.0)
        raise
    reader.join(5.0)
    if status != 0:
        text = b"".join(tail).decode(errors="replace")
        print(f"ocean-warp train: {describe_failure(text, status, job)}", file=sys.stderr)
    return status
