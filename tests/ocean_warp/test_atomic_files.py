"""atomic_output: the target changes in one rename, keeps the old file on failure, and gets a normal mode."""

from __future__ import annotations

import os
import stat

import pytest

from ocean_warp.atomic_files import atomic_output


def test_replaces_in_one_rename_with_the_users_mode(tmp_path):
    target = tmp_path / "table.csv"
    target.write_text("old\n")
    previous = os.umask(0o022)
    try:
        with atomic_output(target) as temporary:
            assert os.path.dirname(temporary) == str(tmp_path) and temporary.endswith(".csv")
            with open(temporary, "w") as stream:
                stream.write("new\n")
            assert target.read_text() == "old\n"  # untouched until the rename
    finally:
        os.umask(previous)
    assert target.read_text() == "new\n"
    assert stat.S_IMODE(target.stat().st_mode) == 0o644  # not mkstemp's private 0600
    assert sorted(os.listdir(tmp_path)) == ["table.csv"]


def test_a_failure_keeps_the_old_file_and_leaves_no_temporary(tmp_path):
    target = tmp_path / "model.pt"
    target.write_bytes(b"saved")
    with pytest.raises(RuntimeError, match="interrupted"):
        with atomic_output(target) as temporary:
            with open(temporary, "wb") as stream:
                stream.write(b"half")
            raise RuntimeError("interrupted")
    assert target.read_bytes() == b"saved"
    assert os.listdir(tmp_path) == ["model.pt"]
