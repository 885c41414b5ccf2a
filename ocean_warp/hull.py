"""Hull meshes: closed triangle meshes in the boat's body frame, checked and repaired on the way in."""

from __future__ import annotations

import math
import os
import warnings

import numpy as np
import trimesh

from .mesh_files import read_mesh_file

__all__ = ["Hull", "HullRepairWarning"]

# A hull longer than this is taken for a model in millimetres (or centimetres) and refused.
MAX_PLAUSIBLE_EXTENT = 400.0
# A hull smaller than this along every axis is taken for a model in kilometres (or a mistake).
MIN_PLAUSIBLE_EXTENT = 0.01


class HullRepairWarning(UserWarning):
    """A hull mesh was changed on loading (winding, orientation, degenerate triangles, holes)."""


class Hull:
    """A closed triangle mesh in the body frame (FLU: x to the bow, y to port, z up; metres).

    The mesh is what the water presses on: it must be watertight with outward normals. On
    construction it is checked: NaN or infinite vertices, a scale that is plainly not metres and a
    mesh with holes that cannot be closed raise ``ValueError``; inconsistent winding, inward normals,
    small holes and degenerate triangles are repaired, with a :class:`HullRepairWarning` that says
    what was done.

    ``visual`` optionally holds a finer mesh (a ``trimesh.Trimesh``) for viewers: physics often wants
    a coarser mesh than the eye.
    """

    def __init__(self, vertices, triangles, *, name: str = "hull", visual: trimesh.Trimesh | None = None):
        self.name = str(name)
        vertices = np.asarray(vertices, dtype=np.float64)
        triangles = np.asarray(triangles)
        if vertices.ndim != 2 or vertices.shape[1] != 3 or len(vertices) < 4:
            raise ValueError(f"Hull {self.name!r}: vertices must have shape (V >= 4, 3) [m], got {vertices.shape}")
        if triangles.ndim != 2 or triangles.shape[1] != 3 or len(triangles) < 4:
            raise ValueError(f"Hull {self.name!r}: triangles must have shape (T >= 4, 3), got {triangles.shape}")
        if not np.issubdtype(triangles.dtype, np.integer):
            raise ValueError(f"Hull {self.name!r}: triangles must hold integer vertex indices, got {triangles.dtype}")
        bad = ~np.all(np.isfinite(vertices), axis=1)
        if bad.any():
            raise ValueError(f"Hull {self.name!r}: {int(bad.sum())} vertices are NaN or infinite (first: index "
                             f"{int(np.flatnonzero(bad)[0])})")
        if triangles.min() < 0 or triangles.max() >= len(vertices):
            raise ValueError(f"Hull {self.name!r}: triangle indices must lie in [0, {len(vertices) - 1}], got "
                             f"[{triangles.min()}, {triangles.max()}]")
        _check_scale(self.name, vertices)
        mesh = trimesh.Trimesh(vertices=vertices, faces=triangles, process=True, validate=False)
        self._mesh = _repaired(self.name, mesh)
        self.visual = visual

    # --- construction -----------------------------------------------------------------------------
    @classmethod
    def from_trimesh(cls, mesh, *, name: str = "hull", scale: float = 1.0) -> "Hull":
        """A hull from a ``trimesh.Trimesh`` (or a ``trimesh.Scene``, whose geometry is merged),
        its coordinates multiplied by ``scale`` (e.g. 0.001 for a model in millimetres)."""
        if isinstance(mesh, trimesh.Scene):
            mesh = mesh.to_geometry() if hasattr(mesh, "to_geometry") else mesh.dump(concatenate=True)
        if not isinstance(mesh, trimesh.Trimesh):
            raise ValueError(f"Hull {name!r}: expected a triangle mesh, got {type(mesh).__name__}")
        if not (isinstance(scale, (int, float)) and math.isfinite(scale) and scale > 0):
            raise ValueError(f"Hull {name!r}: scale must be a finite number > 0, got {scale!r}")
        return cls(np.asarray(mesh.vertices) * scale, np.asarray(mesh.faces), name=name)

    @classmethod
    def from_file(cls, path: str | os.PathLike, *, scale: float = 1.0, name: str | None = None) -> "Hull":
        """Load OBJ, STL, PLY, OFF, GLB or GLTF, multiplied by ``scale``; a folder, another format, a file
        that does not parse and NaN or infinite vertices are refused (``ocean_warp.mesh_files``)."""
        path = os.fspath(path)
        loaded = read_mesh_file("Hull.from_file", path)
        return cls.from_trimesh(loaded, name=name or os.path.splitext(os.path.basename(path))[0], scale=scale)

    @classmethod
    def box(cls, length: float, beam: float, height: float, *, subdivisions: int = 0, name: str = "box") -> "Hull":
        """A box centred on the origin: ``length`` along x, ``beam`` along y, ``height`` along z [m];
        each subdivision splits every triangle in four."""
        _require_positive_sizes(name, length=length, beam=beam, height=height)
        mesh = trimesh.creation.box(extents=[length, beam, height])
        return cls.from_trimesh(_subdivided(mesh, subdivisions), name=name)

    @classmethod
    def ellipsoid(cls, semi_x: float, semi_y: float, semi_z: float, *, subdivisions: int = 3,
                  name: str = "ellipsoid") -> "Hull":
        """An ellipsoid centred on the origin with the given semi-axes [m], from an icosphere of
        ``subdivisions`` (20 * 4**subdivisions triangles)."""
        _require_positive_sizes(name, semi_x=semi_x, semi_y=semi_y, semi_z=semi_z)
        mesh = trimesh.creation.icosphere(subdivisions=_subdivision_count(name, subdivisions), radius=1.0)
        mesh.apply_scale([semi_x, semi_y, semi_z])
        return cls.from_trimesh(mesh, name=name)

    @classmethod
    def sphere(cls, radius: float, *, subdivisions: int = 3, name: str = "sphere") -> "Hull":
        """A sphere of ``radius`` [m] centred on the origin (an icosphere, vertices on the sphere)."""
        return cls.ellipsoid(radius, radius, radius, subdivisions=subdivisions, name=name)

    @classmethod
    def cylinder(cls, radius: float, length: float, *, sections: int = 32, name: str = "cylinder") -> "Hull":
        """A cylinder of ``radius`` and ``length`` [m] along x, centred on the origin."""
        _require_positive_sizes(name, radius=radius, length=length)
        if not isinstance(sections, int) or sections < 3:
            raise ValueError(f"Hull {name!r}: sections must be an integer >= 3, got {sections!r}")
        mesh = trimesh.creation.cylinder(radius=radius, height=length, sections=sections)
        mesh.apply_transform(trimesh.transformations.rotation_matrix(math.pi / 2, [0, 1, 0]))
        return cls.from_trimesh(mesh, name=name)

    # --- geometry -----------------------------------------------------------------------------------
    @property
    def vertices(self) -> np.ndarray:
        """(V, 3) vertex positions in the body frame [m]."""
        return np.asarray(self._mesh.vertices)

    @property
    def triangles(self) -> np.ndarray:
        """(T, 3) vertex indices, counter-clockwise seen from outside (normals point out)."""
        return np.asarray(self._mesh.faces, dtype=np.int32)

    @property
    def triangle_count(self) -> int:
        return len(self._mesh.faces)

    @property
    def vertex_count(self) -> int:
        return len(self._mesh.vertices)

    @property
    def volume(self) -> float:
        """Enclosed volume [m^3]."""
        return float(self._mesh.volume)

    @property
    def center_of_volume(self) -> np.ndarray:
        """Centroid of the enclosed volume in the body frame [m]: the centre of buoyancy when fully submerged."""
        return np.asarray(self._mesh.center_mass, dtype=np.float64)

    @property
    def surface_area(self) -> float:
        """Total area of the triangles [m^2]."""
        return float(self._mesh.area)

    @property
    def bounds(self) -> np.ndarray:
        """(2, 3) minimum and maximum corner of the bounding box [m]."""
        return np.asarray(self._mesh.bounds)

    @property
    def length(self) -> float:
        """Extent along x [m], the reference length of the hull's Reynolds number."""
        return float(np.ptp(self._mesh.vertices[:, 0]))

    def solid_inertia(self, mass: float) -> np.ndarray:
        """(3, 3) inertia tensor [kg m^2] of the enclosed volume as a uniform solid of ``mass`` [kg],
        about its centre of volume, body axes."""
        if not (isinstance(mass, (int, float)) and math.isfinite(mass) and mass > 0):
            raise ValueError(f"Hull {self.name!r}: mass must be a finite number > 0 [kg], got {mass!r}")
        return np.asarray(self._mesh.moment_inertia, dtype=np.float64) * (mass / self.volume)

    def to_trimesh(self) -> trimesh.Trimesh:
        """A copy of the physics mesh."""
        return self._mesh.copy()

    def __repr__(self) -> str:
        return (f"Hull({self.name!r}, {self.triangle_count} triangles, volume {self.volume:.4g} m^3, "
                f"extents {np.round(self._mesh.extents, 4).tolist()} m)")


def _require_positive_sizes(name: str, **sizes) -> None:
    for field, value in sizes.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
            raise ValueError(f"Hull {name!r}: {field} must be a finite number > 0 [m], got {value!r}")


def _subdivision_count(name: str, subdivisions) -> int:
    if isinstance(subdivisions, bool) or not isinstance(subdivisions, int) or not 0 <= subdivisions <= 7:
        raise ValueError(f"Hull {name!r}: subdivisions must be an integer in [0, 7], got {subdivisions!r}")
    return subdivisions


def _subdivided(mesh: trimesh.Trimesh, subdivisions: int) -> trimesh.Trimesh:
    for _ in range(_subdivision_count("box", subdivisions)):
        mesh = mesh.subdivide()
    return mesh


def _check_scale(name: str, vertices: np.ndarray) -> None:
    extent = float(np.ptp(vertices, axis=0).max())
    if extent > MAX_PLAUSIBLE_EXTENT:
        hint = " (millimetres? pass scale=0.001)" if extent > 1000.0 else " (centimetres? pass scale=0.01)"
        raise ValueError(f"Hull {name!r}: the mesh is {extent:.6g} units across, not a plausible boat in metres{hint}")
    if extent < MIN_PLAUSIBLE_EXTENT:
        raise ValueError(f"Hull {name!r}: the mesh is only {extent:.3g} units across; coordinates must be metres")


def _repaired(name: str, mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    """Remove degenerate triangles, close small holes, make the winding consistent and the normals
    point outward, warning for each; raise when the mesh stays open."""
    notes = []
    scale = float(np.ptp(mesh.vertices, axis=0).max())
    degenerate = mesh.area_faces <= 1e-12 * scale**2
    if degenerate.any():
        mesh.update_faces(~degenerate)
        mesh.remove_unreferenced_vertices()
        notes.append(f"removed {int(degenerate.sum())} degenerate triangles")
    if not mesh.is_watertight:
        trimesh.repair.fill_holes(mesh)
        if not mesh.is_watertight:
            open_edges = _open_edge_count(mesh)
            raise ValueError(f"Hull {name!r}: the mesh is not watertight ({open_edges} open edges) and trimesh could "
                             "not close it; the water needs a closed surface")
        notes.append("closed holes")
    if not mesh.is_winding_consistent:
        trimesh.repair.fix_winding(mesh)
        notes.append("made the triangle winding consistent")
    if mesh.volume < 0:
        mesh.invert()
        notes.append("turned inward-facing normals outward")
    if notes:
        warnings.warn(f"Hull {name!r}: {'; '.join(notes)}", HullRepairWarning, stacklevel=3)
    return mesh


def _open_edge_count(mesh: trimesh.Trimesh) -> int:
    edges = np.sort(mesh.edges, axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    return int(np.sum(counts == 1))
