"""A fixed sequence of Warp launches, captured once as a graph and replayed, on CUDA and on the CPU.

On CUDA the capture is a CUDA graph: one replay costs the host a few microseconds, whatever the number
of launches. On the CPU Warp (1.19 and later) records the launches, copies and fills into a stream
that it replays in C++; a plain CPU launch costs tens of microseconds of Python, which at hundreds of
small launches a decision was most of a small batch's time (``benchmarks/RESULTS.md``).

The launches must be capture-safe: no allocation, no host read-back, no Python value that changes
between calls (keep such values in device arrays).
"""

from __future__ import annotations

from typing import Callable

import warp as wp

__all__ = ["ReplayedLaunches"]


class ReplayedLaunches:
    """Call to run ``launches``: captured on the first call and replayed afterwards, or (with
    ``capture=False``) launched anew on every call, for debugging and for comparison."""

    def __init__(self, launches: Callable[[], None], device, *, capture: bool = True):
        self.launches = launches
        self.device = wp.get_device(device)
        self.capture = bool(capture)
        self.graph: wp.Graph | None = None
        """The captured graph, after the first call (None without capture)."""

    def __call__(self) -> None:
        if not self.capture:
            self.launches()
            return
        if self.graph is None:
            with wp.ScopedCapture(device=self.device) as capture:
                self.launches()
            self.graph = capture.graph
        wp.capture_launch(self.graph)
