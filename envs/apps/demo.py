"""``ocean-warp demo``: a fleet of E-Boats sails the BCDACA mission in a JONSWAP sea, some boats with the
shipped policy and the rest with the classical autopilot, all in one batch; it writes the USD stage (with
a preview PNG), the trajectory picture and the results table, and prints a summary.

``--task ID`` sails another registered task (as ``ocean-warp eval --task``): its shipped policy takes the
policy's share of the boats, or, for a task without one, the autopilot sails every boat (said in one line).
On a task with obstacles the stage shows each boat's buoys and piles of its first episode and the
trajectory picture each run's obstacles (``ocean_warp.envs.apps.demo_stage``).

``--record FILE.mcap`` also writes a rosbag2 MCAP log (ROS 2 message schemas; ``ros2 bag``, Foxglove and
PlotJuggler open it; the ``mcap`` extra): every boat under ``/eboat_<i>`` (``/eboat`` for one boat), at the
start and after every decision, log times the simulated time (topics: ``ocean_warp.ros.topics``).

On the CPU the fleet floats on the seed twin's four-point buoyancy by default (``hull="auto"``): the
per-triangle mesh hull costs about 30 times more, too much for a demo of a few minutes on two cores.
On a GPU it uses the mesh hull.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import sys
import time

import numpy as np

from ocean_warp.cli_support import job_parser, plural, report_error
from ocean_warp.devices import resolve_device
from ocean_warp.validation import require_in_range, require_positive

from ..sailing_env import SailingEnv
from .fleet_scenario import (FleetScenario, add_scenario_arguments, controller_observation, scenario_arguments,
                             shipped_policy_or_none)
from .evaluation import (
    DEFAULT_TASK,
    AutopilotController,
    FleetController,
    MissionEvaluation,
    PolicyController,
    sail_mission,
)
from ..training.policy_io import load_policy

__all__ = ["DemoConfig", "DemoResult", "demo_task", "run_demo", "main"]

@dataclasses.dataclass(frozen=True)
class DemoConfig(FleetScenario):
    """What the demo sails and records (see :class:`FleetScenario` for the fleet, sea and stage)."""

    ocean_resolution: int = 96
    """At most this many ocean mesh vertices along a side: the area grows where boats got lost, so the
    demo keeps the mesh finer than a plain scenario's 64 (a loop of 121 frames, a few MB)."""
    policy_share: float = 0.5
    """Fraction of the boats sailed by the task's shipped policy (the first ones); the rest by the autopilot
    (every boat, on a task without a shipped policy)."""
    time_limit: float = 1200.0
    """Per boat [s]; a boat still sailing then counts as timed out."""
    loop_period: float = 60.0
    """The sea repeats every this many seconds [s], so the stage holds one seamless loop of it."""
    usd: bool = True
    """Write the USD stage (and its preview)."""

    def __post_init__(self):
        super().__post_init__()
        owner = "DemoConfig"
        require_in_range(owner, "policy_share", self.policy_share, 0.0, 1.0)
        require_positive(owner, "time_limit", self.time_limit, unit=" [s]")
        require_positive(owner, "loop_period", self.loop_period, unit=" [s]")
        if not isinstance(self.usd, bool):
            raise ValueError(f"{owner}.usd must be True or False, got {self.usd!r}")

    @property
    def policy_boats(self) -> int:
        """Boats the shipped policy sails: the policy's share, or 0 on a task without a shipped policy."""
        if shipped_policy_or_none(self.task_id) is None:
            return 0
        return int(round(self.policy_share * self.boats))


@dataclasses.dataclass
class DemoResult:
    """What :func:`run_demo` did: the evaluation (one result per controller), the files it wrote, and
    its speed."""

    evaluation: MissionEvaluation
    files: dict[str, str]
    sail_wall_s: float
    """Wall time of the sailing loop [s] (recording included, start-up and writing the table not)."""
    simulated_boat_seconds: float
    """Sum over the boats of the simulated time they sailed [s]."""

    @property
    def real_time_factor(self) -> float:
        """Simulated boat-seconds per wall second of the sailing loop."""
        return self.simulated_boat_seconds / self.sail_wall_s if self.sail_wall_s > 0 else math.nan


def demo_task(config: DemoConfig, device, observation=None) -> object:
    """The task the demo sails (by default the mission): the scenario's task with the demo's time limit and
    loop (``observation``: the policy's set, None the task's)."""
    return config.task(time_limit=config.time_limit, loop_period=config.loop_period, device=device,
                       observation=observation)


def run_demo(config: DemoConfig, *, device: str = "cpu", out: str | os.PathLike = "out/demo",
             progress: bool = True, recorder_factory=None, record: str | os.PathLike | None = None) -> DemoResult:
    """Sail the demo's fleet once and write its files into ``out``.

    With ``config.usd`` the fleet is recorded into ``out/eboat_fleet.usdc`` (:mod:`.demo_stage`);
    otherwise ``recorder_factory(env, path, frames_per_decision=F)``, if given, makes the recorder: an
    object with ``record(time_s, frames)``, ``abort()`` and ``close() -> dict[str, str]`` (files written).
    ``record``: also write a rosbag2 MCAP log there (a path ending in .mcap; the ``mcap`` extra), every boat
    under ``/eboat_<i>`` (``/eboat`` for one boat) at the start and after every decision
    (``ocean_warp.ros.mcap_log``); its path is ``files["rosbag"]``.
    """
    out = os.fspath(out)
    policy_mask = np.arange(config.boats) < config.policy_boats
    groups = []
    if policy_mask.any():
        groups.append((PolicyController(load_policy(shipped_policy_or_none(config.task_id))), policy_mask))
    if not policy_mask.all():
        groups.append((AutopilotController(), ~policy_mask))
    fleet = FleetController(groups, name="fleet")
    task = demo_task(config, device, controller_observation(fleet))
    env = SailingEnv(task, config.boats, device=device, seed=config.seed)  # reset: the first episodes drawn
    frames = config.frames_per_second
    recorder = None
    if recorder_factory is None and config.usd:
        from .demo_stage import MissionStageRecorder

        recorder = MissionStageRecorder(env, os.path.join(out, "eboat_fleet.usdc"), frames_per_decision=frames,
                                        **config.stage_options())
    elif recorder_factory is not None:
        recorder = recorder_factory(env, os.path.join(out, "eboat_fleet.usdc"), frames_per_decision=frames)
    log = None
    if record is not None:
        from ocean_warp.ros.mcap_log import McapRecorder

        try:
            log = McapRecorder(record)
        except BaseException:
            if recorder is not None:
                recorder.abort()
            raise
        log.add_metadata("ocean_warp.demo", {f"boat_{i}": "policy" if sails else "autopilot"
                                             for i, sails in enumerate(policy_mask)})

    def on_decision(k: int, decision) -> None:
        if recorder is not None:
            recorder.record((k + 1) * env.decision_period, decision.frames())
        if log is not None:
            log.record(env)

    started = time.perf_counter()
    try:
        result = sail_mission(env, fleet, progress=progress,
                              frames_per_decision=frames if recorder is not None else 1,
                              on_decision=None if recorder is None and log is None else on_decision,
                              on_start=None if log is None else lambda: log.record(env))
    except BaseException:
        for writer in (recorder, log):
            if writer is not None:
                writer.abort()
        raise
    files = recorder.close() if recorder is not None else {}
    if log is not None:
        files["rosbag"] = log.close()
    sail_wall = time.perf_counter() - started
    results = {}
    if policy_mask.any():
        results["policy"] = result.subset(policy_mask, "policy")
    if not policy_mask.all():
        results["autopilot"] = result.subset(~policy_mask, "autopilot")
    low, high = task.start.wind_speed
    settings = {"runs": config.boats, "sea_state": task.simulator.ocean.significant_wave_height,
                "wind": low if low == high else None, "seed": config.seed, "device": str(env.device),
                "time_limit": task.episode_time}
    if config.task_id != DEFAULT_TASK:
        settings["task"] = config.task_id  # named in the picture's title (the mission's stays as it was)
    evaluation = MissionEvaluation(task=task, settings=settings, results=results)
    files.update(evaluation.write(out))
    sailed = sum(len(path.propeller) for path in result.paths) * env.decision_period
    return DemoResult(evaluation=evaluation, files=files, sail_wall_s=sail_wall, simulated_boat_seconds=sailed)


def _summary(config: DemoConfig, result: DemoResult, hull: str) -> str:
    autopilot_boats = config.boats - config.policy_boats
    task = result.evaluation.task
    low, high = task.start.wind_speed
    wind = f"{float(low)}" if low == high else f"{low:g}-{high:g}"
    prefix = "" if config.task_id == DEFAULT_TASK else f"{config.task_id}: "
    ocean = task.simulator.ocean
    spectrum = {"jonswap": "JONSWAP", "pierson_moskowitz": "Pierson-Moskowitz"}.get(ocean.spectrum.value,
                                                                                   ocean.spectrum.value)
    lines = [f"{prefix}{plural(config.boats, 'E-Boat')} ({config.policy_boats} policy, {autopilot_boats} autopilot), "
             f"{hull} hull, {spectrum} Hs {float(ocean.significant_wave_height)} m, wind {wind} m/s with gusts, "
             f"seed {config.seed}"]
    for name, controller in result.evaluation.results.items():
        times = controller.time_s[controller.success]
        timing = (f", mission time {times.mean():.0f} s ({times.min():.0f}-{times.max():.0f})" if times.size else "")
        collided = f", {int(controller.collided.sum())} collided" if controller.has_obstacles else ""
        lines.append(f"  {name:>9}: {int(controller.success.sum())}/{controller.runs} completed{collided}{timing}")
    lines.append(f"simulated {result.simulated_boat_seconds:.0f} boat-seconds in {result.sail_wall_s:.1f} s: "
                 f"real-time factor {result.real_time_factor:.0f}")
    lines += [f"wrote {path}" for path in result.files.values()]
    return "\n".join(lines)


def _parser() -> argparse.ArgumentParser:
    defaults = DemoConfig()
    parser = job_parser("demo", "A fleet of E-Boats sails the BCDACA mission (or --task) in waves, half with the "
                        "shipped policy and half with the classical autopilot; writes a USD stage with a preview "
                        "PNG, trajectories.png and results.csv.")
    add_scenario_arguments(parser, defaults)
    parser.add_argument("--policy-share", type=float, default=defaults.policy_share,
                        help="fraction of the boats sailed by the task's shipped policy (0-1)")
    parser.add_argument("--time-limit", type=float, default=defaults.time_limit, metavar="SECONDS",
                        help="per boat [s]")
    parser.add_argument("--loop-period", type=float, default=defaults.loop_period, metavar="SECONDS",
                        help="the sea repeats every this many seconds (one seamless loop in the stage)")
    parser.add_argument("--no-usd", action="store_true", help="skip the USD stage and its preview")
    parser.add_argument("--out", default="out/demo", help="folder for the stage, PNGs and tables")
    parser.add_argument("--record", default=None, metavar="FILE.mcap",
                        help="also write a rosbag2 MCAP log of the fleet, every boat under /eboat_<i> (needs the "
                             "mcap extra: pip install 'ocean-warp[mcap]')")
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``ocean-warp demo``; returns the exit code (2 for a bad option)."""
    parser = _parser()
    args = parser.parse_args(argv)
    if args.record is not None:
        from ocean_warp.ros.mcap_log import check_record_path

        try:
            check_record_path(args.record)
        except (ValueError, ImportError) as error:  # not a .mcap path; the mcap extra missing
            return report_error(parser.prog, f"--record: {error}")
    try:
        config = DemoConfig(**scenario_arguments(args), policy_share=args.policy_share, time_limit=args.time_limit,
                            loop_period=args.loop_period, usd=not args.no_usd)
        device = resolve_device(args.device, name="--device")
        if config.policy_share > 0.0 and shipped_policy_or_none(config.task_id) is None:
            print(f"no policy is shipped for {config.task_id}: the autopilot sails every boat")
        os.makedirs(args.out, exist_ok=True)
    except (ValueError, OSError) as error:  # a bad setting, task or device; an unusable --out
        return report_error(parser.prog, str(error))
    try:
        result = run_demo(config, device=device, out=args.out, progress=not args.no_progress, record=args.record)
    except OSError as error:  # a file could not be written
        print(f"{parser.prog}: {error}", file=sys.stderr)
        return 1
    hull = demo_task(config, device).simulator.boat.hydrostatics.value
    print(result.evaluation.format_table())
    print(_summary(config, result, hull))
    return 0
