"""Small builders shared by the hull and dynamics tests."""

import numpy as np

import ocean_warp as ow
from ocean_warp.frames import roll_pitch_yaw


def calm_ocean(device, *, tile_size: float = 64.0, resolution: int = 16) -> ow.Ocean:
    """Still water: a JONSWAP sea of zero height."""
    return ow.Ocean(ow.OceanConfig(tile_size=tile_size, resolution=resolution, significant_wave_height=0.0),
                    device=device)


def random_rotations(rng, count: int, max_angle: float) -> np.ndarray:
    """(count, 4) quaternions x y z w of random axes and angles up to ``max_angle`` [rad]."""
    axes = rng.normal(size=(count, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    angles = rng.uniform(0.0, max_angle, size=count)
    return np.concatenate([axes * np.sin(angles / 2)[:, None], np.cos(angles / 2)[:, None]], axis=1)


def rotation_matrix(quaternion) -> np.ndarray:
    """Body -> world rotation of a quaternion x y z w."""
    x, y, z, w = np.asarray(quaternion, dtype=np.float64) / np.linalg.norm(quaternion)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def quaternion_about(axis, angle: float) -> np.ndarray:
    axis = np.asarray(axis, dtype=np.float64)
    axis = axis / np.linalg.norm(axis)
    return np.concatenate([axis * np.sin(angle / 2), [np.cos(angle / 2)]])


def settled_heights(sim, steps: int, average_over: int) -> np.ndarray:
    """Step ``sim`` ``steps`` times; each boat's height [m] averaged over the last ``average_over`` steps
    (the last few millimetres of bobbing averaged out)."""
    heights = []
    for step in range(steps):
        sim.step()
        if step >= steps - average_over:
            heights.append(sim.fleet.numpy()["position"][:, 2].copy())
    return np.mean(heights, axis=0)


def assert_afloat_upright(state) -> None:
    """Every boat of a fleet's ``numpy()`` state heeled less than 1°, trimmed less than 2°, flagged OK."""
    roll, pitch, _ = roll_pitch_yaw(state["orientation"]).T
    assert np.all(np.abs(np.degrees(roll)) < 1.0) and np.all(np.abs(np.degrees(pitch)) < 2.0)
    assert np.all(state["status"] == 0)
