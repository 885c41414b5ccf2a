"""The demo's USD stage: a fleet recorded frame by frame from inside each decision, on one seamless loop of
its ocean (or a mesh per frame), with its course, its obstacles and the wind arrow; then validated and
previewed. The stage plays in real time at ``time_codes_per_second`` (default 24, Blender's frame rate),
whatever the number of frames recorded per decision.

What the stage shows is every boat's FIRST episode, the one it sails from the reset before the recorder is
made:

- the course: a task's fixed route (the BCDACA mission: its buoys and the path from the start, A), or,
  on the single-waypoint tasks, a buoy at each boat's own waypoint (named "boat <i>"; no path);
- on a task with obstacles, each boat's obstacle layout of that episode under ``/World/Objects``, placed
  from its environment's origin (one prim per obstacle, named "boat <i> buoy <k>" / "boat <i> pile <k>";
  every boat's layout is drawn, and with all boats on the same water the layouts overlap: a boat touches
  only its own). Piles stand still; the buoys ride the waves, their poses sampled at every frame from the
  env's obstacle scene (``RecordedDecision``: the scene's object rows as ``scene.refresh()`` gives them);
- the wind arrow: the first boat's mean true wind (tasks that draw the wind per boat give each its own);
- a boat that has finished its episode (done, lost, capsized, collided or timed out) is held where it
  ended, and so are its buoys: the environment restarts it with a new start, waypoint and layout, which
  the stage does not show.
"""

from __future__ import annotations

import os

import numpy as np

from ocean_warp.perception.scene import SceneObject
from ocean_warp.usd import (FleetDrawing, OceanDrawing, RouteDrawing, StageRecorder, WindArrow, render_preview,
                            validate_stage)
from ocean_warp.usd.preview import spread_time_code

from ..sailing_env import SailingEnv
from ..tasks.obstacle_course import OBSTACLE_BUOY, OBSTACLE_PILE
from ..tasks.obstacle_layout import BUOY_COLOR, PILE_COLOR
from ..tasks.task_configs import mission_waypoint_name

__all__ = ["MissionStageRecorder", "obstacle_objects"]

BOAT_FRAMES = ("position", "orientation", "boom_angle", "rudder_angle")
"""The per-boat arrays of ``RecordedDecision.frames()`` ((F, N, ...) each)."""


def obstacle_objects(env: SailingEnv) -> tuple[list[SceneObject], np.ndarray, np.ndarray, list[str]]:
    """The obstacles ``env`` holds now (``env.buffers.obstacles``) as world-placed scene objects: (objects,
    rows (M,) their rows in the obstacle scene (``env.obstacles.scene``), envs (M,) their environment,
    labels (M,) "boat <i> buoy <k>" / "boat <i> pile <k>"). A buoy is ``SceneObject.buoy`` of its radius
    [m] at its environment's origin + (x, y) [m], floating; a pile ``SceneObject.pillar`` of its radius and
    the task's ``pile_height`` [m], standing from a quarter of it below still water. Empty on a task
    without obstacles."""
    course = env.obstacles
    if course is None or course.slots == 0 or env.task.obstacles is None:
        return [], np.zeros(0, np.int64), np.zeros(0, np.int64), []
    table = env.buffers.obstacles.cpu().numpy().astype(np.float64)
    origins = env.origin.numpy().astype(np.float64)
    first_row = np.asarray(course.scene.first_free_slot, dtype=np.int64)
    height = env.task.obstacles.pile_height
    objects, rows, envs, labels = [], [], [], []
    for e in range(env.num_envs):
        for k, (x, y, radius, kind) in enumerate(table[e]):
            kind = int(round(kind))
            where = (origins[e, 0] + x, origins[e, 1] + y)
            if kind == OBSTACLE_BUOY:
                objects.append(SceneObject.buoy(where, radius=radius, color=BUOY_COLOR))
                labels.append(f"boat {e} buoy {k}")
            elif kind == OBSTACLE_PILE:
                objects.append(SceneObject.pillar(where, radius=radius, height=height, color=PILE_COLOR))
                labels.append(f"boat {e} pile {k}")
            else:
                continue
            rows.append(first_row[e] + k)
            envs.append(e)
    return objects, np.array(rows, dtype=np.int64), np.array(envs, dtype=np.int64), labels


class MissionStageRecorder:
    """Records ``env``'s fleet into the stage at ``path``: ``frames_per_decision`` frames per decision, each
    boat's first episode (module docstring). Make it right after the env's reset (its waypoints and
    obstacle layouts are read then; ``sail_mission``'s ``reset(seed=env.seed)`` draws the same ones again)."""

    def __init__(self, env: SailingEnv, path: str | os.PathLike, *, frames_per_decision: int,
                 ocean_resolution: int = 32, ocean_margin: float = OceanDrawing.margin,
                 ocean_normals: bool = OceanDrawing.normals, ocean_loop: bool | None = None,
                 instanced: bool | None = None, **options):
        """``ocean_resolution``, ``ocean_margin`` [m], ``ocean_normals``: the ocean's
        :class:`~ocean_warp.usd.OceanDrawing` (``resolution``, ``margin``, ``normals``); ``ocean_loop`` None:
        one seamless loop where the ocean has a ``loop_period``, else a mesh per frame; ``instanced``: the
        fleet's layout (:class:`~ocean_warp.usd.FleetDrawing`); ``options``: more of
        :class:`~ocean_warp.usd.StageRecorder`'s (``ascii``, ``time_codes_per_second``, ``save_every``)."""
        self.env = env
        self.frames_per_decision = frames_per_decision
        ocean = env.simulator.ocean
        loop = ocean.config.loop_period is not None if ocean_loop is None else ocean_loop
        wind = env.simulator.state
        objects, self._object_rows, self._object_env, labels = obstacle_objects(env)
        self.recorder = StageRecorder(
            path, fps=float(frames_per_decision) / env.decision_period,
            ocean=OceanDrawing(ocean, resolution=ocean_resolution, margin=ocean_margin, normals=ocean_normals,
                               loop=loop),
            fleet=FleetDrawing(env.num_envs, instanced=instanced, vessel=env.vessel),
            route=_course(env),
            wind=WindArrow(float(wind.wind_mean_direction.numpy()[0]), speed=float(wind.wind_mean_speed.numpy()[0])),
            objects=objects, object_labels=labels or None, **options)
        self._held = np.zeros(env.num_envs, dtype=bool)
        self._held_frame: dict[str, np.ndarray] = {}
        scaling = self.recorder.scaling
        self._levels = getattr(env.simulator.state, scaling.level).numpy() if scaling is not None else None
        """Each boat's level of its scaled parts (the sail's reef) in its first episode (drawn at the env's reset,
        as the stage's episodes)."""

    @property
    def object_count(self) -> int:
        """Obstacles drawn in the stage (0 on a task without obstacles)."""
        return len(self._object_rows)

    def record(self, time_s: float, frames: dict[str, np.ndarray]) -> None:
        """Add the frames of the decision that ended at ``time_s`` [s] (``RecordedDecision.frames()``)."""
        count = self.frames_per_decision
        frames = dict(frames)
        if self.object_count:
            if "object_position" not in frames:
                raise ValueError("MissionStageRecorder.record: the task has obstacles, but the frames hold no "
                                 "object poses (RecordedDecision of this env gives them)")
            frames["object_position"] = frames["object_position"][:, self._object_rows]
            frames["object_orientation"] = frames["object_orientation"][:, self._object_rows]
        masks = {name: self._held if name in BOAT_FRAMES else self._held[self._object_env]
                 for name in self._held_frame}
        for name, held in self._held_frame.items():
            frames[name][:, masks[name]] = held[masks[name]]
        period = self.env.decision_period
        for f in range(count):
            poses = (frames["object_position"][f], frames["object_orientation"][f]) if self.object_count else None
            joints = {name: frames[name][f] for name in self.recorder.joint_names}
            self.recorder.record(time_s - period + (f + 1) * period / count, frames["position"][f],
                                 frames["orientation"][f], joints=joints, levels=self._levels, object_poses=poses)
        ended = self.env.done.numpy().astype(bool) & ~self._held
        if ended.any():
            names = BOAT_FRAMES + (("object_position", "object_orientation") if self.object_count else ())
            for name in names:
                values = frames[name][-1]
                mask = ended if name in BOAT_FRAMES else ended[self._object_env]
                held = self._held_frame.setdefault(name, values.copy())
                held[mask] = values[mask]
            self._held |= ended

    def abort(self) -> None:
        self.recorder.abort()

    def close(self) -> dict[str, str]:
        """Finish the stage, check it with USD's validators and draw its preview; the files written."""
        stage = self.recorder.close()
        problems = validate_stage(stage)
        if problems:
            raise RuntimeError(f"the demo's stage {stage} does not validate: {problems[:3]}")
        files = {"stage": stage}
        if self.recorder.loop_path is not None:
            files["ocean loop"] = self.recorder.loop_path
        # The first frame would show the fleet in a heap at its start: draw the one where it is most spread.
        files["preview"] = render_preview(stage, time_code=spread_time_code(stage))
        return files


def _course(env: SailingEnv) -> RouteDrawing:
    """The course the stage shows: the task's route from the first environment's origin, with the path from
    the start; or, on a task whose boats draw their own waypoints, each boat's first-episode waypoints from
    its own origin, buoys only."""
    origins = env.origin.numpy()[:, :2].astype(np.float64)
    if env.task.route is not None:
        route = np.asarray(env.task.route, dtype=np.float64) + origins[0]
        start = np.asarray(env.task.start_point, dtype=np.float64) + origins[0]
        return RouteDrawing(route, labels=_waypoint_names(env.task.route), start=start)
    waypoints = env.buffers.route.cpu().numpy()[:, :, :2].astype(np.float64) + origins[:, None, :]
    legs = waypoints.shape[1]
    labels = [f"boat {e}" if legs == 1 else f"boat {e} waypoint {k}" for e in range(env.num_envs) for k in range(legs)]
    return RouteDrawing(waypoints.reshape(-1, 2), labels=labels, path=False)


def _waypoint_names(route) -> list[str]:
    """The mission's letter for each waypoint of ``route`` that is one of them, else its place in the route."""
    return [mission_waypoint_name(point) or str(i) for i, point in enumerate(route)]
