"""Row pass of a 2-D inverse FFT built on ``wp.tile_ifft`` (unnormalised: x[m] = sum_k X[k] e^{+2 pi i k m / N}).

A 2-D transform is two row passes, the second over a transposed view (``array.transpose()``) of the
first one's output: its rows are the columns of the array behind it, so no transpose is ever written.
Complex numbers are ``wp.vec2f`` (real, imaginary).

Tile shapes are compile-time constants, so each size gets its own kernel from a cached factory;
launch with ``wp.launch_tiled(kernel, dim=[rows], block_dim=...)``, one block per row.
"""

from __future__ import annotations

import functools

import warp as wp

__all__ = ["ifft_rows_kernel"]


@functools.cache
def ifft_rows_kernel(n: int):
    """Kernel ``(src, dst)``: inverse FFT of each row of ``src`` (rows, n) into the same row of ``dst``.
    ``src`` may be a strided view, such as the transpose of a (n, rows) array."""

    @wp.kernel(enable_backward=False, module="unique")
    def ifft_rows(src: wp.array2d(dtype=wp.vec2f), dst: wp.array2d(dtype=wp.vec2f)):
        row = wp.tid()
        values = wp.tile_load(src, shape=(1, n), offset=(row, 0))
        wp.tile_ifft(values)
        wp.tile_store(dst, values, offset=(row, 0))

    return ifft_rows
