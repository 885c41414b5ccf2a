"""A hull's form below a waterline: the particulars a naval architect's resistance methods read.

Measured on the mesh itself (host side, numpy: the triangles are clipped exactly at the plane and the
integrals closed with the divergence theorem, the waterplane contributing nothing to them), upright, with the still-water plane at body height
``waterline_z``. The names follow the Delft Systematic Yacht Hull Series papers (Keuning and
Sonnenberg 1998; Keuning and Katgert 2008): Lwl, Bwl, Tc, the canoe body's displaced volume, its
waterplane area Aw and wetted area Sc, the midship coefficient Cm, the prismatic coefficient Cp and the
longitudinal centres of buoyancy and flotation as fractions of Lwl aft of the forward end of the
waterline.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .hull import Hull
from .validation import require_finite, require_positive

__all__ = ["HullForm", "Topsides", "measure_hull_form", "measure_topsides", "displaced_volume", "floating_waterline",
           "clip_triangles", "areas_and_normals"]

_SECTION_STATIONS = 100
"""Transverse cuts at which the submerged volume aft of them is measured (its derivative is the section
area)."""


@dataclasses.dataclass(frozen=True)
class HullForm:
    """Particulars of the immersed canoe body [m, m^2, m^3]; fractions dimensionless."""

    waterline_length: float
    """Lwl [m]."""
    waterline_beam: float
    """Bwl [m]."""
    canoe_draft: float
    """Tc, waterline to the lowest point of the canoe body [m]."""
    displaced_volume: float
    """Canoe body volume below the waterline [m^3]."""
    waterplane_area: float
    """Aw [m^2]."""
    wetted_area: float
    """Sc, the canoe body's wetted surface [m^2]."""
    max_section_area: float
    """Largest submerged transverse section [m^2]."""
    lcb_fraction: float
    """Centre of buoyancy aft of the forward end of the waterline, as a fraction of Lwl."""
    lcf_fraction: float
    """Centre of flotation aft of the forward end of the waterline, as a fraction of Lwl."""
    center_of_buoyancy: tuple
    """(x, y, z) in the body frame [m]."""
    waterline_forward_x: float
    """Body x of the forward end of the waterline [m]."""

    @property
    def midship_coefficient(self) -> float:
        """Cm = Amax / (Bwl Tc)."""
        return self.max_section_area / (self.waterline_beam * self.canoe_draft)

    @property
    def prismatic_coefficient(self) -> float:
        """Cp = volume / (Amax Lwl)."""
        return self.displaced_volume / (self.max_section_area * self.waterline_length)

    @property
    def length_displacement_ratio(self) -> float:
        """Lwl / volume^(1/3) (ORC's LVR)."""
        return self.waterline_length / self.displaced_volume ** (1.0 / 3.0)

    @property
    def beam_draft_ratio(self) -> float:
        """Bwl / Tc (ORC's BTR)."""
        return self.waterline_beam / self.canoe_draft


def clip_triangles(triangles: np.ndarray, distance: np.ndarray) -> np.ndarray:
    """The parts of ``triangles`` (T, 3, 3) where the per-corner ``distance`` (T, 3), linear over each
    triangle, is positive: (P, 3, 3) triangles with the input's winding."""
    inside = distance > 0.0
    count = inside.sum(axis=1)
    pieces = [triangles[count == 3]]
    for kept in (1, 2):
        chosen = count == kept
        tri, dist, ins = triangles[chosen], distance[chosen], inside[chosen]
        if len(tri) == 0:
            continue
        # Rotate each triangle so that corner 0 is the odd one (alone on its side); winding is kept.
        odd = np.argmax(ins if kept == 1 else ~ins, axis=1)
        order = (odd[:, None] + np.arange(3)[None, :]) % 3
        rows = np.arange(len(tri))[:, None]
        a, b, c = (tri[rows, order][:, i] for i in range(3))
        da, db, dc = (dist[rows, order][:, i] for i in range(3))
        ab = a + (da / (da - db))[:, None] * (b - a)
        ac = a + (da / (da - dc))[:, None] * (c - a)
        if kept == 1:
            pieces.append(np.stack([a, ab, ac], axis=1))
        else:
            pieces.append(np.stack([ab, b, c], axis=1))
            pieces.append(np.stack([ab, c, ac], axis=1))
    return np.concatenate(pieces) if pieces else np.zeros((0, 3, 3))


def areas_and_normals(pieces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(P,) areas [m^2] and (P, 3) area-weighted outward normals of triangles (P, 3, 3)."""
    vector = 0.5 * np.cross(pieces[:, 1] - pieces[:, 0], pieces[:, 2] - pieces[:, 0])
    return np.linalg.norm(vector, axis=1), vector


def _volume_aft_of(wet: np.ndarray, station: float) -> float:
    """Submerged volume [m^3] aft of x = ``station``: the divergence theorem with (x - station, 0, 0),
    which vanishes on both cutting planes."""
    aft = clip_triangles(wet, station - wet[:, :, 0])
    _, vector = areas_and_normals(aft)
    return float(np.sum(vector[:, 0] * (aft[:, :, 0].mean(axis=1) - station)))


def _triangles(hull: Hull) -> np.ndarray:
    return hull.vertices[hull.triangles].astype(np.float64)


def _wet_volume(triangles: np.ndarray, waterline_z: float) -> float:
    wet = clip_triangles(triangles, waterline_z - triangles[:, :, 2])
    _, vector = areas_and_normals(wet)
    return float(np.sum(vector[:, 2] * (wet[:, :, 2].mean(axis=1) - waterline_z)))


def displaced_volume(hull: Hull, waterline_z: float) -> float:
    """Volume [m^3] of ``hull`` (upright) below the plane z = ``waterline_z`` [m]."""
    return _wet_volume(_triangles(hull), float(waterline_z))


def floating_waterline(hull: Hull, mass: float, density: float = 1025.0) -> float:
    """Body height z [m] of the still-water plane when ``hull`` floats upright holding ``mass`` [kg] in water
    of ``density`` [kg/m^3] (bisection on the displaced volume, to 1e-6 m)."""
    triangles = _triangles(hull)
    low, high = triangles[:, :, 2].min(), triangles[:, :, 2].max()
    target = require_positive("floating_waterline", "mass", mass, unit=" [kg]") / require_positive(
        "floating_waterline", "density", density, unit=" [kg/m^3]")
    if target >= _wet_volume(triangles, high - 1e-9):
        raise ValueError(f"floating_waterline: the hull's whole volume holds less than {mass} kg; it sinks")
    while high - low > 1e-6:
        middle = 0.5 * (low + high)
        low, high = (middle, high) if _wet_volume(triangles, middle) < target else (low, middle)
    return 0.5 * (low + high)


def measure_hull_form(hull: Hull, waterline_z: float = 0.0) -> HullForm:
    """The form of ``hull`` (closed mesh, body frame, upright) below the plane z = ``waterline_z`` [m]."""
    waterline_z = require_finite("measure_hull_form", "waterline_z", waterline_z)
    triangles = _triangles(hull)
    low, high = triangles[:, :, 2].min(), triangles[:, :, 2].max()
    if not low < waterline_z < high:
        raise ValueError(f"measure_hull_form: waterline_z must cut the hull, between {low:.4g} and {high:.4g} m; "
                         f"got {waterline_z!r}")
    wet = clip_triangles(triangles, waterline_z - triangles[:, :, 2])
    areas, vector = areas_and_normals(wet)
    depth = wet[:, :, 2] - waterline_z  # <= 0
    # Divergence theorem over the closed submerged body; the waterplane has depth 0 and no x or y normal.
    volume = float(np.sum(vector[:, 2] * depth.mean(axis=1)))
    x = wet[:, :, 0]
    x_squared = (np.sum(x * x, axis=1) + x[:, 0] * x[:, 1] + x[:, 1] * x[:, 2] + x[:, 0] * x[:, 2]) / 6.0
    buoyancy_x = float(np.sum(0.5 * vector[:, 0] * x_squared) / volume)
    d = depth
    depth_squared = (np.sum(d * d, axis=1) + d[:, 0] * d[:, 1] + d[:, 1] * d[:, 2] + d[:, 0] * d[:, 2]) / 6.0
    buoyancy_z = waterline_z + float(np.sum(0.5 * vector[:, 2] * depth_squared) / volume)
    # The waterplane closes the body: its area and first moment are minus those of the wet skin's z normals.
    waterplane = -float(np.sum(vector[:, 2]))
    flotation_x = -float(np.sum(vector[:, 2] * x.mean(axis=1))) / waterplane
    cut = wet[np.abs(depth) < 1e-9]
    forward_x, aft_x = cut[:, 0].max(), cut[:, 0].min()
    length = forward_x - aft_x
    stations = np.linspace(x.min(), x.max(), _SECTION_STATIONS + 1)
    aft_volume = np.array([_volume_aft_of(wet, s) for s in stations])
    max_section = float(np.max(np.gradient(aft_volume, stations)))
    return HullForm(
        waterline_length=float(length), waterline_beam=float(np.ptp(cut[:, 1])),
        canoe_draft=float(waterline_z - low), displaced_volume=volume, waterplane_area=waterplane,
        wetted_area=float(areas.sum()), max_section_area=max_section,
        lcb_fraction=float((forward_x - buoyancy_x) / length), lcf_fraction=float((forward_x - flotation_x) / length),
        center_of_buoyancy=(buoyancy_x, 0.0, buoyancy_z), waterline_forward_x=float(forward_x))


@dataclasses.dataclass(frozen=True)
class Topsides:
    """The hull above its waterline as the wind sees it (upright) [m^2, m]."""

    area_ahead: float
    """Projected area on a transverse plane (the wind from ahead) [m^2]."""
    area_abeam: float
    """Projected area on the centre plane (the wind from abeam) [m^2]."""
    center_abeam: tuple
    """(x, y, z) of the abeam projection's centroid, body frame [m]."""


def measure_topsides(hull: Hull, waterline_z: float = 0.0) -> Topsides:
    """Projected areas of ``hull`` (closed, upright) above the plane z = ``waterline_z`` [m]. A closed surface
    covers its silhouette twice, so each projection is half the sum of |n . d| dA over the dry skin."""
    waterline_z = require_finite("measure_topsides", "waterline_z", waterline_z)
    triangles = _triangles(hull)
    dry = clip_triangles(triangles, triangles[:, :, 2] - waterline_z)
    if len(dry) == 0:
        raise ValueError(f"measure_topsides: waterline_z {waterline_z!r} m is above the hull")
    _, vector = areas_and_normals(dry)
    abeam = np.abs(vector[:, 1])
    centroid = dry.mean(axis=1)
    center = (centroid * abeam[:, None]).sum(axis=0) / abeam.sum()
    return Topsides(area_ahead=float(0.5 * np.abs(vector[:, 0]).sum()), area_abeam=float(0.5 * abeam.sum()),
                    center_abeam=(float(center[0]), 0.0, float(center[2])))
