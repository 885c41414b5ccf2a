"""Orientation helpers on the host (numpy): Warp quaternions (x, y, z, w) to and from angles, their products and
rotations of vectors."""

from __future__ import annotations

import numpy as np

__all__ = ["roll_pitch_yaw", "quaternion_from_roll_pitch_yaw", "quaternion_multiply", "quaternion_rotate",
           "about_z"]


def roll_pitch_yaw(quaternions) -> np.ndarray:
    """(N, 3) roll, pitch, yaw [rad] (Z-Y-X Tait-Bryan: yaw about z, then pitch about y, then roll
    about x) of body -> world quaternions (N, 4) x y z w. Roll > 0 heels to starboard (port side up)."""
    q = np.asarray(quaternions, dtype=np.float64).reshape(-1, 4)
    q = q / np.linalg.norm(q, axis=1, keepdims=True)
    x, y, z, w = q.T
    roll = np.arctan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = np.arcsin(np.clip(2 * (w * y - z * x), -1.0, 1.0))
    yaw = np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return np.stack([roll, pitch, yaw], axis=1)


def quaternion_from_roll_pitch_yaw(angles) -> np.ndarray:
    """(N, 4) quaternions x y z w from (N, 3) roll, pitch, yaw [rad] (the inverse of roll_pitch_yaw)."""
    roll, pitch, yaw = (np.asarray(angles, dtype=np.float64).reshape(-1, 3) * 0.5).T
    cr, sr, cp, sp, cy, sy = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.stack([sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
                     cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy], axis=1)


def quaternion_multiply(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(N, 4) Hamilton products a b of (N, 4) quaternions (x, y, z, w): rotate by b, then by a."""
    ax, ay, az, aw = np.moveaxis(a, -1, 0)
    bx, by, bz, bw = np.moveaxis(b, -1, 0)
    return np.stack([aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw,
                     aw * bw - ax * bx - ay * by - az * bz], axis=-1)


def quaternion_rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """(N, 3) vectors v (N, 3) or (3,) rotated by unit quaternions q (N, 4) (x, y, z, w)."""
    u, w = q[:, :3], q[:, 3:]
    t = 2.0 * np.cross(u, np.broadcast_to(v, u.shape))
    return v + w * t + np.cross(u, t)


def about_z(angle: np.ndarray) -> np.ndarray:
    """(N, 4) quaternions (x, y, z, w) of rotations by ``angle`` (N,) [rad] about z."""
    half = 0.5 * np.asarray(angle, dtype=np.float64)
    zeros = np.zeros_like(half)
    return np.stack([zeros, zeros, np.sin(half), np.cos(half)], axis=-1)
