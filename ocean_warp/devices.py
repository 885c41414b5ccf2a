"""Warp devices for the commands: starting Warp quietly where there is no GPU, and checking a device name.

- :func:`init_warp`: start Warp. Where no NVIDIA driver can be loaded, Warp's native library prints "Warp CUDA
  warning: Could not find or load the NVIDIA CUDA driver. GPU execution will not be available." straight onto
  the process's stderr (file descriptor 2, from C: no Warp setting or logger silences it). On such a machine
  every command would start with that line, so Warp is started with descriptor 2 read into a temporary file,
  and everything it wrote there except that one line is written back to stderr: any other warning or error
  still shows. Where a driver loads, Warp starts untouched.
- :func:`resolve_device`: a device name ("cpu", "cuda", "cuda:N", or None for Warp's preferred device)
  checked against the devices Warp sees, with one-line errors.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import re
import sys
import tempfile

__all__ = ["NO_DRIVER_WARNING", "DEVICE_FORMS", "cuda_driver_loadable", "init_warp", "resolve_device",
           "stderr_without"]

NO_DRIVER_WARNING = "Warp CUDA warning: Could not find or load the NVIDIA CUDA driver."
"""How the line Warp prints where no NVIDIA driver loads begins (warp/native/cuda_util.cpp)."""

DEVICE_FORMS = '"auto" (the first GPU where Warp sees one, else the CPU), "cpu", "cuda" (the first GPU) or "cuda:N"'
"""The device names the commands take, in words."""

_DRIVER_LIBRARIES = ("nvcuda.dll",) if sys.platform == "win32" else ("libcuda.so", "libcuda.so.1")
"""The names Warp loads the NVIDIA driver by, in its order."""


def cuda_driver_loadable() -> bool:
    """Whether the NVIDIA CUDA driver library loads here, as Warp loads it (by the same names)."""
    for name in _DRIVER_LIBRARIES:
        try:
            ctypes.CDLL(name)
        except OSError:
            continue
        return True
    return False


@contextlib.contextmanager
def stderr_without(prefix: str):
    """Inside: what anything (C code included) writes to file descriptor 2 goes to a temporary file; on leaving
    (also on an exception) it is written back to descriptor 2, less the lines that begin with ``prefix``.
    Where descriptor 2 cannot be duplicated (closed), nothing is redirected."""
    try:
        saved = os.dup(2)
    except OSError:
        yield
        return
    with tempfile.TemporaryFile() as captured:
        with contextlib.suppress(Exception):
            sys.stderr.flush()
        os.dup2(captured.fileno(), 2)
        try:
            yield
        finally:
            with contextlib.suppress(Exception):
                sys.stderr.flush()
            os.dup2(saved, 2)
            os.close(saved)
            captured.seek(0)
            kept = [line for line in captured.read().splitlines(keepends=True)
                    if not line.startswith(prefix.encode())]
            if kept:
                os.write(2, b"".join(kept))


def init_warp() -> None:
    """Start Warp (``wp.init()``; nothing when it has started already), without its no-driver warning where no
    NVIDIA driver loads (see the module docstring); other lines it writes to stderr still show."""
    import warp as wp

    if cuda_driver_loadable():
        wp.init()
        return
    with stderr_without(NO_DRIVER_WARNING):
        wp.init()


def resolve_device(device: str | None, *, name: str = "device") -> str:
    """The Warp device ``device`` names, checked against the devices Warp sees: "cpu"; "cuda" (returned as
    "cuda:0") or "cuda:N" where Warp sees at least N + 1 GPUs; None or "auto": Warp's preferred device
    ("cuda:0" where there is a GPU, else "cpu"). Starts Warp (:func:`init_warp`).

    Args:
        name: what the device is called in errors (a command passes its option, "--device").

    Raises:
        ValueError: another form, or a GPU that Warp does not see; one line naming ``name`` and the value.
    """
    init_warp()
    import warp as wp

    text = None if device is None else str(device).strip()
    if text is None or text == "auto":
        return str(wp.get_preferred_device())
    if text == "cpu":
        return text
    match = re.fullmatch(r"cuda(?::(\d+))?", text, flags=re.ASCII)
    if match is None:
        raise ValueError(f"{name} must be {DEVICE_FORMS}, got {device!r}")
    index = int(match.group(1) or 0)
    count = wp.get_cuda_device_count()
    if count == 0:
        why = "no NVIDIA driver loads here" if not cuda_driver_loadable() else "Warp sees no CUDA device"
        raise ValueError(f"{name} {device!r}: this machine has no usable GPU ({why}); use cpu")
    if index >= count:
        raise ValueError(f"{name} {device!r}: Warp sees {count} GPU{'s' if count > 1 else ''} "
                         f"(cuda:0{f' ... cuda:{count - 1}' if count > 1 else ''})")
    return f"cuda:{index}"
