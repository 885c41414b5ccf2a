"""What a fleet command takes (``ocean-warp demo``, ``export-usd``, ``render``, ``ros``): the fleet, its task, sea
and wind (:class:`FleetScenario`) and their command-line options. Light to import (no Warp, no torch), so
that a job's parser and ``--help`` answer at once; the task they build is ``fleet_scenario``'s."""

from __future__ import annotations

import argparse
import dataclasses
import pathlib

from ocean_warp.cli_support import add_device_argument
from ocean_warp.ocean_config import require_significant_wave_height
from ocean_warp.validation import require_in_range, require_int_in_range

from ..registration import DEFAULT_TASK, TASK_IDS, task_name

__all__ = ["FleetScenario", "HULLS", "STEPS_PER_DECISION", "add_sailing_arguments", "add_scenario_arguments",
           "scenario_arguments", "checked_task_name", "shipped_policy_or_none"]

HULLS = ("auto", "mesh", "points")
""""mesh" (per-triangle pressure), "points" (the seed twin's four-point buoyancy) or "auto" (points on the
CPU, where the mesh hull costs about 30 times more, mesh on a GPU)."""


STEPS_PER_DECISION = 20
"""Physics steps in one decision of the course task (1 s of 0.05 s steps): the stage's frames sample them."""


@dataclasses.dataclass(frozen=True)
class FleetScenario:
    """The fleet, its task, sea and wind, and how the stage samples them."""

    boats: int = 16
    """Boats in the fleet."""
    sea_state: float | None = None
    """Significant wave height Hs of the task's JONSWAP sea [m]; None: the task's (0.3 m for the missions
    and the avoidance tasks)."""
    wind: float | None = None
    """Mean true wind speed [m/s] of every boat, with the task's gusts and directions (toward +x on the
    missions); None: the task's (10 m/s on the missions; the waypoint and avoidance tasks draw it per boat
    from their range)."""
    seed: int = 0
    """Seed of the sea, the gusts, the starts (and the waypoints and obstacle layouts of the tasks that
    draw them)."""
    hull: str = "auto"
    """One of :data:`HULLS`."""
    frames_per_second: int = 2
    """Frames of the USD stage per simulated second; must divide the 20 physics steps of a decision."""
    ocean_resolution: int = 64
    """At most this many ocean mesh vertices along a side of the area shown."""
    ocean_margin: float = 20.0
    """Water shown beyond the route and the boats [m] (every place a boat went, for a looping sea)."""
    ocean_normals: bool = False
    """Write the ocean mesh's vertex normals (12 bytes a vertex and frame more)."""
    task_id: str = DEFAULT_TASK
    """The task every boat sails: a registered id (``ocean_warp.envs.registration.TASK_IDS``, with or
    without "ocean_warp/"), stored without the prefix; default the BCDACA mission."""

    def __post_init__(self):
        owner = type(self).__name__
        require_int_in_range(owner, "boats", self.boats, 1, 1_000_000)
        if self.sea_state is not None:
            require_significant_wave_height(f"{owner}.sea_state", self.sea_state)
        if self.wind is not None:
            require_in_range(owner, "wind", self.wind, 0.0, 30.0)
        require_int_in_range(owner, "seed", self.seed, 0, 2**31 - 1)
        if self.hull not in HULLS:
            raise ValueError(f"{owner}.hull must be one of {', '.join(HULLS)}, got {self.hull!r}")
        require_int_in_range(owner, "frames_per_second", self.frames_per_second, 1, 20)
        if STEPS_PER_DECISION % self.frames_per_second:
            raise ValueError(f"{owner}.frames_per_second must divide the {STEPS_PER_DECISION} physics steps of a "
                             f"decision (1, 2, 4, 5, 10 or 20), got {self.frames_per_second}")
        require_int_in_range(owner, "ocean_resolution", self.ocean_resolution, 2, 4096)
        require_in_range(owner, "ocean_margin", self.ocean_margin, 0.0, 10_000.0)
        if not isinstance(self.ocean_normals, bool):
            raise ValueError(f"{owner}.ocean_normals must be True or False, got {self.ocean_normals!r}")
        try:
            object.__setattr__(self, "task_id", task_name(self.task_id))
        except ValueError as error:
            raise ValueError(f"{owner}.task_id: {error}") from None

    def stage_options(self) -> dict:
        """The ocean options of the stage recorder (see ``MissionStageRecorder``)."""
        return dict(ocean_resolution=self.ocean_resolution, ocean_margin=self.ocean_margin,
                    ocean_normals=self.ocean_normals)

    def task(self, *, time_limit: float, loop_period: float | None, device, observation=None) -> object:
        """This scenario's :func:`fleet_course_task` (``observation``: the policy's set, None the task's)."""
        from .fleet_scenario import fleet_course_task  # the simulator's side: Warp and torch

        return fleet_course_task(sea_state=self.sea_state, wind=self.wind, seed=self.seed, time_limit=time_limit,
                                 hull=self.hull, loop_period=loop_period, device=device, task=self.task_id,
                                 observation=observation)


def checked_task_name(value) -> str:
    """``--task``'s value as a task id without "ocean_warp/"; ``ValueError`` "--task: unknown task id ...;
    known: ..." otherwise (as ``ocean-warp eval`` says it)."""
    try:
        return task_name(value)
    except ValueError as error:
        raise ValueError(f"--task: {error}") from None


def shipped_policy_or_none(task_id: str) -> pathlib.Path | None:
    """The policy shipped for ``task_id``, or None where the task has none (the autopilot sails instead).

    Raises:
        FileNotFoundError: the policy is known but its file is not there.
    """
    from ..training.policies import shipped_policy_path

    try:
        return shipped_policy_path(task_id)
    except ValueError:
        return None


def add_sailing_arguments(parser: argparse.ArgumentParser, defaults) -> None:
    """The options of the fleet's run every fleet command has: ``--task``, ``--boats``, ``--sea-state``,
    ``--wind``, ``--seed`` and ``--hull``, with ``defaults``' values (an object with those fields)."""
    parser.add_argument("--task", default=defaults.task_id, metavar="ID",
                        help=f"the task every boat sails: {', '.join(TASK_IDS)}, with or without 'ocean_warp/' "
                             f"(default {defaults.task_id})")
    parser.add_argument("--boats", type=int, default=defaults.boats, help="boats in the fleet")
    parser.add_argument("--sea-state", type=float, default=defaults.sea_state, metavar="HS",
                        help="significant wave height of the JONSWAP sea [m] (default: the task's, 0.3 for the "
                             "mission)")
    parser.add_argument("--wind", type=float, default=defaults.wind,
                        help="mean true wind speed of every boat [m/s] (default: the task's, 10 for the mission; "
                             "the waypoint and avoidance tasks draw it per boat from their range unless this "
                             "fixes it)")
    parser.add_argument("--seed", type=int, default=defaults.seed,
                        help="seed of sea, gusts and starts (and of waypoints and obstacles where the task draws "
                             "them)")
    parser.add_argument("--hull", choices=HULLS, default=defaults.hull,
                        help="mesh: per-triangle pressure; points: the seed's four-point buoyancy; auto: points on "
                        "the CPU, mesh on a GPU")


def add_scenario_arguments(parser: argparse.ArgumentParser, defaults: FleetScenario) -> None:
    """The command-line options of :class:`FleetScenario`'s fields, with ``defaults``' values, and the
    options every fleet command has: ``--device`` and ``--no-progress``."""
    add_sailing_arguments(parser, defaults)
    parser.add_argument("--fps", type=int, default=defaults.frames_per_second,
                        help="USD frames per simulated second (1, 2, 4, 5, 10 or 20)")
    parser.add_argument("--ocean-resolution", type=int, default=defaults.ocean_resolution,
                        help="ocean mesh vertices along a side of the area shown, at most")
    parser.add_argument("--ocean-margin", type=float, default=defaults.ocean_margin, metavar="METRES",
                        help="water shown beyond the route and the boats [m]")
    parser.add_argument("--ocean-normals", action="store_true", help="write the ocean mesh's vertex normals")
    add_device_argument(parser)
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")


def scenario_arguments(args: argparse.Namespace) -> dict:
    """:class:`FleetScenario`'s fields from options parsed by :func:`add_scenario_arguments`; ``ValueError``
    naming --task where it is no registered task id."""
    return dict(boats=args.boats, sea_state=args.sea_state, wind=args.wind, seed=args.seed, hull=args.hull,
                frames_per_second=args.fps, ocean_resolution=args.ocean_resolution, ocean_margin=args.ocean_margin,
                ocean_normals=args.ocean_normals, task_id=checked_task_name(args.task))
