"""Evaluation of controllers on a task (installed as ``ocean_warp.envs.evaluation``): what ``ocean-warp eval``,
``demo``, ``render`` and ``export-usd`` sail with (the command line itself is ``ocean_warp.envs.apps.evaluation``).

- ``controllers``: the :class:`Controller` protocol, ``FixedController``, ``PolicyController``,
  ``AutopilotController``, ``FleetController``; whether a policy reads what a task gives.
- ``recording``: ``RunPath`` (a run's path) and ``RecordedDecision`` (frames from inside a decision).
- ``results``: ``ControllerResult``, a controller's runs and their metrics.
- ``rollout``: ``sail_mission``, one controller sailing every run to the end of its first episode.
- ``presets``: ``evaluation_task`` and ``mission_task``, a task as eval sails it.
- ``results_io``: ``MissionEvaluation`` and its files (``TABLE_COLUMNS``, ``RUN_COLUMNS``).
- ``evaluate``: ``evaluate_mission``, every controller on the same runs.
- ``mission_metrics`` and ``mission_plot``: what a run measures (distance, tacks, cross-track spread) and
  draws.
"""

from ..registration import DEFAULT_TASK
from .controllers import (
    AUTOPILOTS,
    MOTOR_ASSIST_LEVEL,
    AutopilotController,
    Controller,
    FixedController,
    FleetController,
    PolicyController,
    observation_mismatch,
    observation_text,
    warn_other_task,
)
from .evaluate import evaluate_mission
from .presets import conditions_text, course_text, evaluation_task, mission_task, wind_text
from .recording import RecordedDecision, RunPath
from .results import ControllerResult
from .results_io import RUN_COLUMNS, TABLE_COLUMNS, MissionEvaluation
from .rollout import sail_mission

__all__ = ["Controller", "FixedController", "PolicyController", "AutopilotController", "FleetController",
           "AUTOPILOTS", "MOTOR_ASSIST_LEVEL", "observation_text", "observation_mismatch", "warn_other_task",
           "RunPath", "RecordedDecision", "ControllerResult", "sail_mission", "evaluation_task", "mission_task",
           "course_text", "wind_text", "conditions_text", "TABLE_COLUMNS", "RUN_COLUMNS", "MissionEvaluation",
           "evaluate_mission", "DEFAULT_TASK"]
