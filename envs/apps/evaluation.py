"""``ocean-warp eval``: a task's runs (by default the six-waypoint mission BCDACA) sailed many times in waves
by a policy and by the classical autopilot, with the paths drawn and the results tabled.

    ocean-warp eval                                  # the shipped mission policy and the autopilot, 20 runs
    ocean-warp eval --policy out/train/EBoatMission-v0/<date>_<name>/policy.pt --device cuda:0
    ocean-warp eval --no-policy --runs 5 --sea-state 0.5 --wind 8 --seed 1
    ocean-warp eval --task EBoatMissionSail-v0       # the mission under sail alone (no motor)
    ocean-warp eval --task EBoatWaypoint-v0 --runs 50 --wind 6

--task is any registered task id (``ocean_warp.envs.registration.TASK_IDS``: EBoatWaypoint-v0,
EBoatWaypointPlus-v0, EBoatMission-v0, EBoatMissionSail-v0, EBoatAvoid-v0, EBoatAvoidSail-v0; with or
without the "ocean_warp/" prefix), default EBoatMission-v0. Each run is one environment of
``SailingEnv(<the task's config>)`` and its first episode is its result: for the missions, A (0, 0) -> B,
C, D, A, C, A, each reached within 5 m; for the single-waypoint tasks, the episode toward the waypoint the
run drew at its start (its own distance and bearing, heading and wind direction, as the task draws them);
on the avoidance tasks also through the buoys and piles the run drew at its start (its obstacle layout,
taken from ``env.buffers.obstacles`` right after the reset, before the first decision), a touch ending it
(``BoatStatus.COLLIDED``). The sea is the task's with significant
height --sea-state (default: the task's) and ocean seed --seed; the true wind is the task's, its mean
speed --wind (default: the task's; a task that draws each start's wind speed from a range, as the
waypoint tasks do, sails every run at --wind instead); --time-limit replaces the task's episode time.
Every controller sails the SAME runs: the same task and environment seed, so the same waves, gusts,
starts and waypoints. A run's path is recorded from the start to the end of its first episode (the pose
after the physics of the last decision, before the environment resets the run).

The policy is --policy PATH, else the task's shipped policy (``ocean_warp.envs.training.policies``); for a task
that has none (EBoatWaypointPlus-v0) eval says so in one line and sails the autopilot alone. The autopilot
(named "autopilot" in every table) is --autopilot line (default), the line follower of Jaulin and Le Bars
(``ocean_warp.envs.controllers.line_following``), or --autopilot legacy, the line-of-sight autopilot
(``ocean_warp.envs.controllers.sailing_autopilot``). On a task without propeller (EBoatMissionSail-v0:
``TaskConfig.propeller`` False) either sails without motor assist (the legacy one with
``AutopilotConfig.sail_only()``), and the environment ignores any controller's propeller command (level 0).

Written into --out (atomically):
  trajectories.png   all runs' paths, one panel per controller (same axes), over the waypoints (each run's
                     own, in its colour, for the single-waypoint tasks); on a task with obstacles, each
                     run's buoys (orange) and piles (grey) as circles of their true radius at their places
                     from the run's origin, edged in the run's colour
  results.csv        one row per controller (the table printed at the end)
  runs.csv           one row per run and controller; its "end" is how the first episode ended: reached,
                     capsized (BoatStatus.CAPSIZED), collided (BoatStatus.COLLIDED, not capsized), flagged <bits>
                     (other BoatStatus bits), time-out or lost
  trajectories.npz   the paths: <controller>_x, _y [m from the run's origin], _heading [rad], _propeller
                     (level commanded at each decision), _reached (waypoints reached by each sample), _length
                     (decisions per run); NaN-padded to the longest run; _routes (N, R, 2) [m] each run's
                     waypoints; route (R, 2) the task's fixed route (tasks that have one), start_point; on a
                     task with obstacles, _obstacles (N, K, 4) each run's obstacle table of its first episode
                     (``env.buffers.obstacles`` after the reset): x, y [m from the run's origin], radius [m],
                     kind (0 an empty row, 1 a buoy, 2 a pile)

--record FILE.mcap also writes a rosbag2 MCAP log (ROS 2 message schemas; ros2 bag, Foxglove and PlotJuggler
open it; needs the mcap extra): every controller's runs, each under its own namespace, /<controller>/eboat_<run>
(/<controller>/eboat for --runs 1), once per decision from the start until the controller's last decision,
runs that already ended sailing on in new episodes; log times are the simulated time, so the controllers' runs
lie side by side on one time axis and in one map frame (topics: ocean_warp/ros/topics.py).

Columns of results.csv:
  controller, runs      the controller; runs sailed
  completed             runs that reached all their task's waypoints (the mission's six, a waypoint task's
                        one); completion_rate = completed / runs
  time_mean_s, time_std_s, time_min_s, time_max_s
                        time of the completed runs [s] (decisions x decision period; std with ddof 0);
                        NaN when none completed
  distance_mean_m       distance sailed, the sum of the path's segments between decisions [m], mean over
                        all runs (their first episode, however it ended)
  tacks_mean, gybes_mean
                        from the recorded headings, for every controller alike (mean over all runs): a
                        tack when the true wind's source crosses the bow, a gybe when it crosses the
                        stern, counted once the heading has settled 10 deg past the wind axis on the new
                        side (envs/apps/mission_metrics.py: wind_crossings)
  cross_track_spread_m  how consistent the paths are [m]: on each leg (from the run's start or previous
                        waypoint to its next, each run's own), every run that completed the leg is
                        resampled at 50 points equally spaced in along-track distance (where the path first
                        reaches that distance), the population std across those runs of the offset from
                        the straight leg is taken at each point; the mean over the points, then over the
                        legs completed by at least two runs (NaN if none)
  capsizes, collisions, lost, time_outs
                        runs that capsized (BoatStatus.CAPSIZED), touched an obstacle or another boat
                        (BoatStatus.COLLIDED; 0 on a task without obstacles; a run that capsized and touched
                        counts in both), drifted beyond the leg's length + 25 m from their waypoint, or
                        reached the time limit
  motor_use             fraction of decisions with a propeller level other than 0 commanded (as the
                        environment applied it: always 0 on a task without propeller), mean over runs
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import logging
import math
import os
import re
import sys
from typing import Callable, Protocol

import numpy as np
import torch
import warp as wp

from ocean_warp.atomic_files import atomic_output
from ocean_warp.cli_support import (
    check_options,
    checked_device,
    checked_output_folder,
    fail,
    finite_above,
    finite_at_least,
    plural,
)
from ocean_warp.fleet import BoatStatus, episode_end
from ocean_warp.frames import roll_pitch_yaw
from ocean_warp.kernels.ray_cast import float_objects
from ocean_warp.ocean_config import (SIGNIFICANT_WAVE_HEIGHT_RULE, is_valid_significant_wave_height,
                                    require_significant_wave_height)
from ocean_warp.replay import ReplayedLaunches
from ocean_warp.torch_streams import ordered_with_torch

from ..controllers.line_following import LineFollower, LineFollowingConfig
from ..controllers.sailing_autopilot import AutopilotConfig, SailingAutopilot
from ..protocol import BatchedEnv
from ..decision_hook import DecisionHook
from ..sailing_env import SailingEnv
from . import evaluation_options
from .mission_metrics import cross_track_spread, motor_use, path_length, wind_crossings
from .mission_plot import PanelData, plot_trajectories
from ..training.policy_io import CheckpointError, Policy, load_policy, other_task_note
from ..registration import DEFAULT_TASK, make_task_config, task_name
from ..tasks.task_kernels import POLICY_OBS
from ..tasks.task_configs import BCDACA_ROUTE, MissionConfig, ObservationSet, TaskConfig, mission_waypoint_name

__all__ = ["Controller", "PolicyController", "AutopilotController", "AUTOPILOTS", "MOTOR_ASSIST_LEVEL",
           "FixedController", "FleetController", "RecordedDecision", "RunPath", "ControllerResult", "MissionEvaluation",
           "TABLE_COLUMNS", "RUN_COLUMNS",
           "DEFAULT_TASK", "evaluation_task", "mission_task", "sail_mission", "evaluate_mission", "main"]


TABLE_COLUMNS = ("controller", "runs", "completed", "completion_rate", "time_mean_s", "time_std_s", "time_min_s",
                 "time_max_s", "distance_mean_m", "tacks_mean", "gybes_mean", "cross_track_spread_m", "capsizes",
                 "collisions", "lost", "time_outs", "motor_use")
"""Columns of results.csv (module docstring: their definitions)."""
RUN_COLUMNS = ("controller", "run", "completed", "end", "time_s", "waypoints", "distance_m", "tacks", "gybes",
               "own_tacks", "own_gybes", "motor_use", "start_x_m", "start_y_m", "start_heading_deg")
"""Columns of runs.csv: per run, the first episode's outcome; time_s is when it ended, however it ended;
own_tacks / own_gybes are the controller's own counts where it keeps them (the autopilot), else empty."""


class Controller(Protocol):
    """What sails the runs of a :class:`~ocean_warp.envs.protocol.BatchedEnv`: ``reset(env)`` once before the
    batch starts, ``act(env)`` before each decision (it writes ``env.buffers.actions``), a ``name``. Optionally ``own_counts()``: its own
    per-run counters ({"tacks": (N,), "gybes": (N,)}; NaN for runs it keeps none for), read when runs end."""

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
    given = ObservationSet(observation).value
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


@dataclasses.dataclass
class RunPath:
    """One run's first episode, sampled at its start and after each of its T decisions."""

    xy: np.ndarray
    """(T + 1, 2) position [m] from the run's origin."""
    heading: np.ndarray
    """(T + 1,) heading [rad, from +x counter-clockwise]."""
    propeller: np.ndarray
    """(T,) propeller level (-5 ... 5) commanded at each decision (as the environment applied it)."""
    reached: np.ndarray
    """(T + 1,) waypoints reached by each sample."""


@dataclasses.dataclass
class ControllerResult:
    """The runs of one controller: per-run outcomes (arrays of length N) and paths, and their metrics."""

    name: str
    paths: list[RunPath]
    success: np.ndarray
    """(N,) bool: reached every waypoint of its task."""
    time_s: np.ndarray
    """(N,) when the first episode ended [s] (the mission time where ``success``)."""
    waypoints: np.ndarray
    """(N,) waypoints reached."""
    status: np.ndarray
    """(N,) the simulator's BoatStatus bits at the end (0: healthy)."""
    time_out: np.ndarray
    """(N,) bool: reached the time limit."""
    wind_direction: np.ndarray
    """(N,) mean direction the true wind blows toward [rad]."""
    routes: np.ndarray
    """(N, R, 2) each run's waypoints [m] from its origin, in order: the task's route, or the waypoint the
    run drew at its start (single-waypoint tasks)."""
    start_point: np.ndarray
    """(2,) where the runs start [m] (before the task's jitter)."""
    own_tacks: np.ndarray | None = None
    """(N,) the controller's own tack count, where it keeps one: NaN for the runs of a controller that keeps
    none (in a :class:`FleetController` of several); None where no run's controller keeps one."""
    own_gybes: np.ndarray | None = None
    obstacles: np.ndarray | None = None
    """(N, K, 4) each run's obstacles in its first episode (``env.buffers.obstacles`` after the reset): x, y
    from the run's origin [m], radius [m], kind (0 an empty row, 1 a buoy, 2 a pile:
    ``ocean_warp.envs.tasks.obstacle_course.OBSTACLE_*``); None (kept as (N, 0, 4)): a task without
    obstacles."""

    def __post_init__(self):
        runs = len(self.paths)
        obstacles = np.zeros((runs, 0, 4)) if self.obstacles is None else np.asarray(self.obstacles, np.float64)
        if obstacles.ndim != 3 or obstacles.shape[0] != runs or obstacles.shape[2] != 4:
            raise ValueError(f"ControllerResult.obstacles must be ({runs}, K, 4) (x, y, radius, kind per run and "
                             f"row), got shape {obstacles.shape}")
        self.obstacles = obstacles
        self.distance_m = np.array([path_length(p.xy) for p in self.paths])
        crossings = np.array([wind_crossings(p.heading, w) for p, w in zip(self.paths, self.wind_direction)],
                             dtype=np.int64).reshape(-1, 2)
        self.tacks, self.gybes = crossings[:, 0], crossings[:, 1]
        self.motor_use = np.array([motor_use(p.propeller) for p in self.paths])
        self.spread_per_leg, self.cross_track_spread = cross_track_spread(
            [p.xy for p in self.paths], [p.reached for p in self.paths], self.routes, self.start_point)

    @property
    def runs(self) -> int:
        return len(self.paths)

    @property
    def shared_route(self) -> bool:
        """Every run sailed the same waypoints (a task with a fixed route)."""
        return bool(np.all(self.routes == self.routes[:1]))

    @property
    def route(self) -> np.ndarray:
        """(R, 2) the waypoints [m] every run sailed; ValueError where the runs drew their own."""
        if not self.shared_route:
            raise ValueError(f"ControllerResult {self.name!r}: the runs drew their own waypoints; see routes")
        return self.routes[0]

    def subset(self, runs: np.ndarray, name: str) -> ControllerResult:
        """The result of only the ``runs`` (indices or an (N,) bool mask), named ``name``; its metrics are
        recomputed over them (e.g. one controller's boats of a :class:`FleetController`)."""
        index = np.flatnonzero(runs) if np.asarray(runs).dtype == bool else np.asarray(runs, dtype=np.int64)
        pick = (lambda values: None if values is None else _kept_counts(values[index]))  # noqa: E731
        return ControllerResult(name=name, paths=[self.paths[i] for i in index], success=self.success[index],
                                time_s=self.time_s[index], waypoints=self.waypoints[index], status=self.status[index],
                                time_out=self.time_out[index], wind_direction=self.wind_direction[index],
                                routes=self.routes[index], start_point=self.start_point, own_tacks=pick(self.own_tacks),
                                own_gybes=pick(self.own_gybes), obstacles=self.obstacles[index])

    @property
    def capsized(self) -> np.ndarray:
        return (self.status & BoatStatus.CAPSIZED) != 0

    @property
    def collided(self) -> np.ndarray:
        """(N,) bool: the first episode ended with the boat touching an obstacle or another boat
        (``BoatStatus.COLLIDED``)."""
        return (self.status & BoatStatus.COLLIDED) != 0

    @property
    def has_obstacles(self) -> bool:
        """The runs sailed among obstacles (a task with an obstacle layout)."""
        return self.obstacles.shape[1] > 0

    @property
    def lost(self) -> np.ndarray:
        """Ended healthy, before the time limit, without finishing: beyond the lost distance."""
        return ~self.success & ~self.time_out & (self.status == 0)

    def end(self, run: int) -> str:
        """How run ``run``'s first episode ended, for runs.csv (``ocean_warp.fleet.episode_end``): "capsized",
        "collided" (touched, not capsized), "flagged <bits>" (another BoatStatus), "time-out", "reached" or
        "lost"."""
        end = episode_end(bool(self.success[run]), bool(self.time_out[run]), int(self.status[run]))
        return f"flagged {int(self.status[run])}" if end == "flagged" else end

    def summary(self) -> dict:
        """The controller's row of results.csv (``TABLE_COLUMNS``)."""
        times = self.time_s[self.success]
        stat = (lambda f: float(f(times)) if times.size else math.nan)  # noqa: E731
        return {"controller": self.name, "runs": self.runs, "completed": int(self.success.sum()),
                "completion_rate": float(self.success.mean()), "time_mean_s": stat(np.mean),
                "time_std_s": stat(np.std), "time_min_s": stat(np.min), "time_max_s": stat(np.max),
                "distance_mean_m": float(self.distance_m.mean()), "tacks_mean": float(self.tacks.mean()),
                "gybes_mean": float(self.gybes.mean()), "cross_track_spread_m": self.cross_track_spread,
                "capsizes": int(self.capsized.sum()), "collisions": int(self.collided.sum()),
                "lost": int(self.lost.sum()),
                "time_outs": int(self.time_out.sum()), "motor_use": float(np.nanmean(self.motor_use))}

    def run_rows(self) -> list[dict]:
        """Its rows of runs.csv (``RUN_COLUMNS``)."""
        rows = []
        for i, path in enumerate(self.paths):
            rows.append({"controller": self.name, "run": i, "completed": int(self.success[i]), "end": self.end(i),
                         "time_s": float(self.time_s[i]), "waypoints": int(self.waypoints[i]),
                         "distance_m": float(self.distance_m[i]), "tacks": int(self.tacks[i]),
                         "gybes": int(self.gybes[i]),
                         "own_tacks": _count_cell(self.own_tacks, i), "own_gybes": _count_cell(self.own_gybes, i),
                         "motor_use": float(self.motor_use[i]), "start_x_m": float(path.xy[0, 0]),
                         "start_y_m": float(path.xy[0, 1]), "start_heading_deg": math.degrees(path.heading[0])})
        return rows


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


class RecordedDecision(DecisionHook):
    """One decision of a :class:`SailingEnv` with ``frames_per_decision`` F evenly spaced frames kept from
    inside it (after steps S/F, 2 S/F, ..., S of its S physics steps; F must divide S): pose, boom and
    rudder angles of every boat, for a recorder that wants more than one frame a decision (the USD
    stages). Launched by ``SailingEnv.launch_decision`` with this object as its :class:`DecisionHook`, as
    ``SailingEnv.step`` launches it (and captured as one graph likewise); the copies are part of the launch
    sequence (graph-safe: fixed slots, no host work). A test checks that it stays step for step the same
    as ``env.step()``. It needs a SailingEnv: it looks inside a decision, which the batched-env protocol
    does not show (its buffers hold the pose at the end of the decision: ``final_position``).

    On a task with obstacles it also keeps, at each frame, the pose of every object row of the env's
    obstacle scene (``env.obstacles.scene``): what ``scene.refresh()`` would give there (the floating buoys
    on the sea of that moment, the piles at their anchors), computed into its own slots with the same
    kernel (``float_objects``), so that the scene the env's contact and lidar read is left as ``step()``
    leaves it."""

    def __init__(self, env: SailingEnv, frames_per_decision: int = 1):
        if not isinstance(env, SailingEnv):
            raise ValueError(f"RecordedDecision: env must be a SailingEnv (frames come from inside its decision), "
                             f"got {env!r}")
        steps = env.steps_per_decision
        if isinstance(frames_per_decision, bool) or not isinstance(frames_per_decision, int) \
                or not 1 <= frames_per_decision <= steps or steps % frames_per_decision:
            raise ValueError(f"RecordedDecision: frames_per_decision must divide the {steps} physics steps of a "
                             f"decision, got {frames_per_decision!r}")
        self.env = env
        self.frames_per_decision = frames_per_decision
        n, device = env.num_envs, env.device
        frames = frames_per_decision * n
        self.frame_position = wp.zeros(frames, dtype=wp.vec3, device=device)
        """(F * N,) positions [m] at the decision's frames, frame-major."""
        self.frame_orientation = wp.zeros(frames, dtype=wp.quat, device=device)
        self.frame_boom_angle = wp.zeros(frames, dtype=wp.float32, device=device)
        """(F * N,) boom angles [rad], positive to port."""
        self.frame_rudder_angle = wp.zeros(frames, dtype=wp.float32, device=device)
        """(F * N,) rudder angles [rad], positive turns to port."""
        course = env.obstacles
        self.scene = course.scene if course is not None and course.slots > 0 else None
        """The env's obstacle scene whose object rows are kept per frame (None: a task without obstacles)."""
        rows = self.scene.object_count if self.scene is not None else 0
        self.frame_object_position = wp.zeros(frames_per_decision * rows, dtype=wp.vec3, device=device)
        """(F * M,) every object row's position [m, world] at the decision's frames, frame-major (M = 0
        without obstacles)."""
        self.frame_object_orientation = wp.zeros(frames_per_decision * rows, dtype=wp.quat, device=device)
        """(F * M,) every object row's orientation (x, y, z, w)."""
        # One view per frame slot, made here (no allocation inside the captured launches).
        self._object_slots = [(self.frame_object_position[f * rows:(f + 1) * rows],
                               self.frame_object_orientation[f * rows:(f + 1) * rows])
                              for f in range(frames_per_decision)] if rows else []
        self._replayed = ReplayedLaunches(self._launch, device, capture=env.task.simulator.capture_graph)

    def _launch(self) -> None:
        self.env.launch_decision(self)

    def after_physics_step(self, env: SailingEnv, step: int) -> None:
        """The DecisionHook's copies into the frame slots, launched inside the decision."""
        n, every = env.num_envs, env.steps_per_decision // self.frames_per_decision
        if (step + 1) % every:
            return
        slot = (step + 1) // every - 1
        state, offset = env.simulator.state, slot * n
        for source, target in ((state.position, self.frame_position), (state.orientation, self.frame_orientation),
                               (state.boom_angle, self.frame_boom_angle),
                               (state.rudder_angle, self.frame_rudder_angle)):
            wp.copy(target, source, dest_offset=offset, count=n)
        if self._object_slots:
            scene = self.scene
            position, orientation = self._object_slots[slot]
            # As refresh() leaves them: a fixed row keeps its orientation, float_objects writes the rest.
            wp.copy(orientation, scene.view.object_orientation)
            wp.launch(float_objects, dim=scene.object_count, device=scene.device,
                      inputs=[scene.ocean.surface, scene.floats, scene.draft, scene.anchor],
                      outputs=[position, orientation])

    def __call__(self) -> None:
        with ordered_with_torch(self.env.device):
            self._replayed()

    def frames(self) -> dict[str, np.ndarray]:
        """The last decision's frames on the host: "position" (F, N, 3) [m], "orientation" (F, N, 4) xyzw,
        "boom_angle" and "rudder_angle" (F, N) [rad]; on a task with obstacles also "object_position"
        (F, M, 3) [m, world] and "object_orientation" (F, M, 4) xyzw of the obstacle scene's M object rows
        (environment e's layout in rows ``scene.first_free_slot[e]`` on)."""
        f, n = self.frames_per_decision, self.env.num_envs
        frames = {"position": self.frame_position.numpy().reshape(f, n, 3),
                  "orientation": self.frame_orientation.numpy().reshape(f, n, 4),
                  "boom_angle": self.frame_boom_angle.numpy().reshape(f, n),
                  "rudder_angle": self.frame_rudder_angle.numpy().reshape(f, n)}
        if self.scene is not None:
            m = self.scene.object_count
            frames["object_position"] = self.frame_object_position.numpy().reshape(f, m, 3)
            frames["object_orientation"] = self.frame_object_orientation.numpy().reshape(f, m, 4)
        return frames


def sail_mission(env: BatchedEnv, controller: Controller, *, progress: bool = False, frames_per_decision: int = 1,
                 on_decision: Callable[[int, RecordedDecision], None] | None = None,
                 on_start: Callable[[], None] | None = None) -> ControllerResult:
    """Restart ``env`` (any :class:`~ocean_warp.envs.protocol.BatchedEnv`) from its seed
    (``env.reset(seed=env.seed)``: the same starts, waves and gusts every time) and let ``controller`` sail
    every run until its first episode ends; record the paths from the env's buffers. Any task: a run's
    waypoints are the task's route, or the one it drew at its start (single-waypoint tasks); its obstacles
    (a task with an obstacle layout) are the table ``env.buffers.obstacles`` holds right after the reset.

    ``on_decision(k, decision)``, if given, is called after decision k (0, 1, ...) with a
    :class:`RecordedDecision` (``env`` must then be a SailingEnv), whose ``frames()`` hold
    ``frames_per_decision`` frames of every boat from inside it (e.g. for a USD recorder); runs that
    already ended keep sailing new episodes there. ``on_start()``, if given, is called once after the reset
    and the controller's, before the first decision (e.g. for a log of the runs' start)."""
    decision = RecordedDecision(env, frames_per_decision) if on_decision is not None else None
    env.reset(seed=env.seed)
    controller.reset(env)
    if on_start is not None:
        on_start()
    b = env.buffers
    host = lambda tensor: tensor.cpu().numpy()  # noqa: E731
    routes = host(b.route)[:, :, :2].astype(np.float64)  # the first episodes' waypoints, drawn by the reset
    obstacles = host(b.obstacles).astype(np.float64)  # and their obstacle layouts, before a reset redraws them
    n, limit = env.num_envs, env.max_episode_length
    origin = host(b.origin)[:, :2].astype(np.float64)
    xy = np.full((limit + 1, n, 2), np.nan)
    heading = np.full((limit + 1, n), np.nan)
    reached = np.zeros((limit + 1, n), dtype=np.int64)
    levels = np.zeros((limit, n), dtype=np.int64)
    xy[0] = host(b.position)[:, :2] - origin
    heading[0] = roll_pitch_yaw(host(b.orientation))[:, 2]
    wind_direction = host(b.wind_direction).astype(np.float64)
    outcome = {name: np.zeros(n, dtype=kind) for name, kind in (
        ("success", bool), ("time_s", np.float64), ("waypoints", np.int64), ("status", np.int64),
        ("time_out", bool))}
    outcome.update(own_tacks=np.full(n, np.nan), own_gybes=np.full(n, np.nan))
    length = np.zeros(n, dtype=np.int64)
    finished = np.zeros(n, dtype=bool)
    own_counts = getattr(controller, "own_counts", None)

    from tqdm import tqdm

    with tqdm(total=limit, desc=f"{controller.name:>10}", unit="decision", disable=not progress,
              dynamic_ncols=True) as bar:
        for k in range(limit):
            controller.act(env)
            if decision is not None:
                decision()
                on_decision(k, decision)
            else:
                env.step()
            active = ~finished
            levels[k, active] = host(b.propeller_level)[active]
            xy[k + 1, active] = host(b.final_position)[active, :2] - origin[active]
            heading[k + 1, active] = roll_pitch_yaw(host(b.final_orientation))[active, 2]
            reached[k + 1] = host(b.waypoint_index)
            length[active] = k + 1
            done = host(b.done) & active
            if done.any():
                final_waypoints = host(b.final_waypoints)
                reached[k + 1, done] = final_waypoints[done]
                outcome["success"][done] = host(b.final_success)[done] > 0.5
                outcome["time_s"][done] = host(b.final_length)[done] * env.decision_period
                outcome["waypoints"][done] = final_waypoints[done]
                outcome["status"][done] = host(b.final_status)[done]
                outcome["time_out"][done] = host(b.time_out)[done]
                if own_counts is not None:
                    counts = own_counts()
                    outcome["own_tacks"][done] = counts["tacks"][done]
                    outcome["own_gybes"][done] = counts["gybes"][done]
                finished |= done
            bar.update(1)
            bar.set_postfix_str(f"ended {finished.sum()}/{n}, completed {outcome['success'].sum()}", refresh=False)
            if finished.all():
                # Every run ended before the time limit: the job is done, so the bar ends full (at the
                # decisions sailed) instead of stopping part-way.
                bar.total = k + 1
                bar.refresh()
                break
    paths = [RunPath(xy=xy[:length[i] + 1, i].copy(), heading=heading[:length[i] + 1, i].copy(),
                     propeller=levels[:length[i], i].copy(), reached=reached[:length[i] + 1, i].copy())
             for i in range(n)]
    own = {} if own_counts is None else {"own_tacks": _kept_counts(outcome["own_tacks"]),
                                         "own_gybes": _kept_counts(outcome["own_gybes"])}
    return ControllerResult(name=controller.name, paths=paths, success=outcome["success"], time_s=outcome["time_s"],
                            waypoints=outcome["waypoints"], status=outcome["status"], time_out=outcome["time_out"],
                            wind_direction=wind_direction, routes=routes,
                            start_point=np.array(env.task.start_point, dtype=np.float64), obstacles=obstacles, **own)


def _kept_counts(values: np.ndarray) -> np.ndarray | None:
    """Own counts (N,) as a result keeps them: None where no run has one (all NaN)."""
    return None if np.isnan(values).all() else values


def _count_cell(values: np.ndarray | None, run: int):
    """A run's own count in runs.csv: the whole number, or empty where its controller keeps none."""
    return "" if values is None or np.isnan(values[run]) else int(values[run])


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
    if not isinstance(task, TaskConfig):
        raise ValueError(f"evaluation_task: task must be a TaskConfig or a task id, got {task!r}")
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


def _course_text(task: TaskConfig) -> str:
    """What a task's runs sail, in words: "BCDACA", "one waypoint per run" or "a route of R waypoints",
    followed by "through buoys and piles" for a task with obstacles and "under sail alone" for a task
    without propeller."""
    if task.route is None:
        course = "one waypoint per run"
    elif tuple(task.route) == BCDACA_ROUTE:
        course = "BCDACA"
    else:
        course = f"a route of {len(task.route)} waypoints"
    if task.obstacles is not None:
        course = f"{course} through buoys and piles"
    return course if task.propeller else f"{course} under sail alone"


def _wind_text(task: TaskConfig) -> str:
    """The mean true wind speed of a task's runs: "10 m/s", or "2-12 m/s" where each run draws its own."""
    low, high = task.start.wind_speed
    return f"{low:g} m/s" if low == high else f"{low:g}-{high:g} m/s"


def _conditions_text(task: TaskConfig, seed: int) -> str:
    """A task's sea, wind and seed in words: "Hs 0.3 m JONSWAP, wind 10 m/s with gusts, seed 0"."""
    ocean, wind = task.simulator.ocean, task.simulator.wind
    gusty = (wind.gust_speed_std > 0.0 or wind.gust_direction_std > 0.0) and task.start.gust_scale[1] > 0.0
    spectrum = {"jonswap": "JONSWAP", "pierson_moskowitz": "Pierson-Moskowitz"}.get(ocean.spectrum.value,
                                                                                   ocean.spectrum.value)
    return (f"Hs {ocean.significant_wave_height:g} m {spectrum}, wind {_wind_text(task)}"
            f"{' with gusts' if gusty else ''}, seed {seed}")


@dataclasses.dataclass
class MissionEvaluation:
    """What :func:`evaluate_mission` returns: the task sailed, the settings, and one result per controller."""

    task: TaskConfig
    settings: dict
    """runs, sea_state [m], wind [m/s] (None where each run draws its own), seed, device, time_limit [s];
    optionally "task", the task id."""
    results: dict[str, ControllerResult]

    def table(self) -> list[dict]:
        """One row per controller (``TABLE_COLUMNS``)."""
        return [result.summary() for result in self.results.values()]

    def format_table(self) -> str:
        """The table, aligned, one column per controller (a row per column of results.csv)."""
        rows = self.table()
        cells = [[column] + [_format(row[column]) for row in rows] for column in TABLE_COLUMNS]
        widths = [max(len(line[i]) for line in cells) for i in range(len(cells[0]))]
        return "\n".join("  ".join(cell.ljust(w) if i == 0 else cell.rjust(w) for i, (cell, w) in
                                   enumerate(zip(line, widths))) for line in cells)

    def write(self, out_dir: str | os.PathLike) -> dict[str, str]:
        """Write results.csv, runs.csv, trajectories.npz and trajectories.png into ``out_dir``; their paths."""
        out_dir = os.fspath(out_dir)
        paths = {name: os.path.join(out_dir, name) for name in
                 ("results.csv", "runs.csv", "trajectories.npz", "trajectories.png")}
        _write_csv(paths["results.csv"], TABLE_COLUMNS, self.table())
        _write_csv(paths["runs.csv"], RUN_COLUMNS, [row for r in self.results.values() for row in r.run_rows()])
        self._write_npz(paths["trajectories.npz"])
        self._plot(paths["trajectories.png"])
        return paths

    def _write_npz(self, path: str) -> None:
        arrays = {"controllers": np.array(list(self.results)), "start_point": np.array(self.task.start_point),
                  "decision_period": self.task.decision_period}
        if self.task.route is not None:
            arrays["route"] = np.array(self.task.route)
        for name, result in self.results.items():
            arrays[f"{name}_routes"] = result.routes
            longest = max(len(p.xy) for p in result.paths)
            arrays[f"{name}_x"] = _padded([p.xy[:, 0] for p in result.paths], longest)
            arrays[f"{name}_y"] = _padded([p.xy[:, 1] for p in result.paths], longest)
            arrays[f"{name}_heading"] = _padded([p.heading for p in result.paths], longest)
            arrays[f"{name}_reached"] = _padded([p.reached for p in result.paths], longest)
            arrays[f"{name}_propeller"] = _padded([p.propeller for p in result.paths], longest - 1)
            arrays[f"{name}_length"] = np.array([len(p.propeller) for p in result.paths])
            arrays[f"{name}_success"] = result.success
            if result.has_obstacles:
                arrays[f"{name}_obstacles"] = result.obstacles
        with atomic_output(path, suffix=".npz") as temporary:
            np.savez_compressed(temporary, **arrays)

    def _plot(self, path: str) -> None:
        """The picture: the waypoints every run shares, named, or each run's own in its panel; one wind arrow
        where the task fixes the wind's direction, else one per run in its panel."""
        results, task = list(self.results.values()), self.task
        shared = all(result.shared_route for result in results)
        low, high = task.start.wind_direction_deg
        direction = None
        if low == high:  # one direction (the circular mean of the runs', which the gusts do not move)
            direction = float(np.angle(np.exp(1j * np.concatenate([r.wind_direction for r in results])).mean()))
        plot_trajectories([_panel(result, shared, direction is None) for result in results], path,
                          waypoints=_waypoint_names(results[0].route) if shared else {}, start=task.start_point,
                          reach_radius=task.reach_radius, wind_label=f"wind {_wind_text(task)}",
                          wind_direction=direction, suptitle=self._title())

    def _title(self) -> str:
        s = self.settings
        prefix = f"{s['task']}: " if s.get("task") else ""
        runs = plural(s["runs"], "run")
        return f"{prefix}{_course_text(self.task)}, {runs}: {_conditions_text(self.task, s['seed'])}"


def _panel(result: ControllerResult, shared_route: bool, wind_per_run: bool) -> PanelData:
    """A controller's panel: its paths, titled with its completions (and collisions, among obstacles) and
    mean time; its runs' own waypoints unless every run shares the route, their wind directions where each
    run has its own, and their obstacles where the task has them."""
    summary = result.summary()
    mean = summary["time_mean_s"]
    timing = f", mean {mean:.0f} s" if math.isfinite(mean) else ""
    collisions = f", {summary['collisions']} collided" if result.has_obstacles else ""
    return PanelData(f"{result.name}: {summary['completed']}/{result.runs} completed{collisions}{timing}",
                     [p.xy for p in result.paths], waypoints=None if shared_route else list(result.routes),
                     wind_directions=result.wind_direction if wind_per_run else None,
                     obstacles=list(result.obstacles) if result.has_obstacles else None)


def _padded(values, size: int) -> np.ndarray:
    """Rows of different lengths as one float array (len(values), size), NaN after each row's end."""
    return np.array([np.pad(np.asarray(v, dtype=np.float64), (0, size - len(v)), constant_values=np.nan)
                     for v in values]).reshape(len(values), size)


def _waypoint_names(route) -> dict[str, tuple[float, float]]:
    """Each distinct point of the route [m], named as in MISSION_WAYPOINTS where every one is a mission
    waypoint, else "W1", "W2", ... in route order."""
    points = [tuple(float(v) for v in point) for point in route]
    letters = [mission_waypoint_name(point) for point in points]
    if None in letters:
        letters = [f"W{k}" for k in range(1, len(points) + 1)]
    names = {}
    for name, point in zip(letters, points):
        if not any(math.dist(where, point) < 1e-3 for where in names.values()):
            names[name] = point
    return names


def _format(value) -> str:
    if isinstance(value, (bool, np.bool_)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return "nan" if not math.isfinite(value) else f"{value:.6g}"
    return str(value)


def _write_csv(path: str, columns, rows) -> None:
    with atomic_output(path, suffix=".csv") as temporary:
        with open(temporary, "w", newline="") as handle:
            writer = csv.writer(handle)
            writer.writerow(columns)
            for row in rows:
                writer.writerow([_format(row[column]) for column in columns])


def evaluate_mission(policy: Policy | str | os.PathLike | None = None, runs: int = 20, sea_state: float | None = None,
                     wind: float | None = None, seed: int = 0, device="cpu", time_limit: float | None = None,
                     autopilot: bool | str | LineFollowingConfig | AutopilotConfig = True, progress: bool = True, *,
                     task: TaskConfig | str | None = None,
                     record: str | os.PathLike | None = None, reef: int | None = None) -> MissionEvaluation:
    """Sail a task's runs (default the mission, EBoatMission-v0) ``runs`` times with ``policy`` (a Policy, a
    checkpoint path, or None for none) and with a classical controller (``autopilot``: True or "line" for the
    line follower's defaults, "legacy" for the legacy autopilot's, a LineFollowingConfig or an AutopilotConfig,
    or False for none; named "autopilot" either way; without the motor on a task without propeller), all on
    the same runs (one environment per run, the same seed for every controller).

    Args:
        sea_state: significant wave height Hs [m] of the task's sea (>= 0); None: the task's (0.3 m for
            the missions).
        wind: mean true wind speed [m/s] (>= 0) of every run, with the task's gusts and directions; None:
            the task's (10 m/s toward +x for the missions; the waypoint tasks draw it per run).
        seed: seed of the sea and of the environments' random streams (starts, waypoints, gusts).
        device: Warp device ("cpu", "cuda", "cuda:N").
        time_limit: per run [s]; None: the task's (1800 s for the missions).
        progress: a progress bar per controller over its decisions.
        task: a task config or a registered task id (default EBoatMission-v0); tests pass cheaper configs
            (a coarser boat or sea).
        record: a rosbag2 MCAP log to write (a path ending in .mcap; the ``mcap`` extra): every controller's
            runs, each under its own namespace (``/<controller>/eboat_<run>``, ``/<controller>/eboat`` for
            one run), from their start to the end of the controller's last decision, once per decision
            (``ocean_warp.ros.mcap_log``; None: no log).
        reef: one reef level for every run (``evaluation_task``); None: the task's rule.

    Raises:
        ValueError: a bad setting, an unknown task id or nothing to evaluate; CheckpointError: an unusable
            checkpoint path.
    """
    if isinstance(runs, bool) or not isinstance(runs, (int, np.integer)) or runs < 1:
        raise ValueError(f"evaluate_mission: runs must be an integer >= 1, got {runs!r}")
    if sea_state is not None:
        require_significant_wave_height("evaluate_mission: sea_state", sea_state)
    if wind is not None and not (isinstance(wind, (int, float)) and math.isfinite(wind) and wind >= 0.0):
        raise ValueError(f"evaluate_mission: wind must be a finite number >= 0 or None, got {wind!r}")
    if time_limit is not None and not (math.isfinite(time_limit) and time_limit > 0.0):
        raise ValueError(f"evaluate_mission: time_limit must be > 0 [s] or None, got {time_limit!r}")
    if isinstance(policy, (str, os.PathLike)):
        policy = load_policy(policy)
    controllers: list = []
    if policy is not None:
        controllers.append(PolicyController(policy))
    if autopilot is not False and autopilot is not None:
        if isinstance(autopilot, str):
            controllers.append(AutopilotController(autopilot=autopilot))
        else:
            controllers.append(AutopilotController(None if autopilot is True else autopilot))
    if not controllers:
        raise ValueError("evaluate_mission: nothing to evaluate (no policy and autopilot=False)")
    task = DEFAULT_TASK if task is None else task
    config = evaluation_task(task, sea_state=sea_state, wind=wind, seed=seed, time_limit=time_limit,
                             observation=None if policy is None else policy.observation, reef=reef)
    env = SailingEnv(config, int(runs), device=device, seed=seed)
    log = None
    if record is not None:
        from ocean_warp.envs.ros.mcap_log import McapRecorder

        log = McapRecorder(record)
    try:
        results = {controller.name: sail_mission(env, controller, progress=progress,
                                                 **_logging_callbacks(log, env, controller.name))
                   for controller in controllers}
    except BaseException:
        if log is not None:
            log.abort()
        raise
    if log is not None:
        log.close()
    low, high = config.start.wind_speed
    settings = {"task": task_name(task) if isinstance(task, str) else None, "runs": int(runs),
                "sea_state": config.simulator.ocean.significant_wave_height, "wind": low if low == high else None,
                "seed": int(seed), "device": str(env.device), "time_limit": config.episode_time}
    return MissionEvaluation(task=config, settings=settings, results=results)


def _logging_callbacks(log, env: SailingEnv, name: str) -> dict:
    """:func:`sail_mission`'s callbacks that log ``env`` into ``log`` (an ``McapRecorder``) at the start and
    after every decision, under ``/<name>`` (the controller's name, with characters a ROS name cannot hold
    replaced by "_"); none without a log."""
    if log is None:
        return {}
    prefix = "/" + re.sub(r"[^A-Za-z0-9_]", "_", name)
    if not prefix[1:2].isalpha():
        prefix = "/c" + prefix[1:]
    return {"on_start": lambda: log.record(env, prefix=prefix),
            "on_decision": lambda k, decision: log.record(env, prefix=prefix)}


def _check_options(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Exit with status 2 and one line on option values that cannot work (alone or together)."""
    check_options(parser, (
        ("--runs", args.runs, args.runs >= 1, "a whole number >= 1"),
        ("--sea-state", args.sea_state, args.sea_state is None or is_valid_significant_wave_height(args.sea_state),
         SIGNIFICANT_WAVE_HEIGHT_RULE),
        ("--wind", args.wind, args.wind is None or finite_at_least(args.wind, 0.0), "a finite number >= 0 [m/s]"),
        ("--time-limit", args.time_limit, args.time_limit is None or finite_above(args.time_limit, 0.0),
         "a number > 0 [s]"),
    ))
    if args.no_policy and args.no_autopilot:
        fail(parser, "--no-policy and --no-autopilot leave nothing to run")
    if args.no_policy and args.policy is not None:
        fail(parser, "--policy and --no-policy contradict each other")
    if args.record is not None:
        from ocean_warp.envs.ros.mcap_log import check_record_path

        try:
            check_record_path(args.record)
        except (ValueError, ImportError) as error:
            fail(parser, f"--record: {error}")


def _policy_for(parser: argparse.ArgumentParser, args: argparse.Namespace, name: str) -> Policy | None:
    """The policy to sail on task ``name``: --policy, else the task's shipped one. None, said in one line,
    where the task has none (the autopilot sails alone); exits with status 2 on an unusable checkpoint, or
    when there is no policy and --no-autopilot leaves nothing to run."""
    from ..training.policies import shipped_policy_path

    path = args.policy
    if path is None:
        try:
            path = shipped_policy_path(name)
        except ValueError:
            if args.no_autopilot:
                fail(parser, f"no policy is shipped for {name} and --no-autopilot leaves nothing to run; "
                             "pass --policy PATH")
            print(f"no policy is shipped for {name}: sailing the autopilot only (--policy PATH evaluates one)")
            return None
        except FileNotFoundError as error:
            fail(parser, f"{error}; --no-policy sails the autopilot alone")
    try:
        policy = load_policy(path)
    except CheckpointError as error:
        hint = "; --no-policy sails the autopilot alone" if args.policy is None else ""
        fail(parser, f"{error}{hint}")
    print(f"policy {path}: for {policy.task}, observation {policy.observation!r} ({policy.num_obs} values)")
    warn_other_task(parser.prog, policy, name)
    return policy


def warn_other_task(prog: str, policy: Policy, task: str) -> None:
    """One line on stderr, ``<prog>: warning: ...``, where ``policy`` was trained on another task than
    ``task``."""
    note = other_task_note(policy, task)
    if note is not None:
        print(f"{prog}: warning: {note}", file=sys.stderr)


def main(argv=None) -> int:
    """``ocean-warp eval [options]``: returns 0; bad options, unknown task ids and unusable policies exit with
    status 2."""
    parser = evaluation_options.parser()
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    _check_options(parser, args)
    checked_output_folder(parser, args.out)
    try:
        name = task_name(args.task)
    except ValueError as error:
        fail(parser, f"--task: {error}")
    device = checked_device(parser, args.device)
    try:
        reef = None if args.reef == "auto" else int(args.reef)
        task = evaluation_task(name, sea_state=args.sea_state, wind=args.wind, seed=args.seed,
                               time_limit=args.time_limit, reef=reef)
    except ValueError as error:
        fail(parser, str(error))
    print(f"{name} ({_course_text(task)}): {plural(args.runs, 'run')} per controller, "
          f"{_conditions_text(task, args.seed)}, device {device}")
    policy = None if args.no_policy else _policy_for(parser, args, name)
    try:
        evaluation = evaluate_mission(policy, args.runs, sea_state=args.sea_state, wind=args.wind, seed=args.seed,
                                      device=device, time_limit=args.time_limit,
                                      autopilot=False if args.no_autopilot else args.autopilot,
                                      progress=not args.no_progress, task=name, record=args.record, reef=reef)
    except ValueError as error:  # a policy whose observation the task cannot give
        fail(parser, str(error))
    paths = evaluation.write(args.out)
    print(evaluation.format_table())
    for path in list(paths.values()) + ([args.record] if args.record is not None else []):
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
