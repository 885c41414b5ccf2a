"""What every ``ocean-warp <job>`` shares (ocean_warp.cli, cli_support, devices): usage lines and defaults in
the help, one-line errors for bad values and devices, and no Warp no-driver warning on a machine without a GPU."""

from __future__ import annotations

import argparse
import os
import subprocess
import sys

import pytest
import warp as wp

from ocean_warp import cli
from ocean_warp.cli_support import HelpFormatter, plural
from ocean_warp.devices import NO_DRIVER_WARNING, cuda_driver_loadable, resolve_device, stderr_without

HAS_GPU = wp.get_cuda_device_count() > 0


def _job_parser(job: str, monkeypatch) -> argparse.ArgumentParser:
    """The parser ``ocean-warp <job>`` builds, caught where it parses (the job does nothing more)."""
    caught = []

    def catch(self, args=None, namespace=None):
        caught.append(self)
        raise SystemExit(0)

    monkeypatch.setattr(argparse.ArgumentParser, "parse_args", catch)
    with pytest.raises(SystemExit):
        cli.main([job])
    (parser,) = caught
    return parser


JOBS = sorted(cli.JOBS)
"""Every job: each builds its parser with ``cli_support.job_parser``."""


@pytest.mark.parametrize("job", JOBS)
def test_every_job_says_its_name_and_its_defaults(job, monkeypatch, capsys):
    """The usage line names the job; every option with a default worth saying says it in its help."""
    parser = _job_parser(job, monkeypatch)
    assert parser.prog == f"ocean-warp {job}"
    assert parser.format_usage().startswith(f"usage: ocean-warp {job} ")
    help_text = parser.format_help()
    assert "(default: None)" not in help_text and "(default: False)" not in help_text
    formatter = parser.formatter_class(prog=parser.prog)
    for action in parser._actions:
        default = action.default
        if default in (None, argparse.SUPPRESS, []) or action.nargs == 0:
            continue
        assert "default" in formatter._get_help_string(action), (job, action.option_strings)


@pytest.mark.parametrize("job, option, shown", [
    ("ocean", "--resolution", "(default: 256)"), ("polar", "--angle-step", "(default: 15.0)"),
    ("polar", "--wind-speeds", "(default: 4 7 10)"), ("drop-hulls", "--boats-per-shape", "(default: 8)"),
    ("train", "--seed", "(default: 0)"), ("eval", "--runs", "(default 20)"), ("demo", "--boats", "(default: 16)"),
    ("export-usd", "--playback-fps", "(default: 24.0)"), ("render", "--fps", "(default: 10)"),
])
def test_help_shows_the_default(job, option, shown, capsys):
    with pytest.raises(SystemExit) as exit_info:
        cli.main([job, "--help"])
    assert exit_info.value.code == 0
    text = " ".join(capsys.readouterr().out.split())  # argparse wraps lines
    assert text.startswith(f"usage: ocean-warp {job} ")
    assert option in text and shown in text


def test_help_formatter_leaves_out_defaults_that_say_nothing():
    parser = argparse.ArgumentParser(prog="ocean-warp x", formatter_class=HelpFormatter)
    parser.add_argument("--speed", type=float, default=3.5, help="speed [m/s]")
    parser.add_argument("--name", default=None, help="a name")
    parser.add_argument("--fast", action="store_true", help="go fast")
    parser.add_argument("--set", action="append", default=[], help="repeatable")
    parser.add_argument("--limit", default=7, help="limit (default: the task's)")
    text = " ".join(parser.format_help().split())
    assert "speed [m/s] (default: 3.5)" in text
    assert "a name (default" not in text and "go fast (default" not in text and "repeatable (default" not in text
    assert "(default: the task's)" in text and "(default: 7)" not in text


BAD_VALUES = [
    (["ocean", "--resolution", "100"], "--resolution must be a power of two from 16 to 2048, got 100"),
    (["ocean", "--hs", "-1"], "--hs must be a number from 0 to 5 [m] (the wave and boat models hold for seas a small "
     "craft sails), got -1.0"),
    (["ocean", "--tp", "0"], "--tp must be a number > 0 [s]"),
    (["ocean", "--seconds", "nan"], "--seconds must be a number > 0 [s], got nan"),
    (["polar", "--wind-speeds", "7", "-3"], "--wind-speeds must be numbers > 0 [m/s], got -3.0"),
    (["polar", "--angle-step", "0"], "--angle-step must be in (0, 180] [deg], got 0.0"),
    (["polar", "--sheet-step", "91"], "--sheet-step must be in (0, 90] [deg], got 91.0"),
    (["polar", "--settle", "-1"], "--settle must be a number >= 0 [s]"),
    (["drop-hulls", "--boats-per-shape", "0"], "--boats-per-shape must be a whole number from 1 to 4096"),
    (["drop-hulls", "--boats-per-shape", "1000000000"], "--boats-per-shape must be a whole number from 1 to 4096"),
    (["drop-hulls", "--seconds", "0"], "--seconds must be a number of seconds >= one step"),
    (["train", "--num-envs", "0"], "--num-envs must be a whole number >= 1, got 0"),
    (["train", "--iterations", "-2"], "--iterations must be a whole number >= 1, got -2"),
    (["eval", "--runs", "0"], "--runs must be a whole number >= 1, got 0"),
    (["render", "--width", "0"], "RenderConfig.width must be an integer in [2, 8192], got 0"),
] + [([job, "--device", "tpu"], "--device must be \"auto\" (the first GPU where Warp sees one, else the CPU), "
                                "\"cpu\", \"cuda\" (the first GPU) or \"cuda:N\", got 'tpu'")
     for job in ("ocean", "polar", "drop-hulls", "train", "eval", "demo", "render")] + [
    ([job, "--device", "cuda:99"], "--device 'cuda:99': ") for job in ("ocean", "polar", "drop-hulls", "train",
                                                                      "eval", "demo", "render")]


@pytest.mark.parametrize("argv, message", BAD_VALUES)
def test_bad_values_are_one_line_errors(argv, message, tmp_path, capsys):
    """Exit status 2 and one line, ``ocean-warp <job>: error: ...``, before anything is written."""
    out = tmp_path / "out"
    with pytest.raises(SystemExit) as exit_info:
        cli.main(argv + ["--out" if argv[0] != "train" else "--runs-root", str(out)])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"ocean-warp {argv[0]}: error: ") and message in err[0], err
    assert "workers" not in err[0]  # train --num-envs 0 once blamed --workers
    assert not out.exists()


@pytest.mark.skipif(HAS_GPU, reason="needs a machine without a GPU")
@pytest.mark.parametrize("job", ["ocean", "polar", "drop-hulls", "train", "eval", "demo", "render"])
def test_cuda_without_a_gpu_is_a_one_line_error(job, capsys):
    with pytest.raises(SystemExit) as exit_info:
        cli.main([job, "--device", "cuda"])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"ocean-warp {job}: error: --device 'cuda': this machine has no usable GPU "
                   f"({'Warp sees no CUDA device' if cuda_driver_loadable() else 'no NVIDIA driver loads here'}); "
                   "use cpu"]


def test_resolve_device():
    assert resolve_device("cpu") == "cpu"
    assert resolve_device(None) == resolve_device("auto") == ("cuda:0" if HAS_GPU else "cpu")
    if HAS_GPU:
        assert resolve_device("cuda") == resolve_device(" cuda:0") == "cuda:0"
    for bad in ("gpu", "cuda:", "cuda:-1", "cuda:x", "CPU", ""):
        with pytest.raises(ValueError,
                           match=r'^device must be "auto" \(.*\), "cpu", "cuda" \(the first GPU\) or "cuda:N"'):
            resolve_device(bad)
    with pytest.raises(ValueError, match=r"^--device 'cuda:99': "):
        resolve_device("cuda:99", name="--device")


def test_stderr_without_drops_only_the_no_driver_line(capfd):
    """What C code writes to descriptor 2 comes back, less the lines that begin with the prefix; also when
    the block raises."""
    real = b"Warp CUDA error: Failed to get driver entry point 'cuInit'\n"
    with stderr_without(NO_DRIVER_WARNING):
        os.write(2, NO_DRIVER_WARNING.encode() + b" GPU execution will not be available.\n" + real)
    assert capfd.readouterr().err == real.decode()
    with pytest.raises(RuntimeError, match="boom"):
        with stderr_without(NO_DRIVER_WARNING):
            os.write(2, b"before the error\n")
            raise RuntimeError("boom")
    assert capfd.readouterr().err == "before the error\n"


def _run(*argv: str, cwd) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, *argv], capture_output=True, text=True, timeout=300, cwd=cwd)


def test_no_driver_warning_on_the_command_line(tmp_path):
    """A tiny job and an error, as a person runs them: no Warp no-driver warning on stderr. Where no driver
    loads, Warp started plainly does print it (so the check can fail)."""
    if not cuda_driver_loadable():
        plain = _run("-c", "import warp; warp.config.log_level = 30; warp.init()", cwd=tmp_path)
        assert NO_DRIVER_WARNING in plain.stderr
    job = _run("-m", "ocean_warp.cli", "ocean", "--device", "cpu", "--resolution", "16", "--seconds", "1",
               "--out", str(tmp_path / "ocean"), cwd=tmp_path)
    assert job.returncode == 0, job.stderr
    assert "wrote" in job.stdout and "NVIDIA" not in job.stderr and "Warp CUDA" not in job.stderr, job.stderr
    error = _run("-m", "ocean_warp.cli", "drop-hulls", "--device", "cuda:99", cwd=tmp_path)
    lines = error.stderr.strip().splitlines()
    assert error.returncode == 2 and len(lines) == 1, error.stderr
    assert lines[0].startswith("ocean-warp drop-hulls: error: --device 'cuda:99': ")


def test_plural():
    assert plural(1, "run") == "1 run" and plural(0, "run") == "0 runs" and plural(20, "run") == "20 runs"
    assert plural(1, "E-Boat") == "1 E-Boat" and plural(2, "child", "children") == "2 children"


@pytest.mark.parametrize("job", ["ocean", "polar", "drop-hulls"])
def test_an_out_folder_that_cannot_be_made_is_a_one_line_error(job, tmp_path, capsys):
    """``--out`` below a file: exit status 2 and one line naming --out and the folder, nothing made."""
    blocker = tmp_path / "a_file"
    blocker.write_text("not a folder")
    out = blocker / "sub"
    with pytest.raises(SystemExit) as exit_info:
        cli.main([job, "--out", str(out)])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"ocean-warp {job}: error: --out {out}: "), err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file"]
