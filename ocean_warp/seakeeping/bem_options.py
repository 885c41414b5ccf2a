"""``ocean-warp bem``'s options: its parser, light to import (no capytaine, Warp or trimesh), so that ``--help``
and a mistyped option answer at once. The job itself is ``bem_command``."""

from __future__ import annotations

import argparse

from ocean_warp.cli_support import job_parser

__all__ = ["parser", "DEFAULT_OUT_FOLDER"]

DEFAULT_OUT_FOLDER = "out/bem"
"""Where the database goes without --out: <hull name>.json in it."""


def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp bem``."""
    parser = job_parser(
        "bem", "A hull's hydrodynamic database from potential flow (capytaine, pip install -e '.[bem]'): added "
        "mass and damping over frequency, A_inf, state-space fits of the radiation memory and wave forces. Without "
        "--hull, the E-Boat's physics hull at its mass.",
        long_help_from="ocean_warp.seakeeping.bem_command",
        examples=("ocean-warp bem", "ocean-warp bem --hull hull.stl --mass 160 --out out/bem/hull.json"))
    parser.add_argument("--hull", metavar="FILE",
                        help="closed hull mesh (OBJ, STL, PLY, OFF, GLB, GLTF) in the body frame: x to the bow, y to "
                             "port, z up, metres (see --scale); default: the E-Boat's physics hull")
    parser.add_argument("--scale", type=float, default=1.0, help="multiplies the mesh's coordinates (0.001 for mm)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--mass", type=float, metavar="KG",
                       help="the hull floats upright holding this mass [kg] (default with the E-Boat: its mass "
                            "less the water its keel, bulb and rudder displace)")
    where.add_argument("--rest-height", type=float, metavar="M",
                       help="height of the body origin above still water [m], instead of --mass")
    parser.add_argument("--out", metavar="FILE", help=f"the database (JSON) (default: {DEFAULT_OUT_FOLDER}/<hull "
                                                      "name>.json)")
    parser.add_argument("--frequencies", type=float, nargs=3, default=[0.3, 30.0, 50],
                        metavar=("LOW", "HIGH", "COUNT"),
                        help="COUNT frequencies from LOW to HIGH [rad/s], log-spaced (default: 0.3 30 50)")
    parser.add_argument("--headings", type=float, nargs="*", default=[180.0, 90.0], metavar="DEG",
                        help="wave headings of the excitation forces [deg], 180 head seas, 90 beam seas "
                             "(default: 180 90; none: no excitation)")
    parser.add_argument("--density", type=float, default=1025.0, help="water density [kg/m^3]")
    parser.add_argument("--gravity", type=float, default=9.81, help="gravity [m/s^2]")
    parser.add_argument("--no-lid", action="store_true",
                        help="no lid on the inner waterplane (irregular frequencies are then left in)")
    return parser
