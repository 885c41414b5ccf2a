"""``ocean-warp render`` (ocean_warp.envs.apps.render) end to end on tiny runs on the CPU: a GIF and an MP4 hold
duration x fps frames that change; paths that cannot be written, a missing encoder and a failing encoder
are one-line errors that leave no file and no temporary file behind."""

from __future__ import annotations

import dataclasses
import importlib.util
import os

import numpy as np
import pytest
from PIL import Image

from ocean_warp import cli
from ocean_warp.envs import AvoidConfig, SailingEnv, WaypointPlusConfig
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
    ("a_file/inside/fleet.gif", "a_file is a file, not a folder"),  # a folder that cannot be made
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


# --- a task with obstacles: the camera casts through the env's own obstacle scene --------------------

def pile_close_up(env):
    """(eye, target, row) [m]: 3 m from the surface of environment 0's first pile, 1 m above the still
    water, looking level at the pile's axis; its row in the env's obstacle scene."""
    table = env.buffers.obstacles.cpu().numpy()[0].astype(np.float64)
    piles = np.flatnonzero(table[:, 3] == 2)
    assert piles.size, "seed 0 draws no pile in environment 0: pick another seed"
    k = int(piles[0])
    x, y, radius, _ = table[k]
    origin = env.origin.numpy()[0].astype(np.float64)
    centre = origin[:2] + (x, y)
    start = env.buffers.position.cpu().numpy()[0, :2].astype(np.float64)
    toward = (start - centre) / np.linalg.norm(start - centre)
    eye = (*(centre + (radius + 3.0) * toward), 1.0)
    return eye, (*centre, 1.0), int(env.obstacles.scene.first_free_slot[0]) + k


def test_a_frame_of_an_avoid_task_shows_its_obstacles(tmp_path, monkeypatch):
    """``render_scene`` of EBoatAvoid-v0 is the env's obstacle scene: a ray and the camera's centre pixel from
    3 m before a pile hit it at 3 m (an object hit), where the fleet scene of the other tasks sees nothing
    there. ``render_run`` renders through it: its frame from that view (the fixed camera placed there) shows
    the pile as the camera does (not the open view of the fleet scene)."""
    from ocean_warp.envs import SailingEnv
    from ocean_warp.kernels.ray_cast import HIT_OBJECT
    from ocean_warp.perception.camera import ViewCamera
    from ocean_warp.perception.scene import Scene

    config = render.RenderConfig(task_id="ocean_warp/EBoatAvoid-v0", boats=2, hull="points", camera="fixed",
                                 width=33, height=33, field_of_view=40.0, duration=1.0, frames_per_second=1)
    assert config.task_id == "EBoatAvoid-v0"
    env = SailingEnv(config.task(time_limit=1.0, loop_period=None, device="cpu"), 2, device="cpu", seed=0)
    scene, course = render.render_scene(env)
    assert scene is env.obstacles.scene
    eye, target, row = pile_close_up(env)
    hit = scene.cast([eye], [np.subtract(target, eye)], envs=[0])
    assert hit["kind"][0] == HIT_OBJECT and hit["index"][0] == row
    assert hit["distance"][0] == pytest.approx(3.0, abs=1e-3)
    pictures = {}
    for name, seen in (("obstacles", scene), ("fleet", Scene.for_simulator(env.simulator, vessel=env.vessel))):
        camera = ViewCamera(seen, 33, 33, np.radians(40.0), env=0)
        camera.look_at(eye, target)
        camera.render()
        pictures[name] = (camera.depth_image()[16, 16], camera.image()[16, 16].astype(int))
    assert pictures["obstacles"][0] == pytest.approx(3.0, abs=1e-3)
    assert not pictures["fleet"][0] < 10.0  # open water: the horizon, far away
    monkeypatch.setattr(render, "overlook", lambda task, points=None: (eye, target))
    result = render.render_run(config, tmp_path / "pile.gif", progress=False, controller=render.AutopilotController())
    assert result.frames == 1
    frame = gif_frames(tmp_path / "pile.gif")[0][16, 16].astype(int)
    assert np.abs(frame - pictures["obstacles"][1]).max() <= 12  # the pile (a GIF's palette: a few levels off)
    assert np.abs(frame - pictures["fleet"][1]).max() > 30


def test_a_gif_of_an_avoid_task(tmp_path, capsys):
    """``render --task EBoatAvoid-v0`` end to end: every frame, and the autopilot sailing every boat where the
    task has no shipped policy (said in one line)."""
    from ocean_warp.envs.training import policies

    out = tmp_path / "avoid.gif"
    cli.main(["render", "--task", "EBoatAvoid-v0", "--out", str(out), *TINY])
    assert len(gif_frames(out)) == 2 * 4
    said = "no policy is shipped for EBoatAvoid-v0" in capsys.readouterr().out
    assert said == ("EBoatAvoid-v0" not in policies.SHIPPED_POLICIES)


def test_an_unknown_task_is_a_one_line_error(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["render", "--task", "EBoatNowhere-v0", "--out", str(tmp_path / "v.gif"), *TINY])
    line = one_error_line(capsys, 2, exit_info)
    assert "--task: unknown task id 'EBoatNowhere-v0'; known: EBoatWaypoint-v0" in line
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("task", [WaypointPlusConfig, AvoidConfig])
def test_the_rendered_boats_carry_their_reef(task):
    """``render_scene`` (the fleet's scene, or the avoidance task's obstacle scene) reads every boat's reef level
    from the simulator's state (the same array, so a reset's new levels are drawn at once) with the boat's table
    of sail scales, sqrt(A_k / 3.188)."""
    env = SailingEnv(dataclasses.replace(task(), episode_time=4.0), 3, device="cpu", seed=2)
    scene, _ = render.render_scene(env)
    assert scene.view.reef_level.ptr == env.simulator.state.reef_level.ptr
    np.testing.assert_allclose(scene.view.reef_scale.numpy(), np.sqrt(np.array([3.188, 2.0, 1.15]) / 3.188),
                               rtol=1e-6)


# --- any vessel: a frame of VRX's WAM-Vs ------------------------------------------------------------------

def project(point, eye, target, width: int, height: int, fov: float) -> tuple[int, int]:
    """(row, column) of the pixel that sees ``point`` from a level pinhole camera at ``eye`` looking at ``target``
    (horizontal field of view ``fov`` [rad], image x right and rows down), numpy."""
    forward = np.subtract(target, eye) / np.linalg.norm(np.subtract(target, eye))
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    offset = np.subtract(point, eye)
    depth = offset @ forward
    focal = 0.5 * width / np.tan(0.5 * fov)
    return (int(round(0.5 * height - 0.5 - focal * (offset @ up) / depth)),
            int(round(0.5 * width - 0.5 + focal * (offset @ right) / depth)))


def test_a_frame_of_two_wamvs_shows_them_where_they_are():
    """The fleet scene of a VrxEnv of 2 WAM-Vs: from 12 m astern and 7 m above each boat, the pixels that see the
    tops of its pontoons (projected with numpy from the env's buffers) differ from the same view without boats,
    and see something at the distance of the pontoon; far from the boats the two pictures agree."""
    from ocean_warp.envs.vrx import VrxEnv, VrxTaskConfig
    from ocean_warp.frames import quaternion_from_roll_pitch_yaw
    from ocean_warp.perception.camera import ViewCamera
    from ocean_warp.perception.scene import Scene
    from ocean_warp.wamv import Wamv

    vessel = Wamv()
    env = VrxEnv(VrxTaskConfig(kind="wayfinding", goals=2, vessel=vessel), 2, device="cpu", seed=3)
    scene = render.fleet_scene(env)
    empty = Scene.for_vessel(vessel, env.simulator, [[]], envs=1, boat_env=np.full(2, -1))
    width, height, fov = 48, 36, np.radians(50.0)
    boat = vessel.config.boat
    position = env.buffers.position.cpu().numpy().astype(np.float64)
    orientation = env.buffers.orientation.cpu().numpy().astype(np.float64)
    for i in range(2):
        x, y, z, w = orientation[i]
        heading = np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
        astern = np.array([np.cos(heading), np.sin(heading), 0.0])
        eye = position[i] - 12.0 * astern + (0.0, 0.0, 7.0)
        pictures = []
        for seen in (scene, empty):
            camera = ViewCamera(seen, width, height, fov, env=0)
            camera.look_at(eye, position[i])
            camera.render()
            pictures.append((camera.image().astype(int), camera.depth_image()))
        (boats, boats_depth), (water, _) = pictures
        level = quaternion_from_roll_pitch_yaw(np.array([[0.0, 0.0, heading]]))[0]
        assert np.allclose(np.abs(level @ orientation[i]), 1.0, atol=0.05)  # the boat floats nearly level
        for side in (1.0, -1.0):
            top = np.array([boat.pontoon_center_x, side * 0.5 * boat.pontoon_spacing, boat.pontoon_radius])
            top = position[i] + top[0] * astern + top[1] * np.array([-astern[1], astern[0], 0.0]) + (0, 0, top[2])
            row, column = project(top, eye, position[i], width, height, fov)
            assert np.abs(boats[row, column] - water[row, column]).max() > 20, (i, side)
            window = (slice(row - 1, row + 2), slice(column - 1, column + 2))  # a pontoon is about a pixel wide
            assert np.min(np.abs(boats_depth[window] - np.linalg.norm(top - eye))) < 0.5
        assert np.array_equal(boats[0, :], water[0, :])  # the top row: sky and far sea, no boat


def test_render_sails_a_vrx_task_and_refuses_fractional_frames(tmp_path, capsys):
    """``ocean-warp render --task WamvWayfinding-v0``: 1 s at 10 frames a second (5 in each 0.5 s decision) of
    the WAM-Vs under their shipped policy; 1 frame a second cannot split a 0.5 s decision: one line, status 2."""
    out = tmp_path / "wamv.gif"
    assert render.main(["--task", "WamvWayfinding-v0", "--boats", "2", "--duration", "1", "--width", "32",
                        "--height", "24", "--out", str(out), "--device", "cpu", "--no-progress"]) == 0
    assert Image.open(out).n_frames == 10
    assert render.main(["--task", "WamvWayfinding-v0", "--duration", "1", "--fps", "1", "--width", "32", "--height",
                        "24", "--out", str(tmp_path / "one.gif"), "--device", "cpu", "--no-progress"]) == 2
    assert "0.5 s decisions" in capsys.readouterr().err
