"""One spec per task: its id, its default config, how it is trained, its shipped policy and what it is.

The task registry (``registration``: ``TASK_IDS``, ``make_task_config``, the gymnasium ids), the training
presets (``training.agents.agent_config``) and the shipped policies (``training.policies``) all read
``TASK_SPECS``: a new task is one :class:`TaskSpec` entry here. This module stays light (no Warp, no torch):
the factories name their module and attribute and import it on their first call (:class:`Deferred`).
"""

from __future__ import annotations

import dataclasses
import importlib
from collections.abc import Callable
from typing import Any

__all__ = ["NAMESPACE", "Deferred", "TaskSpec", "TASK_SPECS", "task_spec"]

NAMESPACE = "ocean_warp"
"""Gymnasium namespace of the task ids ("ocean_warp/EBoatMission-v0")."""


@dataclasses.dataclass(frozen=True)
class Deferred:
    """A zero-argument factory named by its module and attribute: calling it imports ``module`` and returns
    ``getattr(module, name)()`` (a config class or a function building one), so that naming it imports
    nothing."""

    module: str
    """Absolute module name, e.g. "ocean_warp.envs.tasks.task_configs"."""
    name: str
    """The attribute of ``module`` to call without arguments."""

    def __call__(self) -> Any:
        return getattr(importlib.import_module(self.module), self.name)()


@dataclasses.dataclass(frozen=True)
class TaskSpec:
    """Everything the package knows of one task by its id."""

    id: str
    """Task id without the namespace, e.g. "EBoatMission-v0"."""
    make_config: Callable[[], Any]
    """Zero-argument factory of the task's default config (a ``TaskConfig``)."""
    make_agent_config: Callable[[], Any]
    """Zero-argument factory of its training config (``training.agents.TrainConfig``)."""
    policy_file: str | None
    """File name of its shipped policy in ``ocean_warp/envs/training/policies/`` (None: none is shipped)."""
    description: str
    """What the task is, in one line."""

    def __post_init__(self):
        owner = f"TaskSpec {self.id!r}"
        if not isinstance(self.id, str) or not self.id or "/" in self.id or self.id != self.id.strip():
            raise ValueError(f"TaskSpec.id must be a task id without namespace (e.g. 'EBoatMission-v0'), "
                             f"got {self.id!r}")
        for name in ("make_config", "make_agent_config"):
            if not callable(getattr(self, name)):
                raise ValueError(f"{owner}: {name} must be a zero-argument factory, got {getattr(self, name)!r}")
        if self.policy_file is not None and (not isinstance(self.policy_file, str) or "/" in self.policy_file
                                             or not self.policy_file.endswith(".pt")):
            raise ValueError(f"{owner}: policy_file must be None or a file name ending in .pt, "
                             f"got {self.policy_file!r}")
        if not isinstance(self.description, str) or not self.description.strip() or "\n" in self.description:
            raise ValueError(f"{owner}: description must be one non-empty line, got {self.description!r}")


_CONFIGS = f"{__package__}.tasks.task_configs"
_AGENTS = f"{__package__}.training.agents"
_VRX = f"{__package__}.vrx.tasks"


def _spec(task_id: str, config_class: str, agent: str, policy_file: str | None, description: str) -> TaskSpec:
    """A spec whose config is ``tasks.task_configs.<config_class>()`` and whose training config is
    ``training.agents.<agent>()``."""
    return TaskSpec(task_id, Deferred(_CONFIGS, config_class), Deferred(_AGENTS, agent), policy_file, description)


TASK_SPECS: tuple[TaskSpec, ...] = (
    _spec("EBoatWaypoint-v0", "WaypointConfig", "waypoint_agent", "eboat_waypoint.pt",
          "the seed paper's task: one waypoint 100 m away, exact observations (5 values)"),
    _spec("EBoatWaypointPlus-v0", "WaypointPlusConfig", "waypoint_plus_agent", "eboat_waypoint_plus.pt",
          "one waypoint 50-150 m away at any bearing, noisy sensors and the 'plus' observation, a choppy sea"),
    _spec("EBoatMission-v0", "MissionConfig", "mission_agent", "eboat_mission.pt",
          "the six-waypoint mission BCDACA in a gusty 10 m/s wind and a JONSWAP sea"),
    _spec("EBoatMissionSail-v0", "MissionSailConfig", "mission_sail_agent", "eboat_mission_sail.pt",
          "the BCDACA mission under sail alone (propeller off, the 'plus' observation)"),
    _spec("EBoatAvoid-v0", "AvoidConfig", "avoid_agent", "eboat_avoid.pt",
          "a waypoint 100-200 m away through 6-12 buoys and piles, with a lidar"),
    _spec("EBoatAvoidSail-v0", "AvoidSailConfig", "avoid_sail_agent", None,
          "the avoidance task under sail alone (propeller off)"),
    TaskSpec("WamvStationKeeping-v0", Deferred(_VRX, "station_keeping_task"),
             Deferred(_AGENTS, "wamv_station_keeping_agent"), "wamv_station_keeping.pt",
             "VRX's station keeping on the WAM-V: hold a goal pose for 60 s in wind, waves and current"),
    TaskSpec("WamvWayfinding-v0", Deferred(_VRX, "wayfinding_task"), Deferred(_AGENTS, "wamv_wayfinding_agent"),
             "wamv_wayfinding.pt", "VRX's wayfinding on the WAM-V: visit three to five goal poses in turn"),
    TaskSpec("WamvFollowPath-v0", Deferred(_VRX, "follow_path_task"), Deferred(_AGENTS, "wamv_follow_path_agent"),
             "wamv_follow_path.pt", "VRX's follow-the-path on the WAM-V: pass three to nine gates in order"),
)
"""Every task, in the order the command line lists them."""


def task_spec(task_id: str) -> TaskSpec:
    """The spec of a task id, with or without the "ocean_warp/" prefix.

    Raises:
        ValueError: not a known task id (one line naming the known ones).
    """
    name = str(task_id).removeprefix(f"{NAMESPACE}/")
    for spec in TASK_SPECS:
        if spec.id == name:
            return spec
    raise ValueError(f"unknown task id {task_id!r}; known: {', '.join(spec.id for spec in TASK_SPECS)} "
                     f"(optionally prefixed '{NAMESPACE}/')")
