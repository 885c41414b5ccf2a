"""An independent numpy hydrostatics of a closed hull mesh symmetric about y = 0, by waterlines: where the
triangles cross a level plane, the port half-breadths y(x) of that waterplane, and the submerged volume as the
waterplane area integrated over height. Not the divergence theorem of ``ocean_warp.hull_form`` and
``ocean_warp.stability``, which the tests check against it."""

import numpy as np


def port_waterline(triangles: np.ndarray, level: float) -> np.ndarray:
    """(S, 2, 2) segments (x, y) where triangles (T, 3, 3) cross z = ``level``, on the port side (y >= 0)."""
    above = triangles[:, :, 2] >= level
    crossing = triangles[(above.sum(axis=1) == 1) | (above.sum(axis=1) == 2)]
    points, cuts = [], []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        pa, pb = crossing[:, a], crossing[:, b]
        cut = (pa[:, 2] >= level) != (pb[:, 2] >= level)
        t = (level - pa[:, 2]) / np.where(cut, pb[:, 2] - pa[:, 2], 1.0)
        points.append(pa[:, :2] + t[:, None] * (pb[:, :2] - pa[:, :2]))
        cuts.append(cut)
    segments = np.stack(points, axis=1)[np.stack(cuts, axis=1)].reshape(-1, 2, 2)
    return segments[segments[:, :, 1].mean(axis=1) >= 0.0]


def waterplane(triangles: np.ndarray, level: float) -> tuple[float, float]:
    """Area [m^2] and transverse second moment about the centre line I_T [m^4] of the waterplane of a hull
    symmetric about y = 0, from its port half-breadths y(x): A = 2 int y dx, I_T = 2 int y^3 / 3 dx."""
    segments = port_waterline(triangles, level)
    dx = np.abs(segments[:, 1, 0] - segments[:, 0, 0])
    y1, y2 = segments[:, 0, 1], segments[:, 1, 1]
    return (float(2.0 * np.sum(dx * (y1 + y2) / 2.0)),
            float(2.0 * np.sum(dx * (y1**3 + y1**2 * y2 + y1 * y2**2 + y2**3) / 12.0)))


def waterplane_moment(triangles: np.ndarray, level: float) -> float:
    """First moment of the waterplane's area about x = 0 [m^3]: 2 int x y dx (exact on straight segments)."""
    segments = port_waterline(triangles, level)
    (x1, y1), (x2, y2) = segments[:, 0].T, segments[:, 1].T
    return float(2.0 * np.sum(np.abs(x2 - x1) * (y1 * (2.0 * x1 + x2) + y2 * (x1 + 2.0 * x2)) / 6.0))


def volume_by_waterlines(triangles: np.ndarray, level: float, slices: int = 600) -> tuple[float, float]:
    """Volume [m^3] below z = ``level`` and the height of its centre [m], as integrals of the waterplane area
    over height (trapezoid rule on ``slices`` waterlines)."""
    heights = np.linspace(triangles[:, :, 2].min(), level, slices + 1)
    areas = np.array([waterplane(triangles, z)[0] for z in heights])
    volume = np.trapezoid(areas, heights)
    return float(volume), float(np.trapezoid(areas * heights, heights) / volume)


def centre_of_volume_x(triangles: np.ndarray, level: float, slices: int = 600) -> float:
    """x [m] of the centre of the volume below z = ``level``: the waterplanes' first moments over their areas,
    each integrated over height."""
    heights = np.linspace(triangles[:, :, 2].min(), level, slices + 1)
    areas = np.array([waterplane(triangles, z)[0] for z in heights])
    moments = np.array([waterplane_moment(triangles, z) for z in heights])
    return float(np.trapezoid(moments, heights) / np.trapezoid(areas, heights))
