"""``ocean-warp demo``: a fleet of E-Boats sails the BCDACA mission in a JONSWAP sea, some boats with the
shipped policy and the rest with the classical autopilot, all in one batch; it writes the USD stage (with
a preview PNG), the trajectory picture and the results table, and prints a summary.

``--policy FILE`` sails a checkpoint of your own in the shipped policy's place: the ``policy.pt`` (or a
``model_<it>.pt``) that ``ocean-warp train`` wrote into ``out/train/<task>/<date>_<name>/``. A file that is
no policy checkpoint is one line and exit status 2, before anything sails.

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

import dataclasses
import math
import os
import sys
import time

import numpy as np

from ocean_warp.cli_support import checked_output_folder, checked_device, plural, report_error

from ..sailing_env import SailingEnv
from .demo_options import DemoConfig, parser as _parser
from .fleet_scenario import controller_observation, scenario_arguments, shipped_policy_or_none
from ..evaluation import (
    DEFAULT_TASK,
    AutopilotController,
    FleetController,
    MissionEvaluation,
    PolicyController,
    sail_mission,
)
from ..training.policy_io import CheckpointError, Policy, load_policy

__all__ = ["DemoConfig", "DemoResult", "demo_task", "run_demo", "main"]

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
             progress: bool = True, recorder_factory=None, record: str | os.PathLike | None = None,
             policy: Policy | None = None) -> DemoResult:
    """Sail the demo's fleet once and write its files into ``out``.

    With ``config.usd`` the fleet is recorded into ``out/eboat_fleet.usdc`` (:mod:`.demo_stage`);
    otherwise ``recorder_factory(env, path, frames_per_decision=F)``, if given, makes the recorder: an
    object with ``record(time_s, frames)``, ``abort()`` and ``close() -> dict[str, str]`` (files written).
    ``record``: also write a rosbag2 MCAP log there (a path ending in .mcap; the ``mcap`` extra), every boat
    under ``/eboat_<i>`` (``/eboat`` for one boat) at the start and after every decision
    (``ocean_warp.envs.ros.mcap_log``); its path is ``files["rosbag"]``. ``policy``: the policy the policy's
    share sails, loaded already (None: ``config.policy``'s file, else the task's shipped policy).
    """
    out = os.fspath(out)
    policy_mask = np.arange(config.boats) < config.policy_boats
    groups = []
    if policy_mask.any():
        if policy is None:
            policy = load_policy(config.policy or shipped_policy_or_none(config.task_id))
        groups.append((PolicyController(policy), policy_mask))
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
        from ocean_warp.envs.ros.mcap_log import McapRecorder

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


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``ocean-warp demo``; returns the exit code (2 for a bad option or policy)."""
    parser = _parser()
    args = parser.parse_args(argv)
    if args.record is not None:
        from ocean_warp.envs.ros.mcap_log import check_record_path

        try:
            check_record_path(args.record)
        except (ValueError, ImportError) as error:  # not a .mcap path; the mcap extra missing
            return report_error(parser.prog, f"--record: {error}")
    checked_output_folder(parser, args.out)
    try:
        config = DemoConfig(**scenario_arguments(args), policy_share=args.policy_share, time_limit=args.time_limit,
                            loop_period=args.loop_period, usd=not args.no_usd, policy=args.policy)
    except ValueError as error:  # a bad setting or task
        return report_error(parser.prog, str(error))
    device = checked_device(parser, args.device)
    print(f"{config.task_id}: {plural(config.boats, 'boat')}, device {device}")
    policy = None
    if config.policy is not None:
        try:
            policy = load_policy(config.policy)
        except CheckpointError as error:
            return report_error(parser.prog, f"--policy: {error}")
        print(f"policy {config.policy}: for {policy.task}, observation {policy.observation!r} "
              f"({policy.num_obs} values)")
    elif config.policy_share > 0.0 and shipped_policy_or_none(config.task_id) is None:
        print(f"no policy is shipped for {config.task_id}: the autopilot sails every boat")
    try:
        os.makedirs(args.out, exist_ok=True)
        result = run_demo(config, device=device, out=args.out, progress=not args.no_progress, record=args.record,
                          policy=policy)
    except ValueError as error:  # a policy whose observation the task cannot give
        return report_error(parser.prog, str(error))
    except OSError as error:  # a file could not be written
        print(f"{parser.prog}: {error}", file=sys.stderr)
        return 1
    hull = demo_task(config, device).simulator.boat.hydrostatics.value
    print(result.evaluation.format_table())
    print(_summary(config, result, hull))
    return 0
