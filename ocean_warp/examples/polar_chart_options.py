"""``ocean-warp polar``'s options: its parser, light to import (no Warp), so that ``--help`` and a mistyped
option answer at once. The job itself is ``polar_chart``."""

from __future__ import annotations

import argparse

from ocean_warp.cli_support import add_device_argument, job_parser

__all__ = ["parser"]


def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp polar``."""
    parser = job_parser("polar", "The E-Boat's speed polar: steady speed over true wind angles 0-180 deg, the "
                        "sheet trimmed for speed (polar.png and polar.csv in --out).",
                        long_help_from="ocean_warp.examples.polar_chart")
    parser.add_argument("--out", default="out/polar", help="folder for polar.png and polar.csv")
    add_device_argument(parser)
    parser.add_argument("--wind-speeds", type=float, nargs="+", default=[4.0, 7.0, 10.0], metavar="MPS",
                        help="true wind speeds [m/s] (default: 4 7 10)")
    parser.add_argument("--angle-step", type=float, default=15.0, metavar="DEG",
                        help="true wind angle step [deg] (angles 0 to 180)")
    parser.add_argument("--sheet-step", type=float, default=15.0, metavar="DEG",
                        help="sheet search step [deg] (settings 0 to 90)")
    parser.add_argument("--settle", type=float, default=60.0, metavar="SECONDS",
                        help="settling time before the speed is averaged [s]")
    parser.add_argument("--seakeeping", action="store_true",
                        help="the hull's radiation memory and diffraction from its hydrodynamic database (off: the "
                             "boat's default)")
    return parser
