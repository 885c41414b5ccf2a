"""The E-Boat digital twin: a 2.5 m autonomous sailing robot (sail on a boom, keel, rudder, electric
propeller), rebuilt from the data sheet of its original Gazebo model."""

from .eboat import EBoat, EBoatConfig, Hydrostatics, Profile, eboat_hydrodynamics, load_foil_table
from .geometry import Ballast, EBoatGeometry, HullKind
from .hull_shape import HullShape, eboat_hull
from .offsets_hull import offsets_hull
from .mass_properties import MassProperties, eboat_mass_properties
from .reef import ReefedSail, reefed_sail
from .sheet import Version
from .eboat_simulator import EBoatSimulator, SailingRig
from .simulator_config import EBoatSimulatorConfig, still_water
from .state import EBoatControl, EBoatStart, EBoatState, EBoatTensors
from .vessel import EBOAT_ACTIONS, MASTHEAD_MOUNT, EBoatVessel

__all__ = ["EBoat", "EBoatConfig", "Hydrostatics", "Profile", "Version", "EBoatSimulator", "EBoatSimulatorConfig",
           "EBoatState", "EBoatControl", "EBoatStart", "EBoatTensors", "SailingRig", "HullShape", "eboat_hull",
           "HullKind", "Ballast", "EBoatGeometry", "offsets_hull", "MassProperties", "eboat_mass_properties",
           "load_foil_table", "eboat_hydrodynamics", "still_water", "ReefedSail", "reefed_sail",
           "EBoatVessel", "EBOAT_ACTIONS", "MASTHEAD_MOUNT"]
