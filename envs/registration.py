"""Task ids: their configs, and their registration with gymnasium, read from the task specs
(``task_specs.TASK_SPECS``: one per task).

``register_envs()`` registers ``ocean_warp/EBoatWaypoint-v0``, ``ocean_warp/EBoatWaypointPlus-v0``,
``ocean_warp/EBoatMission-v0``, ``ocean_warp/EBoatMissionSail-v0`` (the mission under sail alone: the
propeller off, a0 ignored; the physics profile's boat), ``ocean_warp/EBoatAvoid-v0`` (a waypoint through
buoys and piles, with a lidar) and ``ocean_warp/EBoatAvoidSail-v0`` (the same under sail alone), each with a
single-boat ``entry_point`` (``gymnasium.make``) and a batched ``vector_entry_point`` (``gymnasium.make_vec(...,
vectorization_mode="vector_entry_point")``).
Nothing is registered with ``max_episode_steps``: the simulator times episodes out itself, so
gymnasium adds no TimeLimit wrapper unless the caller asks for one.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import gymnasium as gym

from . import task_specs
from .task_specs import NAMESPACE, task_spec

__all__ = ["NAMESPACE", "TASK_IDS", "DEFAULT_TASK", "task_name", "make_task_config", "register_envs"]

TASK_IDS = tuple(spec.id for spec in task_specs.TASK_SPECS)
"""Task ids, without the namespace (``task_specs.TASK_SPECS``)."""

DEFAULT_TASK = "EBoatMission-v0"
"""The task every ``ocean-warp`` job that takes ``--task`` sails without it: the BCDACA mission."""


def task_name(task_id: str) -> str:
    """A registered task id without the namespace ("ocean_warp/EBoatMission-v0" -> "EBoatMission-v0").

    Raises:
        ValueError: not a registered task id (the message, one line, names the known ones).
    """
    return task_spec(task_id).id


def make_task_config(task: Any, *, max_episode_steps: int | None = None, **overrides: Any) -> Any:
    """A task config from an id or a config, with fields replaced.

    Args:
        task: a task id ("EBoatWaypoint-v0" or "ocean_warp/EBoatWaypoint-v0", ...) or a config object.
        max_episode_steps: episode length limit [decisions]; None keeps the config's.
        **overrides: config fields to replace (``dataclasses.replace``; the config validates them).

    Returns:
        the config (a new object when anything was replaced).
    """
    config = task_spec(task).make_config() if isinstance(task, str) else task
    if max_episode_steps is not None:
        overrides = {**overrides, **_episode_steps_override(config, int(max_episode_steps))}
    return dataclasses.replace(config, **overrides) if overrides else config


def _episode_steps_override(config: Any, steps: int) -> dict[str, Any]:
    """The config field that makes an episode last ``steps`` decisions: ``episode_time`` [s]."""
    if steps < 1:
        raise ValueError(f"max_episode_steps must be >= 1, got {steps}")
    return {"episode_time": steps * config.decision_period}


def register_envs() -> None:
    """Register every task (``task_specs.TASK_SPECS``) with gymnasium; calling it again changes nothing."""
    for name in (spec.id for spec in task_specs.TASK_SPECS):
        env_id = f"{NAMESPACE}/{name}"
        if env_id in gym.registry:
            continue
        gym.register(
            id=env_id,
            entry_point="ocean_warp.envs.interfaces.gym_env:SailingEnvSingle",
            vector_entry_point="ocean_warp.envs.interfaces.gym_env:SailingVectorEnv",
            kwargs={"task": name},
        )
