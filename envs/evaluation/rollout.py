"""The rollout of an evaluation: one controller sails every run of an environment until its first episode
ends (:func:`sail_mission`)."""

from __future__ import annotations

from typing import Callable

import numpy as np

from ocean_warp.frames import roll_pitch_yaw

from ..protocol import BatchedEnv
from .controllers import Controller
from .recording import RecordedDecision, RunPath
from .results import ControllerResult, kept_counts

__all__ = ["sail_mission"]


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
    outcome["vrx_score"] = np.full(n, np.nan)
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
                outcome["vrx_score"][done] = host(b.final_score)[done]
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
    own = {} if own_counts is None else {"own_tacks": kept_counts(outcome["own_tacks"]),
                                         "own_gybes": kept_counts(outcome["own_gybes"])}
    return ControllerResult(name=controller.name, paths=paths, success=outcome["success"], time_s=outcome["time_s"],
                            waypoints=outcome["waypoints"], status=outcome["status"], time_out=outcome["time_out"],
                            wind_direction=wind_direction, routes=routes,
                            start_point=np.array(env.task.start_point, dtype=np.float64), obstacles=obstacles,
                            vrx_score=outcome["vrx_score"], **own)
