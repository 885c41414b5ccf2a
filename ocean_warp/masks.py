"""Host-side helpers that turn index lists into the per-item masks the device reset kernels read.

The device path of every reset takes a mask (N,) int32 and per-item rows (N, ...): nothing built on the
host, so it can run inside a captured CUDA graph. The host paths (``reset(indices, ...)``) build such a
mask and rows once here and call the same kernels, so each reset has one home.
"""

from __future__ import annotations

import numpy as np
import warp as wp

__all__ = ["mask_of", "rows_at"]


def mask_of(indices: np.ndarray, count: int, device) -> wp.array:
    """(count,) int32 device array: 1 at ``indices``, 0 elsewhere."""
    mask = np.zeros(count, dtype=np.int32)
    mask[np.asarray(indices, dtype=np.int64)] = 1
    return wp.array(mask, dtype=wp.int32, device=device)


def rows_at(indices: np.ndarray, values, count: int) -> np.ndarray:
    """(count, ...) float32 host array holding ``values`` (one row per index) at ``indices``, zeros elsewhere."""
    values = np.asarray(values, dtype=np.float32)
    full = np.zeros((count,) + values.shape[1:], dtype=np.float32)
    full[np.asarray(indices, dtype=np.int64)] = values
    return full
