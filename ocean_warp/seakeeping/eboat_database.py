"""The E-Boat's hydrodynamic database, shipped with the package (``ocean_warp/eboat/eboat_hydrodynamics.json``).

It was computed for the default physics hull (``EBoat().hull``, the real boat's canoe body) at its rest pose,
upright in sea water (1025 kg/m^3), holding what the mesh carries (the boat's 158.45 kg less the 8.5 kg of water
its keel fin, bulb and rudder displace: ``EBoat.hull_load``), by the command that regenerates it (one to two
minutes on two cores):

    ocean-warp bem --out ocean_warp/eboat/eboat_hydrodynamics.json

The appendages are not in the mesh: their added mass and wave loads are not in the database (the keel and
rudder are lifting surfaces in the simulator). Above about 9 rad/s the panels no longer resolve the waves
(``provenance["resolved_up_to_rad_s"]``) and A(w), B(w) there are unreliable; the fits use 0.3-8.8 rad/s.

A change of the E-Boat's hull changes its fingerprint: :func:`eboat_hydro_database` with that hull then refuses
the file until it is regenerated.
"""

from __future__ import annotations

import importlib.resources

from .database import HydroDatabase

__all__ = ["EBOAT_DATABASE_FILE", "eboat_hydro_database"]

EBOAT_DATABASE_FILE = "eboat_hydrodynamics.json"
"""The file's name in the package ``ocean_warp.eboat``."""


def eboat_hydro_database(hull=None) -> HydroDatabase:
    """The shipped E-Boat database; with ``hull`` (an :class:`ocean_warp.Hull`), checked to be that mesh's
    (``ValueError`` otherwise)."""
    resource = importlib.resources.files("ocean_warp.eboat").joinpath(EBOAT_DATABASE_FILE)
    with importlib.resources.as_file(resource) as path:
        return HydroDatabase.load(path, hull=hull)
