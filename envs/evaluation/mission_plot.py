"""The picture of ``ocean-warp eval``: every run's path of each controller over the task's waypoints.

One panel per controller, side by side on the same axes (metres from each run's origin, equal aspect):
each run a thin line (run i has the same colour in every panel: the runs share their starts, waves and
gusts), the waypoints the runs share labelled, or each run's own waypoints in its colour (tasks whose
runs draw them), their reach circles dashed, the start marked, and an arrow for the true wind with its
speed (one per run, in the run's colour, where each run has its own direction). On a task with obstacles,
each run's buoys (orange) and piles (grey) are circles of their true radius at their places from the run's
origin, edged in the run's colour, under the paths. Written with matplotlib's Agg backend, atomically.
"""

from __future__ import annotations

import math
import os
import textwrap
from collections.abc import Mapping, Sequence

import numpy as np

from ocean_warp.atomic_files import save_figure

__all__ = ["PanelData", "plot_trajectories", "OBSTACLE_COLORS"]

OBSTACLE_COLORS = {1: "tab:orange", 2: "0.55"}
"""Fill of an obstacle by kind (1 a buoy, 2 a pile: ``ocean_warp.envs.tasks.obstacle_course.OBSTACLE_*``)."""
OBSTACLE_NAMES = {1: "buoy", 2: "pile"}


class PanelData:
    """What one panel shows: ``title``, and ``paths``, per run (T_i, 2) positions [m]. Optionally, per run
    i: ``waypoints`` (R_i, 2) its own waypoints [m] (tasks whose runs draw them), ``wind_directions``
    (N,) the direction its wind blows toward [rad] (tasks that draw it per run) and ``obstacles`` (K_i, 4)
    its obstacle table: x, y [m], radius [m], kind (0 an empty row, left out; 1 a buoy; 2 a pile); each
    drawn in run i's colour."""

    def __init__(self, title: str, paths: Sequence[np.ndarray], waypoints: Sequence[np.ndarray] | None = None,
                 wind_directions: Sequence[float] | None = None, obstacles: Sequence[np.ndarray] | None = None):
        self.title = title
        self.paths = [np.asarray(path, dtype=np.float64).reshape(-1, 2) for path in paths]
        self.waypoints = [np.asarray(points, dtype=np.float64).reshape(-1, 2) for points in
                          ([] if waypoints is None else waypoints)]
        self.wind_directions = None if wind_directions is None else np.asarray(wind_directions, dtype=np.float64)
        self.obstacles = [np.asarray(table, dtype=np.float64).reshape(-1, 4) for table in
                          ([] if obstacles is None else obstacles)]
        for name, values in (("waypoints", self.waypoints), ("wind_directions", self.wind_directions),
                             ("obstacles", self.obstacles)):
            if values is not None and len(values) not in (0, len(self.paths)):
                raise ValueError(f"PanelData.{name} must have one entry per run ({len(self.paths)}), got {len(values)}")
        for table in self.obstacles:
            used = table[table[:, 3] != 0]
            if not (np.all(np.isfinite(used)) and np.all(used[:, 2] > 0) and np.all(np.isin(used[:, 3], (1, 2)))):
                raise ValueError("PanelData.obstacles: each row must be x, y [m], radius > 0 [m] and kind 1 (buoy) "
                                 "or 2 (pile), or all zeros (an empty row)")

    def obstacle_extent(self) -> np.ndarray:
        """(2 P, 2) the corners of every obstacle's bounding square [m] (for the axes' limits)."""
        rows = [table[table[:, 3] != 0] for table in self.obstacles]
        rows = np.concatenate(rows) if rows else np.zeros((0, 4))
        return np.concatenate([rows[:, :2] - rows[:, 2:3], rows[:, :2] + rows[:, 2:3]])


def plot_trajectories(panels: Sequence[PanelData], path: str | os.PathLike, *, waypoints: Mapping[str, tuple],
                      start: tuple[float, float], reach_radius: float, wind_label: str,
                      wind_direction: float | None, suptitle: str | None = None) -> None:
    """Write ``path`` (PNG): one panel per entry of ``panels``, sharing both axes. Each panel also draws its
    runs' own waypoints (with their reach circles) and wind directions, where it has them.

    Args:
        waypoints: name -> (x, y) [m], waypoints every run shares, drawn labelled with a dashed circle of
            ``reach_radius`` [m].
        start: where the runs start [m].
        wind_label: the wind arrow's label ("wind 10 m/s").
        wind_direction: direction the wind blows toward [rad, from +x counter-clockwise], one arrow; None:
            each panel's ``wind_directions``, an arrow per run in its colour from a common tail (none if
            the panel has none).
        suptitle: a line above the panels.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if not panels:
        raise ValueError("plot_trajectories: nothing to plot (no panels)")
    shared = np.array(list(waypoints.values()), dtype=np.float64).reshape(-1, 2)
    own = [points for panel in panels for points in panel.waypoints]
    finite = [p[np.all(np.isfinite(p), axis=1)] for panel in panels for p in panel.paths]
    obstacles = [panel.obstacle_extent() for panel in panels]
    everything = np.vstack([shared, *own, np.asarray(start, dtype=np.float64).reshape(1, 2), *finite, *obstacles])
    low, high = everything.min(axis=0), everything.max(axis=0)
    pad = 0.08 * float(max(high - low)) + reach_radius
    low, high = low - pad, high + pad
    high[1] += 0.12 * (high[1] - low[1])  # room for the wind arrow at the top

    # Panels as wide as the course is (equal axes), so a tall course does not leave blank margins.
    aspect = float(high[0] - low[0]) / float(high[1] - low[1])
    width = len(panels) * min(max(5.2 * aspect + 1.0, 3.5), 9.0)
    fig, axes = plt.subplots(1, len(panels), figsize=(width, 6.0), sharex=True, sharey=True, squeeze=False)
    colours = plt.get_cmap("tab20")
    run_colour = lambda i: colours(i % 20)  # noqa: E731
    for ax, panel in zip(axes[0], panels):
        _obstacles(ax, panel.obstacles, run_colour)
        for i, run in enumerate(panel.paths):
            ax.plot(run[:, 0], run[:, 1], lw=0.7, alpha=0.85, color=run_colour(i))
        for name, (x, y) in waypoints.items():
            _waypoint(ax, (x, y), reach_radius, circle="0.25", dot="k", ms=4, lw=0.9)
            ax.annotate(name, (x, y), xytext=(7, 7), textcoords="offset points", fontsize=12, fontweight="bold")
        for i, points in enumerate(panel.waypoints):
            for point in points:
                _waypoint(ax, point, reach_radius, circle=run_colour(i), dot=run_colour(i), ms=3, lw=0.7)
        ax.plot([start[0]], [start[1]], marker="^", ms=9, color="tab:green", ls="none", label="start", zorder=5)
        if wind_direction is not None:
            _wind_arrow(ax, low, high, wind_label, wind_direction)
        elif panel.wind_directions is not None and len(panel.wind_directions):
            _wind_rose(ax, low, high, wind_label, panel.wind_directions, run_colour)
        ax.set_title(panel.title)
        ax.set_xlabel("x (east) [m]")
        ax.set_aspect("equal", adjustable="box")
        ax.grid(True, lw=0.3, alpha=0.5)
        ax.legend(loc="lower right", fontsize=8)
    axes[0][0].set_xlim(low[0], high[0])
    axes[0][0].set_ylim(low[1], high[1])
    axes[0][0].set_ylabel("y (north) [m]")
    if suptitle:  # wrapped to the figure's width: about 13 characters of 10 pt text an inch
        fig.suptitle(textwrap.fill(suptitle, width=max(40, int(13 * width))), fontsize=10)
    fig.tight_layout()
    save_figure(fig, path, dpi=120)


def _obstacles(ax, tables: Sequence[np.ndarray], run_colour) -> None:
    """Every run's obstacles (``tables``: per run i, (K_i, 4) rows x, y [m], radius [m], kind) as filled
    circles of their radius, buoys orange and piles grey, edged in run i's colour, beneath the paths; one
    legend entry per kind drawn."""
    from matplotlib.patches import Circle

    drawn = set()
    for i, table in enumerate(tables):
        for x, y, radius, kind in table[table[:, 3] != 0]:
            drawn.add(int(kind))
            ax.add_patch(Circle((x, y), radius, facecolor=OBSTACLE_COLORS[int(kind)], edgecolor=run_colour(i),
                                lw=0.6, alpha=0.9, zorder=1.5))
    for kind in sorted(drawn):  # legend entries alone (empty), edged neutrally: the edges are the runs' colours
        ax.scatter([], [], marker="o", s=40, facecolor=OBSTACLE_COLORS[kind], edgecolor="0.2", lw=0.6,
                   label=OBSTACLE_NAMES[kind])


def _waypoint(ax, point, reach_radius: float, *, circle, dot, ms: float, lw: float) -> None:
    """A waypoint at ``point`` (x, y) [m]: a dot (colour ``dot``, size ``ms`` [pt]) and its dashed reach
    circle of ``reach_radius`` [m] (colour ``circle``, line width ``lw`` [pt])."""
    from matplotlib.patches import Circle

    ax.add_patch(Circle(tuple(point), reach_radius, fill=False, ls="--", lw=lw, color=circle))
    ax.plot([point[0]], [point[1]], marker="o", ms=ms, color=dot)


def _wind_rose(ax, low, high, label: str, directions: np.ndarray, run_colour) -> None:
    """A wind arrow per run, toward its ``directions`` [rad], in the run's colour, from a common tail."""
    span = float(min(high - low))
    length = 0.07 * span
    tail = np.array([low[0] + 0.08 * (high[0] - low[0]) + length, high[1] - 0.06 * (high[1] - low[1]) - length])
    for i, angle in enumerate(directions):
        tip = tail + length * np.array([math.cos(angle), math.sin(angle)])
        ax.annotate("", xy=tuple(tip), xytext=tuple(tail),
                    arrowprops={"arrowstyle": "-|>", "lw": 1.2, "color": run_colour(i)})
    ax.annotate(f"{label}, per run", (tail[0] + length, tail[1]), xytext=(6, 0), textcoords="offset points",
                va="center", color="tab:blue", fontsize=9)


def _wind_arrow(ax, low, high, label: str, direction: float) -> None:
    span = float(min(high - low))
    length = 0.14 * span
    tail = np.array([low[0] + 0.10 * (high[0] - low[0]), high[1] - 0.07 * (high[1] - low[1])])
    tail = tail + np.array([length / 2.0 * (1.0 - math.cos(direction)), -length / 2.0 * max(0.0, math.sin(direction))])
    dx, dy = length * math.cos(direction), length * math.sin(direction)
    ax.annotate("", xy=(tail[0] + dx, tail[1] + dy), xytext=tuple(tail),
                arrowprops={"arrowstyle": "-|>", "lw": 2.0, "color": "tab:blue"})
    ax.annotate(label, (tail[0] + dx / 2.0, tail[1] + dy / 2.0), xytext=(0, 8),
                textcoords="offset points", ha="center", color="tab:blue", fontsize=9)
