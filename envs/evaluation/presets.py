"""A task as ``ocean-warp eval`` sails it (:func:`evaluation_task`, :func:`mission_task`), and its course,
wind and sea in words."""

from __future__ import annotations

import dataclasses

from ..registration import DEFAULT_TASK, make_task_config
from ..vrx.task_config import VrxTaskConfig
from ..tasks.task_configs import BCDACA_ROUTE, MissionConfig, ObservationSet, TaskConfig

__all__ = ["evaluation_task", "mission_task", "course_text", "wind_text", "conditions_text"]


def _replace_given(config, **fields):
    """``config`` (a dataclass) with the ``fields`` whose value is not None replaced."""
    given = {name: value for name, value in fields.items() if value is not None}
    return dataclasses.replace(config, **given) if given else config


def evaluation_task(task: TaskConfig | str = DEFAULT_TASK, *, sea_state: float | None = None,
                    wind: float | None = None, seed: int = 0, time_limit: float | None = None,
                    observation: ObservationSet | str | None = None, reef: int | None = None) -> TaskConfig:
    """``task`` (a config, or a registered task id with or without "ocean_warp/") as ``ocean-warp eval``
    sails it: the sea's significant height ``sea_state`` [m] (None: the task's) and its seed ``seed``; the
    mean true wind ``wind`` [m/s] (None: the task's), which also fixes every start's wind speed (tasks that
    draw it from a range, as the waypoint tasks do, then sail every run at ``wind``); the time limit
    ``time_limit`` [s] (None: the task's); the policy's ``observation`` set (None: the task's); ``reef``, one
    reef level for every run (None: the task's rule, ``TaskConfig.reef``; a task without a rule takes None
    only). Gusts, wind directions and the rest of the start stay the task's. Invalid values raise the configs'
    ``ValueError`` (an unknown id: one naming the known ones)."""
    task = make_task_config(task) if isinstance(task, str) else task
    if isinstance(task, VrxTaskConfig):
        if reef is not None:
            raise ValueError(f"evaluation_task: reef {reef!r} given, but VRX's {task.kind.value} has no sail")
        return vrx_evaluation_task(task, sea_state=sea_state, wind=wind, seed=seed, time_limit=time_limit)
    if not isinstance(task, TaskConfig):
        raise ValueError(f"evaluation_task: task must be a task config or a task id, got {type(task).__name__}")
    if reef is not None:
        if task.reef is None:
            raise ValueError(f"evaluation_task: reef {reef!r} given, but {type(task).__name__} sails without a reef "
                             "rule (the full sail always); leave reef None")
        task = dataclasses.replace(task, reef=dataclasses.replace(task.reef, level=reef, random_level=0.0))
    simulator = dataclasses.replace(
        task.simulator, ocean=_replace_given(task.simulator.ocean, significant_wave_height=sea_state, seed=seed),
        wind=_replace_given(task.simulator.wind, speed=wind))
    start = _replace_given(task.start, wind_speed=None if wind is None else (wind, wind))
    return _replace_given(task, simulator=simulator, start=start, episode_time=time_limit, observation=observation)


def mission_task(*, sea_state: float = 0.3, wind: float = 10.0, seed: int = 0, time_limit: float | None = None,
                 observation: ObservationSet | str | None = None, task: TaskConfig | None = None) -> TaskConfig:
    """A mission as ``ocean-warp eval`` sails it (:func:`evaluation_task`): ``task`` (default
    ``MissionConfig()``; it must have a fixed route) with the sea's significant height ``sea_state`` [m] and
    seed ``seed``, the mean true wind ``wind`` [m/s] (gusts as the task's), the time limit ``time_limit`` [s]
    (None: the task's) and the policy's ``observation`` set (None: the task's). Invalid values raise the
    configs' ``ValueError``."""
    task = task if task is not None else MissionConfig()
    if not isinstance(task, TaskConfig) or task.route is None:
        raise ValueError(f"mission_task: task must be a TaskConfig with a fixed route (a MissionConfig), got {task!r}")
    return evaluation_task(task, sea_state=sea_state, wind=wind, seed=seed, time_limit=time_limit,
                           observation=observation)


def vrx_evaluation_task(task: VrxTaskConfig, *, sea_state: float | None = None, wind: float | None = None,
                        seed: int = 0, time_limit: float | None = None) -> VrxTaskConfig:
    """One of VRX's tasks as ``ocean-warp eval`` sails it: its vessel's sea at ``sea_state`` [m] with seed ``seed``,
    every start's mean wind at ``wind`` [m/s], the time limit ``time_limit`` [s] (None: each the task's)."""
    vessel = task.vessel
    config = dataclasses.replace(vessel.config, ocean=_replace_given(vessel.config.ocean,
                                                                      significant_wave_height=sea_state, seed=seed))
    start = _replace_given(task.start, wind_speed=None if wind is None else (wind, wind))
    return _replace_given(task, vessel=type(vessel)(config), start=start, episode_time=time_limit)


def course_text(task) -> str:
    """What a task's runs sail, in words: "BCDACA", "one waypoint per run" or "a route of R waypoints",
    followed by "through buoys and piles" for a task with obstacles and "under sail alone" for a task
    without propeller; VRX's: "station keeping", "wayfinding through G goal poses", "G gates in order" (G a count or a range,
    "3-5")."""
    if isinstance(task, VrxTaskConfig):
        low, high = task.goal_range
        count = str(low) if low == high else f"{low}-{high}"
        return {"station_keeping": f"station keeping ({task.vessel.name})",
                "wayfinding": f"wayfinding through {count} goal poses ({task.vessel.name})",
                "follow_path": f"{count} gates in order ({task.vessel.name})"}[task.kind.value]
    if task.route is None:
        course = "one waypoint per run"
    elif tuple(task.route) == BCDACA_ROUTE:
        course = "BCDACA"
    else:
        course = f"a route of {len(task.route)} waypoints"
    if task.obstacles is not None:
        course = f"{course} through buoys and piles"
    return course if task.propeller else f"{course} under sail alone"


def wind_text(task: TaskConfig) -> str:
    """The mean true wind speed of a task's runs: "10 m/s", or "2-12 m/s" where each run draws its own."""
    low, high = task.start.wind_speed
    return f"{low:g} m/s" if low == high else f"{low:g}-{high:g} m/s"


def conditions_text(task: TaskConfig, seed: int) -> str:
    """A task's sea, wind and seed in words: "Hs 0.3 m JONSWAP, wind 10 m/s with gusts, seed 0"."""
    ocean, wind = task.simulator.ocean, task.simulator.wind
    gusty = (wind.gust_speed_std > 0.0 or wind.gust_direction_std > 0.0) and task.start.gust_scale[1] > 0.0
    spectrum = {"jonswap": "JONSWAP", "pierson_moskowitz": "Pierson-Moskowitz"}.get(ocean.spectrum.value,
                                                                                   ocean.spectrum.value)
    return (f"Hs {ocean.significant_wave_height:g} m {spectrum}, wind {wind_text(task)}"
            f"{' with gusts' if gusty else ''}, seed {seed}")
