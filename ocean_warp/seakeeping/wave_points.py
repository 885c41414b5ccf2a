"""Where the simulator samples the water's motion under a hull with a hydrodynamic database, and what a regular
wave gives there.

Each point reads the ocean once: the orbital velocity (u, v, w) [m/s] at the ocean's middle pressure depth and the
dynamic pressure head [m] at its deepest (the two come from the same two field lookups). The hull pass reduces
them, per degree of freedom i, to an effective water velocity V_i = sum over points p and inputs c of
W[i, p, c] s[p, c] (body frame, about the body origin: [m/s] for surge, sway, heave, [rad/s] for roll, pitch, yaw)
whose acceleration loads the hull through A_inf and whose difference from the hull's velocity drives the radiation
memory (``ocean_warp.kernels.radiation``). :func:`rigid_motion_weights` gives the W of a least-squares rigid-motion
fit of the velocities; ``ocean_warp.seakeeping.diffraction_fit`` fits W to a BEM's diffraction forces.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["WAVE_POINT_COUNT", "WAVE_POINT_INPUTS", "wave_point_grid", "rigid_motion_weights",
           "regular_wave_inputs"]

WAVE_POINT_COUNT = 33
"""Points per hull: 11 along by 3 across its plan (``kernels.hull_forces.WAVE_POINTS``)."""
WAVE_POINT_INPUTS = 4
"""What each point reads: u, v, w [m/s] at the middle depth and the dynamic pressure head [m] at the deepest."""
_ALONG = np.linspace(-0.45, 0.45, 11)
_ACROSS = np.array([-0.25, 0.0, 0.25])


def wave_point_grid(hull) -> np.ndarray:
    """(33, 2) body-frame x, y [m] of ``hull``'s wave points (an :class:`ocean_warp.Hull`): x at 0.05 to 0.95 of
    its length, y at 0.25 to 0.75 of its breadth, about the centre of its plan. A wave as short as 0.4 of the hull
    still has four points a wavelength along it."""
    low, high = (np.asarray(v, dtype=np.float64) for v in hull.bounds)
    length, breadth = high[0] - low[0], high[1] - low[1]
    centre = 0.5 * (low[:2] + high[:2])
    grid = np.array([(x * length, y * breadth) for x in _ALONG for y in _ACROSS])
    return grid + centre


def rigid_motion_weights(points) -> np.ndarray:
    """(6, 33, 4) the weights of the least-squares rigid motion of the velocities at ``points`` (33, 2) [m],
    about the body origin (the pressure heads unused). About the grid's centre (x, y offsets), v_z = w + p y - q x,
    v_x = u - r y, v_y = v + r x give w = mean v_z, p = sum(y v_z) / sum(y^2), q = -sum(x v_z) / sum(x^2),
    r = (sum(x v_y) - sum(y v_x)) / (sum x^2 + sum y^2), u, v the means; the origin's velocity adds the rotation's
    at the centre's offset."""
    points = np.asarray(points, dtype=np.float64)
    centre = points.mean(axis=0)
    x, y = (points - centre).T
    count = len(points)
    weights = np.zeros((6, count, WAVE_POINT_INPUTS))
    weights[0, :, 0] = weights[1, :, 1] = weights[2, :, 2] = 1.0 / count
    weights[3, :, 2] = y / np.sum(y**2)
    weights[4, :, 2] = -x / np.sum(x**2)
    spread = np.sum(x**2) + np.sum(y**2)
    weights[5, :, 0] = -y / spread
    weights[5, :, 1] = x / spread
    # linear velocity at the origin = at the centre - angular x centre (centre at z = 0)
    cx, cy = centre
    weights[0] += cy * weights[5]
    weights[1] -= cx * weights[5]
    weights[2] -= cy * weights[3] - cx * weights[4]
    return weights


def regular_wave_inputs(points, omega: float, heading: float, velocity_depth: float, pressure_depth: float,
                        gravity: float) -> np.ndarray:
    """(33, 4) complex inputs of the ``points`` (33, 2) [m] of a hull at rest (upright, heading +x, body origin
    over the world's) in a deep-water Airy wave of frequency ``omega`` [rad/s] travelling toward ``heading`` [rad]
    (counter-clockwise from +x), per metre of amplitude with the phase of its elevation at the origin
    (Re(X e^(i w t)) for the elevation Re(e^(i w t))): u, v, w [m/s] at ``velocity_depth`` [m] below still water
    and the dynamic pressure head [m] at ``pressure_depth``."""
    points = np.asarray(points, dtype=np.float64)
    k = omega**2 / gravity
    elevation = np.exp(-1j * k * (points[:, 0] * math.cos(heading) + points[:, 1] * math.sin(heading)))
    at_velocity_depth = omega * elevation * math.exp(-k * velocity_depth)
    return np.stack([at_velocity_depth * math.cos(heading), at_velocity_depth * math.sin(heading),
                     1j * at_velocity_depth, elevation * math.exp(-k * pressure_depth)], axis=1)
