"""The controllers that sail an evaluation's runs: the :class:`Controller` protocol, a fixed command, a trained
policy, the classical autopilot and a fleet of several; and whether a policy reads what a task gives."""

from __future__ import annotations

import dataclasses
import sys
from typing import Protocol

import numpy as np
import torch
import warp as wp

from ocean_warp.torch_streams import ordered_with_torch

from ..controllers.line_following import LineFollower, LineFollowingConfig
from ..controllers.sailing_autopilot import AutopilotConfig, SailingAutopilot
from ..protocol import BatchedEnv
from ..sailing_env import SailingEnv
from ..tasks.task_configs import ObservationSet, TaskConfig
from ..tasks.task_kernels import POLICY_OBS
from ..training.policy_io import Policy, other_task_note

__all__ = ["Controller", "FixedController", "PolicyController", "AutopilotController", "FleetController", "AUTOPILOTS",
           "MOTOR_ASSIST_LEVEL", "observation_text", "observation_mismatch", "warn_other_task"]


class Controller(Protocol):
    """What sails the runs of a :class:`~ocean_warp.envs.protocol.BatchedEnv`: ``reset(env)`` once before the
    batch starts, ``act(env)`` before each decision (it writes ``env.buffers.actions``), a ``name``. Optionally
    ``own_counts()``: its own per-run counters ({"tacks": (N,), "gybes": (N,)}; NaN for runs it keeps none for),
    read when runs end."""

    name: str

    def reset(self, env: BatchedEnv) -> None: ...

    def act(self, env: BatchedEnv) -> None: ...


def observation_text(observation: str, num_obs: int) -> str:
    """An observation in words: "5 values (the 'seed' set)", "30 values (the 'seed' set's 5 and 25 the task
    appends)": the set's values, then what a task appends (its reef level, its lidar's sectors: ``SailingEnv``)."""
    base = POLICY_OBS.get(str(observation))
    if base is None or num_obs == base:
        return f"{num_obs} values (the {observation!r} set)"
    return (f"{num_obs} values (the {observation!r} set's {base} and {num_obs - base} the task appends: reef level, "
            "lidar sectors)")


def observation_mismatch(policy: Policy, observation, num_obs: int) -> str | None:
    """None where ``policy`` reads what a task gives (its observation set ``observation`` of ``num_obs``
    values in all); else both, in words, and what to do."""
    name = str(getattr(observation, "value", observation))  # an ObservationSet, its value, or another task's set
    given = ObservationSet(name).value if name in {member.value for member in ObservationSet} else name
    if policy.observation == given and policy.num_obs == num_obs:
        return None
    return (f"the policy (trained on {policy.task}) reads {observation_text(policy.observation, policy.num_obs)}, "
            f"the task gives {observation_text(given, num_obs)}: sail it on {policy.task}, or pass a policy "
            "trained for this task")


class FixedController:
    """The same commands for every boat, every decision."""

    def __init__(self, actions, name: str = "fixed"):
        self.actions = torch.as_tensor(np.asarray(actions, dtype=np.float32)).reshape(1, 3)
        self.name = name

    def reset(self, env: SailingEnv) -> None:
        self._actions = self.actions.to(env.torch_device).expand(env.num_envs, 3).contiguous()

    def act(self, env: SailingEnv) -> None:
        env.buffers.actions.copy_(self._actions)


class PolicyController:
    """A trained :class:`~ocean_warp.envs.training.policy_io.Policy`: actions = policy(env.buffers.policy_obs)."""

    def __init__(self, policy: Policy, name: str = "policy"):
        if not isinstance(policy, Policy):
            raise ValueError(f"PolicyController: policy must be an ocean_warp Policy (load_policy), got {policy!r}")
        self.policy = policy
        self.name = name

    def reset(self, env: BatchedEnv) -> None:
        problem = observation_mismatch(self.policy, env.task.observation, env.num_policy_obs)
        if problem is not None:
            raise ValueError(f"PolicyController: {problem}")
        self.policy.to(env.torch_device).eval()

    def act(self, env: BatchedEnv) -> None:
        with torch.inference_mode():
            env.buffers.actions.copy_(self.policy(env.buffers.policy_obs))


AUTOPILOTS = ("line", "legacy")
"""The classical controllers :class:`AutopilotController` sails: ``line`` the line follower (Jaulin and Le Bars;
``ocean_warp.envs.controllers.line_following``), the default baseline; ``legacy`` the line-of-sight autopilot
(``ocean_warp.envs.controllers.sailing_autopilot``)."""
MOTOR_ASSIST_LEVEL = 5
"""The line follower's propeller level on beats, through forced turns and at low speed, on a task with a
propeller (``LineFollowingConfig.assist_level``), as the legacy autopilot's default assist."""


class AutopilotController:
    """A classical controller sailing to each run's current waypoint (``env.buffers.target``), reading the
    boats from the buffers: by default the line follower
    (:class:`~ocean_warp.envs.controllers.line_following.LineFollower`, ``autopilot="line"``), or the legacy
    :class:`~ocean_warp.envs.controllers.sailing_autopilot.SailingAutopilot` (``autopilot="legacy"``).
    ``config``: a :class:`LineFollowingConfig` or an :class:`AutopilotConfig` (it picks the controller; None:
    the defaults of ``autopilot``'s). Either is named "autopilot" in the results unless ``name`` says
    otherwise. It forgets a run's line, tack side, integrator and counters when the run starts a new episode
    (``env.buffers.done`` of the last step). On a task without propeller (``TaskConfig.propeller`` False) it
    sails without the motor (assist and propeller levels 0; the environment would ignore them anyway); on one
    with, the line follower's defaults assist at ``MOTOR_ASSIST_LEVEL``."""

    def __init__(self, config: LineFollowingConfig | AutopilotConfig | None = None, name: str = "autopilot", *,
                 autopilot: str | None = None):
        if config is not None and not isinstance(config, (LineFollowingConfig, AutopilotConfig)):
            raise ValueError(f"AutopilotController: config must be a LineFollowingConfig or an AutopilotConfig, "
                             f"got {config!r}")
        if autopilot is not None and autopilot not in AUTOPILOTS:
            raise ValueError(f"AutopilotController: autopilot must be one of {', '.join(AUTOPILOTS)}, "
                             f"got {autopilot!r}")
        implied = None if config is None else ("line" if isinstance(config, LineFollowingConfig) else "legacy")
        if autopilot is not None and implied is not None and autopilot != implied:
            raise ValueError(f"AutopilotController: a {type(config).__name__} configures the {implied!r} autopilot, "
                             f"not {autopilot!r}")
        self.autopilot = implied or autopilot or "line"
        """Which controller sails: "line" or "legacy"."""
        self.config = config
        self.name = name
        self.pilot: LineFollower | SailingAutopilot | None = None

    def reset(self, env: BatchedEnv) -> None:
        kind = LineFollower if self.autopilot == "line" else SailingAutopilot
        self.pilot = kind.for_env(env, self.config_for(env.task))
        self.pilot.reset()
        buffers = env.buffers
        self._targets = wp.from_torch(buffers.target, dtype=wp.vec3)
        self._actions = wp.from_torch(buffers.actions)
        self._restarted = torch.zeros(env.num_envs, dtype=torch.int32, device=env.torch_device)
        self._restarted_mask = wp.from_torch(self._restarted)

    def config_for(self, task: TaskConfig) -> LineFollowingConfig | AutopilotConfig:
        """The controller's config on ``task``: this controller's, with the motor off (assist and propeller
        level 0) where the task has no propeller; None: the defaults with the decision period [s] of the task
        (line: assist at ``MOTOR_ASSIST_LEVEL`` where the task has a propeller, else 0; legacy:
        ``AutopilotConfig()``, or ``AutopilotConfig.sail_only()`` where the task has no propeller)."""
        if self.autopilot == "line":
            if self.config is None:
                return LineFollowingConfig(decision_period=task.decision_period,
                                           assist_level=MOTOR_ASSIST_LEVEL if task.propeller else 0)
            return self.config if task.propeller else dataclasses.replace(self.config, assist_level=0)
        if self.config is None:
            preset = AutopilotConfig if task.propeller else AutopilotConfig.sail_only
            return preset(decision_period=task.decision_period)
        return self.config if task.propeller else dataclasses.replace(self.config, assist_level=0, propeller_level=0)

    def act(self, env: BatchedEnv) -> None:
        # The runs that ended in the last step started new episodes in it: forget their side and counts
        # (after their counts were read: the runner reads own_counts() right after the step).
        self._restarted.copy_(env.buffers.done)
        with ordered_with_torch(self.pilot.device):
            self.pilot.reset(self._restarted_mask)
            self.pilot.act(self._targets, self._actions)

    def own_counts(self) -> dict[str, np.ndarray]:
        """The controller's own tack and gybe counters since each run's episode began."""
        return {"tacks": self.pilot.tacks.numpy().copy(), "gybes": self.pilot.gybes.numpy().copy()}


class FleetController:
    """Several controllers in one fleet: ``groups`` pairs each controller with the runs it steers, (N,)
    bool masks that together cover every run once. Each controller acts on the whole fleet, and each
    run keeps the actions of its own controller (a few wasted actions, no per-group environments)."""

    def __init__(self, groups: list[tuple[Controller, np.ndarray]], name: str = "fleet"):
        if not groups:
            raise ValueError("FleetController: no controllers")
        masks = [np.asarray(mask, dtype=bool) for _, mask in groups]
        if len({mask.shape for mask in masks}) != 1 or masks[0].ndim != 1:
            raise ValueError("FleetController: the masks must all be (N,) of the same N")
        coverage = np.sum(masks, axis=0)
        if not (coverage == 1).all():
            raise ValueError(f"FleetController: every run needs exactly one controller; runs "
                             f"{np.flatnonzero(coverage != 1).tolist()} have {sorted(set(coverage[coverage != 1]))}")
        self.groups = [(controller, mask) for (controller, _), mask in zip(groups, masks)]
        self.name = name
        self._masks: list = []
        self._actions = None

    def reset(self, env: BatchedEnv) -> None:
        if self.groups[0][1].shape[0] != env.num_envs:
            raise ValueError(f"FleetController: masks for {self.groups[0][1].shape[0]} runs, the environment has "
                             f"{env.num_envs}")
        for controller, _ in self.groups:
            controller.reset(env)
        self._masks = [torch.as_tensor(mask, device=env.torch_device).unsqueeze(1) for _, mask in self.groups]
        self._actions = torch.zeros_like(env.buffers.actions)

    def act(self, env: BatchedEnv) -> None:
        actions = env.buffers.actions
        for (controller, _), mask in zip(self.groups, self._masks):
            controller.act(env)
            torch.where(mask, actions, self._actions, out=self._actions)
        actions.copy_(self._actions)

    def own_counts(self) -> dict[str, np.ndarray]:
        """Each run's tack and gybe counters from its own controller, where that controller keeps them (the
        autopilot's runs); NaN for the runs of controllers that keep none (a policy's)."""
        runs = self.groups[0][1].shape[0]
        counts = {"tacks": np.full(runs, np.nan), "gybes": np.full(runs, np.nan)}
        for controller, mask in self.groups:
            own_counts = getattr(controller, "own_counts", None)
            if own_counts is not None:
                for key, values in own_counts().items():
                    counts[key][mask] = np.asarray(values, dtype=np.float64)[mask]
        return counts


def warn_other_task(prog: str, policy: Policy, task: str) -> None:
    """One line on stderr, ``<prog>: warning: ...``, where ``policy`` was trained on another task than
    ``task``."""
    note = other_task_note(policy, task)
    if note is not None:
        print(f"{prog}: warning: {note}", file=sys.stderr)
