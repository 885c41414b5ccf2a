"""The runs of one controller: per-run outcomes and paths (:class:`ControllerResult`), and the metrics of the
tables (results.csv's row, runs.csv's rows) computed from them."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ocean_warp.fleet import BoatStatus, episode_end

from .mission_metrics import cross_track_spread, motor_use, path_length, wind_crossings
from .recording import RunPath

__all__ = ["ControllerResult"]


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
    vrx_score: np.ndarray | None = None
    """(N,) the task's VRX score of each run's first episode (``env.buffers.final_score`` where it ended), NaN
    where the task has none (every E-Boat task); None: NaN for every run."""

    def __post_init__(self):
        runs = len(self.paths)
        obstacles = np.zeros((runs, 0, 4)) if self.obstacles is None else np.asarray(self.obstacles, np.float64)
        if obstacles.ndim != 3 or obstacles.shape[0] != runs or obstacles.shape[2] != 4:
            raise ValueError(f"ControllerResult.obstacles must be ({runs}, K, 4) (x, y, radius, kind per run and "
                             f"row), got shape {obstacles.shape}")
        self.obstacles = obstacles
        score = np.full(runs, np.nan) if self.vrx_score is None else np.asarray(self.vrx_score, np.float64)
        if score.shape != (runs,):
            raise ValueError(f"ControllerResult.vrx_score must be ({runs},) (one score per run), got shape "
                             f"{score.shape}")
        self.vrx_score = score
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
        pick = (lambda values: None if values is None else kept_counts(values[index]))  # noqa: E731
        return ControllerResult(name=name, paths=[self.paths[i] for i in index], success=self.success[index],
                                time_s=self.time_s[index], waypoints=self.waypoints[index], status=self.status[index],
                                time_out=self.time_out[index], wind_direction=self.wind_direction[index],
                                routes=self.routes[index], start_point=self.start_point, own_tacks=pick(self.own_tacks),
                                own_gybes=pick(self.own_gybes), obstacles=self.obstacles[index],
                                vrx_score=self.vrx_score[index])

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
                "time_outs": int(self.time_out.sum()), "motor_use": float(np.nanmean(self.motor_use)),
                "vrx_score": score_cell(float(self.vrx_score.mean()) if self.runs else math.nan)}

    def run_rows(self) -> list[dict]:
        """Its rows of runs.csv (``RUN_COLUMNS``)."""
        rows = []
        for i, path in enumerate(self.paths):
            rows.append({"controller": self.name, "run": i, "completed": int(self.success[i]), "end": self.end(i),
                         "time_s": float(self.time_s[i]), "waypoints": int(self.waypoints[i]),
                         "distance_m": float(self.distance_m[i]), "tacks": int(self.tacks[i]),
                         "gybes": int(self.gybes[i]),
                         "own_tacks": count_cell(self.own_tacks, i), "own_gybes": count_cell(self.own_gybes, i),
                         "motor_use": float(self.motor_use[i]), "start_x_m": float(path.xy[0, 0]),
                         "start_y_m": float(path.xy[0, 1]), "start_heading_deg": math.degrees(path.heading[0]),
                         "vrx_score": score_cell(float(self.vrx_score[i]))})
        return rows


def kept_counts(values: np.ndarray) -> np.ndarray | None:
    """Own counts (N,) as a result keeps them: None where no run has one (all NaN)."""
    return None if np.isnan(values).all() else values


def count_cell(values: np.ndarray | None, run: int):
    """A run's own count in runs.csv: the whole number, or empty where its controller keeps none."""
    return "" if values is None or np.isnan(values[run]) else int(values[run])


def score_cell(value: float):
    """A VRX score in results.csv and runs.csv: the number, or empty where it is NaN (a task without a score, or a
    mean over runs of which one has none)."""
    return "" if math.isnan(value) else value
