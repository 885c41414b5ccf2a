"""``ocean-warp train --gpus G``: start torchrun with G ranks on this host's GPUs, pass its output through,
forward Ctrl-C, and say in one line which rank failed (see :mod:`.distributed` for what each rank does)."""

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

__all__ = ["visible_gpus", "gpus_problem", "torchrun_command", "describe_failure", "launch"]


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
    if int_variable(environ, "WORLD_SIZE", 1) > 1:
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


def torchrun_command(argv: list[str], gpus: int, executable: str | None = None) -> list[str]:
    """The command that trains ``argv`` (``ocean-warp train``'s arguments) on ``gpus`` GPUs of this host:
    ``python -m torch.distributed.run --standalone --nproc_per_node=G -m ocean_warp.envs.training.train <argv without
    --gpus>``, with ``--device cuda`` added where ``argv`` names no device."""
    rest, skip = [], False
    for token in argv:
        if skip:
            skip = False
            continue
        name = token.split("=", 1)[0]
        if len(name) >= 3 and "--gpus".startswith(name):  # --gpus and its abbreviations (argparse takes them)
            skip = "=" not in token
            continue
        rest.append(token)
    if not any(t.split("=", 1)[0] in ("--device", "--dev", "--devi", "--devic") for t in rest):
        rest += ["--device", "cuda"]
    return [executable or sys.executable, "-m", "torch.distributed.run", "--standalone", f"--nproc_per_node={int(gpus)}",
            "-m", "ocean_warp.envs.training.train", *rest]


def describe_failure(output: str, status: int, gpus: int) -> str:
    """One line for a failed torchrun job, from the tail of its output (torchrun's failure summary names
    the first rank that failed) and its exit ``status``."""
    found = re.search(r"Root Cause.*?rank\s*:\s*(\d+).*?exitcode\s*:\s*(-?\d+)", output, re.S)
    if found is None:
        return f"training on {gpus} GPUs failed: torchrun exited with status {status}; the messages above say why"
    rank, code = int(found.group(1)), int(found.group(2))
    how = f"with status {code}"
    if code < 0:
        names = {s.value: s.name for s in signal.Signals}
        how = f"killed by signal {-code} ({names.get(-code, 'unknown')})"
    return (f"training on {gpus} GPUs failed: rank {rank} exited first, {how}, and torchrun stopped the others; "
            "the messages above say why")


def launch(command: list[str], gpus: int, *, grace_s: float = 60.0) -> int:
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
        print(f"ocean-warp train: {describe_failure(text, status, gpus)}", file=sys.stderr)
    return status
