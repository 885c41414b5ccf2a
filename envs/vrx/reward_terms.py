"""The terms of a VRX task's reward, each a device function with its weight's name (``VrxRewardConfig``); a task's
reward kernel holds the progress and the terms whose weight is not zero (``vrx_kernels.vrx_evaluate_kernel``)."""

from __future__ import annotations

import warp as wp

__all__ = ["VRX_REWARD_TERMS", "TERM_WEIGHTS", "vrx_reward_terms", "pose_progress", "error_cost", "effort_cost",
           "reach_bonus", "flagged_penalty"]

VRX_REWARD_TERMS = ("error", "effort", "reach", "flagged")
"""The optional terms, in the order they are summed after the progress."""
TERM_WEIGHTS = {"error": "error_cost", "effort": "action_cost", "reach": "reach_bonus", "flagged": "flagged_penalty"}
"""Each optional term's weight in ``VrxRewardConfig``."""


def vrx_reward_terms(task) -> tuple[str, ...]:
    """The optional terms ``task``'s reward holds: those whose weight is not zero."""
    return tuple(term for term in VRX_REWARD_TERMS if getattr(task.reward, TERM_WEIGHTS[term]) != 0.0)


@wp.func
def pose_progress(previous_error: float, error: float, scale: float) -> float:
    """``scale`` per metre of VRX's pose error removed in the decision."""
    return scale * (previous_error - error)


@wp.func
def error_cost(error: float, cost: float, decision_period: float) -> float:
    """-``cost`` per metre of pose error per second, over the decision's ``decision_period`` [s]."""
    return -(cost * error * decision_period)


@wp.func
def effort_cost(effort: float, actions: int, cost: float) -> float:
    """-``cost`` times the mean squared action (``effort`` is the sum of the squares of ``actions`` actions)."""
    return -(cost * effort / float(actions))


@wp.func
def reach_bonus(bonus: float) -> float:
    """``bonus`` when a goal of wayfinding or a gate of the path is reached."""
    return bonus


@wp.func
def flagged_penalty(penalty: float) -> float:
    """-``penalty`` when the simulator flags the boat."""
    return -penalty
