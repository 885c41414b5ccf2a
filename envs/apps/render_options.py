"""``ocean-warp render``'s options: the run and the video (:class:`RenderConfig`) and its parser, light to
import (no Warp, no torch), so that ``--help`` and a mistyped option answer at once. The job itself is
``render``."""

from __future__ import annotations

import argparse
import dataclasses

from ocean_warp.cli_support import add_device_argument, job_parser
from ocean_warp.validation import require_in_range, require_int_in_range

from .scenario_options import FleetScenario, add_sailing_arguments

__all__ = ["CAMERAS", "VIDEO_SUFFIXES", "RenderConfig", "parser"]

CAMERAS = ("chase", "fixed")
VIDEO_SUFFIXES = (".mp4", ".gif")

@dataclasses.dataclass(frozen=True)
class RenderConfig(FleetScenario):
    """The run to render and the video (see :class:`FleetScenario` for the fleet and its sea;
    ``frames_per_second`` is the video's)."""

    boats: int = 8
    frames_per_second: int = 10
    duration: float = 30.0
    """Simulated time [s], rounded to whole decisions of 1 s."""
    width: int = 1280
    """[px]"""
    height: int = 720
    """[px]"""
    field_of_view: float = 60.0
    """Horizontal [deg]."""
    camera: str = "chase"
    """One of :data:`CAMERAS`."""
    policy: str | None = None
    """A policy checkpoint that sails every boat (None: the demo's mix, or the autopilot)."""
    autopilot: bool = False
    """The autopilot sails every boat."""
    policy_share: float = 0.5
    """The demo's mix: the first share of the boats sail the task's shipped policy, the rest the autopilot
    (every boat, on a task without a shipped policy)."""

    def __post_init__(self):
        super().__post_init__()
        owner = "RenderConfig"
        require_in_range(owner, "duration", self.duration, 1.0, 10**6)
        require_int_in_range(owner, "width", self.width, 2, 8192)
        require_int_in_range(owner, "height", self.height, 2, 8192)
        fov = require_in_range(owner, "field_of_view", self.field_of_view, 0.0, 180.0, unit=" [deg]")
        if not 0.0 < fov < 180.0:
            raise ValueError(f"{owner}.field_of_view must be in (0, 180) [deg], got {self.field_of_view!r}")
        if self.camera not in CAMERAS:
            raise ValueError(f"{owner}.camera must be one of {', '.join(CAMERAS)}, got {self.camera!r}")
        if not isinstance(self.autopilot, bool):
            raise ValueError(f"{owner}.autopilot must be True or False, got {self.autopilot!r}")
        if self.autopilot and self.policy is not None:
            raise ValueError(f"{owner}: autopilot and policy contradict each other (each sails every boat)")
        require_in_range(owner, "policy_share", self.policy_share, 0.0, 1.0)

    @property
    def decisions(self) -> int:
        """Decisions of 1 s the run lasts."""
        return max(1, int(round(self.duration)))

    @property
    def frames(self) -> int:
        """Frames the video holds when no run ends early."""
        return self.decisions * self.frames_per_second


def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp render``."""
    d = RenderConfig()
    parser = job_parser(
        "render", "A video (MP4 or GIF) of a fleet's run (the demo's, or --task), ray-traced on the CPU or a GPU "
        "from a chase or a fixed camera; written atomically to --out.", long_help_from="ocean_warp.envs.apps.render",
        examples=("ocean-warp render", "ocean-warp render --out out/render/fleet.gif --width 480 --height 270 "
                  "--duration 10 --camera fixed",
                  "ocean-warp render --policy out/train/EBoatMission-v0/<date>_<name>/policy.pt "
                  "--out out/render/policy.mp4"))
    parser.add_argument("--out", default="out/render/fleet.mp4", help="the video: .mp4 or .gif")
    parser.add_argument("--duration", type=float, default=d.duration, metavar="SECONDS",
                        help="simulated time [s], whole seconds")
    parser.add_argument("--width", type=int, default=d.width, help="[px]")
    parser.add_argument("--height", type=int, default=d.height, help="[px]")
    parser.add_argument("--fps", type=int, default=d.frames_per_second,
                        help="frames per simulated second, played in real time (1, 2, 4, 5, 10 or 20)")
    parser.add_argument("--camera", choices=CAMERAS, default=d.camera,
                        help="chase: astern of and above the first boat; fixed: overlooking the course")
    parser.add_argument("--fov", type=float, default=d.field_of_view, metavar="DEGREES",
                        help="horizontal field of view [deg]")
    who = parser.add_mutually_exclusive_group()
    who.add_argument("--policy", default=None, metavar="FILE", help="a policy checkpoint sails every boat")
    who.add_argument("--autopilot", action="store_true", help="the autopilot sails every boat")
    parser.add_argument("--policy-share", type=float, default=d.policy_share,
                        help="without --policy or --autopilot: the share of boats the shipped policy sails, the "
                        "rest the autopilot (the demo's fleet)")
    add_sailing_arguments(parser, d)
    add_device_argument(parser)
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    return parser
