"""The WAM-V's boat type (pontoon mesh, mass properties, damping, added mass) and water model per profile.

The physics profile's hydrodynamic database, ``ocean_warp/wamv/wamv_hydrodynamics.json``, was computed for the
default pontoon mesh (``wamv_hull_mesh(WamvConfig())``) floating upright at rest with VRX's 180 kg in sea water
(1025 kg/m^3), by the project's BEM command on that mesh written to an OBJ file:

    ocean-warp bem --hull wamv_pontoons.obj --mass 180 --out ocean_warp/wamv/wamv_hydrodynamics.json

A change of the default mesh changes its fingerprint: :func:`wamv_hydro_database` then refuses the file until it
is regenerated.
"""

from __future__ import annotations

import importlib.resources

import numpy as np

from ..boat_type import BoatType
from ..hull import Hull
from ..hydrodynamics_config import HydrodynamicsConfig
from ..seakeeping.database import HydroDatabase
from ..eboat.eboat import Profile as EBoatProfile, eboat_hydrodynamics
from . import figures
from .config import WamvConfig, WamvProfile
from .hull_mesh import wamv_hull_mesh
from .wave_resistance import wamv_wave_resistance

__all__ = ["WAMV_DATABASE_FILE", "wamv_hydro_database", "wamv_boat_type", "wamv_hydrodynamics"]

WAMV_DATABASE_FILE = "wamv_hydrodynamics.json"
"""The database's file name in the package ``ocean_warp.wamv``."""


def wamv_hydro_database(hull: Hull | None = None) -> HydroDatabase:
    """The shipped WAM-V database; with ``hull``, checked to be that mesh's (``ValueError`` otherwise)."""
    resource = importlib.resources.files("ocean_warp.wamv").joinpath(WAMV_DATABASE_FILE)
    with importlib.resources.as_file(resource) as path:
        return HydroDatabase.load(path, hull=hull)


def wamv_hydrodynamics(config: WamvConfig) -> HydrodynamicsConfig:
    """The per-triangle water model of ``config``'s profile: the E-Boat physics profile's cross-flow drag, form
    factor and ITTC friction (their viscous part alone when the database's radiation damps the hull), or, for
    "vrx", hydrostatic pressure alone (VRX's lumped damping stands for the rest)."""
    if config.profile is WamvProfile.VRX:
        return HydrodynamicsConfig().without_drag()
    return eboat_hydrodynamics(EBoatProfile.PHYSICS, radiation=config.uses_hydro_database)


def wamv_boat_type(config: WamvConfig, hull: Hull | None = None) -> BoatType:
    """The WAM-V of ``config`` as a :class:`BoatType` on ``hull`` (default ``wamv_hull_mesh(config)``): its mass,
    principal inertia and centre of mass; "vrx": VRX's lumped damping and added mass
    (``figures.VRX_LINEAR_DAMPING``...); "physics": the database's added mass and radiation with
    ``seakeeping``, else none (the mesh's drag damps it), and the pontoons' wave resistance with
    ``wave_resistance``."""
    hull = hull if hull is not None else wamv_hull_mesh(config)
    fields = {}
    if config.profile is WamvProfile.VRX:
        fields = dict(linear_damping=figures.VRX_LINEAR_DAMPING, quadratic_damping=figures.VRX_QUADRATIC_DAMPING,
                      added_mass=figures.VRX_ADDED_MASS)
    else:
        if config.uses_hydro_database:
            fields["seakeeping"] = wamv_hydro_database(hull)
        if config.wave_resistance:
            fields["residuary"] = wamv_wave_resistance(config, hull)
    return BoatType(hull=hull, mass=config.mass, center_of_mass=config.center_of_mass,
                    inertia=np.diag(config.inertia), name=f"wamv {config.profile.value}", **fields)
