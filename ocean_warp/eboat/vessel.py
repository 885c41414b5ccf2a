"""The E-Boat as a vessel (``ocean_warp.vessel``): its actions, its parts as a viewer sees them, its capsule."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..contact import boat_capsule
from ..meshes import concatenate
from ..vessel import ActionSpec, CollisionShape, PartScaling, VesselPart
from .eboat import MAST_LENGTH
from .eboat_simulator import EBoatSimulator
from .parts import BODY, BOOM, REEF, RUDDER, eboat_parts
from .sheet import MAST_STEP
from .simulator_config import EBoatSimulatorConfig

__all__ = ["EBoatVessel", "EBOAT_ACTIONS", "MASTHEAD_MOUNT"]

MASTHEAD_MOUNT = (MAST_STEP[0], 0.0, MAST_STEP[2] + MAST_LENGTH)
"""The top of the E-Boat's mast, 3.61 m above the waterline (body frame [m]): a 3D lidar's usual place."""

EBOAT_ACTIONS = (
    ActionSpec("propeller", "electric propeller level int(5 a), -5 .. 5 (astern .. ahead)"),
    ActionSpec("sheet", "sheet length as the boom's largest angle (a + 1) 45 deg, 0 .. 90 deg"),
    ActionSpec("rudder", "rudder angle 60 deg a, -60 .. 60 deg, + turns the boat to port"),
)
"""The E-Boat's three actions in [-1, 1], in column order (``ocean_warp.kernels.eboat_actions``)."""


@dataclasses.dataclass(frozen=True)
class EBoatVessel:
    """The E-Boat of ``config`` as a :class:`~ocean_warp.vessel.Vessel`: ``simulator(count)`` builds an
    :class:`~ocean_warp.eboat.EBoatSimulator`."""

    config: EBoatSimulatorConfig = dataclasses.field(default_factory=EBoatSimulatorConfig)
    name: str = "E-Boat"
    actions: tuple[ActionSpec, ...] = EBOAT_ACTIONS

    def __post_init__(self):
        if not isinstance(self.config, EBoatSimulatorConfig):
            raise ValueError(f"EBoatVessel.config must be an EBoatSimulatorConfig, got {self.config!r}")

    def simulator(self, count: int, *, device=None, first_boat: int = 0, ocean=None) -> EBoatSimulator:
        return EBoatSimulator(self.config, count, device=device, ocean=ocean, first_boat=first_boat)

    def parts(self, hull_detail: int = 2, *, rudder: bool = True) -> tuple[VesselPart, ...]:
        """Body (hull, keel, mast), the boom's spar and sail on ``boom_angle``, the rudder on ``rudder_angle``
        (``rudder`` False: without it, the parts the sensors saw before the vessel seam); the hull lofted at
        ``hull_detail`` (1: the physics mesh)."""
        meshes = eboat_parts(self.config.boat, hull_detail=hull_detail)
        boom_pivot = tuple(float(v) for v in meshes.boom_pivot)
        parts = (
            VesselPart(BODY, concatenate(meshes.hull, meshes.keel, meshes.mast)),
            VesselPart(BOOM, meshes.spar, joint="boom_angle", pivot=boom_pivot, material="metal"),
            VesselPart(REEF, meshes.sail, joint="boom_angle", pivot=boom_pivot, material="sail"),
        )
        if rudder:
            parts += (VesselPart(RUDDER, meshes.blade, joint="rudder_angle",
                                 pivot=tuple(float(v) for v in meshes.rudder_pivot), material="foil"),)
        return parts

    def part_scaling(self) -> PartScaling:
        """The sail (``REEF``) drawn at each boat's reef: scaled by ``reef_scales[reef_level]`` about its tack."""
        tack = eboat_parts(self.config.boat, hull_detail=1).sail_tack
        return PartScaling((REEF,), "reef_level", tuple(float(s) for s in self.config.boat.reef_scales),
                           tuple(float(v) for v in tack))

    def sensor_mounts(self) -> dict[str, tuple[float, float, float]]:
        """Where sensors sit (body frame [m]): ``masthead``, the top of the mast (see
        ``ocean_warp.vessel.sensor_mount``)."""
        return {"masthead": MASTHEAD_MOUNT}

    def collision_shape(self) -> CollisionShape:
        """The capsule of the physics hull (half beam radius, spanning its length)."""
        hull = eboat_parts(self.config.boat, hull_detail=1).hull.points
        stern, bow, radius = boat_capsule(np.asarray(hull))
        return CollisionShape(tuple(map(float, stern)), tuple(map(float, bow)), float(radius))
