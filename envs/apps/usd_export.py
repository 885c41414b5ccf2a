"""``ocean-warp export-usd``: record any scenario to a USD stage: a fleet sailing a task (by default the
BCDACA mission) in a JONSWAP sea, steered by the task's shipped policy, the classical autopilot or fixed
commands, for a given duration.

    ocean-warp export-usd --boats 8 --sea-state 0.5 --wind 8 --duration 120 --controller autopilot \\
        --out out/autopilot.usdc
    ocean-warp export-usd --task EBoatAvoid-v0 --boats 4 --duration 60 --out out/avoid.usdc

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

import argparse
import dataclasses
import os
import sys
import time

from ocean_warp.cli_support import job_parser, plural, report_error
from ocean_warp.devices import resolve_device
from ocean_warp.usd.recorder import TIME_CODES_PER_SECOND
from ocean_warp.usd.stage_file import check_stage_path
from ocean_warp.validation import require_in_range, require_positive

from ..sailing_env import SailingEnv
from .fleet_scenario import FleetScenario, add_scenario_arguments, scenario_arguments, shipped_policy_or_none
from .evaluation import AutopilotController, FixedController, PolicyController, RecordedDecision
from ..training.policies import shipped_policy_path
from ..training.policy_io import CheckpointError, load_policy

__all__ = ["ExportConfig", "FixedController", "export_scenario", "main"]

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


def _actions(text: str) -> tuple[float, float, float]:
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected three numbers like 0.4,0,0.1, got {text!r}") from None
    if len(values) != 3:
        raise argparse.ArgumentTypeError(f"expected three numbers like 0.4,0,0.1, got {text!r}")
    return values


PROG = "ocean-warp export-usd"


def _parser() -> argparse.ArgumentParser:
    d = ExportConfig()
    parser = job_parser(
        "export-usd", "Record a fleet sailing a task (by default the BCDACA mission) in a JONSWAP sea to a USD "
        "stage (Z up, metres), with a preview PNG beside it; a task with obstacles shows each boat's buoys and "
        "piles.")
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
    parser.add_argument("--out", default="out/scenario.usdc", help="the stage to write: .usdc, .usda or .usd")
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``ocean-warp export-usd``; returns the exit code (2 for a bad option or policy)."""
    args = _parser().parse_args(argv)
    out = args.out
    if args.usda and out.endswith(".usdc"):
        out = out[: -len(".usdc")] + ".usda"
    try:
        # Before anything is made: a stage's extension, a folder that can be made. The folder itself is made
        # by the recorder, which removes it again if the export fails.
        check_stage_path("--out", out, True if args.usda else None)
        config = ExportConfig(**scenario_arguments(args), duration=args.duration, controller=args.controller,
                              actions=args.actions, policy=getattr(args, "policy", None), loop_period=args.loop_period,
                              instanced=args.instanced, time_codes_per_second=args.playback_fps)
        device = resolve_device(args.device, name="--device")
        if config.controller == "policy" and config.policy is None \
                and shipped_policy_or_none(config.task_id) is None:
            print(f"no policy is shipped for {config.task_id}: the autopilot steers every boat "
                  "(--policy PATH steers with one)")
            config = dataclasses.replace(config, controller="autopilot")
    except (ValueError, OSError) as error:  # a bad setting or task; an unknown device; an unusable --out
        return report_error(PROG, str(error))
    started = time.perf_counter()
    try:
        files = export_scenario(config, out, device=device, ascii=True if args.usda else None,
                                progress=not args.no_progress)
    except (ValueError, CheckpointError) as error:
        return report_error(PROG, str(error))
    except OSError as error:  # the stage could not be written
        print(f"{PROG}: {error}", file=sys.stderr)
        return 1
    seconds = time.perf_counter() - started
    print(f"{plural(config.boats, 'boat')} x {config.duration:g} s of {config.task_id} ({config.controller}) "
          f"recorded in {seconds:.1f} s")
    for name, path in files.items():
        print(f"wrote {path} ({name}, {os.path.getsize(path) / 2**20:.1f} MiB)")
    return 0
