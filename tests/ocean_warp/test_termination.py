"""SIGTERM unwinds a job like Ctrl-C: temporary files go, the status is 143, one line and no traceback."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from ocean_warp.atomic_files import atomic_output
from ocean_warp.termination import Terminated, exit_cleanly_on_sigterm


@pytest.fixture
def sigterm_handler_restored():
    previous = signal.getsignal(signal.SIGTERM)
    yield
    signal.signal(signal.SIGTERM, previous)


def test_sigterm_inside_atomic_output_removes_the_temporary_and_exits_143(tmp_path, sigterm_handler_restored,
                                                                          capsys):
    assert exit_cleanly_on_sigterm(["export-usd"])
    target = tmp_path / "table.csv"
    with pytest.raises(Terminated) as caught:
        with atomic_output(target) as temporary:
            with open(temporary, "w") as handle:
                handle.write("half a table")
            os.kill(os.getpid(), signal.SIGTERM)
            pytest.fail("SIGTERM did not interrupt the writer")
    assert caught.value.code == 128 + 15
    assert os.listdir(tmp_path) == []
    assert capsys.readouterr().err == "ocean-warp export-usd: terminated; files written before it are complete\n"
    # A second SIGTERM while the first unwinds is ignored rather than cutting the cleanup short.
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_IGN


def _hidden_files(folder) -> list[str]:
    return [name for name in os.listdir(folder) if name.startswith(".")] if os.path.isdir(folder) else []


def test_sigterm_to_export_usd_leaves_no_temporary_stage(tmp_path):
    pytest.importorskip("pxr")
    out = tmp_path / "stages"
    command = [sys.executable, "-m", "ocean_warp.cli", "export-usd", "--device", "cpu", "--boats", "2",
               "--duration", "3000", "--controller", "autopilot", "--no-progress", "--out", str(out / "run.usdc")]
    job = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path)
    try:
        # Wait until the stage is being written (its hidden temporary exists), or the job has ended.
        deadline = time.monotonic() + 600  # a guard against a hang, not a measurement
        while not _hidden_files(out) and job.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        assert _hidden_files(out), f"no temporary stage appeared; the job ended with {job.poll()}"
        job.send_signal(signal.SIGTERM)
        stdout, stderr = job.communicate(timeout=600)
    finally:
        if job.poll() is None:
            job.kill()
            job.communicate()
    assert job.returncode == 143, stderr
    assert not os.path.isdir(out) or os.listdir(out) == []
    assert "Traceback" not in stderr
    assert "ocean-warp export-usd: terminated; files written before it are complete" in stderr
