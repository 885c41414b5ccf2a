"""How ``ocean-warp`` starts: every job's parser builds without the heavy libraries (so ``--help`` and typos
answer at once), short help with ``--help-long`` beside it, the job list and ``--version``, output paths
checked before any work, Ctrl-C during the start-up imports, and train's ``--torch-threads``."""

from __future__ import annotations

import importlib
import importlib.util
import os
import subprocess
import sys
import textwrap

import pytest

from ocean_warp import cli

HEAVY = ("torch", "warp", "pxr", "matplotlib", "trimesh", "rsl_rl")
"""What building a parser must not import."""


def test_every_parser_builds_without_the_heavy_libraries():
    """In a fresh interpreter: each job's options module builds and parses its defaults, and none of the heavy
    libraries has been imported."""
    script = textwrap.dedent(f"""
        import importlib, sys
        from ocean_warp.cli import JOBS
        for job, (_, options, _) in JOBS.items():
            importlib.import_module(options).parser().parse_args([])
        print(",".join(name for name in {HEAVY!r} if name in sys.modules))
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "", done.stdout


def test_help_and_a_typo_load_no_heavy_library():
    """The command itself: ``ocean-warp eval --help`` and a mistyped option exit before Warp or torch load."""
    script = textwrap.dedent(f"""
        import sys
        from ocean_warp import cli
        for argv in (["eval", "--help"], ["train", "--tsak", "x"]):
            try:
                cli.main(argv)
            except SystemExit as done:
                print("exit", done.code, file=sys.stderr)
        print("loaded:" + ",".join(name for name in {HEAVY!r} if name in sys.modules), file=sys.stderr)
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.stdout.startswith("usage: ocean-warp eval ")
    assert done.stderr.splitlines() == ["exit 0", "ocean-warp train: error: unrecognized arguments: --tsak x",
                                        "exit 2", "loaded:"], done.stderr


@pytest.mark.parametrize("job", sorted(cli.JOBS))
def test_help_is_short_and_help_long_is_plain_text(job, capsys):
    """``--help``: at most three sentences before the options; ``--help-long``: the module's docstring without
    RST markup."""
    with pytest.raises(SystemExit) as exit_info:
        cli.main([job, "--help"])
    assert exit_info.value.code == 0
    text = capsys.readouterr().out
    description = text.split("\n\n")[1]
    assert not description.startswith("options:")
    assert description.count(". ") + description.rstrip().endswith(".") <= 3, description
    with pytest.raises(SystemExit) as exit_info:
        cli.main([job, "--help-long"])
    assert exit_info.value.code == 0
    long_text = capsys.readouterr().out
    assert len(long_text.splitlines()) > 3
    assert "``" not in long_text and ":class:" not in long_text and ":func:" not in long_text
    assert "runs/" not in long_text.replace("out/train/", "") and "out/train/policy.pt" not in long_text
    assert "out/train/policy.pt" not in text


def test_the_job_list_has_one_job_a_line(capsys):
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["--help"])
    assert exit_info.value.code == 0
    lines = capsys.readouterr().out.splitlines()
    for job, (_, _, summary) in cli.JOBS.items():
        assert sum(line.split()[:1] == [job] and summary in line for line in lines) == 1, job


def test_version_is_the_distributions(capsys):
    from importlib import metadata

    with pytest.raises(SystemExit) as exit_info:
        cli.main(["--version"])
    assert exit_info.value.code == 0
    assert capsys.readouterr().out.strip() == f"ocean-warp {metadata.version('ocean-warp')}"


def test_every_job_with_a_task_defaults_to_the_mission_and_auto():
    """One rule: --task EBoatMission-v0, --device auto; a prefixed task id parses like a bare one."""
    for job, (_, options, _) in cli.JOBS.items():
        args = importlib.import_module(options).parser().parse_args([])
        if hasattr(args, "task") and job != "export-policy":  # export-policy: the checkpoint's task
            assert args.task == "EBoatMission-v0", job
        if hasattr(args, "device"):
            assert args.device == "auto", job


def test_train_takes_a_prefixed_task_and_writes_under_out_train():
    from ocean_warp.envs.training.train_options import parser

    args = parser().parse_args(["--task", "ocean_warp/EBoatWaypoint-v0"])
    assert args.runs_root == os.path.join("out", "train")
    from ocean_warp.envs.registration import task_name

    assert task_name(args.task) == "EBoatWaypoint-v0"


# --- output paths, checked before any work ---------------------------------------------------------

NEEDS_PXR = pytest.mark.skipif(importlib.util.find_spec("pxr") is None, reason="export-usd needs usd-core (pxr)")

FOLDER_OUTPUTS = [("eval", "--out"), ("demo", "--out"), ("ocean", "--out"), ("polar", "--out"),
                  ("drop-hulls", "--out"), ("train", "--runs-root")]
"""Jobs that write into a folder, and the option that names it."""
FILE_OUTPUTS = [pytest.param("export-usd", "--out", "stage.usdc", marks=NEEDS_PXR), ("render", "--out", "video.gif"),
                ("export-policy", "--out", "policy.onnx")]
"""Jobs that write one file, the option that names it and a name it takes."""


def _refused(argv, capsys) -> str:
    """The one error line of ``ocean-warp argv``, which must exit with status 2."""
    with pytest.raises(SystemExit) as exit_info:
        cli.main(argv)
    assert exit_info.value.code == 2, argv
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    return err[0]


@pytest.mark.parametrize("job, option", FOLDER_OUTPUTS)
def test_a_file_where_the_output_folder_goes_is_refused(job, option, tmp_path, capsys):
    blocker = tmp_path / "a_file"
    blocker.write_text("mine")
    for path in (blocker, blocker / "sub"):
        line = _refused([job, option, str(path), "--device", "cpu"], capsys)
        assert line.startswith(f"ocean-warp {job}: error: {option} {path}: "), line
        assert "file" in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file"] and blocker.read_text() == "mine"


@pytest.mark.parametrize("job, option, name", FILE_OUTPUTS)
def test_a_folder_where_the_output_file_goes_is_refused(job, option, name, tmp_path, capsys):
    folder = tmp_path / name
    folder.mkdir()
    line = _refused([job, option, str(folder)], capsys)
    assert line.startswith(f"ocean-warp {job}: error: {option} {folder}: is a folder"), line
    blocker = tmp_path / "a_file"
    blocker.write_text("mine")
    line = _refused([job, option, str(blocker / name)], capsys)
    assert line.startswith(f"ocean-warp {job}: error: {option} {blocker / name}: "), line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file", name] and not any(folder.iterdir())


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="root writes in read-only folders")
@pytest.mark.parametrize("job, option, name", [(job, option, "results") for job, option in FOLDER_OUTPUTS]
                         + FILE_OUTPUTS)
def test_a_folder_without_write_permission_is_refused(job, option, name, tmp_path, capsys):
    locked = tmp_path / "locked"
    locked.mkdir(mode=0o500)
    try:
        line = _refused([job, option, str(locked / name), "--device", "cpu"], capsys)
        assert line.startswith(f"ocean-warp {job}: error: {option} {locked / name}: cannot write in {locked}"), line
        assert list(locked.iterdir()) == []
    finally:
        locked.chmod(0o700)


# --- Ctrl-C, train's threads -------------------------------------------------------------------------

def test_ctrl_c_while_the_job_imports_is_one_line_and_130(tmp_path, monkeypatch, capsys):
    """A KeyboardInterrupt raised while a job's module is being imported (Ctrl-C during start-up)."""
    (tmp_path / "slow_job_for_test.py").write_text("raise KeyboardInterrupt\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setitem(cli.JOBS, "eval", ("slow_job_for_test",) + cli.JOBS["eval"][1:])
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["eval"])
    assert exit_info.value.code == 130
    assert capsys.readouterr().err.strip().splitlines() == [
        "ocean-warp eval: interrupted; files written before it are complete"]


@pytest.mark.parametrize("value, message", [("0", "--torch-threads must be a whole number >= 1, got 0"),
                                            ("-1", "--torch-threads must be a whole number >= 1, got -1"),
                                            ("x", "argument --torch-threads: invalid int value: 'x'")])
def test_torch_threads_is_checked(value, message, tmp_path, capsys):
    line = _refused(["train", "--torch-threads", value, "--runs-root", str(tmp_path / "runs")], capsys)
    assert line == f"ocean-warp train: error: {message}"
    assert not (tmp_path / "runs").exists()
