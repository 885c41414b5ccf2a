"""The terms of a sailing task's reward, one ``wp.func`` each, and which of them a task's config selects.

A decision's reward is the progress toward the waypoint (shaped by the seed's propeller term), plus the reach bonus,
less the lost, flagged or collision penalty, the proximity cost, the smoothness cost, the time cost and the motor's
energy, summed in that order (``RewardConfig`` gives the weights). ``task_kernels.evaluate_kernel`` builds the
evaluation kernel from the terms a task selects: a term whose weight is 0, or a propeller term on a task without a
propeller (its level is always 0 there), is left out of the kernel, which gives the same reward bit for bit.
Every term but the progress returns what it adds to the reward (a cost as a negative number); the reward is
dimensionless, one unit being ``progress_scale`` metres of progress.

    reward_terms(task)       # the names of the terms a TaskConfig selects, in REWARD_TERMS' order
"""

from __future__ import annotations

import warp as wp

from ocean_warp.kernels.eboat_actions import MAX_LEVEL

__all__ = ["REWARD_TERMS", "TERM_WEIGHTS", "reward_terms", "progress", "propeller_shaping", "reach", "lost",
           "flagged", "collision", "proximity", "smoothness", "time_cost", "motor_energy"]

TERM_WEIGHTS = {
    "propeller": ("propeller_gain", "propeller_cost"),
    "reach": ("reach_bonus",),
    "lost": ("lost_penalty",),
    "flagged": ("flagged_penalty",),
    "collision": ("collision_penalty",),
    "proximity": ("proximity_cost",),
    "smoothness": ("smoothness",),
    "time": ("time_cost",),
    "energy": ("energy_cost",),
}
"""Each optional term's weights in ``RewardConfig``: the term is in the kernel when any of them is not 0."""
REWARD_TERMS = tuple(TERM_WEIGHTS)
"""The optional terms, in the order the reward sums them (the progress, always there, comes first)."""
PROPELLER_TERMS = ("propeller", "energy")
"""The terms of the propeller's level: none on a task without a propeller (``TaskConfig.propeller`` False)."""


def reward_terms(task) -> tuple[str, ...]:
    """The optional terms ``task`` (a ``TaskConfig``) selects, in :data:`REWARD_TERMS`' order: those with a
    weight that is not 0, less the propeller's on a task without one."""
    return tuple(name for name, weights in TERM_WEIGHTS.items()
                 if any(getattr(task.reward, weight) != 0.0 for weight in weights)
                 and (task.propeller or name not in PROPELLER_TERMS))


@wp.func
def progress(previous_distance: float, distance: float, progress_scale: float) -> float:
    """Progress toward the waypoint over the decision, (d_prev - d) / ``progress_scale``: distances [m] in the
    horizontal plane, before and after the decision; the scale [m] is one unit of reward."""
    return (previous_distance - distance) / progress_scale


@wp.func
def propeller_shaping(progress: float, level: float, propeller_gain: float, propeller_cost: float) -> float:
    """The seed's propeller term applied to ``progress`` (it scales a gain rather than adding to it): a gain keeps
    1 - ``propeller_gain`` |level| / 5 of itself, a loss grows by ``propeller_cost`` |level|; ``level`` is the
    commanded propeller level's magnitude (0 to 5)."""
    if progress > 0.0:
        return progress * (1.0 - propeller_gain * level / float(MAX_LEVEL))
    return progress - propeller_cost * level


@wp.func
def reach(reach_bonus: float) -> float:
    """+``reach_bonus`` on the decision that brings the boat within the reach radius of its waypoint."""
    return reach_bonus


@wp.func
def lost(lost_penalty: float) -> float:
    """-``lost_penalty`` on the decision the boat is farther from its waypoint than the leg's length plus the
    lost margin (the episode ends)."""
    return -lost_penalty


@wp.func
def flagged(flagged_penalty: float) -> float:
    """-``flagged_penalty`` on a decision the simulator flags the boat (capsized, non-finite, sunk, flying, bad
    input; the episode ends) for anything but a collision."""
    return -flagged_penalty


@wp.func
def collision(collision_penalty: float) -> float:
    """-``collision_penalty`` on a decision the simulator flags a collision (the episode ends)."""
    return -collision_penalty


@wp.func
def proximity(clearance: float, proximity_cost: float, proximity_range: float) -> float:
    """-``proximity_cost`` max(0, 1 - g / ``proximity_range``): the cost of sailing a gap g = ``clearance`` [m]
    from the nearest obstacle, falling linearly from the whole cost at g = 0 to none at the range [m]."""
    return -(proximity_cost * wp.max(1.0 - clearance / proximity_range, 0.0))


@wp.func
def smoothness(now: wp.vec3, before: wp.vec3, weight: float) -> float:
    """-``weight`` sum_k (a_k - a_prev_k)^2: the change of the actions (each in [-1, 1]) since the last decision."""
    change = float(0.0)
    for k in range(3):
        step = now[k] - before[k]
        change += step * step
    return -(weight * change)


@wp.func
def time_cost(cost: float) -> float:
    """-``cost`` every decision."""
    return -cost


@wp.func
def motor_energy(level: float, energy_cost: float, decision_period: float) -> float:
    """-``energy_cost`` ``decision_period`` (|level| / 5)^1.5: the motor's energy over the decision; the cost is
    per second [1/s] at full thrust (level 5), the period [s], ``level`` the commanded level's magnitude."""
    return -(energy_cost * decision_period * wp.pow(level / float(MAX_LEVEL), 1.5))
