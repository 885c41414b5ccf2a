"""What a rollout records of a run: its path (:class:`RunPath`), and frames from inside a decision
(:class:`RecordedDecision`, for recorders that want more than one frame a decision)."""

from __future__ import annotations

import dataclasses

import numpy as np
import warp as wp

from ocean_warp.kernels.ray_cast import float_objects
from ocean_warp.replay import ReplayedLaunches
from ocean_warp.torch_streams import ordered_with_torch

from ..decision_hook import DecisionHook
from ..sailing_env import SailingEnv

__all__ = ["RunPath", "RecordedDecision"]


@dataclasses.dataclass
class RunPath:
    """One run's first episode, sampled at its start and after each of its T decisions."""

    xy: np.ndarray
    """(T + 1, 2) position [m] from the run's origin."""
    heading: np.ndarray
    """(T + 1,) heading [rad, from +x counter-clockwise]."""
    propeller: np.ndarray
    """(T,) propeller level (-5 ... 5) commanded at each decision (as the environment applied it)."""
    reached: np.ndarray
    """(T + 1,) waypoints reached by each sample."""


class RecordedDecision(DecisionHook):
    """One decision of a :class:`SailingEnv` with ``frames_per_decision`` F evenly spaced frames kept from
    inside it (after steps S/F, 2 S/F, ..., S of its S physics steps; F must divide S): pose, boom and
    rudder angles of every boat, for a recorder that wants more than one frame a decision (the USD
    stages). Launched by ``SailingEnv.launch_decision`` with this object as its :class:`DecisionHook`, as
    ``SailingEnv.step`` launches it (and captured as one graph likewise); the copies are part of the launch
    sequence (graph-safe: fixed slots, no host work). A test checks that it stays step for step the same
    as ``env.step()``. It needs a SailingEnv: it looks inside a decision, which the batched-env protocol
    does not show (its buffers hold the pose at the end of the decision: ``final_position``).

    On a task with obstacles it also keeps, at each frame, the pose of every object row of the env's
    obstacle scene (``env.obstacles.scene``): what ``scene.refresh()`` would give there (the floating buoys
    on the sea of that moment, the piles at their anchors), computed into its own slots with the same
    kernel (``float_objects``), so that the scene the env's contact and lidar read is left as ``step()``
    leaves it."""

    def __init__(self, env: SailingEnv, frames_per_decision: int = 1):
        if not isinstance(env, SailingEnv):
            raise ValueError(f"RecordedDecision: env must be a SailingEnv (frames come from inside its decision), "
                             f"got {env!r}")
        steps = env.steps_per_decision
        if isinstance(frames_per_decision, bool) or not isinstance(frames_per_decision, int) \
                or not 1 <= frames_per_decision <= steps or steps % frames_per_decision:
            raise ValueError(f"RecordedDecision: frames_per_decision must divide the {steps} physics steps of a "
                             f"decision, got {frames_per_decision!r}")
        self.env = env
        self.frames_per_decision = frames_per_decision
        n, device = env.num_envs, env.device
        frames = frames_per_decision * n
        self.frame_position = wp.zeros(frames, dtype=wp.vec3, device=device)
        """(F * N,) positions [m] at the decision's frames, frame-major."""
        self.frame_orientation = wp.zeros(frames, dtype=wp.quat, device=device)
        self.frame_boom_angle = wp.zeros(frames, dtype=wp.float32, device=device)
        """(F * N,) boom angles [rad], positive to port."""
        self.frame_rudder_angle = wp.zeros(frames, dtype=wp.float32, device=device)
        """(F * N,) rudder angles [rad], positive turns to port."""
        course = env.obstacles
        self.scene = course.scene if course is not None and course.slots > 0 else None
        """The env's obstacle scene whose object rows are kept per frame (None: a task without obstacles)."""
        rows = self.scene.object_count if self.scene is not None else 0
        self.frame_object_position = wp.zeros(frames_per_decision * rows, dtype=wp.vec3, device=device)
        """(F * M,) every object row's position [m, world] at the decision's frames, frame-major (M = 0
        without obstacles)."""
        self.frame_object_orientation = wp.zeros(frames_per_decision * rows, dtype=wp.quat, device=device)
        """(F * M,) every object row's orientation (x, y, z, w)."""
        # One view per frame slot, made here (no allocation inside the captured launches).
        self._object_slots = [(self.frame_object_position[f * rows:(f + 1) * rows],
                               self.frame_object_orientation[f * rows:(f + 1) * rows])
                              for f in range(frames_per_decision)] if rows else []
        self._replayed = ReplayedLaunches(self._launch, device, capture=env.task.simulator.capture_graph)

    def _launch(self) -> None:
        self.env.launch_decision(self)

    def after_physics_step(self, env: SailingEnv, step: int) -> None:
        """The DecisionHook's copies into the frame slots, launched inside the decision."""
        n, every = env.num_envs, env.steps_per_decision // self.frames_per_decision
        if (step + 1) % every:
            return
        slot = (step + 1) // every - 1
        state, offset = env.simulator.state, slot * n
        for source, target in ((state.position, self.frame_position), (state.orientation, self.frame_orientation),
                               (state.boom_angle, self.frame_boom_angle),
                               (state.rudder_angle, self.frame_rudder_angle)):
            wp.copy(target, source, dest_offset=offset, count=n)
        if self._object_slots:
            scene = self.scene
            position, orientation = self._object_slots[slot]
            # As refresh() leaves them: a fixed row keeps its orientation, float_objects writes the rest.
            wp.copy(orientation, scene.view.object_orientation)
            wp.launch(float_objects, dim=scene.object_count, device=scene.device,
                      inputs=[scene.ocean.surface, scene.floats, scene.draft, scene.anchor],
                      outputs=[position, orientation])

    def __call__(self) -> None:
        with ordered_with_torch(self.env.device):
            self._replayed()

    def frames(self) -> dict[str, np.ndarray]:
        """The last decision's frames on the host: "position" (F, N, 3) [m], "orientation" (F, N, 4) xyzw,
        "boom_angle" and "rudder_angle" (F, N) [rad]; on a task with obstacles also "object_position"
        (F, M, 3) [m, world] and "object_orientation" (F, M, 4) xyzw of the obstacle scene's M object rows
        (environment e's layout in rows ``scene.first_free_slot[e]`` on)."""
        f, n = self.frames_per_decision, self.env.num_envs
        frames = {"position": self.frame_position.numpy().reshape(f, n, 3),
                  "orientation": self.frame_orientation.numpy().reshape(f, n, 4),
                  "boom_angle": self.frame_boom_angle.numpy().reshape(f, n),
                  "rudder_angle": self.frame_rudder_angle.numpy().reshape(f, n)}
        if self.scene is not None:
            m = self.scene.object_count
            frames["object_position"] = self.frame_object_position.numpy().reshape(f, m, 3)
            frames["object_orientation"] = self.frame_object_orientation.numpy().reshape(f, m, 4)
        return frames
