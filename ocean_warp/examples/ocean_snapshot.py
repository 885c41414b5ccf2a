"""Example: a JONSWAP sea, advanced in time, with a picture of its surface and its spectrum.

    ocean-warp ocean --out out/ocean          # or: python -m ocean_warp.examples.ocean_snapshot --out out/ocean

Writes ``ocean_height.png`` (the height field at the last time) and ``ocean_spectrum.png`` (the
spectrum the sea was drawn from against the one measured on the evolving grid).
"""

from __future__ import annotations

import logging
import math
import os
import sys
import time

import numpy as np
import warp as wp

from ocean_warp import Ocean, OceanConfig, spectra
from ocean_warp.atomic_files import save_figure
from ocean_warp.cli_support import (
    check_options,
    checked_device,
    checked_output_folder,
    finite_above,
)
from ocean_warp.ocean_config import (MAX_RESOLUTION, MIN_RESOLUTION, SIGNIFICANT_WAVE_HEIGHT_RULE,
                                    is_valid_significant_wave_height)

from .ocean_snapshot_options import parser as _parser


def measured_frequency_spectrum(heights: list[np.ndarray], config: OceanConfig, bin_width: float):
    """Frequency spectrum [m^2 s/rad] of height snapshots: each Fourier mode's variance, put in the
    frequency bin of its wavenumber (dispersion relation), averaged over the snapshots."""
    n = config.resolution
    k_axis = 2 * math.pi * np.fft.fftfreq(n, d=config.cell_size)
    k = np.hypot(*np.meshgrid(k_axis, k_axis))
    omega = spectra.dispersion_omega(k, config.depth, config.water.gravity)
    bins = np.floor(omega / bin_width).astype(np.int64)
    variance = sum(np.abs(np.fft.fft2(h)) ** 2 for h in heights) / (len(heights) * float(n) ** 4)
    per_bin = np.bincount(bins.ravel(), weights=variance.ravel())
    centres = (np.arange(per_bin.size) + 0.5) * bin_width
    return centres, per_bin / bin_width


def save_height_png(ocean: Ocean, path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    height = ocean.field_numpy("height")
    extent = [0.0, ocean.config.tile_size, 0.0, ocean.config.tile_size]
    limit = float(np.abs(height).max())
    fig, ax = plt.subplots(figsize=(6.4, 5.4))
    image = ax.imshow(height, origin="lower", extent=extent, cmap="RdBu_r", vmin=-limit, vmax=limit)
    fig.colorbar(image, ax=ax, label="surface height [m]")
    ax.set_xlabel("x (east) [m]")
    ax.set_ylabel("y (north) [m]")
    t = float(ocean.time.numpy()[0])
    ax.set_title(f"JONSWAP Hs {ocean.config.significant_wave_height} m, Tp {ocean.config.peak_period} s, t = {t:.1f} s")
    fig.tight_layout()
    save_figure(fig, path, dpi=110)


def save_spectrum_png(config: OceanConfig, heights: list[np.ndarray], path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    omega_peak = 2 * math.pi / config.peak_period
    centres, measured = measured_frequency_spectrum(heights, config, bin_width=0.04 * omega_peak)
    omega = np.linspace(0.2 * omega_peak, 4.0 * omega_peak, 400)
    target = spectra.jonswap(omega, config.significant_wave_height, config.peak_period, config.gamma)
    keep = centres <= omega[-1]
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(omega, target, label="JONSWAP (target)")
    ax.step(centres[keep], measured[keep], where="mid", label=f"measured on the grid ({len(heights)} snapshots)")
    ax.set_xlabel("angular frequency ω [rad/s]")
    ax.set_ylabel("S(ω) [m² s/rad]")
    hs_measured = 4 * math.sqrt(np.mean([h.var() for h in heights]))
    ax.set_title(f"Hs: target {config.significant_wave_height:.2f} m, measured {hs_measured:.2f} m")
    ax.legend()
    fig.tight_layout()
    save_figure(fig, path, dpi=110)


def run(out_dir: str, *, device=None, resolution: int = 256, significant_wave_height: float = 2.0,
        peak_period: float = 8.0, seconds: float = 120.0, snapshots: int = 16) -> dict:
    """Build the sea, advance it for ``seconds`` [s], write the two PNGs into ``out_dir``."""
    config = OceanConfig(tile_size=4.0 * resolution, resolution=resolution, significant_wave_height=significant_wave_height,
                         peak_period=peak_period, choppiness=0.8, spreading=10.0, seed=7)
    ocean = Ocean(config, device=device)
    heights = []
    start = time.perf_counter()
    for t in np.linspace(0.0, seconds, snapshots):
        ocean.update(float(t))
        heights.append(ocean.field_numpy("height").astype(np.float64))
    elapsed = time.perf_counter() - start
    height_png = os.path.join(out_dir, "ocean_height.png")
    spectrum_png = os.path.join(out_dir, "ocean_spectrum.png")
    save_height_png(ocean, height_png)
    save_spectrum_png(config, heights, spectrum_png)
    return {"device": str(ocean.device), "grid_hs": ocean.significant_wave_height,
            "measured_hs": 4 * math.sqrt(np.mean([h.var() for h in heights])),
            "seconds_per_update": elapsed / snapshots, "files": [height_png, spectrum_png]}


def main(argv=None) -> int:
    """``ocean-warp ocean``: returns 0; bad options exit with status 2 and one line."""
    parser = _parser()
    args = parser.parse_args(argv)
    resolution = args.resolution
    check_options(parser, (
        ("--resolution", resolution,
         MIN_RESOLUTION <= resolution <= MAX_RESOLUTION and not resolution & (resolution - 1),
         f"a power of two from {MIN_RESOLUTION} to {MAX_RESOLUTION}"),
        ("--hs", args.hs, is_valid_significant_wave_height(args.hs), SIGNIFICANT_WAVE_HEIGHT_RULE),
        ("--tp", args.tp, finite_above(args.tp, 0.0), "a number > 0 [s]"),
        ("--seconds", args.seconds, finite_above(args.seconds, 0.0), "a number > 0 [s]"),
    ))
    device = checked_device(parser, args.device)
    wp.config.log_level = logging.WARNING
    checked_output_folder(parser, args.out)
    os.makedirs(args.out, exist_ok=True)
    report = run(args.out, device=device, resolution=args.resolution, significant_wave_height=args.hs,
                 peak_period=args.tp, seconds=args.seconds)
    print(f"ocean on {report['device']}: Hs on the grid {report['grid_hs']:.3f} m, measured {report['measured_hs']:.3f} m, "
          f"{report['seconds_per_update'] * 1e3:.2f} ms per update (with copies to the host)")
    for path in report["files"]:
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
