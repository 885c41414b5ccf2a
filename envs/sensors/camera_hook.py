"""A camera on every boat of a :class:`~ocean_warp.envs.SailingEnv`, capturing inside every decision (the
core's :class:`~ocean_warp.perception.camera.Camera` driven by a decision hook).

Example::

    env = SailingEnv(WaypointPlusConfig(), 4096, device="cuda:0")
    hook = CameraHook(env, CameraConfig(width=64, height=64, rgb=False, rate=2.0), objects=[SceneObject.buoy((30, 5))])
    env.attach(hook)                       # renders at 2 Hz inside every decision, in its graph
    env.step(actions)
    hook.camera.depth                      # torch (4096, 64, 64) float32 [m], the latest capture
"""

from __future__ import annotations

import numpy as np
import warp as wp

from ocean_warp.kernels.camera_render import count_decisions
from ocean_warp.perception.camera import Camera, CameraConfig
from ocean_warp.perception.scene import Scene

from ..decision_hook import DecisionHook
from ..sailing_env import SailingEnv

__all__ = ["CameraHook"]


class CameraHook(DecisionHook):
    """A camera on every boat of a :class:`~ocean_warp.envs.SailingEnv` (boat i in environment i, blind to its
    own boat), capturing at its config's rate inside every decision: after each capturing physics step the
    scene is refreshed (the sea's band, the floating objects) and every camera renders. Launches only: the
    captures are part of the decision's graph. Attach it with ``env.attach(hook)``; read ``hook.camera``.

    The physics rate (1 / dt) divided by ``CameraConfig.rate`` must be a whole number K of steps, and K must
    divide the decision's steps (captures after steps K, 2K, ... of every decision; the images hold the
    last one) or be a multiple of them (a capture after the last step of every K / steps-th decision, the
    first decision included); otherwise ``ValueError`` naming ``CameraConfig.rate``. The images are those
    of the decision's physics, before the environments that ended restart (like ``env.final_position``).

    Args:
        env: the environment whose boats carry the cameras.
        config: the camera (default ``CameraConfig()``).
        objects: the objects of every environment, placed from each environment's origin (as
            ``Scene.for_env``); ignored when ``scene`` is given.
        scene: a scene of this environment's boats and sea to render instead.
        record: also keep every capture of the decision, not only the last: ``recorded_depth`` (K N, H, W)
            and ``recorded_rgb`` (K N, H, W, 3) for its K captures, oldest first (capture k of camera c in
            row k N + c), preallocated on the device (see :meth:`frames`).
    """

    def __init__(self, env: SailingEnv, config: CameraConfig | None = None, *, objects=(), scene: Scene | None = None,
                 record: bool = False):
        if not isinstance(env, SailingEnv):
            raise ValueError(f"CameraHook: env must be a SailingEnv (it captures inside its decisions), got {env!r}")
        config = config if config is not None else CameraConfig()
        if not isinstance(config, CameraConfig):
            raise ValueError(f"CameraHook: config must be a CameraConfig, got {config!r}")
        steps = env.steps_per_decision
        self.steps_between_captures = _steps_between_captures(config.rate, env.task.simulator.dt, steps)
        """Physics steps from one capture to the next."""
        self.scene = scene if scene is not None else Scene.for_env(env, objects)
        if not isinstance(self.scene, Scene) or self.scene.ocean is not env.simulator.ocean \
                or self.scene.view.boat_position.shape[0] != env.num_envs:
            raise ValueError(f"CameraHook.scene must be a Scene of the environment's sea and its {env.num_envs} boats "
                             "(Scene.for_env)")
        self.camera = Camera(config, self.scene, np.arange(env.num_envs))
        every = self.steps_between_captures
        self.capture_steps = frozenset(range(every - 1, steps, every)) if steps % every == 0 else frozenset({steps - 1})
        """The physics steps of a decision after which it captures (0-based)."""
        self.decisions_between_captures = max(every // steps, 1)
        """1, or the decisions from one capture to the next when the rate is below the decision rate."""
        if not isinstance(record, bool):
            raise ValueError(f"CameraHook.record must be True or False, got {record!r}")
        self.record = record
        self._slot_of_step = {step: slot for slot, step in enumerate(sorted(self.capture_steps))}
        captures, camera = len(self.capture_steps), self.camera
        recorded = (lambda image: None if image is None or not record  # noqa: E731
                    else wp.zeros((captures * image.shape[0],) + image.shape[1:], dtype=image.dtype, device=env.device))
        self.recorded_depth = recorded(camera.depth_array)
        """(K N, H, W) the decision's depth images, with ``record`` and depth on (else None)."""
        self.recorded_rgb = recorded(camera.rgb_array)
        """(K N, H, W, 3) the decision's RGB images, with ``record`` and RGB on (else None)."""

    def after_physics_step(self, env: SailingEnv, step: int) -> None:
        """After a capturing step: refresh the scene and render (and count the decision when skipping some)."""
        if step not in self.capture_steps:
            return
        camera = self.camera
        self.scene.refresh()
        camera.capture()
        if self.decisions_between_captures > 1:
            wp.launch(count_decisions, dim=1, device=camera.device,
                      inputs=[camera.gate, self.decisions_between_captures])
        slot = self._slot_of_step[step]
        for recorded, image in ((self.recorded_depth, camera.depth_array), (self.recorded_rgb, camera.rgb_array)):
            if recorded is not None:
                wp.copy(recorded, image, dest_offset=slot * image.size, count=image.size)

    def frames(self) -> dict[str, np.ndarray]:
        """The last decision's captures on the host (``record`` only): "depth" (K, N, H, W) [m] and "rgb"
        (K, N, H, W, 3) uint8 where the camera renders them; capture k taken after physics step
        ``sorted(capture_steps)[k]`` (0-based) of the decision."""
        if not self.record:
            raise ValueError("CameraHook.frames: build the hook with record=True to keep every capture")
        captures, cameras = len(self.capture_steps), self.camera.count
        return {name: array.numpy().reshape((captures, cameras) + array.shape[1:])
                for name, array in (("depth", self.recorded_depth), ("rgb", self.recorded_rgb)) if array is not None}


def _steps_between_captures(rate: float, dt: float, steps_per_decision: int) -> int:
    """Physics steps per capture at ``rate`` [Hz] with steps of ``dt`` [s]; ValueError naming
    CameraConfig.rate unless it fits the decision's steps (see :class:`CameraHook`)."""
    physics_rate = 1.0 / dt
    ratio = physics_rate / rate
    steps = int(round(ratio))
    if steps < 1 or abs(ratio - steps) > 1e-6 * ratio:
        raise ValueError(f"CameraConfig.rate must be the physics rate {physics_rate:g} Hz divided by a whole number "
                         f"of steps, got {rate!r} Hz")
    if steps_per_decision % steps and steps % steps_per_decision:
        raise ValueError(f"CameraConfig.rate {rate!r} Hz captures every {steps} physics steps, which neither divides "
                         f"nor is a multiple of the decision's {steps_per_decision} steps")
    return steps
