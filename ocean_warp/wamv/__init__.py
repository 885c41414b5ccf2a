"""VRX's WAM-V on the core: twin-pontoon hull, VRX's thrusters and lumped hydrodynamics, a Vessel preset."""

from . import figures
from .boat import WAMV_DATABASE_FILE, wamv_boat_type, wamv_hydro_database, wamv_hydrodynamics
from .config import ThrusterLayout, WamvConfig, WamvProfile
from .hull_mesh import section_radius, wamv_hull_mesh
from .simulator import WamvSimulator
from .simulator_config import WamvSimulatorConfig
from .state import WamvControl, WamvStart, WamvState, WamvTensors
from .thrusters import Thrusters
from .wamv import Wamv

__all__ = ["figures", "WAMV_DATABASE_FILE", "wamv_boat_type", "wamv_hydro_database", "wamv_hydrodynamics",
           "ThrusterLayout", "WamvConfig", "WamvProfile", "section_radius", "wamv_hull_mesh", "WamvSimulator",
           "WamvSimulatorConfig", "WamvControl", "WamvStart", "WamvState", "WamvTensors", "Thrusters", "Wamv"]
