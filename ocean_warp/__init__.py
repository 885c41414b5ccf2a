"""ocean_warp: fleets of robotic sailboats on a spectral ocean, as NVIDIA Warp kernels.

The same kernels run on CUDA GPUs and on the CPU. Host-side classes live here; the kernels in
``ocean_warp.kernels``; reinforcement-learning environments in ``ocean_warp.envs``.
"""

import importlib.util as _importlib_util
import os as _os
import sys as _sys


def _map_sibling_subpackages() -> None:
    """The installer maps the top-level folders kernels/ and envs/ to ocean_warp.kernels and
    ocean_warp.envs. Where that mapping is missing (a source checkout on sys.path, a legacy editable
    install), load them from beside this package under the same names."""
    root = _os.path.dirname(_os.path.dirname(_os.path.abspath(__file__)))
    for name in ("kernels", "envs"):
        qualified = f"{__name__}.{name}"
        if qualified in _sys.modules or _importlib_util.find_spec(qualified) is not None:
            continue
        init = _os.path.join(root, name, "__init__.py")
        if not _os.path.isfile(init):
            continue
        spec = _importlib_util.spec_from_file_location(qualified, init, submodule_search_locations=[_os.path.dirname(init)])
        module = _importlib_util.module_from_spec(spec)
        _sys.modules[qualified] = module
        spec.loader.exec_module(module)


_map_sibling_subpackages()

# The public names, each with the module that holds it. They are imported on first use (PEP 562), so that
# ``import ocean_warp.<light module>`` (the command line's parsers, ``ocean-warp --help``) does not load Warp.
_PUBLIC = {
    "BoatType": "boat_type",
    "BoatStatus": "fleet",
    "Fleet": "fleet",
    "FleetTensors": "fleet",
    "Hull": "hull",
    "HullRepairWarning": "hull",
    "HydrodynamicsConfig": "hydrodynamics_config",
    "FftPlan": "ocean",
    "Ocean": "ocean",
    "SurfaceSample": "ocean",
    "OceanConfig": "ocean_config",
    "Spectrum": "ocean_config",
    "WaterConfig": "water_config",
    "Simulator": "simulator",
    "SimulatorConfig": "simulator",
    "RegularWave": "wave_grid",
    "Wind": "wind",
    "WindConfig": "wind",
    "Current": "current",
    "CurrentConfig": "current_config",
    "CHANNEL_NAMES": "sensors",
    "SensorConfig": "sensors",
    "Sensors": "sensors",
    "EBoat": "eboat",
    "EBoatConfig": "eboat",
    "EBoatSimulator": "eboat",
    "EBoatSimulatorConfig": "eboat",
}


from .lazy_names import lazy_attributes  # noqa: E402

__getattr__, __dir__ = lazy_attributes(__name__, _PUBLIC)


__all__ = [
    "Ocean", "OceanConfig", "WaterConfig", "Spectrum", "SurfaceSample", "RegularWave", "FftPlan",
    "Hull", "HullRepairWarning", "BoatType", "HydrodynamicsConfig",
    "Fleet", "FleetTensors", "BoatStatus", "Simulator", "SimulatorConfig",
    "Wind", "WindConfig", "Current", "CurrentConfig", "Sensors", "SensorConfig", "CHANNEL_NAMES", "EBoat", "EBoatConfig",
    "EBoatSimulator",
    "EBoatSimulatorConfig",
]

__version__ = "0.1.0"
