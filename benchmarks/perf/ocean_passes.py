"""Where an ocean update's time goes on CUDA: each FFT pass alone, against a plain copy of the same
bytes in the same tile shapes (the memory floor of each access pattern).

    python -m benchmarks.perf.ocean_passes --sizes 512 1024
"""

from __future__ import annotations

import argparse
import functools
import logging

import warp as wp


from benchmarks.perf.bench_ocean import sea
from benchmarks.perf.timing import median_seconds_warp_graph
from ocean_warp import Ocean
from ocean_warp.kernels.ocean_spectrum import packed_spectra


@functools.cache
def copy_rows_kernel(n: int):
    """Copies n packed cells per row through a shared tile (Warp's vectorised path)."""

    @wp.kernel(enable_backward=False, module="unique")
    def copy_rows(src: wp.array2d(dtype=packed_spectra), dst: wp.array2d(dtype=packed_spectra)):
        row = wp.tid()
        values = wp.tile_load(src, shape=(1, n), offset=(row, 0), storage="shared")
        wp.tile_store(dst, values, offset=(row, 0))

    return copy_rows


@functools.cache
def copy_columns_kernel(n: int):
    """Copies column strips (n, 2) of a (n, 2 n) vec4f array, as pass 2 reads them, into rows."""

    @wp.kernel(enable_backward=False, module="unique")
    def copy_columns(src: wp.array2d(dtype=wp.vec4f), dst: wp.array2d(dtype=wp.vec4f)):
        column = wp.tid()
        strip = wp.tile_load(src, shape=(n, 2), offset=(0, 2 * column), storage="shared")
        wp.tile_store(dst, strip, offset=(0, 2 * column))

    return copy_columns


def time_launch(launch, device) -> float:
    """Median time [us] of one captured replay of ``launch``."""
    launch()
    with wp.ScopedCapture(device=device) as capture:
        launch()
    return median_seconds_warp_graph(capture.graph, device) * 1e6


def breakdown(n: int, device) -> None:
    ocean = Ocean(sea(n), device=device)
    block_dim = ocean.fft_plan.block_dim
    scratch = wp.empty_like(ocean._spectra)

    def along_y():
        wp.launch_tiled(ocean._along_y, dim=[n], inputs=[ocean._cells, ocean.time, ocean._spectra],
                        block_dim=block_dim, device=device)

    def along_x():
        wp.launch_tiled(ocean._along_x, dim=[n], inputs=[ocean._spectra_quads, ocean._field_rows],
                        block_dim=block_dim, device=device)

    def copy_contiguous():
        wp.launch_tiled(copy_rows_kernel(n), dim=[n], inputs=[ocean._spectra], outputs=[scratch],
                        block_dim=block_dim, device=device)

    scratch_quads = wp.empty_like(ocean._spectra_quads)

    def copy_strided():
        wp.launch_tiled(copy_columns_kernel(n), dim=[n], inputs=[ocean._spectra_quads], outputs=[scratch_quads],
                        block_dim=block_dim, device=device)

    megabytes = 2 * n * n * 32 / 1e6
    full, first, second = (time_launch(f, device) for f in (ocean.update, along_y, along_x))
    contiguous, strided = time_launch(copy_contiguous, device), time_launch(copy_strided, device)
    print(f"n={n} block_dim={block_dim}: update {full:.1f} us = along y {first:.1f} + along x {second:.1f} us; "
          f"copy of {megabytes:.0f} MB: rows {contiguous:.1f} us ({megabytes / contiguous:.2f} TB/s), "
          f"columns {strided:.1f} us ({megabytes / strided:.2f} TB/s)", flush=True)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--sizes", type=int, nargs="+", default=[512])
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    for n in args.sizes:
        breakdown(n, wp.get_device("cuda:0"))


if __name__ == "__main__":
    main()
