"""The demo's USD stage: a mission fleet recorded frame by frame from inside each decision, on one
seamless loop of its ocean, with the route's buoys, its path from the start (A for BCDACA) and the wind
arrow; then validated and previewed. The stage plays in real time at ``time_codes_per_second`` (default
24, Blender's frame rate), whatever the number of frames recorded per decision.

A boat that has finished its mission (or failed it) is held where it ended: the environment restarts it
at the start for a new episode, which the stage does not show.
"""

from __future__ import annotations

import os

import numpy as np

from ocean_warp.usd import (FleetDrawing, OceanDrawing, RouteDrawing, StageRecorder, WindArrow, render_preview,
                            validate_stage)

from ..sailing_env import SailingEnv
from ..tasks.task_configs import mission_waypoint_name

__all__ = ["MissionStageRecorder"]


class MissionStageRecorder:
    """Records ``env``'s fleet into the stage at ``path``: ``frames_per_decision`` frames per decision."""

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
        origin = env.origin.numpy()[0, :2].astype(np.float64)
        route = np.asarray(env.task.route, dtype=np.float64) + origin
        start = np.asarray(env.task.start_point, dtype=np.float64) + origin
        wind = env.simulator.state
        self.recorder = StageRecorder(
            path, fps=float(frames_per_decision) / env.decision_period,
            ocean=OceanDrawing(ocean, resolution=ocean_resolution, margin=ocean_margin, normals=ocean_normals,
                               loop=loop),
            fleet=FleetDrawing(env.num_envs, instanced=instanced, boat=env.task.simulator.boat),
            route=RouteDrawing(route, labels=_waypoint_names(env.task.route), start=start),
            wind=WindArrow(float(wind.wind_mean_direction.numpy()[0]), speed=float(wind.wind_mean_speed.numpy()[0])),
            **options)
        self._held = np.zeros(env.num_envs, dtype=bool)
        self._held_frame: dict[str, np.ndarray] = {}

    def record(self, time_s: float, frames: dict[str, np.ndarray]) -> None:
        """Add the frames of the decision that ended at ``time_s`` [s] (``RecordedDecision.frames()``)."""
        count = self.frames_per_decision
        if self._held_frame:
            for name, values in frames.items():
                values[:, self._held] = self._held_frame[name][self._held]
        period = self.env.decision_period
        for f in range(count):
            self.recorder.record(time_s - period + (f + 1) * period / count, frames["position"][f],
                                 frames["orientation"][f], frames["boom_angle"][f], frames["rudder_angle"][f])
        ended = self.env.done.numpy().astype(bool) & ~self._held
        if ended.any():
            for name, values in frames.items():
                held = self._held_frame.setdefault(name, values[-1].copy())
                held[ended] = values[-1][ended]
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
        files["preview"] = render_preview(stage)
        return files


def _waypoint_names(route) -> list[str]:
    """The mission's letter for each waypoint of ``route`` that is one of them, else its place in the route."""
    return [mission_waypoint_name(point) or str(i) for i, point in enumerate(route)]
