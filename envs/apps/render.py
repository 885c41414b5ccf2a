"""``ocean-warp render``: a video of a fleet's run, rendered with the perception ray tracer (the camera's shading:
sky, water with Fresnel reflections, lit boats and buoys), on the CPU or a GPU.

    ocean-warp render                                            # out/render/fleet.mp4: the demo's fleet, chase camera
    ocean-warp render --out out/render/fleet.gif --width 480 --height 270 --duration 10 --camera fixed
    ocean-warp render --autopilot --boats 4 --device cuda:0 --out out/render/autopilot.mp4
    ocean-warp render --policy out/train/EBoatMission-v0/<date>_<name>/policy.pt --out out/render/policy.mp4

The run is the demo's: the fleet on the BCDACA course (or --task ID, any registered task, as ``ocean-warp
eval --task``) in a JONSWAP sea, the first --policy-share of the boats sailed by the task's shipped policy
and the rest by the classical autopilot (every boat by the autopilot on a task without a shipped policy,
said in one line; or every boat by --policy FILE, or by the --autopilot), every boat on the same water.
The route's waypoints float as buoys (on a task whose boats draw their own waypoint: each boat's first
one). On a task with obstacles (EBoatAvoid-v0, EBoatAvoidSail-v0) the camera casts through the env's own
obstacle scene (``env.obstacles.scene``): the first boat's environment, that boat among its buoys and piles
as the env draws them at every reset (the waves moving the buoys at every frame); the other boats sail
their own courses and are not in that view, nor are the waypoint buoys (the scene holds none). Refreshing
that scene at every frame also moves the buoys the env's contact sees within the decision, so a rendered
run can part from an unrendered one where a boat touches a buoy.
The camera is --camera chase (astern of and above the fleet's first boat, following it smoothly) or
fixed (a point south of the course overlooking all of it: the route, or the first boat's start, waypoint
and obstacles).

Frames are taken at --fps frames per second of simulated time, inside each decision of 1 s: after every
20 / fps of its 20 physics steps of 0.05 s, so --fps must divide 20 (1, 2, 4, 5, 10 or 20). The video
plays at --fps, in real time, and holds --duration x --fps frames (--duration rounded to whole seconds;
fewer frames if every boat's run ends first). The file is --out: .mp4 (H.264, through imageio-ffmpeg:
``pip install "ocean-warp[video]"``; even --width and --height) or .gif (Pillow; every frame is held in
memory until the end, a byte a pixel: keep GIFs small). It is written to a temporary file beside --out and
renamed onto it when complete, so a failed or interrupted run leaves no file behind.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import importlib.util
import math
import os
import sys
import time

import numpy as np
import warp as wp

from ocean_warp.atomic_files import atomic_output
from ocean_warp.cli_support import checked_device, checked_output_file, made_folder, plural, report_error
from ocean_warp.perception.camera import ViewCamera
from ocean_warp.perception.scene import Scene, SceneObject
from ocean_warp.kernels.camera_render import follow_boat

from ..decision_hook import DecisionHook
from ..env_factory import make_env
from ..evaluation.evaluate import vrx_baseline
from ..evaluation.presets import vrx_evaluation_task
from ..registration import make_task_config, task_name
from ..sailing_env import SailingEnv
from ..vrx.task_config import VrxTaskConfig
from ..evaluation import AutopilotController, FleetController, PolicyController, sail_mission, warn_other_task
from .render_options import CAMERAS, VIDEO_SUFFIXES, RenderConfig, parser as _parser  # noqa: F401 (re-exported)
from .fleet_scenario import checked_task_name, controller_observation, shipped_policy_or_none
from ..training.policy_io import load_policy

__all__ = ["RenderConfig", "RenderResult", "FrameHook", "fleet_controller", "chase_camera", "render_run", "route_buoys",
           "overlook", "render_scene", "fleet_scene", "video_path_problem", "main"]

MP4_HINT = 'MP4 needs imageio-ffmpeg: pip install "ocean-warp[video]", or write a .gif'

CHASE_BEHIND = 14.0
"""Chase camera: distance astern of the boat [m]."""
CHASE_ABOVE = 5.0
"""Chase camera: height over the boat [m]."""
CHASE_AHEAD = 6.0
"""Chase camera: it looks at a point this far before the boat, 1 m up [m]."""
CHASE_TIME_CONSTANT = 1.5
"""Chase camera: it closes 63 % of the way to where it should be in this time [s] (smooths the boat's
yawing and pitching)."""
BUOY_RADIUS = 0.75
"""[m]"""
BUOY_COLOR = (0.95, 0.72, 0.05)
VIEW_RANGE = 2000.0
"""The video camera's range [m]; the haze hides its end."""
HAZE_DISTANCE = 500.0
"""[m]"""


@dataclasses.dataclass
class RenderResult:
    """What :func:`render_run` wrote and how long it took."""

    path: str
    frames: int
    wall_s: float
    """Wall time of the run [s]: physics, rendering and encoding (start-up not)."""

    @property
    def seconds_per_frame(self) -> float:
        return self.wall_s / self.frames if self.frames else math.nan


def fleet_controller(config: RenderConfig, boats: int):
    """Who sails: the policy at ``config.policy`` (every boat), the autopilot (every boat), or the demo's
    mix of the task's shipped policy and the autopilot (the autopilot alone on a task without one)."""
    if config.policy is not None:
        return PolicyController(load_policy(config.policy))
    if config.autopilot:
        return AutopilotController()
    shipped = shipped_policy_or_none(config.task_id)
    share = config.policy_share if shipped is not None else 0.0
    policy_boats = np.arange(boats) < int(round(share * boats))
    groups = []
    if policy_boats.any():
        groups.append((PolicyController(load_policy(shipped)), policy_boats))
    if not policy_boats.all():
        groups.append((AutopilotController(), ~policy_boats))
    return FleetController(groups, name="fleet")


def vrx_controller(config: RenderConfig, task):
    """Who sails one of VRX's tasks: the policy at ``config.policy``, the task's classical baseline
    (``config.autopilot``), or its shipped policy (the baseline where none is shipped)."""
    if config.policy is not None:
        return PolicyController(load_policy(config.policy))
    shipped = None if config.autopilot else shipped_policy_or_none(config.task_id)
    return vrx_baseline(task) if shipped is None else PolicyController(load_policy(shipped))


def _course_points(task, waypoints=None) -> np.ndarray:
    """(K, 2) the start and every distinct waypoint [m]: of the task's route, or ``waypoints`` (P, 2) [m]
    where given (the waypoints a task's boats drew)."""
    route = task.route if waypoints is None else np.asarray(waypoints, dtype=np.float64).reshape(-1, 2)
    if route is None:
        raise ValueError("render: a task without a fixed route needs the waypoints its boats drew")
    points = [tuple(task.start_point)] + [tuple(point) for point in route]
    return np.unique(np.round(np.array(points, dtype=np.float64), 6), axis=0)


def route_buoys(task, waypoints=None) -> list[SceneObject]:
    """A floating buoy on the start and each waypoint of ``task``'s route, or of ``waypoints`` (P, 2) [m]
    where given (a task whose boats draw their own)."""
    return [SceneObject.buoy(point, radius=BUOY_RADIUS, color=BUOY_COLOR)
            for point in _course_points(task, waypoints)]


def overlook(task, points=None) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """(eye, target) [m] of the fixed camera: south of the course, high enough to see all of it with a
    60 degree field of view, looking at its centre. The course: the start and the task's route, or
    ``points`` (P, 2) [m] where given."""
    points = _course_points(task) if points is None else np.asarray(points, dtype=np.float64).reshape(-1, 2)
    low, high = points.min(axis=0), points.max(axis=0)
    centre = 0.5 * (low + high)
    reach = float(np.max(high - low)) * 0.5 + 20.0
    eye = (float(centre[0]), float(centre[1] - 1.6 * reach), 0.6 * reach)
    return eye, (float(centre[0]), float(centre[1]), 0.0)


class FrameHook(DecisionHook):
    """Renders ``frames_per_decision`` frames of ``view`` inside every decision (after physics steps S/F,
    2 S/F, ..., S) into :attr:`frames`; before each it refreshes the scene and lets ``aim`` (launches, or
    None) move the camera. Launches only: part of the decision's graph."""

    def __init__(self, env: SailingEnv, view: ViewCamera, frames_per_decision: int, aim=None):
        steps = env.steps_per_decision
        if steps % frames_per_decision:
            raise ValueError(f"FrameHook: frames_per_decision must divide the {steps} physics steps of a decision, "
                             f"got {frames_per_decision}")
        self.view, self.aim = view, aim
        self.every = steps // frames_per_decision
        config = view.config
        self.frames = wp.zeros((frames_per_decision, config.height, config.width, 3), dtype=wp.uint8,
                               device=view.device)
        """(F, H, W, 3) uint8 sRGB: the last decision's frames."""
        self._pixels = config.height * config.width * 3

    def after_physics_step(self, env: SailingEnv, step: int) -> None:
        if (step + 1) % self.every:
            return
        self.view.scene.refresh()
        if self.aim is not None:
            self.aim()
        self.view.render()
        slot = (step + 1) // self.every - 1
        wp.copy(self.frames, self.view.rgb_array, dest_offset=slot * self._pixels, count=self._pixels)


def chase_camera(env: SailingEnv, view: ViewCamera, frame_period: float):
    """A function that launches the chase camera's move (``camera_render.follow_boat``): ``view`` after the
    fleet's first boat, smoothed over :data:`CHASE_TIME_CONSTANT` at one call every ``frame_period`` [s]."""
    state, primed = env.simulator.state, wp.zeros(1, dtype=int, device=view.device)
    smoothing = 1.0 - math.exp(-frame_period / CHASE_TIME_CONSTANT)

    def aim() -> None:
        wp.launch(follow_boat, dim=1, device=view.device,
                  inputs=[state.position, state.orientation, 0, CHASE_BEHIND, CHASE_ABOVE, CHASE_AHEAD, smoothing,
                          primed], outputs=[view.eye, view.target])

    return aim


class _Mp4Writer:
    """H.264 frames into an MP4 through imageio-ffmpeg."""

    def __init__(self, path: str, width: int, height: int, fps: int):
        import imageio_ffmpeg

        self._frames = imageio_ffmpeg.write_frames(path, (width, height), fps=fps, codec="libx264", quality=8,
                                                   macro_block_size=2, ffmpeg_log_level="error")
        self._frames.send(None)

    def write(self, frame: np.ndarray) -> None:
        self._frames.send(np.ascontiguousarray(frame))

    def close(self) -> None:
        self._frames.close()

    abort = close
    """ffmpeg stops either way; the caller removes the file."""


class _GifWriter:
    """Frames (each to its own 256-colour palette) held until :meth:`close` writes the looping GIF."""

    def __init__(self, path: str, width: int, height: int, fps: int):
        self.path, self.fps, self._frames = path, fps, []

    def write(self, frame: np.ndarray) -> None:
        from PIL import Image

        self._frames.append(Image.fromarray(frame).quantize(256))

    def close(self) -> None:
        if self._frames:
            first, *rest = self._frames
            first.save(self.path, save_all=True, append_images=rest, duration=1000.0 / self.fps, loop=0)
        self._frames = []

    def abort(self) -> None:
        self._frames = []


@contextlib.contextmanager
def _video(path: str, width: int, height: int, fps: int):
    """A writer of ``path`` (its suffix picks MP4 or GIF), written atomically: the file appears when the block
    ends without an error; on an error nothing is left."""
    writer_type = _Mp4Writer if path.lower().endswith(".mp4") else _GifWriter
    with atomic_output(path) as temporary:
        writer = writer_type(temporary, width, height, fps)
        try:
            yield writer
        except BaseException:
            writer.abort()
            raise
        writer.close()


def fleet_scene(env, objects=()) -> Scene:
    """Every boat of ``env`` (a ``SailingEnv``, a ``VrxEnv``: any env with a ``vessel`` and its ``simulator``) in
    one environment, drawn with the vessel's parts at their joints, with ``objects`` placed from the world
    origin: what a free camera (``ViewCamera``) over the whole fleet sees."""
    return Scene.for_simulator(env.simulator, objects, vessel=env.vessel)


def render_scene(env: SailingEnv) -> tuple[Scene, np.ndarray]:
    """What the camera sees of ``env`` (just reset: its first episodes), and the course the fixed camera
    overlooks, (P, 2) world [m]. On a task with obstacles: the env's own obstacle scene
    (``env.obstacles.scene``, the camera in environment 0: the first boat among its buoys and piles), the
    course the first boat's start, waypoints and obstacles. Otherwise a scene of the whole fleet in one
    environment with a buoy on the start and each waypoint (the task's route, or every boat's first
    waypoint), the course those points."""
    task = env.task
    origins = env.origin.numpy()[:, :2].astype(np.float64)
    route = env.buffers.route.cpu().numpy()[:, :, :2].astype(np.float64) + origins[:, None, :]
    course = env.obstacles
    if course is not None and course.slots > 0:
        table = env.buffers.obstacles.cpu().numpy()[0].astype(np.float64)
        table = table[table[:, 3] != 0]
        start = env.buffers.position.cpu().numpy()[0, :2].astype(np.float64)
        corners = np.concatenate([table[:, :2] - table[:, 2:3], table[:, :2] + table[:, 2:3]]) + origins[0]
        return course.scene, np.concatenate([start[None, :], route[0], corners])
    waypoints = None if task.route is not None else route.reshape(-1, 2)
    return fleet_scene(env, route_buoys(task, waypoints)), _course_points(task, waypoints)


def render_run(config: RenderConfig, out: str | os.PathLike, *, device: str = "cpu", progress: bool = True,
               controller=None) -> RenderResult:
    """Sail ``config``'s run and write its video to ``out`` (.mp4 or .gif); ``controller``: who sails (None:
    :func:`fleet_controller`). The scene: :func:`render_scene`."""
    from tqdm import tqdm

    out = os.fspath(out)
    vrx = isinstance(make_task_config(config.task_id), VrxTaskConfig)
    if vrx:  # one of VRX's tasks: its vessel, sea, wind and seed as eval sails it
        task = vrx_evaluation_task(make_task_config(config.task_id), sea_state=config.sea_state, wind=config.wind,
                                   seed=config.seed, time_limit=float(config.decisions))
        controller = vrx_controller(config, task) if controller is None else controller
    else:
        controller = fleet_controller(config, config.boats) if controller is None else controller
        task = config.task(time_limit=float(config.decisions), loop_period=None, device=device,
                           observation=controller_observation(controller))
    env = make_env(task, config.boats, device=device, seed=config.seed)  # reset: the rollout's reset draws the same
    scene, course = render_scene(env)
    view = ViewCamera(scene, config.width, config.height, math.radians(config.field_of_view), max_range=VIEW_RANGE,
                      haze_distance=HAZE_DISTANCE)
    per_decision = int(round(config.frames_per_second * env.decision_period))
    if per_decision < 1 or abs(per_decision - config.frames_per_second * env.decision_period) > 1e-9:
        raise ValueError(f"--fps {config.frames_per_second} does not give whole frames in {task_name(config.task_id)}'s "
                         f"{env.decision_period:g} s decisions; choose a multiple of {1.0 / env.decision_period:g}")
    if config.camera == "fixed":
        view.look_at(*overlook(task, course))
        hook = FrameHook(env, view, per_decision)
    else:
        hook = FrameHook(env, view, per_decision, chase_camera(env, view, env.decision_period / per_decision))
    env.attach(hook)
    written = [0]
    started = time.perf_counter()
    with _video(out, config.width, config.height, config.frames_per_second) as video, \
            tqdm(total=config.frames, desc="render", unit="frame", disable=not progress, dynamic_ncols=True) as bar:
        def write_frames(k: int, decision) -> None:
            for frame in hook.frames.numpy():
                video.write(frame)
            written[0] += per_decision
            bar.update(per_decision)

        if vrx:  # a VRX env has no recorded decision (boom, rudder): step it and take the hook's frames
            env.reset(seed=env.seed)
            controller.reset(env)
            for k in range(int(round(config.decisions / env.decision_period))):
                controller.act(env)
                env.step()
                write_frames(k, None)
        else:
            sail_mission(env, controller, frames_per_decision=per_decision, on_decision=write_frames)
    return RenderResult(path=out, frames=written[0], wall_s=time.perf_counter() - started)


def video_path_problem(out: str) -> str | None:
    """What makes ``out`` unusable as --out before anything runs (a folder, a wrong suffix, MP4 without
    imageio-ffmpeg), in words; None when nothing does. Whether its folder can be made is checked by making it."""
    if os.path.isdir(out):
        return f"--out {out!r} is a folder: give a file name ending in {' or '.join(VIDEO_SUFFIXES)}"
    suffix = os.path.splitext(out)[1].lower()
    if suffix not in VIDEO_SUFFIXES:
        return f"--out must end in {' or '.join(VIDEO_SUFFIXES)}, got {out!r}"
    if suffix == ".mp4":
        if importlib.util.find_spec("imageio_ffmpeg") is None:
            return f"--out {out!r}: {MP4_HINT}"
    return None


def _output_folder(parser: argparse.ArgumentParser, out: str) -> None:
    """Make --out's folder if it is missing (:func:`made_folder`), and exit with status 2 where it cannot be
    made or written in."""
    folder = made_folder(parser, os.path.dirname(os.path.abspath(out)))
    if not os.access(folder, os.W_OK | os.X_OK):
        report_error(parser.prog, f"--out {out!r}: cannot write in the folder {folder!r}")
        parser.exit(2)


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``ocean-warp render``; returns the exit code (2 for a bad option or an unusable --out,
    1 when the run or the encoding fails)."""
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        config = RenderConfig(boats=args.boats, sea_state=args.sea_state, wind=args.wind, seed=args.seed,
                              hull=args.hull, frames_per_second=args.fps, duration=args.duration, width=args.width,
                              height=args.height, field_of_view=args.fov, camera=args.camera, policy=args.policy,
                              autopilot=args.autopilot, policy_share=args.policy_share,
                              task_id=checked_task_name(args.task))
    except ValueError as error:  # a bad setting or task
        return report_error(parser.prog, str(error))
    device = checked_device(parser, args.device)
    checked_output_file(parser, args.out, "--out")  # its suffix: video_path_problem
    problem = None
    if args.out.lower().endswith(".mp4") and (config.width % 2 or config.height % 2):  # a value, before the setup
        problem = f"--width and --height must be even for MP4 (H.264 4:2:0), got {config.width} x {config.height}"
    problem = problem or video_path_problem(args.out)
    if problem is not None:
        return report_error(parser.prog, problem)
    try:
        task = make_task_config(config.task_id)
        controller = vrx_controller(config, task) if isinstance(task, VrxTaskConfig) else \
            fleet_controller(config, config.boats)
    except (ValueError, FileNotFoundError) as error:  # an unusable policy checkpoint, or none shipped
        return report_error(parser.prog, str(error))
    if isinstance(controller, PolicyController):  # --policy
        warn_other_task(parser.prog, controller.policy, config.task_id)
    if config.policy is None and not config.autopilot and config.policy_share > 0.0 \
            and shipped_policy_or_none(config.task_id) is None:
        print(f"no policy is shipped for {config.task_id}: the autopilot sails every boat")
    _output_folder(parser, args.out)
    try:
        result = render_run(config, args.out, device=device, progress=not args.no_progress, controller=controller)
    except ValueError as error:  # a policy that cannot sail this run
        return report_error(parser.prog, str(error))
    except OSError as error:  # the video could not be written (the temporary file is gone: see render_run)
        reason = error.strerror or str(error)
        print(f"{parser.prog}: error: cannot write --out {args.out!r}: {reason}", file=sys.stderr)
        return 1
    print(f"{plural(result.frames, 'frame')} of {config.width} x {config.height} ({plural(config.boats, 'boat')}, "
          f"{config.camera} camera, device {device}) in {result.wall_s:.1f} s: "
          f"{1e3 * result.seconds_per_frame:.0f} ms a frame with the physics and the encoding")
    print(f"wrote {result.path} ({os.path.getsize(result.path) / 2**20:.2f} MiB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
