"""``ocean-warp ocean``'s options: its parser, light to import (no Warp), so that ``--help`` and a mistyped
option answer at once. The job itself is ``ocean_snapshot``."""

from __future__ import annotations

import argparse

from ocean_warp.cli_support import add_device_argument, job_parser
from ocean_warp.ocean_config import MAX_RESOLUTION, MIN_RESOLUTION

__all__ = ["parser"]


def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp ocean``."""
    parser = job_parser("ocean", "A JONSWAP sea, advanced in time: its height field and its spectrum (the target "
                        "against the one measured on the grid), as PNGs in --out.",
                        long_help_from="ocean_warp.examples.ocean_snapshot")
    parser.add_argument("--out", default="out/ocean", help="folder for the PNGs")
    add_device_argument(parser)
    parser.add_argument("--resolution", type=int, default=256,
                        help=f"grid points per side (a power of two, {MIN_RESOLUTION} to {MAX_RESOLUTION}); the "
                        "tile is 4 m per point")
    parser.add_argument("--hs", type=float, default=2.0, help="significant wave height [m]")
    parser.add_argument("--tp", type=float, default=8.0, help="peak period [s]")
    parser.add_argument("--seconds", type=float, default=120.0, help="simulated time [s]")
    return parser
