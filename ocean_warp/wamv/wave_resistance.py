"""The WAM-V's wave-making resistance: Michell's thin-ship integral for its pair of pontoons
(``ocean_warp.thin_ship``), tabulated over the Froude number for the hull kernel.

The physics profile's per-triangle model resists motion ahead with friction only; the waves the pontoons make
come from their own mesh here: the half-breadths of one pontoon below the waterline at which it floats with
the boat's mass, and the pair at the pontoons' spacing (their interference included). The pontoons of the
mesh have flat ends, so the waterline's half-breadth steps at bow and stern: in thin-ship theory such a blunt
end makes waves whose resistance grows as U^2 from rest and stays near 50 N for the pair from Fn 0.2 on.
"""

from __future__ import annotations

import numpy as np

from ..hull import Hull
from ..hull_form import floating_waterline, measure_hull_form
from ..resistance import ResiduaryResistance
from ..thin_ship import HullOffsets, mesh_offsets, michell_residuary
from .config import WamvConfig
from .hull_mesh import wamv_hull_mesh

__all__ = ["pontoon_offsets", "wamv_wave_resistance", "SEA_WATER_DENSITY"]

SEA_WATER_DENSITY = 1025.0
"""[kg/m^3] The water the pontoons float in when their offsets are taken (as the hydrodynamic database's)."""


def _left_pontoon(hull: Hull) -> np.ndarray:
    """(T, 3) the triangles of the pontoon on the port side (y > 0)."""
    triangles = hull.triangles
    return triangles[hull.vertices[triangles].mean(axis=1)[:, 1] > 0.0]


def pontoon_offsets(config: WamvConfig | None = None, hull: Hull | None = None, *,
                    density: float = SEA_WATER_DENSITY) -> HullOffsets:
    """One pontoon's half-breadths below the still-water plane when the WAM-V of ``config`` (default VRX's) floats
    upright at rest on ``hull`` (default ``wamv_hull_mesh(config)``) in water of ``density`` [kg/m^3]."""
    config = config if config is not None else WamvConfig()
    hull = hull if hull is not None else wamv_hull_mesh(config)
    waterline = floating_waterline(hull, config.mass, density)
    return mesh_offsets(hull.vertices, _left_pontoon(hull), waterline)


def wamv_wave_resistance(config: WamvConfig | None = None, hull: Hull | None = None, *,
                         density: float = SEA_WATER_DENSITY) -> ResiduaryResistance:
    """Michell's wave resistance of the pair of pontoons ``config.pontoon_spacing`` apart, as the hull kernel's
    table: r = R / (rho g volume) over Fn = U / sqrt(g L), L the pontoon's length, volume the boat's displacement
    at rest (both pontoons), acting at their centre of buoyancy (about 0.23 s to compute)."""
    config = config if config is not None else WamvConfig()
    hull = hull if hull is not None else wamv_hull_mesh(config)
    waterline = floating_waterline(hull, config.mass, density)
    form = measure_hull_form(hull, waterline)
    offsets = mesh_offsets(hull.vertices, _left_pontoon(hull), waterline)
    return michell_residuary(offsets, separation=config.pontoon_spacing, hulls=2, volume=form.displaced_volume,
                             center=form.center_of_buoyancy)
