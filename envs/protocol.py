"""The batched-environment protocol: what training, evaluation and the library adapters use of an environment.

Two classes implement it: :class:`~ocean_warp.envs.sailing_env.SailingEnv` (one batch on one device) and
:class:`~ocean_warp.envs.parallel.sharded.ShardedSailingEnv` (one batch over CPU worker processes). Code
that takes a :class:`BatchedEnv` reads and writes the torch tensors of ``env.buffers`` (bound once, updated
in place by ``step`` and ``reset``), calls ``step``, ``reset``, ``episode_log``,
``set_significant_wave_height`` and ``close``, and reads the sizes and periods below. Nothing reaches
through to a simulator: what a controller or a recorder of runs needs of the boats (pose, velocity, wind,
waypoints, the applied propeller level) is in the buffers.
"""

from __future__ import annotations

import dataclasses
from typing import Any, Protocol, runtime_checkable

import torch

from ocean_warp.fleet import BoatStatus

__all__ = ["BatchedEnv", "EnvBuffers", "episode_log"]


@dataclasses.dataclass(frozen=True)
class EnvBuffers:
    """torch tensors of one batch of N environments, bound once and updated in place (in a SailingEnv, views
    of its Warp arrays; in a ShardedSailingEnv, shared memory the workers write)."""

    # --- the decision: what the learner writes and reads ---
    actions: Any
    """(N, 3) float32: the last actions, in [-1, 1] (see ``ocean_warp.envs.tasks``)."""
    policy_obs: Any
    """(N, P) float32: what the policy sees now (after the same-step reset of ended environments)."""
    critic_obs: Any
    """(N, P + 12) float32: the policy's observation and privileged truth."""
    final_policy_obs: Any
    """(N, P) float32: the observation at the end of the last decision, before any reset."""
    final_critic_obs: Any
    """(N, P + 12) float32: likewise for the critic."""
    reward: Any
    """(N,) float32: the reward of the last decision."""
    terminated: Any
    """(N,) bool: the episode ended in a terminal state (waypoint or mission done, lost, flagged)."""
    time_out: Any
    """(N,) bool: the episode reached its time limit (not a terminal state)."""
    done: Any
    """(N,) bool: terminated or time_out; these environments were reset in the same step."""
    episode_length: Any
    """(N,) int32: decisions taken in the current episode (the learner may write it: rsl-rl's random start)."""
    episode_return: Any
    """(N,) float32: reward summed over the current episode."""
    # --- the course ---
    target: Any
    """(N, 3) float32: world position of each environment's current waypoint [m]."""
    origin: Any
    """(N, 3) float32: world position of each environment's origin [m]."""
    route: Any
    """(N, R, 3) float32: the current episode's waypoints, from the environment's origin [m]."""
    waypoint_index: Any
    """(N,) int32: index into ``route`` of the waypoint sailed to now (waypoints reached this episode)."""
    # --- the boats now (after the same-step reset) ---
    position: Any
    """(N, 3) float32: body origin, world frame (ENU, still water at z = 0) [m]."""
    orientation: Any
    """(N, 4) float32: body (FLU) -> world quaternion (x, y, z, w)."""
    velocity: Any
    """(N, 6) float32: Fossen's nu: body-frame velocity of the origin [m/s] and angular velocity [rad/s]."""
    wind_velocity: Any
    """(N, 3) float32: true wind at the reference height, gusts included, world frame [m/s]."""
    wind_direction: Any
    """(N,) float32: the episode's mean true wind direction, where it blows towards, from +x [rad]."""
    # --- the last decision, before the same-step reset ---
    propeller_level: Any
    """(N,) int32: propeller level the last decision applied, -5 ... 5 (0 on a task without propeller)."""
    final_position: Any
    """(N, 3) float32: ``position`` after the last decision's physics, before any reset [m]."""
    final_orientation: Any
    """(N, 4) float32: ``orientation`` likewise."""
    # --- the last episode that ended in each environment ---
    final_return: Any
    """(N,) float32: its return."""
    final_length: Any
    """(N,) int32: its length in decisions."""
    final_success: Any
    """(N,) float32: 1 if it reached its last waypoint."""
    final_status: Any
    """(N,) int32: the simulator's ``BoatStatus`` bits when it ended (0: healthy)."""
    final_waypoints: Any
    """(N,) int32: waypoints it reached."""
    final_score: Any
    """(N,) float32: its score by the rules of the competition the task comes from (VRX's, lower is better for
    station keeping and wayfinding, higher for following the path); NaN where the task has no such score."""
    # --- the obstacles (a task with ``obstacles``; K = 0 without) ---
    obstacles: Any
    """(N, K, 4) float32: each environment's obstacles now: x, y from its origin [m], radius [m] and kind
    (0: an empty row, 1: a buoy, 2: a pile; ``ocean_warp.envs.tasks.obstacle_course.OBSTACLE_*``)."""


@runtime_checkable
class BatchedEnv(Protocol):
    """N environments of one task, one decision per :meth:`step` (see the module's docstring).

    Writes into ``buffers.actions`` and ``buffers.episode_length`` take effect at the next step."""

    task: Any
    """The ``TaskConfig`` every environment sails."""
    num_envs: int
    num_actions: int
    num_policy_obs: int
    num_critic_obs: int
    max_episode_length: int
    """The episode's time limit [decisions]."""
    decision_period: float
    """Simulated time of one decision [s]."""
    steps_per_decision: int
    """Physics steps in a decision."""
    seed: int
    """The seed the batch was last (re)started from."""
    device: Any
    """The Warp device the batch runs on."""
    torch_device: torch.device
    buffers: EnvBuffers

    def step(self, actions: torch.Tensor | None = None) -> None:
        """One decision with ``actions`` (N, 3) (None: those in ``buffers.actions``); results in ``buffers``."""

    def reset(self, seed: int | None = None) -> None:
        """A new episode everywhere; with ``seed``, the whole batch restarted from it."""

    def episode_log(self) -> dict[str, torch.Tensor]:
        """Statistics of the episodes that ended in the last step (see :func:`episode_log`)."""

    @property
    def significant_wave_height(self) -> float:
        """The sea's significant wave height as the wave grid holds it [m]."""

    def set_significant_wave_height(self, hs: float) -> float:
        """Rescale the sea to significant wave height ``hs`` [m] (same spectrum shape and phases); returns
        the height the grid holds."""

    def close(self) -> None:
        """Release what the batch holds (worker processes); idempotent."""


def episode_log(b: EnvBuffers) -> dict[str, torch.Tensor]:
    """Statistics of the episodes that ended in the last step (one host synchronisation to find them),
    from an env's ``buffers``: mean return and length, the rates of success and of each simulator flag,
    and how many ended. Keys start with "/" (rsl-rl's namespace convention)."""
    ended = torch.nonzero(b.done, as_tuple=False).squeeze(1)
    status = b.final_status.index_select(0, ended)
    log = {
        "/episode/return": b.final_return.index_select(0, ended),
        "/episode/length": b.final_length.index_select(0, ended).float(),
        "/episode/success_rate": b.final_success.index_select(0, ended),
        "/episode/waypoints": b.final_waypoints.index_select(0, ended).float(),
        "/episode/time_out_rate": b.time_out.index_select(0, ended).float(),
    }
    for name, bit in (("capsized", BoatStatus.CAPSIZED), ("nonfinite", BoatStatus.NONFINITE),
                      ("sunk", BoatStatus.SUNK), ("flying", BoatStatus.FLYING), ("bad_input", BoatStatus.BAD_INPUT),
                      ("collided", BoatStatus.COLLIDED)):
        log[f"/episode/{name}_rate"] = ((status & bit) != 0).float()
    log["/episode/ended"] = ended.numel() * torch.ones((), device=b.done.device)
    return log
