"""Benchmark: what the camera costs. (1) ``SailingEnv.step`` with and without a :class:`CameraHook` on every
boat (depth only, 64 x 64, 90 degree field of view, 2 Hz: two captures in each decision of 1 s); (2) the
time to render one frame of the demo's fleet from the chase camera of ``ocean-warp render`` (1280 x 720).

    python -m benchmarks.perf.bench_camera --device cuda:0 --envs 4096 16384 --json camera.json
    python -m benchmarks.perf.bench_camera --device cpu --envs 16 64 --decisions 3 --render-width 320 \\
        --render-height 180

(1) The task is Waypoint+ as ``bench_envs`` has it (mesh hull; JONSWAP Hs 0.5 m, Tp 3.5 s, choppiness 0.5,
64 x 64 grid over 256 m; decisions of 1 s = 20 steps of 0.05 s), with a buoy and a pile in every
environment; both batches sail the same seeds and fixed actions. Printed per batch size: ms a decision,
environment decisions per second and the real-time factor (simulated boat-seconds per wall-second) without
and with the camera, and the camera's added share of the step.

(2) The demo's fleet (``--boats``, shipped policy and autopilot, ``fleet_course_task``: the mesh hull on a
GPU, four-point buoyancy on the CPU) sails ``--sail`` decisions, then one frame is timed (median of
``--frames`` renders): the scene's refresh, the chase camera's move and the render, as one video frame
of ``ocean-warp render`` costs without the physics and the encoding. ``--save-frame PNG`` writes that frame.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import logging
import math

import torch
import warp as wp

from benchmarks.perf.bench_envs import seconds_per_call
from benchmarks.perf.timing import device_description, write_results_json
from ocean_warp.envs import SailingEnv, WaypointPlusConfig
from ocean_warp.envs.apps.render import (
    HAZE_DISTANCE,
    VIEW_RANGE,
    RenderConfig,
    chase_camera,
    fleet_controller,
    route_buoys,
)
from ocean_warp.envs.sensors import CameraHook
from ocean_warp.perception import CameraConfig, Scene, SceneObject, ViewCamera

ENV_OBJECTS = (SceneObject.buoy((30.0, 5.0)), SceneObject.pillar((60.0, -10.0)))
"""What every environment holds besides its boat and the sea (placed from its origin)."""


def camera_task(choppiness: float) -> WaypointPlusConfig:
    """Waypoint+ with ``bench_envs``'s sea (its choppiness): mesh hull, decisions of 1 s = 20 steps."""
    task = WaypointPlusConfig()
    ocean = dataclasses.replace(task.simulator.ocean, choppiness=choppiness)
    return dataclasses.replace(task, simulator=dataclasses.replace(task.simulator, ocean=ocean))


def _sync(env: SailingEnv):
    device = env.torch_device
    return (lambda: torch.cuda.synchronize(device)) if device.type == "cuda" else (lambda: None)


def step_seconds(task, envs: int, device, camera: CameraConfig | None, repeats: int) -> float:
    """Median wall time of one ``SailingEnv.step`` [s] with fixed actions, with a camera hook if given."""
    env = SailingEnv(task, envs, device=device, seed=1)
    if camera is not None:
        env.attach(CameraHook(env, camera, objects=ENV_OBJECTS))
    fixed = torch.tensor([[0.0, 0.2, 0.1]], device=env.torch_device).repeat(envs, 1)
    for _ in range(3):  # sail away from the start first
        env.step(fixed)
    seconds = seconds_per_call(lambda: env.step(fixed), repeats, _sync(env))
    assert torch.all(torch.isfinite(env.buffers.policy_obs)), "observations must stay finite"
    return seconds


def measure_steps(task, envs: int, device, camera: CameraConfig, repeats: int) -> dict:
    plain = step_seconds(task, envs, device, None, repeats)
    with_camera = step_seconds(task, envs, device, camera, repeats)
    period = task.decision_period
    return {"envs": envs, "env_s": plain, "env_camera_s": with_camera, "added_fraction": with_camera / plain - 1.0,
            "env_real_time_factor": envs * period / plain, "env_camera_real_time_factor": envs * period / with_camera}


def measure_render(device, *, boats: int, width: int, height: int, sail: int, frames: int,
                   save_frame: str | None) -> dict:
    """One chase-camera frame of the demo's fleet after ``sail`` decisions: median seconds of a frame."""
    config = RenderConfig(boats=boats, width=width, height=height)
    task = config.task(time_limit=1200.0, loop_period=None, device=device)
    env = SailingEnv(task, boats, device=device, seed=config.seed)
    controller = fleet_controller(config, boats)
    env.reset(seed=config.seed)
    controller.reset(env)
    for _ in range(sail):
        controller.act(env)
        env.step()
    scene = Scene.for_simulator(env.simulator, route_buoys(task), vessel=env.vessel)
    view = ViewCamera(scene, width, height, math.radians(config.field_of_view), max_range=VIEW_RANGE,
                      haze_distance=HAZE_DISTANCE)
    aim = chase_camera(env, view, 1.0 / config.frames_per_second)

    def frame() -> None:
        scene.refresh()
        aim()
        view.render()

    sync = (lambda: wp.synchronize_device(view.device))
    seconds = seconds_per_call(frame, frames, sync)
    if save_frame:
        from PIL import Image

        from ocean_warp.atomic_files import atomic_output

        with atomic_output(save_frame, suffix=".png") as temporary:
            Image.fromarray(view.image()).save(temporary, optimize=True)
    return {"boats": boats, "width": width, "height": height, "sailed_s": sail * env.decision_period,
            "frame_s": seconds}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--device", default="cuda:0" if wp.get_cuda_device_count() else "cpu")
    parser.add_argument("--envs", type=int, nargs="*", default=[4096, 16384], help="batch sizes for (1); none: skip")
    parser.add_argument("--decisions", type=int, default=10, help="timed decisions per case (median)")
    parser.add_argument("--camera-size", type=int, nargs=2, default=[64, 64], metavar=("WIDTH", "HEIGHT"))
    parser.add_argument("--camera-rate", type=float, default=2.0, help="[Hz]")
    parser.add_argument("--choppiness", type=float, default=0.5)
    parser.add_argument("--boats", type=int, default=16, help="the demo fleet of (2)")
    parser.add_argument("--render-width", type=int, default=1280)
    parser.add_argument("--render-height", type=int, default=720)
    parser.add_argument("--sail", type=int, default=40, help="decisions sailed before the frame of (2)")
    parser.add_argument("--frames", type=int, default=10, help="timed renders (median); 0: skip (2)")
    parser.add_argument("--save-frame", metavar="PNG", help="write the frame of (2) here")
    parser.add_argument("--json", help="write the results here")
    args = parser.parse_args(argv)
    wp.config.log_level = logging.WARNING
    device = wp.get_device(args.device)
    task = camera_task(args.choppiness)
    width, height = args.camera_size
    camera = CameraConfig(width=width, height=height, rate=args.camera_rate, rgb=False)
    print(f"Waypoint+ decisions of {task.decision_period} s ({task.steps_per_decision} steps), mesh hull, choppiness "
          f"{args.choppiness}; camera {width} x {height} depth at {args.camera_rate:g} Hz, fov 90 deg, range "
          f"{camera.max_range:g} m; {device_description(device)}; {datetime.date.today()}")
    rows = []
    if args.envs:
        print("| envs | env: ms, RTF | env + camera: ms, RTF | camera added |")
    for envs in args.envs:
        row = measure_steps(task, envs, device, camera, args.decisions)
        rows.append(row)
        print(f"| {envs} | {row['env_s'] * 1e3:.1f}, {row['env_real_time_factor']:,.0f} | "
              f"{row['env_camera_s'] * 1e3:.1f}, {row['env_camera_real_time_factor']:,.0f} | "
              f"{100 * row['added_fraction']:.1f} % |", flush=True)
    render = None
    if args.frames > 0:
        render = measure_render(device, boats=args.boats, width=args.render_width, height=args.render_height,
                                sail=args.sail, frames=args.frames, save_frame=args.save_frame)
        print(f"render: {args.boats} boats after {render['sailed_s']:g} s, chase camera, {args.render_width} x "
              f"{args.render_height}: {render['frame_s'] * 1e3:.1f} ms a frame")
        if args.save_frame:
            print(f"wrote {args.save_frame}")
    if args.json:
        write_results_json(args.json, device, task="Waypoint+", choppiness=args.choppiness,
                           camera={"width": width, "height": height, "rate_hz": args.camera_rate, "depth": True,
                                   "rgb": False, "horizontal_fov_rad": camera.horizontal_fov,
                                   "max_range_m": camera.max_range},
                           rows=rows, render=render)


if __name__ == "__main__":
    main()
