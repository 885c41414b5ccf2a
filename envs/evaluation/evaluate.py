"""The evaluation of a task: every controller sails the same runs (:func:`evaluate_mission`), optionally logged
into a rosbag2 MCAP file."""

from __future__ import annotations

import math
import os
import re

import numpy as np

from ocean_warp.ocean_config import require_significant_wave_height

from ..controllers.line_following import LineFollowingConfig
from ..controllers.sailing_autopilot import AutopilotConfig
from ..registration import DEFAULT_TASK, make_task_config, task_name
from ..env_factory import make_env
from ..sailing_env import SailingEnv
from ..vrx.task_config import VrxTask, VrxTaskConfig
from ..tasks.task_configs import TaskConfig
from ..training.policy_io import Policy, load_policy
from ..controllers.gate_guidance import GateGuidanceController
from ..controllers.los_guidance import LosGuidanceController
from ..controllers.pivot_station_keeping import PivotStationKeepingController
from ..controllers.station_keeping import WAMV_STATION_KEEPING, StationKeepingController
from .controllers import AutopilotController, PolicyController
from .presets import evaluation_task
from .results_io import MissionEvaluation
from .rollout import sail_mission

__all__ = ["evaluate_mission"]


def evaluate_mission(policy: Policy | str | os.PathLike | None = None, runs: int = 20, sea_state: float | None = None,
                     wind: float | None = None, seed: int = 0, device="cpu", time_limit: float | None = None,
                     autopilot: bool | str | LineFollowingConfig | AutopilotConfig = True, progress: bool = True, *,
                     task: TaskConfig | str | None = None,
                     record: str | os.PathLike | None = None, reef: int | None = None) -> MissionEvaluation:
    """Sail a task's runs (default the mission, EBoatMission-v0) ``runs`` times with ``policy`` (a Policy, a
    checkpoint path, or None for none) and with a classical controller (``autopilot``: True or "line" for the
    line follower's defaults, "legacy" for the legacy autopilot's, a LineFollowingConfig or an AutopilotConfig,
    or False for none; named "autopilot" either way; without the motor on a task without propeller), all on
    the same runs (one environment per run, the same seed for every controller).

    Args:
        sea_state: significant wave height Hs [m] of the task's sea (>= 0); None: the task's (0.3 m for
            the missions).
        wind: mean true wind speed [m/s] (>= 0) of every run, with the task's gusts and directions; None:
            the task's (10 m/s toward +x for the missions; the waypoint tasks draw it per run).
        seed: seed of the sea and of the environments' random streams (starts, waypoints, gusts).
        device: Warp device ("cpu", "cuda", "cuda:N").
        time_limit: per run [s]; None: the task's (1800 s for the missions).
        progress: a progress bar per controller over its decisions.
        task: a task config or a registered task id (default EBoatMission-v0); tests pass cheaper configs
            (a coarser boat or sea).
        record: a rosbag2 MCAP log to write (a path ending in .mcap; the ``mcap`` extra): every controller's
            runs, each under its own namespace (``/<controller>/eboat_<run>``, ``/<controller>/eboat`` for
            one run), from their start to the end of the controller's last decision, once per decision
            (``ocean_warp.envs.ros.mcap_log``; None: no log).
        reef: one reef level for every run (``evaluation_task``); None: the task's rule.

    Raises:
        ValueError: a bad setting, an unknown task id or nothing to evaluate; CheckpointError: an unusable
            checkpoint path.
    """
    if isinstance(runs, bool) or not isinstance(runs, (int, np.integer)) or runs < 1:
        raise ValueError(f"evaluate_mission: runs must be an integer >= 1, got {runs!r}")
    if sea_state is not None:
        require_significant_wave_height("evaluate_mission: sea_state", sea_state)
    if wind is not None and not (isinstance(wind, (int, float)) and math.isfinite(wind) and wind >= 0.0):
        raise ValueError(f"evaluate_mission: wind must be a finite number >= 0 or None, got {wind!r}")
    if time_limit is not None and not (math.isfinite(time_limit) and time_limit > 0.0):
        raise ValueError(f"evaluate_mission: time_limit must be > 0 [s] or None, got {time_limit!r}")
    if isinstance(policy, (str, os.PathLike)):
        policy = load_policy(policy)
    controllers: list = []
    if policy is not None:
        controllers.append(PolicyController(policy))
    task = DEFAULT_TASK if task is None else task
    resolved = make_task_config(task) if isinstance(task, str) else task
    if autopilot is not False and autopilot is not None and isinstance(resolved, VrxTaskConfig):
        controllers.append(vrx_baseline(resolved, autopilot))
    elif autopilot is not False and autopilot is not None:
        if isinstance(autopilot, str):
            controllers.append(AutopilotController(autopilot=autopilot))
        else:
            controllers.append(AutopilotController(None if autopilot is True else autopilot))
    if not controllers:
        raise ValueError("evaluate_mission: nothing to evaluate (no policy and autopilot=False)")
    config = evaluation_task(task, sea_state=sea_state, wind=wind, seed=seed, time_limit=time_limit,
                             observation=None if policy is None else policy.observation, reef=reef)
    env = make_env(config, int(runs), device=device, seed=seed)
    log = None
    if record is not None:
        from ..ros.mcap_log import McapRecorder

        log = McapRecorder(record)
    try:
        results = {controller.name: sail_mission(env, controller, progress=progress,
                                                 **_logging_callbacks(log, env, controller.name))
                   for controller in controllers}
    except BaseException:
        if log is not None:
            log.abort()
        raise
    if log is not None:
        log.close()
    low, high = config.start.wind_speed
    settings = {"task": task_name(task) if isinstance(task, str) else None, "runs": int(runs),
                "sea_state": config.simulator.ocean.significant_wave_height, "wind": low if low == high else None,
                "seed": int(seed), "device": str(env.device), "time_limit": config.episode_time}
    return MissionEvaluation(task=config, settings=settings, results=results)


def vrx_baseline(task: VrxTaskConfig, autopilot: bool | str = True):
    """The classical controller of one of VRX's tasks. By default (``autopilot`` True or "line"): station keeping
    in transit, back-and-fill and holding modes for station keeping and for wayfinding (each goal is a pose to
    reach, held until the env shows the next), LOS guidance through the gates clear of the buoys for the path.
    ``autopilot`` "legacy": the earlier baselines, PID station keeping (``WAMV_STATION_KEEPING``) and LOS guidance
    along the legs, blind to the buoys."""
    legacy = autopilot == "legacy"
    if task.kind is VrxTask.FOLLOW_PATH:
        return LosGuidanceController() if legacy else GateGuidanceController()
    return StationKeepingController(WAMV_STATION_KEEPING) if legacy else PivotStationKeepingController()


def _logging_callbacks(log, env: SailingEnv, name: str) -> dict:
    """:func:`sail_mission`'s callbacks that log ``env`` into ``log`` (an ``McapRecorder``) at the start and
    after every decision, under ``/<name>`` (the controller's name, with characters a ROS name cannot hold
    replaced by "_"); none without a log."""
    if log is None:
        return {}
    prefix = "/" + re.sub(r"[^A-Za-z0-9_]", "_", name)
    if not prefix[1:2].isalpha():
        prefix = "/c" + prefix[1:]
    return {"on_start": lambda: log.record(env, prefix=prefix),
            "on_decision": lambda k, decision: log.record(env, prefix=prefix)}
