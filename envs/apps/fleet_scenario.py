"""A fleet sailing one task (by default the BCDACA mission), all boats on the same water: the task the demo,
the USD export and the video build from their :class:`FleetScenario` (``scenario_options``: the settings and
their options)."""

from __future__ import annotations

import dataclasses

import warp as wp

from ocean_warp.eboat import Hydrostatics

from ..evaluation import DEFAULT_TASK, evaluation_task
from .scenario_options import (HULLS, FleetScenario, add_sailing_arguments, add_scenario_arguments,
                               checked_task_name, scenario_arguments, shipped_policy_or_none)

__all__ = ["FleetScenario", "HULLS", "fleet_course_task", "add_sailing_arguments", "add_scenario_arguments",
           "scenario_arguments", "checked_task_name", "shipped_policy_or_none", "controller_observation"]


def fleet_course_task(*, sea_state: float | None, wind: float | None, seed: int, time_limit: float, hull: str,
                      loop_period: float | None, device, task=DEFAULT_TASK, observation=None) -> object:
    """``task`` (a registered id or a TaskConfig; default the BCDACA mission) as ``ocean-warp eval`` sails it
    (``evaluation_task``: this sea [m] and wind [m/s], None the task's, seed, time limit [s] and the
    policy's ``observation`` set, None the task's), on the hull ``hull`` resolves to on ``device`` (see
    :data:`HULLS`), the sea looping every ``loop_period`` [s] (None: no loop), and every boat on the same
    water."""
    if hull not in HULLS:
        raise ValueError(f"fleet_course_task: hull must be one of {', '.join(HULLS)}, got {hull!r}")
    task = evaluation_task(task, sea_state=sea_state, wind=wind, seed=seed, time_limit=time_limit,
                           observation=observation)
    simulator = task.simulator
    if hull == "auto":
        hull = "mesh" if wp.get_device(device).is_cuda else "points"
    hydrostatics = Hydrostatics.MESH if hull == "mesh" else Hydrostatics.POINTS
    simulator = dataclasses.replace(
        simulator, boat=dataclasses.replace(simulator.boat, hydrostatics=hydrostatics),
        ocean=dataclasses.replace(simulator.ocean, loop_period=loop_period))
    # Every boat on the same water (not each on its own part of the periodic tile): the stage then shows
    # a fleet racing the one course on the one sea, each boat with its own start and gusts.
    return dataclasses.replace(task, simulator=simulator, ocean_spacing=False)


def controller_observation(controller):
    """The observation set of the policy ``controller`` sails with (a ``PolicyController``, or one inside a
    ``FleetController``); None where no policy sails (the task's own set is then used)."""
    inner = [controller] + [member for member, _ in getattr(controller, "groups", [])]
    for member in inner:
        policy = getattr(member, "policy", None)
        if policy is not None:
            return policy.observation
    return None
