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

from .boat_type import BoatType  # noqa: E402
from .fleet import BoatStatus, Fleet, FleetTensors  # noqa: E402
from .hull import Hull, HullRepairWarning  # noqa: E402
from .hydrodynamics_config import HydrodynamicsConfig  # noqa: E402
from .ocean import FftPlan, Ocean, SurfaceSample  # noqa: E402
from .ocean_config import OceanConfig, Spectrum  # noqa: E402
from .water_config import WaterConfig  # noqa: E402
from .simulator import Simulator, SimulatorConfig  # noqa: E402
from .wave_grid import RegularWave  # noqa: E402
from .wind import Wind, WindConfig  # noqa: E402
from .sensors import CHANNEL_NAMES, SensorConfig, Sensors  # noqa: E402
from .eboat import EBoat, EBoatConfig, EBoatSimulator, EBoatSimulatorConfig  # noqa: E402

__all__ = [
    "Ocean", "OceanConfig", "WaterConfig", "Spectrum", "SurfaceSample", "RegularWave", "FftPlan",
    "Hull", "HullRepairWarning", "BoatType", "HydrodynamicsConfig",
    "Fleet", "FleetTensors", "BoatStatus", "Simulator", "SimulatorConfig",
    "Wind", "WindConfig", "Sensors", "SensorConfig", "CHANNEL_NAMES", "EBoat", "EBoatConfig", "EBoatSimulator",
    "EBoatSimulatorConfig",
]

__version__ = "0.1.0"
