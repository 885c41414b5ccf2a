"""``ocean-warp export-usd``: record any scenario to a USD stage: a fleet sailing a task (by default the
BCDACA mission) in a JONSWAP sea, steered by the task's shipped policy, the classical autopilot or fixed
commands, for a given duration.

    ocean-warp export-usd --boats 8 --sea-state 0.5 --wind 8 --duration 120 --controller autopilot \\
        --out out/export-usd/autopilot.usdc
    ocean-warp export-usd --task EBoatAvoid-v0 --boats 4 --duration 60 --out out/export-usd/avoid.usdc

``--task`` is any registered task id (as ``ocean-warp eval --task``; with or without "ocean_warp/"). A task
whose boats draw their own waypoints shows a buoy at each boat's waypoint; a task with obstacles
(EBoatAvoid-v0, EBoatAvoidSail-v0) shows each boat's buoys and piles under /World/Objects, the buoys
riding the waves frame by frame. The stage shows each boat's first episode: a boat whose episode ended is
held where it ended, with its obstacles (``ocean_warp.envs.apps.demo_stage``). ``--controller policy`` on a
task without a shipped policy (and without ``--policy``) says so in one line and steers with the autopilot.

``--fps`` is how many frames are recorded per simulated second; ``--playback-fps`` the stage's time codes
(and frames) per second, 24 by default, so that Blender (24 fps) plays it in real time.
"""

from __future__ import annotations

import contextlib
import dataclasses
import os
import sys
import time

from ocean_warp.cli_support import checked_device, checked_output_file, plural, report_error
from ocean_warp.usd.stage_file import check_stage_path

from ..env_factory import make_env
from ..evaluation.evaluate import vrx_baseline
from ..evaluation.presets import vrx_evaluation_task
from ..registration import make_task_config
from ..sailing_env import SailingEnv
from ..vrx.task_config import VrxTaskConfig
from .fleet_scenario import scenario_arguments, shipped_policy_or_none
from .usd_export_options import ExportConfig, parser as _parser
from ..evaluation import AutopilotController, FixedController, PolicyController, RecordedDecision, warn_other_task
from ..training.policies import shipped_policy_path
from ..training.policy_io import CheckpointError, load_policy

__all__ = ["ExportConfig", "FixedController", "export_scenario", "main"]



def scenario_task(config: ExportConfig, device, observation=None):
    """The scenario's task (by default the BCDACA mission) with its sea, wind, seed, hull and loop, every boat
    on the same water; ``observation``: the policy's set (None: the task's)."""
    return config.task(time_limit=max(config.duration, 1.0), loop_period=config.loop_period, device=device,
                       observation=observation)


def export_scenario(config: ExportConfig, path: str | os.PathLike, *, device: str = "cpu", ascii: bool | None = None,
                    progress: bool = True) -> dict[str, str]:
    """Sail the scenario and record it to the stage at ``path``; returns the files written (stage, ocean
    loop where there is one, preview PNG). The stage shows each boat's first episode (its course and, on a
    task with obstacles, its obstacle layout: ``demo_stage``)."""
    from tqdm import tqdm

    from .demo_stage import MissionStageRecorder

    if isinstance(make_task_config(config.task_id), VrxTaskConfig):
        return _export_vrx(config, path, device=device, progress=progress, ascii=ascii)
    observation = None
    if config.controller == "policy":
        policy = load_policy(config.policy or shipped_policy_path(config.task_id))
        controller, observation = PolicyController(policy), policy.observation
    elif config.controller == "autopilot":
        controller = AutopilotController()
    else:
        controller = FixedController(config.actions)
    task = scenario_task(config, device, observation)
    env = SailingEnv(task, config.boats, device=device, seed=config.seed)
    env.reset(seed=config.seed)
    controller.reset(env)
    decision = RecordedDecision(env, config.frames_per_second)
    recorder = MissionStageRecorder(env, path, frames_per_decision=config.frames_per_second,
                                    instanced=config.instanced, ascii=ascii,
                                    time_codes_per_second=config.time_codes_per_second, **config.stage_options())
    decisions = int(round(config.duration / env.decision_period))
    try:
        for k in tqdm(range(decisions), desc="export-usd", unit="decision", disable=not progress):
            controller.act(env)
            decision()
            recorder.record((k + 1) * env.decision_period, decision.frames())
    except BaseException:
        recorder.abort()
        raise
    return recorder.close()


def _export_vrx(config: ExportConfig, path, *, device, progress: bool, ascii: bool | None) -> dict[str, str]:
    """One of VRX's tasks to a stage: its vessel drawn part by part (``StageRecorder.for_vessel``, one prim per
    boat or point instancers as ``config.instanced`` says), a frame after every decision (a boat whose episode
    ended is shown at its next start)."""
    from tqdm import tqdm

    from ocean_warp.usd.recorder import StageRecorder, record_vessel
    from ocean_warp.usd.stage_options import FleetDrawing

    task = vrx_evaluation_task(make_task_config(config.task_id), sea_state=config.sea_state, wind=config.wind,
                               seed=config.seed, time_limit=max(config.duration, 1.0))
    if config.controller == "policy":
        controller = PolicyController(load_policy(config.policy or shipped_policy_path(config.task_id)))
    elif config.controller == "autopilot":
        controller = vrx_baseline(task)
    else:
        raise ValueError(f"--controller fixed: {config.task_id}'s {task.num_actions} actions are the "
                         f"{task.vessel.name}'s; steer it with the policy or the autopilot")
    env = make_env(task, config.boats, device=device, seed=config.seed)
    env.reset(seed=config.seed)
    controller.reset(env)
    fleet = FleetDrawing(config.boats, vessel=task.vessel, instanced=config.instanced)
    recorder = StageRecorder.for_vessel(path, task.vessel, env.simulator, fps=1.0 / env.decision_period, fleet=fleet,
                                        time_codes_per_second=config.time_codes_per_second, ascii=ascii)
    decisions = int(round(config.duration / env.decision_period))
    try:
        record_vessel(recorder, env.simulator, 0.0)
        for k in tqdm(range(decisions), desc="export-usd", unit="decision", disable=not progress):
            controller.act(env)
            env.step()
            record_vessel(recorder, env.simulator, (k + 1) * env.decision_period)
    except BaseException:
        recorder.abort()
        raise
    return {"stage": recorder.close()}


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``ocean-warp export-usd``; returns the exit code (2 for a bad option or policy)."""
    parser = _parser()
    args = parser.parse_args(argv)
    out = args.out
    if args.usda and out.endswith(".usdc"):
        out = out[: -len(".usdc")] + ".usda"
    checked_output_file(parser, out, "--out")  # its suffix: check_stage_path
    device = checked_device(parser, args.device)
    try:
        # Before anything is made: a stage's extension, a folder that can be made. The folder itself is made
        # by the recorder, which removes it again if the export fails.
        check_stage_path("--out", out, True if args.usda else None)
        config = ExportConfig(**scenario_arguments(args), duration=args.duration, controller=args.controller,
                              actions=args.actions, policy=getattr(args, "policy", None), loop_period=args.loop_period,
                              instanced=args.instanced, time_codes_per_second=args.playback_fps)
        if config.controller == "policy" and config.policy is None \
                and shipped_policy_or_none(config.task_id) is None:
            print(f"no policy is shipped for {config.task_id}: the autopilot steers every boat "
                  "(--policy PATH steers with one)")
            config = dataclasses.replace(config, controller="autopilot")
    except (ValueError, OSError) as error:  # a bad setting or task; an unusable --out
        return report_error(parser.prog, str(error))
    if config.controller == "policy" and config.policy is not None:
        with contextlib.suppress(CheckpointError):  # an unusable file is reported by the export
            warn_other_task(parser.prog, load_policy(config.policy), config.task_id)
    started = time.perf_counter()
    try:
        files = export_scenario(config, out, device=device, ascii=True if args.usda else None,
                                progress=not args.no_progress)
    except (ValueError, CheckpointError) as error:
        return report_error(parser.prog, str(error))
    except OSError as error:  # the stage could not be written
        print(f"{parser.prog}: {error}", file=sys.stderr)
        return 1
    seconds = time.perf_counter() - started
    print(f"{plural(config.boats, 'boat')} x {config.duration:g} s of {config.task_id} ({config.controller}) "
          f"recorded on {device} in {seconds:.1f} s")
    for name, path in files.items():
        print(f"wrote {path} ({name}, {os.path.getsize(path) / 2**20:.1f} MiB)")
    return 0
