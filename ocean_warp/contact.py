"""Contact: boats against the objects and other boats of their environment, as a force model of the simulator.

    scene = Scene.for_simulator(sim, objects=[SceneObject.pillar((6.0, 0.0), radius=0.5)], vessel=vessel)
    contact = Contact(scene, ContactConfig(), shape=vessel.collision_shape())
    sim.simulator.add_model(contact)             # flags BoatStatus.COLLIDED and pushes the boats apart

The kernel: ``ocean_warp.kernels.contact``. The capsule a boat is taken as is its vessel's
(``ocean_warp.vessel.CollisionShape``): the caller passes it, so that each kind of boat collides as itself.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import warp as wp

from .device_structs import struct_from
from .kernels.contact import ContactModel, contact_wrenches
from .validation import require_non_negative, require_positive
from .vessel import CollisionShape

__all__ = ["ContactConfig", "Contact", "boat_capsule", "contact_model"]


@dataclasses.dataclass(frozen=True)
class ContactConfig:
    """The contact force's law and the boats' capsule. Invalid values raise ``ValueError`` naming the field."""

    stiffness: float = 5.0e4
    """k [N/m] of the penalty force; 0: contacts are flagged, not pushed. With 5e4 N/m the E-Boat pushed at
    60 N into a pile or a quay comes no closer than 6 cm inside its surface (tests/ocean_warp/test_contact.py)."""
    damping: float = 3.0e3
    """c [N s/m] on the approach speed along the contact normal."""
    radius: float | None = None
    """The capsule's radius [m]; None: the vessel's (``CollisionShape.radius``). The axis stays the vessel's."""

    def __post_init__(self):
        owner = "ContactConfig"
        object.__setattr__(self, "stiffness", require_non_negative(owner, "stiffness", self.stiffness, unit=" [N/m]"))
        object.__setattr__(self, "damping", require_non_negative(owner, "damping", self.damping, unit=" [N s/m]"))
        if self.radius is not None:
            object.__setattr__(self, "radius", require_positive(owner, "radius", self.radius, unit=" [m]"))


def boat_capsule(hull_vertices: np.ndarray, radius: float | None = None) -> tuple[np.ndarray, np.ndarray, float]:
    """(stern end, bow end, radius) of the horizontal capsule that stands for a hull of ``hull_vertices``
    (body frame [m]): radius the half beam (or ``radius``), the axis along x at mid-height of the hull,
    ending ``radius`` short of the hull's ends so that the capsule spans its length."""
    vertices = np.asarray(hull_vertices, dtype=np.float64)
    half_beam = float(np.abs(vertices[:, 1]).max()) if radius is None else float(radius)
    x_low, x_high = float(vertices[:, 0].min()), float(vertices[:, 0].max())
    height = 0.5 * float(vertices[:, 2].min() + vertices[:, 2].max())
    inset = min(half_beam, 0.5 * (x_high - x_low))
    return (np.array([x_low + inset, 0.0, height]), np.array([x_high - inset, 0.0, height]), half_beam)


def contact_model(config: ContactConfig | None, shape: CollisionShape) -> ContactModel:
    """The kernels' view of ``config`` (None: ``ContactConfig()``) and of the vessel's capsule ``shape``
    (``Vessel.collision_shape()``; ``config.radius``, when set, replaces its radius)."""
    config = config if config is not None else ContactConfig()
    if not isinstance(config, ContactConfig):
        raise ValueError(f"contact_model: config must be a ContactConfig, got {config!r}")
    if not isinstance(shape, CollisionShape):
        raise ValueError(f"contact_model: shape must be the vessel's CollisionShape (Vessel.collision_shape()), "
                         f"got {shape!r:.80}")
    radius = shape.radius if config.radius is None else config.radius
    return struct_from(ContactModel, config, stern=wp.vec3(*shape.stern), bow=wp.vec3(*shape.bow), radius=radius)


class Contact:
    """Contact of the boats of ``scene`` (an ``ocean_warp.perception.Scene`` over the simulator's boats)
    with its objects and with each other, environment by environment: a simulator force model (add it with
    ``Simulator.add_model``, after the models that write the boats' poses' forces it should add to). Each
    substep it flags touching boats ``BoatStatus.COLLIDED`` (kept until a reset) and, with a stiffness,
    adds the penalty wrench; ``contacts`` (N,) counts the bodies each boat touched at the last substep. Every
    boat is taken as ``shape``, its vessel's capsule (``Vessel.collision_shape()``)."""

    def __init__(self, scene, config: ContactConfig | None = None, *, shape: CollisionShape):
        self.config = config if config is not None else ContactConfig()
        if not isinstance(self.config, ContactConfig):
            raise ValueError(f"Contact: config must be a ContactConfig, got {self.config!r}")
        self.scene, self.device = scene, scene.device
        self.model = contact_model(self.config, shape)
        """What the kernel reads (``kernels.contact.ContactModel``)."""
        count = scene.view.boat_position.shape[0]
        self._boat_env = wp.array(scene.boat_env.astype(np.int32), dtype=int, device=self.device)
        self.contacts = wp.zeros(count, dtype=int, device=self.device)
        """(N,) bodies each boat touched at the last substep."""

    def substep(self, simulator) -> None:
        fleet = simulator.fleet
        wp.launch(contact_wrenches, dim=self.contacts.shape[0], device=self.device,
                  inputs=[self.scene.view, self.model, self._boat_env, fleet.state.velocity],
                  outputs=[fleet.state.status, fleet.forces.model_wrench, self.contacts])
