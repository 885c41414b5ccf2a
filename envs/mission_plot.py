"""The picture of ``ocean-warp eval``: every run's path of each controller over the mission's waypoints.

One panel per controller, side by side on the same axes (metres from each run's origin, equal aspect):
each run a thin line (run i has the same colour in every panel: the runs share their starts, waves and
gusts), the waypoints labelled, their reach circles dashed, the start marked, and an arrow for the true
wind with its speed. Written with matplotlib's Agg backend, atomically.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence

import numpy as np

from ocean_warp.atomic_files import atomic_output

__all__ = ["PanelData", "plot_trajectories"]


class PanelData:
    """What one panel shows: ``title``, and ``paths``, per run (T_i, 2) positions [m]."""

    def __init__(self, title: str, paths: Sequence[np.ndarray]):
        self.title = title
        self.paths = [np.asarray(path, dtype=np.float64).reshape(-1, 2) for path in paths]


def plot_trajectories(panels: Sequence[PanelData], path: str | os.PathLike, *, waypoints: Mapping[str, tuple],
                      start: tuple[float, float], reach_radius: float, wind_speed: float, wind_direction: float,
                      suptitle: str | None = None) -> None:
    """Write ``path`` (PNG): one panel per entry of ``panels``, sharing both axes.

    Args:
        waypoints: name -> (x, y) [m], drawn labelled with a dashed circle of ``reach_radius`` [m].
        start: where the runs start [m].
        wind_speed: mean true wind [m/s], the arrow's label.
        wind_direction: direction the wind blows toward [rad, from +x counter-clockwise].
        suptitle: a line above the panels.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle

    if not panels:
        raise ValueError("plot_trajectories: nothing to plot (no panels)")
    points = np.array(list(waypoints.values()), dtype=np.float64).reshape(-1, 2)
    finite = [p[np.all(np.isfinite(p), axis=1)] for panel in panels for p in panel.paths]
    everything = np.vstack([points, np.asarray(start, dtype=np.float64).reshape(1, 2), *finite])
    low, high = everything.min(axis=0), everything.max(axis=0)
    pad = 0.08 * float(max(high - low)) + reach_radius
    low, high = low - pad, high + pad
    high[1] += 0.12 * (high[1] - low[1])  # room for the wind arrow at the top

    # Panels as wide as the course is (equal axes), so a tall course does not leave blank margins.
    aspect = float(high[0] - low[0]) / float(high[1] - low[1])
    width = len(panels) * min(max(5.2 * aspect + 1.0, 3.5), 9.0)
    fig, axes = plt.subplots(1, len(panels), figsize=(width, 6.0), sharex=True, sharey=True, squeeze=False)
    colours = plt.get_cmap("tab20")
    for ax, panel in zip(axes[0], panels):
        for i, run in enumerate(panel.paths):
            ax.plot(run[:, 0], run[:, 1], lw=0.7, alpha=0.85, color=colours(i % 20))
        for name, (x, y) in waypoints.items():
            ax.add_patch(Circle((x, y), reach_radius, fill=False, ls="--", lw=0.9, color="0.25"))
            ax.plot([x], [y], marker="o", ms=4, color="k")
            ax.annotate(name, (x, y), xytext=(7, 7), textcoords="offset points", fontsize=12, fontweight="bold")
        ax.plot([start[0]], [start[1]], marker="^", ms=9, color="tab:green", ls="none", label="start", zorder=5)
        _wind_arrow(ax, low, high, wind_speed, wind_direction)
        ax.set_title(panel.title)
        ax.set_xlabel("x (east) [m]")
        ax.set_aspect("equal", adjustable="box")
        ax.grid(True, lw=0.3, alpha=0.5)
        ax.legend(loc="lower right", fontsize=8)
    axes[0][0].set_xlim(low[0], high[0])
    axes[0][0].set_ylim(low[1], high[1])
    axes[0][0].set_ylabel("y (north) [m]")
    if suptitle:
        fig.suptitle(suptitle, fontsize=10)
    fig.tight_layout()
    with atomic_output(path, suffix=".png") as temporary:
        fig.savefig(temporary, dpi=120)
    plt.close(fig)


def _wind_arrow(ax, low, high, speed: float, direction: float) -> None:
    span = float(min(high - low))
    length = 0.14 * span
    tail = np.array([low[0] + 0.10 * (high[0] - low[0]), high[1] - 0.07 * (high[1] - low[1])])
    tail = tail + np.array([length / 2.0 * (1.0 - math.cos(direction)), -length / 2.0 * max(0.0, math.sin(direction))])
    dx, dy = length * math.cos(direction), length * math.sin(direction)
    ax.annotate("", xy=(tail[0] + dx, tail[1] + dy), xytext=tuple(tail),
                arrowprops={"arrowstyle": "-|>", "lw": 2.0, "color": "tab:blue"})
    ax.annotate(f"wind {speed:g} m/s", (tail[0] + dx / 2.0, tail[1] + dy / 2.0), xytext=(0, 8),
                textcoords="offset points", ha="center", color="tab:blue", fontsize=9)
