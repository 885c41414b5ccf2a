"""An evaluation's results (:class:`MissionEvaluation`) and their files: results.csv (``TABLE_COLUMNS``),
runs.csv (``RUN_COLUMNS``), trajectories.npz and trajectories.png (definitions: ``ocean_warp.envs.apps.evaluation``)."""

from __future__ import annotations

import csv
import dataclasses
import math
import os

import numpy as np

from ocean_warp.atomic_files import atomic_output
from ocean_warp.cli_support import plural

from .mission_plot import PanelData, plot_trajectories
from ..tasks.task_configs import TaskConfig, mission_waypoint_name
from .presets import conditions_text, course_text, wind_text
from .results import ControllerResult

__all__ = ["TABLE_COLUMNS", "RUN_COLUMNS", "MissionEvaluation"]


TABLE_COLUMNS = ("controller", "runs", "completed", "completion_rate", "time_mean_s", "time_std_s", "time_min_s",
                 "time_max_s", "distance_mean_m", "tacks_mean", "gybes_mean", "cross_track_spread_m", "capsizes",
                 "collisions", "lost", "time_outs", "motor_use", "vrx_score")
"""Columns of results.csv (module docstring: their definitions)."""
RUN_COLUMNS = ("controller", "run", "completed", "end", "time_s", "waypoints", "distance_m", "tacks", "gybes",
               "own_tacks", "own_gybes", "motor_use", "start_x_m", "start_y_m", "start_heading_deg", "vrx_score")
"""Columns of runs.csv: per run, the first episode's outcome; time_s is when it ended, however it ended;
own_tacks / own_gybes are the controller's own counts where it keeps them (the autopilot), else empty;
vrx_score is the task's VRX score of the episode (``env.buffers.final_score``), empty where the task has none."""


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
                          reach_radius=task.reach_radius, wind_label=f"wind {wind_text(task)}",
                          wind_direction=direction, suptitle=self._title())

    def _title(self) -> str:
        s = self.settings
        prefix = f"{s['task']}: " if s.get("task") else ""
        runs = plural(s["runs"], "run")
        return f"{prefix}{course_text(self.task)}, {runs}: {conditions_text(self.task, s['seed'])}"


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
