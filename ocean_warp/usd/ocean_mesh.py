"""The ocean surface as a USD mesh: a lattice of the ocean's own grid nodes (every ``stride``-th) over a
rectangle of the world, displaced as the ocean displaces them, one time sample per frame.

The ocean's patch is periodic, so the lattice may cover any rectangle: node (ix, iy) of the lattice reads
grid node (ix mod n, iy mod n). Because the vertices are grid nodes, they carry the ocean's fields
exactly (no interpolation): vertex (ix, iy) sits at (ix h + c Dx, iy h + c Dy, eta) for grid spacing h,
choppiness c, horizontal displacement D and height eta at that node. Decimation (stride > 1) drops the
waves shorter than about two lattice spacings from view; it does not filter them.

Size: float arrays are stored uncompressed, so each frame costs 12 bytes per vertex for the points, as
much again for colours and for normals.

The first frame written is also each attribute's default value, so the mesh has a shape at the default
time (and before any sample, for a reader that asks there); in a layer, time samples win over the default.
The mesh's material (:mod:`~ocean_warp.usd.materials`) takes its colours from the per-vertex
displayColor when there is one, else it is a plain sea colour.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from pxr import Gf, Kind, Usd, UsdGeom, Vt

from ..kernels.ocean_spectrum import FIELD_DISPLACEMENT, FIELD_HEIGHT, FIELD_SLOPE
from ..ocean import Ocean
from ..ocean_config import OceanConfig
from .materials import LOOKS_BY_NAME, bind_look, define_look, define_vertex_color_look

__all__ = ["OceanLattice", "OceanMeshWriter", "ocean_fields_at", "height_colors", "check_extent",
           "define_referenced_ocean", "bind_ocean_look"]

_DEEP = np.array([0.02, 0.12, 0.30])
_MEAN = np.array(LOOKS_BY_NAME["Sea"].color)
_CREST = np.array([0.80, 0.93, 0.97])


def check_extent(owner: str, extent, *, field: str = "extent") -> tuple[float, float, float, float]:
    """``extent`` as (xmin, xmax, ymin, ymax) [m] of finite numbers with xmax > xmin and ymax > ymin, else
    ValueError naming ``owner.field``."""
    try:
        values = tuple(float(v) for v in extent)
    except (TypeError, ValueError):
        raise ValueError(f"{owner}.{field} must be (xmin, xmax, ymin, ymax) [m], got {extent!r}") from None
    if len(values) != 4 or not all(math.isfinite(v) for v in values) or values[1] <= values[0] \
            or values[3] <= values[2]:
        raise ValueError(f"{owner}.{field} must be (xmin, xmax, ymin, ymax) [m], finite, with xmax > xmin and "
                         f"ymax > ymin, got {extent!r}")
    return values


@dataclasses.dataclass(frozen=True)
class OceanLattice:
    """Which grid nodes the mesh's vertices are: ``ix`` (nx,) and ``iy`` (ny,) unwrapped grid indices (world
    x = ix * cell_size), every ``stride``-th node. Vertex v = j nx + i is node (ix[i], iy[j])."""

    cell_size: float
    """Ocean grid spacing [m]."""
    grid_resolution: int
    """Ocean grid points per side (the indices wrap modulo this)."""
    stride: int
    """Grid cells between neighbouring vertices."""
    ix: np.ndarray
    iy: np.ndarray

    @classmethod
    def covering(cls, config: OceanConfig, extent, resolution: int) -> "OceanLattice":
        """The finest lattice that covers ``extent`` (xmin, xmax, ymin, ymax) [m] with at most ``resolution``
        vertices along either side: it starts at the grid node at or below (xmin, ymin), and its spacing is
        the smallest whole number of grid cells that reaches past (xmax, ymax) in that many vertices."""
        xmin, xmax, ymin, ymax = check_extent("OceanLattice", extent)
        if isinstance(resolution, bool) or not isinstance(resolution, int) or resolution < 2:
            raise ValueError(f"OceanLattice: resolution must be an integer >= 2, got {resolution!r}")
        cell = config.cell_size
        first = (math.floor(xmin / cell + 1e-9), math.floor(ymin / cell + 1e-9))
        # Cells from the first node to past the far side, along x and y.
        cells = (math.ceil(xmax / cell - 1e-9) - first[0], math.ceil(ymax / cell - 1e-9) - first[1])
        stride = max(1, math.ceil(max(cells) / (resolution - 1)))
        counts = [math.ceil(c / stride) + 1 for c in cells]
        return cls(cell_size=cell, grid_resolution=config.resolution, stride=stride,
                   ix=first[0] + stride * np.arange(counts[0]), iy=first[1] + stride * np.arange(counts[1]))

    @property
    def shape(self) -> tuple[int, int]:
        """(ny, nx) vertices."""
        return len(self.iy), len(self.ix)

    @property
    def vertex_count(self) -> int:
        return len(self.ix) * len(self.iy)

    @property
    def spacing(self) -> float:
        """Distance between neighbouring vertices before displacement [m]."""
        return self.stride * self.cell_size

    def topology(self) -> tuple[np.ndarray, np.ndarray]:
        """(face vertex counts, face vertex indices): one quad per lattice cell, counter-clockwise seen from
        above (normals up)."""
        ny, nx = self.shape
        corner = (np.arange(ny - 1)[:, None] * nx + np.arange(nx - 1)[None, :]).reshape(-1)
        indices = np.stack([corner, corner + 1, corner + 1 + nx, corner + nx], axis=1).reshape(-1)
        return np.full(len(corner), 4, dtype=np.int32), indices.astype(np.int32)

    def surface(self, fields: np.ndarray, choppiness: float, *, normals: bool = False):
        """Vertex positions (M, 3) [m] and, with ``normals``, unit upward normals (M, 3) (else None) of the
        displaced surface, from the ocean's host fields ``fields`` (4, n, n, 2) (``Ocean.fields.numpy()``)."""
        n = self.grid_resolution
        rows, cols = np.ix_(self.iy % n, self.ix % n)
        height = fields[FIELD_HEIGHT, :, :, 0][rows, cols]
        dx = fields[FIELD_DISPLACEMENT, :, :, 0]
        dy = fields[FIELD_DISPLACEMENT, :, :, 1]
        x = (self.ix * self.cell_size)[None, :] + choppiness * dx[rows, cols]
        y = (self.iy * self.cell_size)[:, None] + choppiness * dy[rows, cols]
        points = np.stack([x, y, height], axis=-1).reshape(-1, 3)
        if not normals:
            return points, None
        # The tangents d(q + c D, eta)/dq at the node, D's gradient by central differences over the grid
        # (what ``ocean_surface.surface_normal`` evaluates at a node).
        east, west = np.ix_(self.iy % n, (self.ix + 1) % n), np.ix_(self.iy % n, (self.ix - 1) % n)
        north, south = np.ix_((self.iy + 1) % n, self.ix % n), np.ix_((self.iy - 1) % n, self.ix % n)
        scale = choppiness / (2.0 * self.cell_size)
        tangent_x = np.stack([1.0 + scale * (dx[east] - dx[west]), scale * (dy[east] - dy[west]),
                              fields[FIELD_SLOPE, :, :, 0][rows, cols]], axis=-1)
        tangent_y = np.stack([scale * (dx[north] - dx[south]), 1.0 + scale * (dy[north] - dy[south]),
                              fields[FIELD_SLOPE, :, :, 1][rows, cols]], axis=-1)
        normal = np.cross(tangent_x, tangent_y).reshape(-1, 3)
        return points, normal / np.linalg.norm(normal, axis=1, keepdims=True)


def ocean_fields_at(ocean: Ocean, time_s: float) -> np.ndarray:
    """The ocean's fields (4, n, n, 2) at ``time_s`` [s] on the host. Evaluates them on the device and leaves
    them there at ``time_s``, but puts the ocean's clock (``ocean.time``) back as it was, so a simulator
    sharing the ocean keeps its time (its next step evaluates the fields again anyway)."""
    clock = float(ocean.time.numpy()[0])
    ocean.update(float(time_s))
    fields = ocean.fields.numpy()
    ocean.time.fill_(clock)
    return fields


def height_colors(heights: np.ndarray, half_range: float) -> np.ndarray:
    """(M, 3) colours in 0-1 for surface heights (M,) [m]: deep blue at -``half_range`` [m] and below, sea
    blue at 0, foam white at +``half_range`` and above."""
    s = np.clip(np.asarray(heights, dtype=np.float64) / half_range, -1.0, 1.0)[:, None]
    return np.where(s < 0.0, _MEAN + (-s) * (_DEEP - _MEAN), _MEAN + s * (_CREST - _MEAN))


def bind_ocean_look(prim, *, colors: bool) -> None:
    """Bind the ocean's material to ``prim``: the per-vertex displayColor through a primvar reader when the
    mesh has ``colors``, else the plain sea colour."""
    stage = prim.GetStage()
    bind_look(prim, define_vertex_color_look(stage, "Ocean") if colors else define_look(stage, "Sea"))


def define_referenced_ocean(stage, path: str, rest_path: str, *, colors: bool) -> UsdGeom.Mesh:
    """The ocean mesh at ``path`` as a reference to the mesh at ``rest_path`` (its topology and still values,
    written by an :class:`OceanMeshWriter` with ``model=False``): a ``component`` model with the ocean's
    material, whose animation comes from stronger opinions authored later (value clips)."""
    mesh = UsdGeom.Mesh.Define(stage, path)
    prim = mesh.GetPrim()
    prim.GetReferences().AddInternalReference(rest_path)
    Usd.ModelAPI(prim).SetKind(Kind.Tokens.component)
    bind_ocean_look(prim, colors=colors)
    return mesh


class OceanMeshWriter:
    """Authors the ocean mesh at ``path``: topology once, then :meth:`write` adds one frame (points, extent and
    optionally vertex normals and a displayColor by height) at a time code, the first one also as the
    default values. ``model``: make the mesh a ``component`` model with the ocean's material (False for a
    mesh that others reference)."""

    def __init__(self, stage, path: str, lattice: OceanLattice, *, choppiness: float, normals: bool,
                 colors: bool, color_range: float, model: bool = True):
        self.lattice = lattice
        self.choppiness = float(choppiness)
        self.color_range = float(color_range)
        self.mesh = UsdGeom.Mesh.Define(stage, path)
        counts, indices = lattice.topology()
        self.mesh.CreateFaceVertexCountsAttr(Vt.IntArray.FromNumpy(counts))
        self.mesh.CreateFaceVertexIndicesAttr(Vt.IntArray.FromNumpy(indices))
        self.mesh.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
        self._points = self.mesh.CreatePointsAttr()
        self._extent = self.mesh.CreateExtentAttr()
        self._normals = None
        if normals:
            self._normals = self.mesh.CreateNormalsAttr()
            self.mesh.SetNormalsInterpolation(UsdGeom.Tokens.vertex)
        self._colors = self.mesh.CreateDisplayColorPrimvar(UsdGeom.Tokens.vertex) if colors else None
        if model:
            Usd.ModelAPI(self.mesh.GetPrim()).SetKind(Kind.Tokens.component)
            bind_ocean_look(self.mesh.GetPrim(), colors=colors)
        self._has_default = False

    def write(self, time_code: float | None, fields: np.ndarray) -> np.ndarray:
        """Add the surface of the host fields ``fields`` (4, n, n, 2) at ``time_code`` (None: as the default
        values only); the first surface written is also the default values. Returns its points [m]."""
        points, normals = self.lattice.surface(fields, self.choppiness, normals=self._normals is not None)
        points32 = points.astype(np.float32)
        low, high = points32.min(axis=0), points32.max(axis=0)
        values = [(self._points, Vt.Vec3fArray.FromNumpy(points32)),
                  (self._extent, Vt.Vec3fArray([Gf.Vec3f(*map(float, low)), Gf.Vec3f(*map(float, high))]))]
        if self._normals is not None:
            values.append((self._normals, Vt.Vec3fArray.FromNumpy(normals.astype(np.float32))))
        if self._colors is not None:
            colors = height_colors(points[:, 2], self.color_range).astype(np.float32)
            values.append((self._colors, Vt.Vec3fArray.FromNumpy(colors)))
        for attribute, value in values:
            if not self._has_default:
                attribute.Set(value)
            if time_code is not None:
                attribute.Set(value, time_code)
        self._has_default = True
        return points
