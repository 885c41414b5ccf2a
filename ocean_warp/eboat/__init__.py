"""The E-Boat digital twin: a 2.5 m autonomous sailing robot (sail on a boom, keel, rudder, electric
propeller), rebuilt from the data sheet of its original Gazebo model."""

from .eboat import EBoat, EBoatConfig, Hydrostatics, load_foil_table
from .hull_shape import HullShape, eboat_hull
from .mass_properties import MassProperties, eboat_mass_properties
from .sheet import Version
from .simulator import EBoatSimulator, EBoatTensors, SailingRig

__all__ = ["EBoat", "EBoatConfig", "Hydrostatics", "Version", "EBoatSimulator", "EBoatTensors", "SailingRig",
           "HullShape", "eboat_hull", "MassProperties", "eboat_mass_properties", "load_foil_table"]
