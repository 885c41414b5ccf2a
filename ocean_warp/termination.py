"""SIGTERM ends a job as Ctrl-C does: the stack unwinds, so every ``atomic_output`` and ``StageFile`` removes
its temporary file, and the process exits with status 143 (128 + SIGTERM, what a shell reports for a job it
killed) after one line on stderr.

Without a handler SIGTERM kills the process at once: no ``finally`` runs and a hidden temporary file (a
stage being written can be megabytes) is left beside the output.
"""

from __future__ import annotations

import signal
import sys
import threading

__all__ = ["TERMINATED_STATUS", "Terminated", "exit_cleanly_on_sigterm"]

TERMINATED_STATUS = 128 + signal.SIGTERM
"""The exit status after SIGTERM: 143 on Linux."""


class Terminated(SystemExit):
    """Raised in the main thread when SIGTERM arrives. A ``SystemExit`` (status 143), so ``except Exception``
    does not swallow it, cleanup written as ``except BaseException``/``finally`` runs, and the interpreter
    exits with its status and no traceback."""

    def __init__(self) -> None:
        super().__init__(TERMINATED_STATUS)


def exit_cleanly_on_sigterm(argv: list[str] | None = None) -> bool:
    """Make SIGTERM raise :class:`Terminated` in the main thread, after one line on stderr naming the job
    (``argv[0]``, the job's name on the ``ocean-warp`` command line). A second SIGTERM while the first
    unwinds is ignored, so that cleanup is not cut short. Returns False (and installs nothing) outside the
    main thread, where Python allows no signal handler."""
    if threading.current_thread() is not threading.main_thread():
        return False
    job = f"ocean-warp {argv[0]}" if argv and not argv[0].startswith("-") else "ocean-warp"

    def terminate(signum, frame):
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        print(f"{job}: terminated; files written before it are complete", file=sys.stderr, flush=True)
        raise Terminated()

    signal.signal(signal.SIGTERM, terminate)
    return True
