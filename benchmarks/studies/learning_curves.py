"""Learning curves of training runs: mean return and success rate against wall time and against samples.

    python -m benchmarks.studies.learning_curves out/train/EBoatWaypoint-v0/<run> out/train/EBoatWaypointPlus-v0/<run> \
        --labels Waypoint Waypoint+ --out benchmarks/figures/learning_curves.png

Each run folder holds the ``progress.csv`` that ``ocean-warp train`` writes (one row per PPO iteration:
samples = environment decisions so far, wall time, the mean return and the success rate of the
episodes that ended in that iteration). Curves are smoothed over a few iterations.
"""

from __future__ import annotations

import argparse
import csv
import json
import os

import numpy as np


from ocean_warp.atomic_files import atomic_output


def read_progress(run_dir: str) -> dict[str, np.ndarray]:
    """The columns of ``run_dir/progress.csv`` as float arrays."""
    path = os.path.join(run_dir, "progress.csv")
    if not os.path.isfile(path):
        raise SystemExit(f"learning_curves: {path} not found (is {run_dir!r} a run folder of ocean-warp train?)")
    with open(path, newline="") as stream:
        rows = list(csv.DictReader(stream))
    return {key: np.array([float(row[key]) for row in rows]) for key in rows[0]}


def restart_iterations(run_dir: str, last_iteration: int) -> list[int]:
    """Iterations at which every environment restarted from a seeded reset (``save_interval`` multiples,
    from the run's config.json); none where the run has no config."""
    path = os.path.join(run_dir, "config.json")
    if not os.path.isfile(path):
        return []
    with open(path) as stream:
        interval = int(json.load(stream)["train_config"]["save_interval"])
    return list(range(interval, last_iteration + 1, interval))


def smooth(values: np.ndarray, width: int) -> np.ndarray:
    """Moving mean over ``width`` iterations, ignoring NaN (iterations in which no episode ended)."""
    out = np.empty_like(values)
    for i in range(len(values)):
        window = values[max(0, i - width + 1): i + 1]
        window = window[np.isfinite(window)]
        out[i] = window.mean() if window.size else np.nan
    return out


def plot(runs: list[str], labels: list[str], out: str, width: int = 5, title: str = "") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(2, 2, figsize=(10, 6.5), sharey="row")
    any_restart = False
    for run, label in zip(runs, labels):
        data = read_progress(run)
        iterations = data["iteration"].astype(int)
        restarts = np.isin(iterations, restart_iterations(run, int(iterations[-1])))
        any_restart |= bool(restarts.any())
        for column, (x_key, x_label, scale) in enumerate((("wall_time_s", "wall time [s]", 1.0),
                                                           ("samples", "samples [M decisions]", 1e-6))):
            x = data[x_key] * scale
            line, = axes[0, column].plot(x, smooth(data["mean_return"], width), label=label)
            axes[1, column].plot(x, 100.0 * smooth(data["success_rate"], width), label=label)
            for row in range(2):
                for position in x[restarts]:
                    axes[row, column].axvline(position, color=line.get_color(), alpha=0.35, linestyle=":")
            axes[1, column].set_xlabel(x_label)
    axes[0, 0].set_ylabel("mean episode return")
    axes[1, 0].set_ylabel("success [%]")
    for axis in axes.flat:
        axis.grid(alpha=0.3)
    axes[0, 0].legend()
    if title:
        figure.suptitle(title)
    if any_restart:
        figure.text(0.5, 0.005, "dotted: every environment restarts from a seeded reset (what makes --resume exact); "
                    "the first episodes to end after one are the short ones, mostly failures, hence the dips",
                    ha="center", va="bottom", fontsize=8, color="0.35")
    figure.tight_layout(rect=(0, 0.03 if any_restart else 0, 1, 1))
    with atomic_output(out, suffix=".png") as temporary:
        figure.savefig(temporary, dpi=90)
    plt.close(figure)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", help="run folders (each with progress.csv)")
    parser.add_argument("--labels", nargs="+", default=None, help="one label per run (default: folder names)")
    parser.add_argument("--out", default="learning_curves.png")
    parser.add_argument("--smooth", type=int, default=5, help="iterations in the moving mean")
    parser.add_argument("--title", default="")
    args = parser.parse_args(argv)
    labels = args.labels or [os.path.basename(os.path.normpath(run)) for run in args.runs]
    if len(labels) != len(args.runs):
        raise SystemExit("learning_curves: give one label per run")
    plot(args.runs, labels, args.out, args.smooth, args.title)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
