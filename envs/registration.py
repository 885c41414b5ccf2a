"""Task ids: their configs, and their registration with gymnasium.

``register_envs()`` registers ``ocean_warp/EBoatWaypoint-v0``, ``ocean_warp/EBoatWaypointPlus-v0``,
``ocean_warp/EBoatMission-v0``, ``ocean_warp/EBoatMissionSail-v0`` (the mission under sail alone: the
propeller off, a0 ignored; the physics profile's boat), ``ocean_warp/EBoatAvoid-v0`` (a waypoint through
buoys and piles, with a lidar) and ``ocean_warp/EBoatAvoidSail-v0`` (the same under sail alone), each with a single-boat ``entry_point``
(``gymnasium.make``) and a batched ``vector_entry_point`` (``gymnasium.make_vec(...,
vectorization_mode="vector_entry_point")``).
Nothing is registered with ``max_episode_steps``: the simulator times episodes out itself, so
gymnasium adds no TimeLimit wrapper unless the caller asks for one.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import gymnasium as gym

__all__ = ["NAMESPACE", "TASK_IDS", "DEFAULT_TASK", "task_name", "make_task_config", "register_envs"]

NAMESPACE = "ocean_warp"
"""Gymnasium namespace of the ids registered here."""

TASK_IDS = ("EBoatWaypoint-v0", "EBoatWaypointPlus-v0", "EBoatMission-v0", "EBoatMissionSail-v0", "EBoatAvoid-v0",
            "EBoatAvoidSail-v0")
"""Task ids, without the namespace."""

DEFAULT_TASK = "EBoatMission-v0"
"""The task every ``ocean-warp`` job that takes ``--task`` sails without it: the BCDACA mission."""

_CONFIG_CLASS_NAMES = {
    "EBoatWaypoint-v0": "WaypointConfig",
    "EBoatWaypointPlus-v0": "WaypointPlusConfig",
    "EBoatMission-v0": "MissionConfig",
    "EBoatMissionSail-v0": "MissionSailConfig",
    "EBoatAvoid-v0": "AvoidConfig",
    "EBoatAvoidSail-v0": "AvoidSailConfig",
}


def task_name(task_id: str) -> str:
    """A registered task id without the namespace ("ocean_warp/EBoatMission-v0" -> "EBoatMission-v0").

    Raises:
        ValueError: not a registered task id (the message, one line, names the known ones).
    """
    name = str(task_id).removeprefix(f"{NAMESPACE}/")
    if name not in _CONFIG_CLASS_NAMES:
        raise ValueError(f"unknown task id {task_id!r}; known: {', '.join(TASK_IDS)} "
                         f"(optionally prefixed '{NAMESPACE}/')")
    return name


def _default_config(task_id: str) -> Any:
    """The default config of a task id (with or without the namespace)."""
    name = task_name(task_id)
    from .tasks import task_configs as tasks  # deferred: tasks pull in the simulator, registration must stay light

    return getattr(tasks, _CONFIG_CLASS_NAMES[name])()


def make_task_config(task: Any, *, max_episode_steps: int | None = None, **overrides: Any) -> Any:
    """A task config from an id or a config, with fields replaced.

    Args:
        task: a task id ("EBoatWaypoint-v0" or "ocean_warp/EBoatWaypoint-v0", ...) or a config object.
        max_episode_steps: episode length limit [decisions]; None keeps the config's.
        **overrides: config fields to replace (``dataclasses.replace``; the config validates them).

    Returns:
        the config (a new object when anything was replaced).
    """
    config = _default_config(task) if isinstance(task, str) else task
    if max_episode_steps is not None:
        overrides = {**overrides, **_episode_steps_override(config, int(max_episode_steps))}
    return dataclasses.replace(config, **overrides) if overrides else config


def _episode_steps_override(config: Any, steps: int) -> dict[str, Any]:
    """The config field that makes an episode last ``steps`` decisions: ``episode_time`` [s]."""
    if steps < 1:
        raise ValueError(f"max_episode_steps must be >= 1, got {steps}")
    return {"episode_time": steps * config.decision_period}


def register_envs() -> None:
    """Register the task ids (``TASK_IDS``) with gymnasium; calling it again changes nothing."""
    for name in TASK_IDS:
        env_id = f"{NAMESPACE}/{name}"
        if env_id in gym.registry:
            continue
        gym.register(
            id=env_id,
            entry_point="ocean_warp.envs.interfaces.gym_env:SailingEnvSingle",
            vector_entry_point="ocean_warp.envs.interfaces.gym_env:SailingVectorEnv",
            kwargs={"task": name},
        )
