"""The WAM-V as an ``ocean_warp.vessel.Vessel``: its actions, its look and its collision capsule."""

from __future__ import annotations

import numpy as np

from ..meshes import concatenate, extruded, tube
from ..vessel import ActionSpec, CollisionShape, VesselPart
from . import figures
from .config import ThrusterLayout
from .hull_mesh import section_radius
from .simulator import WamvSimulator
from .simulator_config import WamvSimulatorConfig

__all__ = ["Wamv"]


class Wamv:
    """VRX's WAM-V: two pontoons, a frame and deck, two stern thrusters (fixed or azimuth)."""

    name = "WAM-V"

    def __init__(self, config: WamvSimulatorConfig | None = None):
        """``config``: what every simulator of this vessel is built from (default ``WamvSimulatorConfig()``)."""
        self.config = config if config is not None else WamvSimulatorConfig()
        if not isinstance(self.config, WamvSimulatorConfig):
            raise ValueError(f"Wamv: config must be a WamvSimulatorConfig, got {self.config!r}")
        boat = self.config.boat
        thrust = f"-1 .. 1: {boat.max_reverse_thrust:g} N astern .. {boat.max_forward_thrust:g} N ahead (VRX's mapping)"
        actions = (ActionSpec("left_thrust", f"left (port) thruster's command, {thrust}"),
                   ActionSpec("right_thrust", f"right (starboard) thruster's command, {thrust}"))
        if boat.thrusters is ThrusterLayout.AZIMUTH:
            limit = np.degrees(boat.max_thruster_angle)
            actions += tuple(ActionSpec(f"{side}_angle", f"{side} thruster's angle, -{limit:.0f} .. {limit:.0f} deg, "
                                        "+ turns the boat to port") for side in ("left", "right"))
        self.actions: tuple[ActionSpec, ...] = actions

    def __eq__(self, other) -> bool:
        """Two WAM-Vs are the same vessel when they are built from equal configs."""
        return isinstance(other, Wamv) and other.config == self.config

    def __hash__(self) -> int:
        return hash(self.config)

    def __repr__(self) -> str:
        return f"Wamv({self.config!r})"

    def simulator(self, count: int, *, device=None, first_boat: int = 0, ocean=None) -> WamvSimulator:
        """``count`` WAM-Vs (boats [first_boat, first_boat + count) of a larger batch) on ``ocean`` (None: built)."""
        return WamvSimulator(self.config, count, device=device, ocean=ocean, first_boat=first_boat)

    def parts(self) -> tuple[VesselPart, ...]:
        """Pontoons, frame and deck (fixed, body frame) and each thruster's engine and propeller on its pivot, turning
        with ``thruster_angle`` column 0 (left) and 1 (right)."""
        boat = self.config.boat
        half, radius = 0.5 * boat.pontoon_length, boat.pontoon_radius
        pontoons = concatenate(*(tube((boat.pontoon_center_x - half, y, 0.0), (boat.pontoon_center_x + half, y, 0.0),
                                      radius, sides=boat.pontoon_sides)
                                 for y in (0.5 * boat.pontoon_spacing, -0.5 * boat.pontoon_spacing)))
        length, width, thickness = figures.DECK_SIZE
        deck_section = np.array([[-0.5 * length, -0.5 * width], [0.5 * length, -0.5 * width],
                                 [0.5 * length, 0.5 * width], [-0.5 * length, 0.5 * width]])
        deck = extruded(deck_section, figures.DECK_HEIGHT - 0.5 * thickness, figures.DECK_HEIGHT + 0.5 * thickness)
        struts = [tube((x, sign * 0.5 * boat.pontoon_spacing, radius), (x, sign * 0.5 * width, figures.DECK_HEIGHT),
                       0.04, sides=8) for x in (0.9, -0.7) for sign in (1.0, -1.0)]
        parts = [VesselPart("pontoons", pontoons), VesselPart("frame", concatenate(deck, *struts), material="metal")]
        offset = np.asarray(boat.propeller_offset)
        engine = concatenate(tube((0.0, 0.0, 0.1), (offset[0], 0.0, offset[2]), 0.05, sides=8),
                             tube(offset + (0.05, 0.0, 0.0), offset - (0.05, 0.0, 0.0), 0.12, sides=12))
        for column, (side, pivot) in enumerate(zip(("left", "right"), boat.engine_pivots)):
            parts.append(VesselPart(f"{side}_thruster", engine, joint="thruster_angle", pivot=tuple(pivot),
                                    joint_column=column, material="dark"))
        return tuple(parts)

    def collision_shape(self) -> CollisionShape:
        """The capsule that holds both pontoons: its axis along the centre line from their stern ends to their bow
        ends, its radius half the spacing plus a pontoon's (polygonal) section radius."""
        boat = self.config.boat
        radius = 0.5 * boat.pontoon_spacing + section_radius(boat.pontoon_radius, boat.pontoon_sides)
        half = 0.5 * boat.pontoon_length
        return CollisionShape(stern=(boat.pontoon_center_x - half, 0.0, 0.0),
                              bow=(boat.pontoon_center_x + half, 0.0, 0.0), radius=radius)
