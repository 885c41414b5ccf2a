"""``ocean-warp ros``'s options: its parser, light to import (no Warp, torch or ROS), so that ``--help`` and a
mistyped option answer at once. The node itself is ``node``."""

from __future__ import annotations

import argparse
import dataclasses

from ocean_warp.cli_support import add_device_argument, job_parser
from ocean_warp.envs.apps.scenario_options import add_sailing_arguments
from ocean_warp.envs.registration import DEFAULT_TASK

from ocean_warp.ros.ros1 import split_remaps

__all__ = ["DEFAULT_CLOCK_HZ", "MAX_CLOCK_HZ", "parser", "own_arguments"]

DEFAULT_CLOCK_HZ = 20.0
"""/clock ticks per second of simulated time (between decisions too)."""
MAX_CLOCK_HZ = 1000.0
"""The most /clock ticks per simulated second the node offers (one every millisecond)."""


def own_arguments(argv: list[str]) -> list[str]:
    """The arguments of ``argv`` that :func:`parser` parses: all but rospy's ``name:=value`` remaps."""
    return split_remaps(argv)[1]


@dataclasses.dataclass(frozen=True)
class _Defaults:
    task_id: str = DEFAULT_TASK
    boats: int = 1
    sea_state: float | None = None
    wind: float | None = None
    seed: int = 0
    hull: str = "auto"


def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp ros`` (its options; rospy's ``name:=value`` remaps are split off first:
    :func:`own_arguments`)."""
    parser = job_parser(
        "ros", "The simulator as a ROS node (ROS 1 through rospy, or ROS 2 through rclpy): each boat publishes the "
        "seed's topics and standard ones once per decision and takes sail, rudder and propulsion commands; a "
        "reset service restarts every boat. --help-long lists the topics.", long_help_from="ocean_warp.envs.ros.node",
        examples=("ocean-warp ros", "ocean-warp ros --boats 4 --rate-factor 10 --record out/ros/run.mcap",
                  "ocean-warp ros /eboat/gps/fix:=/fix"))
    add_sailing_arguments(parser, _Defaults())
    parser.add_argument("--rate-factor", type=float, default=1.0, metavar="F",
                        help="simulated seconds per wall-clock second (1: real time; 0: as fast as possible)")
    parser.add_argument("--as-fast-as-possible", action="store_true", help="no sleeping: --rate-factor 0")
    parser.add_argument("--clock-hz", type=float, default=DEFAULT_CLOCK_HZ, metavar="HZ",
                        help="/clock ticks per second of simulated time between decisions (0: only at each "
                             "decision)")
    parser.add_argument("--duration", type=float, default=None, metavar="SECONDS",
                        help="stop when the simulated clock reaches this [s] (default: run until shut down)")
    parser.add_argument("--lockstep", action="store_true",
                        help="each decision waits for every boat's sail, rudder and propulsion commands (what "
                             "the controller node sends for each observation); the observations are latched")
    parser.add_argument("--lockstep-timeout", type=float, default=0.0, metavar="SECONDS",
                        help="with --lockstep: step with the commands held after this long without them [s, wall "
                             "clock] (default 0: wait for them)")
    parser.add_argument("--lidar", action="store_true",
                        help="a 360-beam lidar (the avoidance task's) on every boat of a task without one, "
                             "published on lidar/scan")
    parser.add_argument("--camera", action="store_true",
                        help="a 64 x 64 bow camera on every boat: RGB and depth images once per decision")
    parser.add_argument("--record", default=None, metavar="FILE.mcap",
                        help="also write a rosbag2 MCAP log of the run (needs the mcap extra: pip install "
                             "'ocean-warp[mcap]')")
    parser.add_argument("--ros", choices=("1", "2", "auto"), default="auto",
                        help="ROS 1 (rospy, needs a master) or ROS 2 (rclpy, DDS discovery; written against "
                             "rclpy's documented API and tested only with fakes); auto (default): ROS 1 where "
                             "rospy is found, else ROS 2 where rclpy imports")
    add_device_argument(parser)
    return parser
