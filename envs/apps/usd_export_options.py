"""``ocean-warp export-usd``'s options: the scenario it records (:class:`ExportConfig`) and its parser, light
to import (no Warp, torch or pxr), so that ``--help`` and a mistyped option answer at once. The job itself is
``usd_export``."""

from __future__ import annotations

import argparse
import dataclasses

from ocean_warp.cli_support import job_parser
from ocean_warp.usd.playback import TIME_CODES_PER_SECOND
from ocean_warp.validation import require_in_range, require_positive

from .scenario_options import FleetScenario, add_scenario_arguments

__all__ = ["CONTROLLERS", "ExportConfig", "parser"]
CONTROLLERS = ("policy", "autopilot", "fixed")


@dataclasses.dataclass(frozen=True)
class ExportConfig(FleetScenario):
    """The scenario to record (see :class:`FleetScenario` for the fleet, sea and stage)."""

    boats: int = 8
    frames_per_second: int = 5
    duration: float = 120.0
    """Simulated time to record [s] (whole decisions of 1 s)."""
    controller: str = "policy"
    """"policy" (``policy`` or the task's shipped one), "autopilot" or "fixed" (``actions`` throughout)."""
    actions: tuple[float, float, float] = (0.4, 0.0, 0.0)
    """The fixed commands, each in [-1, 1]: propeller level int(5 a0), sheet (a1 + 1) 45 deg, rudder 60 a2 deg."""
    policy: str | None = None
    """Path of an exported policy (None: the task's shipped policy; ``ValueError`` naming the task where it
    has none)."""
    loop_period: float | None = None
    """Make the sea repeat every this many seconds and store one loop of it (None: a mesh per frame)."""
    instanced: bool | None = None
    """Point instancers (True), a prim per boat (False), or chosen by the fleet's size (None)."""
    time_codes_per_second: float = TIME_CODES_PER_SECOND
    """The stage's time codes (and frames) per second of playback [1/s]: 24 (Blender's default), 30, or any
    positive rate; one simulated second is this many time codes, so the stage plays in real time."""

    def __post_init__(self):
        super().__post_init__()
        owner = "ExportConfig"
        require_in_range(owner, "duration", self.duration, 1.0, 10**7)  # at least one decision of 1 s
        if self.controller not in CONTROLLERS:
            raise ValueError(f"{owner}.controller must be one of {', '.join(CONTROLLERS)}, got {self.controller!r}")
        if len(self.actions) != 3 or any(not -1.0 <= float(a) <= 1.0 for a in self.actions):
            raise ValueError(f"{owner}.actions must be three numbers in [-1, 1], got {self.actions!r}")
        if self.loop_period is not None:
            require_positive(owner, "loop_period", self.loop_period, unit=" [s]")
        require_positive(owner, "time_codes_per_second", self.time_codes_per_second, unit=" [1/s]")


def _actions(text: str) -> tuple[float, float, float]:
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected three numbers like 0.4,0,0.1, got {text!r}") from None
    if len(values) != 3:
        raise argparse.ArgumentTypeError(f"expected three numbers like 0.4,0,0.1, got {text!r}")
    return values


def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp export-usd``."""
    d = ExportConfig()
    parser = job_parser(
        "export-usd", "Record a fleet sailing a task (by default the BCDACA mission) in a JONSWAP sea to a USD "
        "stage (Z up, metres), with a preview PNG beside it; a task with obstacles shows each boat's buoys and "
        "piles.", long_help_from="ocean_warp.envs.apps.usd_export",
        examples=("ocean-warp export-usd --boats 8 --duration 120 --controller autopilot "
                  "--out out/export-usd/autopilot.usdc",
                  "ocean-warp export-usd --task EBoatAvoid-v0 --boats 4 --duration 60 --out out/export-usd/avoid.usdc"))
    add_scenario_arguments(parser, d)
    parser.add_argument("--duration", type=float, default=d.duration, metavar="SECONDS", help="simulated time [s]")
    parser.add_argument("--controller", choices=CONTROLLERS, default=d.controller, help="who steers every boat")
    parser.add_argument("--policy", default=argparse.SUPPRESS, metavar="PATH",
                        help="exported policy (default: the task's shipped policy; a task without one is steered "
                             "by the autopilot, said in one line)")
    parser.add_argument("--actions", type=_actions, default=d.actions, metavar="A0,A1,A2",
                        help="fixed commands in [-1, 1]: propeller int(5 a0), sheet (a1 + 1) 45 deg, rudder 60 a2 deg")
    parser.add_argument("--loop-period", type=float, default=None, metavar="SECONDS",
                        help="a sea that repeats every this many seconds, stored once as a seamless loop")
    layout = parser.add_mutually_exclusive_group()
    layout.add_argument("--instanced", dest="instanced", action="store_true", default=None,
                        help="point instancers for the boats (by default: above 64 boats)")
    layout.add_argument("--prims", dest="instanced", action="store_false", default=argparse.SUPPRESS,
                        help="one prim per boat (by default: up to 64 boats)")
    parser.add_argument("--playback-fps", type=float, default=d.time_codes_per_second, metavar="RATE",
                        help="the stage's time codes (frames) per second of playback, e.g. 24 or 30: one simulated "
                        "second plays in one second (--fps is how many frames are recorded per second)")
    parser.add_argument("--usda", action="store_true", help="text (.usda) instead of crate (.usdc)")
    parser.add_argument("--out", default="out/export-usd/scenario.usdc",
                        help="the stage to write: .usdc, .usda or .usd")
    return parser
