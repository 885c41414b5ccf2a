"""Seakeeping from potential flow: a hull's hydrodynamic database (added mass and damping over frequency, the
infinite-frequency added mass, state-space fits of the radiation memory for Cummins' equation, wave excitation),
computed offline by ``ocean-warp bem`` (capytaine, the optional extra ``[bem]``), stored as a small JSON file,
and the linear seakeeping (RAOs) it gives.

A hull without a database keeps its constant added mass and drag-only damping: :func:`database_for` says so.
The public names are imported on first use, so that ``ocean-warp bem --help`` loads nothing heavy.
"""

from ..lazy_names import lazy_attributes

_PUBLIC = {
    "FORMAT_VERSION": "database",
    "RadiationTerm": "database",
    "HydroDatabase": "database",
    "hull_fingerprint": "database",
    "database_for": "database",
    "NoHydroDatabaseWarning": "database",
    "KernelFit": "radiation_fit",
    "RadiationFit": "radiation_fit",
    "fit_kernel": "radiation_fit",
    "fit_radiation": "radiation_fit",
    "retardation_kernels": "radiation_fit",
    "BemResult": "bem",
    "compute_database": "bem",
    "rest_height_for_mass": "bem",
    "rigid_body_mass_matrix": "response",
    "hydrostatic_stiffness": "response",
    "response_amplitude_operators": "response",
    "natural_period": "response",
    "eboat_hydro_database": "eboat_database",
}

__getattr__, __dir__ = lazy_attributes(__name__, _PUBLIC)

__all__ = list(_PUBLIC)
