"""Small procedural meshes (foils, spars, a sail, buoys, an arrow): the boat's parts and markers, for the USD
stages and for the ray-cast scene alike (no USD here).

Every mesh is a :class:`MeshData` in metres, wound counter-clockwise seen from outside (USD's default
right-handed orientation), so closed meshes have outward normals.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

__all__ = ["MeshData", "concatenate", "extruded", "tube", "ellipsoid", "triangle", "arrow", "foil_section"]


@dataclasses.dataclass(frozen=True)
class MeshData:
    """A polygon mesh: vertices (P, 3) [m], polygon sizes (F,) and the vertex indices of each polygon."""

    points: np.ndarray
    face_counts: np.ndarray
    face_indices: np.ndarray

    def transformed(self, offset=(0.0, 0.0, 0.0)) -> "MeshData":
        """The same mesh moved by ``offset`` [m]."""
        return MeshData(self.points + np.asarray(offset, dtype=np.float64), self.face_counts, self.face_indices)

    def triangles(self) -> np.ndarray:
        """(T, 3) vertex indices: every polygon split into a fan of triangles from its first vertex."""
        rows, start = [], 0
        for count in self.face_counts:
            face = self.face_indices[start:start + count]
            rows.extend((face[0], face[k], face[k + 1]) for k in range(1, count - 1))
            start += count
        return np.asarray(rows, dtype=np.int32).reshape(-1, 3)

    @property
    def extent(self) -> np.ndarray:
        """(2, 3) smallest and largest corner of the bounding box [m]."""
        return np.stack([self.points.min(axis=0), self.points.max(axis=0)])


def _mesh(points, counts, indices) -> MeshData:
    return MeshData(np.asarray(points, dtype=np.float64).reshape(-1, 3), np.asarray(counts, dtype=np.int32),
                    np.asarray(indices, dtype=np.int32))


def concatenate(*meshes: MeshData) -> MeshData:
    """One mesh holding all of ``meshes``."""
    offsets = np.cumsum([0] + [len(m.points) for m in meshes[:-1]])
    return _mesh(np.concatenate([m.points for m in meshes]), np.concatenate([m.face_counts for m in meshes]),
                 np.concatenate([m.face_indices + o for m, o in zip(meshes, offsets)]))


def _ring_band(rings: int, sides: int) -> tuple[list[int], list[int]]:
    """Quads joining ``rings`` consecutive closed loops of ``sides`` vertices (loop r starts at r * sides)."""
    counts, indices = [], []
    for r in range(rings - 1):
        for s in range(sides):
            a, b = r * sides + s, r * sides + (s + 1) % sides
            indices += [a, b, b + sides, a + sides]
            counts.append(4)
    return counts, indices


def extruded(section: np.ndarray, bottom: float, top: float, *, top_scale: float = 1.0) -> MeshData:
    """A prism: the closed counter-clockwise polygon ``section`` (K, 2) in the x-y plane [m], from
    z = ``bottom`` to ``top`` [m], scaled by ``top_scale`` about the section's first vertex at the top
    (a tapered fin), closed at both ends."""
    section = np.asarray(section, dtype=np.float64)
    k = len(section)
    tip = section[0] + top_scale * (section - section[0])
    points = np.concatenate([np.column_stack([section, np.full(k, bottom)]), np.column_stack([tip, np.full(k, top)])])
    counts, indices = _ring_band(2, k)
    counts += [k, k]
    indices += list(range(k - 1, -1, -1)) + list(range(k, 2 * k))
    return _mesh(points, counts, indices)


def tube(start, end, radius: float, *, sides: int = 12) -> MeshData:
    """A closed cylinder of ``radius`` [m] from point ``start`` to ``end`` [m]."""
    start, end = np.asarray(start, dtype=np.float64), np.asarray(end, dtype=np.float64)
    axis = end - start
    length = float(np.linalg.norm(axis))
    axis /= length
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    v = np.cross(axis, u)
    angles = 2.0 * math.pi * np.arange(sides) / sides
    circle = radius * (np.cos(angles)[:, None] * u + np.sin(angles)[:, None] * v)
    points = np.concatenate([start + circle, end + circle])
    counts, indices = _ring_band(2, sides)
    counts += [sides, sides]
    indices += list(range(sides - 1, -1, -1)) + list(range(sides, 2 * sides))
    return _mesh(points, counts, indices)


def ellipsoid(center, radii, *, rings: int = 8, sides: int = 12) -> MeshData:
    """A closed ellipsoid of semi-axes ``radii`` (x, y, z) [m] about ``center`` [m]."""
    center, radii = np.asarray(center, dtype=np.float64), np.asarray(radii, dtype=np.float64)
    polar = math.pi * np.arange(1, rings) / rings  # from the south pole (-z) up, poles apart
    azimuth = 2.0 * math.pi * np.arange(sides) / sides
    band = np.stack([np.sin(polar)[:, None] * np.cos(azimuth), np.sin(polar)[:, None] * np.sin(azimuth),
                     -np.cos(polar)[:, None] * np.ones(sides)], axis=-1).reshape(-1, 3)
    points = np.concatenate([band, [[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]]]) * radii + center
    counts, indices = _ring_band(rings - 1, sides)
    south, north, last = len(points) - 2, len(points) - 1, (rings - 2) * sides
    for s in range(sides):
        counts += [3, 3]
        indices += [south, (s + 1) % sides, s, north, last + s, last + (s + 1) % sides]
    return _mesh(points, counts, indices)


def triangle(a, b, c) -> MeshData:
    """One triangle (a, b, c) [m] (for a sail: author it double-sided)."""
    return _mesh([a, b, c], [3], [0, 1, 2])


def arrow(length: float, *, shaft_radius: float, head_length: float, head_radius: float, sides: int = 12) -> MeshData:
    """A closed arrow along +x from the origin, ``length`` [m] overall: a cylindrical shaft and a cone."""
    shaft = tube((0.0, 0.0, 0.0), (length - head_length, 0.0, 0.0), shaft_radius, sides=sides)
    angles = 2.0 * math.pi * np.arange(sides) / sides
    base = np.column_stack([np.full(sides, length - head_length), head_radius * np.cos(angles),
                            head_radius * np.sin(angles)])
    tip = len(base)
    counts = [3] * sides + [sides]
    indices = [i for s in range(sides) for i in (s, (s + 1) % sides, tip)] + list(range(sides - 1, -1, -1))
    return concatenate(shaft, _mesh(np.concatenate([base, [[length, 0.0, 0.0]]]), counts, indices))


def foil_section(chord: float, thickness: float, *, points: int = 10, leading_edge_x: float = 0.0) -> np.ndarray:
    """A symmetric foil section in the x-y plane, counter-clockwise, (2 points - 2, 2) [m]: NACA 4-digit
    thickness ``thickness`` (fraction of ``chord`` [m]), leading edge at ``leading_edge_x`` and the chord
    running aft (towards -x), as keels and rudders point in the body frame (x to the bow)."""
    s = 0.5 * (1.0 - np.cos(np.linspace(0.0, math.pi, points)))  # clustered at both edges
    half = 5.0 * thickness * (0.2969 * np.sqrt(s) - 0.1260 * s - 0.3516 * s**2 + 0.2843 * s**3 - 0.1036 * s**4)
    x = leading_edge_x - chord * s
    # Counter-clockwise seen from +z: aft along the port side (y > 0), forward along starboard (y < 0).
    port = np.column_stack([x, chord * half])
    starboard = np.column_stack([x, -chord * half])[::-1]
    return np.concatenate([port[:-1], starboard[:-1]])
