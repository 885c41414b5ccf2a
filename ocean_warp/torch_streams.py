"""Ordering Warp's work with torch's on a CUDA device.

Warp launches on a stream of its own; torch works on its current stream. Through the zero-copy views
(``Fleet.tensors``) both touch the same memory, so a torch write followed by a Warp launch, or a Warp
launch followed by a torch read, needs the two streams ordered. :func:`ordered_with_torch` does that
with events only (no host synchronisation): Warp's stream waits for torch's on entry, torch's waits
for Warp's on exit. Without torch initialised on CUDA it does nothing.
"""

from __future__ import annotations

import contextlib
import sys

import warp as wp

__all__ = ["ordered_with_torch"]


def _torch_stream(device):
    torch = sys.modules.get("torch")
    if torch is None or not device.is_cuda or not torch.cuda.is_initialized():
        return None
    return wp.stream_from_torch(torch.cuda.current_stream(torch.device("cuda", device.ordinal)))


@contextlib.contextmanager
def ordered_with_torch(device):
    """Run the block's Warp launches on ``device`` after torch's pending work, and torch's later work
    after them."""
    device = wp.get_device(device)
    torch_stream = _torch_stream(device)
    if torch_stream is None:
        yield
        return
    warp_stream = device.stream
    warp_stream.wait_stream(torch_stream)
    try:
        yield
    finally:
        torch_stream.wait_stream(warp_stream)
