"""``ocean-warp drop-hulls``'s options: its parser, light to import (no Warp), so that ``--help`` and a
mistyped option answer at once. The job itself is ``drop_hulls``."""

from __future__ import annotations

import argparse

from ocean_warp.cli_support import add_device_argument, job_parser

__all__ = ["MAX_BOATS_PER_SHAPE", "parser"]

MAX_BOATS_PER_SHAPE = 4096
"""The most hulls of each shape: the heave and roll of every hull are kept at every step (2 x 8 bytes a step:
4 x 4096 hulls over the default 40 s of 0.02 s steps hold 0.5 GB), and every hull is a line of the plot."""


def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp drop-hulls``."""
    parser = job_parser("drop-hulls", "Hulls of four shapes (box, ellipsoid, sphere, cylinder) dropped into a "
                        "JONSWAP sea: heave and roll of each over time (hull_motions.png and hull_motions.csv in "
                        "--out).", long_help_from="ocean_warp.examples.drop_hulls")
    parser.add_argument("--out", default="out/drop-hulls", help="folder for the PNG and CSV")
    add_device_argument(parser)
    parser.add_argument("--boats-per-shape", type=int, default=8, metavar="N",
                        help=f"hulls of each shape, 1 to {MAX_BOATS_PER_SHAPE} (every hull's heave and roll are kept "
                             "at every step, 16 bytes a step: 0.5 GB for the most over 40 s, and each "
                             "hull is a line of the plot)")
    parser.add_argument("--seconds", type=float, default=40.0, help="simulated time [s]")
    return parser
