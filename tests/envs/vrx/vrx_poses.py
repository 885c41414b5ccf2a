"""What the VRX env tests compute VRX's rules from, in numpy: every physics step's pose (a decision hook that
copies it), the yaw of a quaternion and VRX's pose error."""

from __future__ import annotations

import numpy as np
import warp as wp

from ocean_warp.envs.decision_hook import DecisionHook


def yaw_of(q: np.ndarray) -> np.ndarray:
    """Yaw [rad] of (..., 4) x y z w quaternions."""
    x, y, z, w = np.moveaxis(q, -1, 0)
    return np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def pose_error(position, yaw, goal):
    """VRX's d + 0.75^d |heading error| (numpy)."""
    d = np.hypot(goal[..., 0] - position[..., 0], goal[..., 1] - position[..., 1])
    return d + 0.75**d * np.abs((goal[..., 2] - yaw + np.pi) % (2 * np.pi) - np.pi)


class StepPoses(DecisionHook):
    """Every physics step's positions and orientations of the last decision, (steps, N) each, copied on the
    device (``env.attach(StepPoses(env))``)."""

    def __init__(self, env):
        shape = (env.steps_per_decision, env.num_envs)
        self.position = wp.zeros(shape, dtype=wp.vec3, device=env.device)
        self.orientation = wp.zeros(shape, dtype=wp.quat, device=env.device)

    def after_physics_step(self, env, step: int) -> None:
        n = env.num_envs
        wp.copy(self.position, env.simulator.state.position, dest_offset=step * n, count=n)
        wp.copy(self.orientation, env.simulator.state.orientation, dest_offset=step * n, count=n)

    def local(self, origin: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(steps, N, 3) positions from each environment's ``origin`` [m] and (steps, N) yaws [rad]."""
        return self.position.numpy() - origin, yaw_of(self.orientation.numpy())
