"""``ocean-warp render`` (ocean_warp.envs.apps.render) end to end on tiny runs on the CPU: a GIF and an MP4 hold
duration x fps frames that change; paths that cannot be written, a missing encoder and a failing encoder
are one-line errors that leave no file and no temporary file behind."""

from __future__ import annotations

import importlib.util
import os

import numpy as np
import pytest
from PIL import Image

from ocean_warp import cli
from ocean_warp.envs.apps import render

TINY = ["--width", "64", "--height", "48", "--duration", "2", "--fps", "4", "--boats", "3", "--no-progress"]
"""3 boats, 2 s at 4 frames a second: 8 frames of 64 x 48."""
HAS_FFMPEG = importlib.util.find_spec("imageio_ffmpeg") is not None


def gif_frames(path) -> list[np.ndarray]:
    with Image.open(path) as image:
        frames = []
        for index in range(image.n_frames):
            image.seek(index)
            frames.append(np.asarray(image.convert("RGB")))
        return frames


def one_error_line(capsys, code: int, exit_info) -> str:
    assert exit_info.value.code == code
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1, lines
    return lines[0]


def test_a_gif_of_a_tiny_run_holds_every_frame(tmp_path, capsys):
    out = tmp_path / "fleet.gif"
    cli.main(["render", "--out", str(out), *TINY])
    frames = gif_frames(out)
    assert len(frames) == 2 * 4 and frames[0].shape == (48, 64, 3)
    assert not np.array_equal(frames[0], frames[-1])
    assert sum(not np.array_equal(a, b) for a, b in zip(frames, frames[1:])) >= 6  # the chase camera moves on
    assert sorted(os.listdir(tmp_path)) == ["fleet.gif"]  # no temporary file left
    assert f"wrote {out}" in capsys.readouterr().out


@pytest.mark.skipif(not HAS_FFMPEG, reason="imageio-ffmpeg is not installed")
def test_an_mp4_of_a_tiny_run_from_the_fixed_camera(tmp_path):
    import imageio_ffmpeg

    out = tmp_path / "new" / "fleet.mp4"  # its folder is made
    cli.main(["render", "--out", str(out), "--camera", "fixed", "--autopilot", *TINY])
    frames, seconds = imageio_ffmpeg.count_frames_and_secs(str(out))
    assert frames == 8 and seconds == pytest.approx(2.0, abs=0.01)
    reader = imageio_ffmpeg.read_frames(str(out))
    meta = next(reader)
    assert tuple(meta["size"]) == (64, 48)
    pictures = [np.frombuffer(frame, np.uint8).reshape(48, 64, 3) for frame in reader]
    assert len(pictures) == 8 and not np.array_equal(pictures[0], pictures[-1])
    assert sorted(os.listdir(out.parent)) == ["fleet.mp4"]


@pytest.mark.parametrize("name, message", [
    (".", "is a folder"),
    ("fleet.avi", "--out must end in .mp4 or .gif"),
    ("fleet", "--out must end in .mp4 or .gif"),
    ("a_file/inside/fleet.gif", "a_file/inside: Not a directory"),  # a folder that cannot be made
])
def test_an_unusable_out_is_a_one_line_error(tmp_path, capsys, name, message):
    (tmp_path / "a_file").write_text("not a folder")
    before = sorted(os.listdir(tmp_path))
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["render", "--out", str(tmp_path / name), *TINY])
    line = one_error_line(capsys, 2, exit_info)
    assert line.startswith("ocean-warp render: error: ") and message in line, line
    assert sorted(os.listdir(tmp_path)) == before


@pytest.mark.parametrize("option, value, message", [
    ("--fps", "3", "frames_per_second must divide the 20 physics steps"),
    ("--width", "0", "RenderConfig.width"),
    ("--duration", "0.5", "RenderConfig.duration"),
    ("--fov", "180", "RenderConfig.field_of_view"),
])
def test_a_bad_value_is_a_one_line_error(tmp_path, capsys, option, value, message):
    arguments = dict(zip(TINY[:-1:2], TINY[1::2])) | {option: value}
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["render", "--out", str(tmp_path / "v.gif"), "--no-progress",
                  *[item for pair in arguments.items() for item in pair]])
    assert message in one_error_line(capsys, 2, exit_info)
    assert os.listdir(tmp_path) == []


def test_mp4_needs_even_sizes_and_imageio_ffmpeg(tmp_path, capsys, monkeypatch):
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["render", "--out", str(tmp_path / "v.mp4"), *TINY, "--width", "63"])
    assert "must be even for MP4" in one_error_line(capsys, 2, exit_info)
    real_find_spec = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *rest: None if name == "imageio_ffmpeg" else real_find_spec(name, *rest))
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["render", "--out", str(tmp_path / "v.mp4"), *TINY])
    assert 'pip install "ocean-warp[video]"' in one_error_line(capsys, 2, exit_info)
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("suffix", [".gif", ".mp4"])
def test_an_error_while_encoding_leaves_nothing(tmp_path, capsys, monkeypatch, suffix):
    """The encoder fails at the fifth frame (as a full disk would): one line, exit status 1, and neither the
    video nor its temporary file is left; an older video at that path stays as it was."""
    if suffix == ".mp4" and not HAS_FFMPEG:
        pytest.skip("imageio-ffmpeg is not installed")
    writer = render._Mp4Writer if suffix == ".mp4" else render._GifWriter
    real_write, written = writer.write, []

    def failing_write(self, frame):
        if len(written) == 4:
            raise OSError(28, "No space left on device")
        written.append(1)
        real_write(self, frame)

    monkeypatch.setattr(writer, "write", failing_write)
    out = tmp_path / f"fleet{suffix}"
    out.write_bytes(b"an older video")
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["render", "--out", str(out), *TINY])
    assert "No space left on device" in one_error_line(capsys, 1, exit_info)
    assert sorted(os.listdir(tmp_path)) == [out.name] and out.read_bytes() == b"an older video"


def test_the_fixed_camera_overlooks_the_course():
    """South of the BCDACA course (x 0 ... 141 m, y -71 ... 71 m), above it, looking at its centre."""
    task = render.RenderConfig().task(time_limit=10.0, loop_period=None, device="cpu")
    eye, target = render.overlook(task)
    assert target == pytest.approx((70.71, 0.0, 0.0), abs=1e-6)
    assert eye[1] < -71.0 - 50.0 and eye[2] > 30.0
    assert len(render.route_buoys(task)) == 4  # A, B, C and D
