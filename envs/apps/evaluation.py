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
(``ocean_warp.envs.controllers.sailing_autopilot``). On the WAM-V's tasks the baseline is named as it is:
by default ``pivot-station-keeping`` (station keeping and wayfinding: transit, back and fill, holding) and
``gate-guidance`` (the path: LOS through the gates clear of the buoys); with --autopilot legacy the earlier
``pid-station-keeping`` and ``los-guidance``. On a task without propeller (EBoatMissionSail-v0:
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
                        side (envs/evaluation/mission_metrics.py: wind_crossings)
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
  vrx_score             the task's VRX score (``env.buffers.final_score`` at the end of each run's first
                        episode), mean over runs; empty on a task without one (every E-Boat task). runs.csv
                        has each run's in its own vrx_score column (empty likewise)
"""

from __future__ import annotations

import argparse
import logging
import sys

import warp as wp

from ocean_warp.cli_support import (
    check_options,
    checked_device,
    checked_output_folder,
    fail,
    finite_above,
    finite_at_least,
    plural,
)
from ocean_warp.ocean_config import SIGNIFICANT_WAVE_HEIGHT_RULE, is_valid_significant_wave_height

from ..evaluation import conditions_text, course_text, evaluate_mission, evaluation_task, warn_other_task
from ..registration import task_name
from ..training.policy_io import CheckpointError, Policy, load_policy
from . import evaluation_options

__all__ = ["main"]


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
    print(f"{name} ({course_text(task)}): {plural(args.runs, 'run')} per controller, "
          f"{conditions_text(task, args.seed)}, device {device}")
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
