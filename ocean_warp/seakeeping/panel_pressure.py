"""The Froude-Krylov load of a regular wave as the simulator's hull pass integrates it, linearised, in numpy.

The hull pass (``kernels.hull_forces``) clips each triangle at the waterline and integrates a pressure linear
over each submerged piece from its corners' pressure heads; below still water a corner's dynamic head is the
wave's, decaying with depth piecewise linearly between the ocean's pressure depths (exact at them) and held below
the deepest (``kernels.ocean_surface.pressure_head``). For a small wave at rest that is: the pieces of the mesh
under z = 0, the dynamic head at each vertex (the elevation itself above z = 0), linear along the cut edges.
Against a BEM's Froude-Krylov force, which integrates e^(k z) exactly, this shows what the panels and the depth
profile leave out; :mod:`ocean_warp.seakeeping.diffraction_fit` fits the diffraction weights to make up the
difference too.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["submerged_pieces", "depth_decay", "panel_froude_krylov"]


def submerged_pieces(vertices, triangles) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The pieces of a triangle mesh below z = 0 as the hull pass cuts them: (first (P, 3), second (P, 3),
    fraction (P, 3)); corner c of piece n lies at vertices[first] + fraction (vertices[second] - vertices[first])."""
    z = np.asarray(vertices, dtype=np.float64)[:, 2]
    first, second, fraction = [], [], []
    for corners in np.asarray(triangles):
        wet = z[corners] < 0.0
        count = int(wet.sum())
        if count == 0:
            continue
        if count == 3:
            first.append(corners)
            second.append(corners)
            fraction.append((0.0, 0.0, 0.0))
            continue
        odd = int(np.flatnonzero(wet if count == 1 else ~wet)[0])
        a, b, c = corners[odd], corners[(odd + 1) % 3], corners[(odd + 2) % 3]
        if count == 1:  # (a, ab, ac)
            first.append((a, a, a))
            second.append((a, b, c))
            fraction.append((0.0, z[a] / (z[a] - z[b]), z[a] / (z[a] - z[c])))
        else:  # (ba, b, c) and (ba, c, ca)
            tb, tc = z[b] / (z[b] - z[a]), z[c] / (z[c] - z[a])
            first += [(b, b, c), (b, c, c)]
            second += [(a, b, c), (a, c, a)]
            fraction += [(tb, 0.0, 0.0), (tb, 0.0, tc)]
    return np.array(first, dtype=np.int64), np.array(second, dtype=np.int64), np.array(fraction)


def depth_decay(z, wavenumber: float, pressure_depths) -> np.ndarray:
    """The simulator's e^(k z) at heights ``z`` [m] (1 above still water): linear between z = 0 and the
    ``pressure_depths`` [m, positive down], held below the deepest."""
    z = np.minimum(np.asarray(z, dtype=np.float64), 0.0)
    levels = np.concatenate([[0.0], -np.asarray(pressure_depths, dtype=np.float64)])
    values = np.exp(wavenumber * levels)
    return np.where(z < levels[-1], values[-1], np.interp(z, levels[::-1], values[::-1]))


def panel_froude_krylov(vertices, triangles, omega: float, headings, pressure_depths, *, density: float,
                        gravity: float) -> np.ndarray:
    """(H, 6) complex Froude-Krylov wrench [N, N m per metre of wave amplitude] about the origin of the mesh
    (``vertices`` (V, 3) [m] in still-water coordinates, z up, ``triangles`` (T, 3) counter-clockwise from
    outside) in a deep-water Airy wave of frequency ``omega`` [rad/s] travelling toward each of ``headings`` [rad],
    phase against the elevation at the origin (Re(X e^(i w t))), as the hull pass integrates it (module
    docstring)."""
    vertices = np.asarray(vertices, dtype=np.float64)
    first, second, fraction = submerged_pieces(vertices, triangles)
    corners = vertices[first] + fraction[..., None] * (vertices[second] - vertices[first])  # (P, 3, 3)
    area_vector = 0.5 * np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    area = np.linalg.norm(area_vector, axis=1)
    normal = area_vector / np.maximum(area, 1e-300)[:, None]
    k = omega**2 / gravity
    decay = depth_decay(vertices[:, 2], k, pressure_depths)
    wrenches = []
    for heading in np.atleast_1d(np.asarray(headings, dtype=np.float64)):
        phase = np.exp(-1j * k * (vertices[:, 0] * math.cos(heading) + vertices[:, 1] * math.sin(heading)))
        head = phase * decay
        pressure = density * gravity * (head[first] + fraction * (head[second] - head[first]))  # (P, 3)
        total = pressure.sum(axis=1)
        force = -(total / 3.0)[:, None] * area_vector
        # int p r dA = A/12 (sum p_i r_i + sum p_i sum r_i) for p linear over the piece
        first_moment = (area / 12.0)[:, None] * (np.einsum("pc,pcj->pj", pressure, corners)
                                                 + total[:, None] * corners.sum(axis=1))
        moment = np.cross(normal, first_moment)
        wrenches.append(np.concatenate([force.sum(axis=0), moment.sum(axis=0)]))
    return np.array(wrenches)
