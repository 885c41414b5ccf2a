"""The long examples (polar, drop-hulls) show a progress bar of their time steps on stderr, and only where
asked (their commands: where stderr is a terminal)."""

from __future__ import annotations

import re
import subprocess
import sys

from ocean_warp.eboat.polar import speed_polar
from ocean_warp.examples import drop_hulls


def _bar_counts(text: str, label: str) -> list[tuple[int, int]]:
    """Every "label: ... n/total" that tqdm drew."""
    return [(int(n), int(total)) for n, total in re.findall(rf"{label}: .*?(\d+)/(\d+)", text)]


def test_polar_shows_its_steps(capsys):
    # 0.5 s settling + 0.5 s averaging at 0.05 s a step: 20 steps.
    speed_polar(wind_speeds=(5.0,), wind_angles_deg=[90.0], sheets_deg=[30.0], settle_time=0.5, average_time=0.5,
                dt=0.05, device="cpu", progress=True)
    counts = _bar_counts(capsys.readouterr().err, "polar")
    assert counts and counts[-1] == (20, 20)


def test_drop_hulls_shows_its_steps(tmp_path, capsys):
    drop_hulls.run(str(tmp_path), device="cpu", boats_per_shape=1, seconds=0.1, progress=True)
    counts = _bar_counts(capsys.readouterr().err, "drop-hulls")
    assert counts and counts[-1] == (5, 5)  # 0.1 s at 0.02 s a step
    drop_hulls.run(str(tmp_path), device="cpu", boats_per_shape=1, seconds=0.1, progress=False)
    assert capsys.readouterr().err == ""


def test_the_command_draws_no_bar_into_a_pipe(tmp_path):
    job = subprocess.run([sys.executable, "-m", "ocean_warp.cli", "drop-hulls", "--device", "cpu",
                          "--boats-per-shape", "1", "--seconds", "0.1", "--out", str(tmp_path)],
                         capture_output=True, text=True, timeout=600)
    assert job.returncode == 0, job.stderr
    assert _bar_counts(job.stderr, "drop-hulls") == [] and "wrote" in job.stdout
