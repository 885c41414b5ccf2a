"""The vessel seam: what tasks, sensors, contact, USD, render and ROS may know of a kind of boat.

A vessel (the E-Boat, the WAM-V) is a preset on the core (hull, fleet, force models): it builds a
simulator of N boats of its kind and says what its actions mean and what it looks like. Everything above
the core takes a :class:`Vessel` and reads the common part of its simulator's state (:class:`VesselSimulator`),
never a particular vessel's module, as Isaac Lab swaps a robot in one line.

As in Newton and MuJoCo, what describes (the vessel and its config), what moves (``state``) and what is
commanded (``control``) are kept apart. Unlike Newton's ``solver.step(state_in, state_out, control, contacts,
dt)``, a step advances ``state`` in place with the ``dt`` of the config, and contact is one of the simulator's
force models: every kernel of a step reads and writes the same arrays, which the captured CUDA graph of a
decision binds once. Two states to swap would mean a second copy of every array and a graph per pairing.

Two things a vessel may say, each through an optional method read by a function here: which parts a viewer
draws at a size of each boat's own (``part_scaling()``, :func:`part_scaling`) and where its sensors sit
(``sensor_mounts()``, :func:`sensor_mount`).

Actions are always a (N, A) float32 array in [-1, 1]; ``Vessel.actions`` names each column and says what
it commands, and ``VesselSimulator.launch_actions`` is the kernel that turns them into the simulator's
commands (clamped and scaled), graph-safe.
"""

from __future__ import annotations

import dataclasses
from typing import Any, Protocol, runtime_checkable

import numpy as np

from .meshes import MeshData

__all__ = ["ActionSpec", "VesselPart", "PartScaling", "CollisionShape", "Vessel", "VesselSimulator", "require_vessel",
           "require_actions", "part_scaling", "sensor_mount"]


@dataclasses.dataclass(frozen=True)
class ActionSpec:
    """One column of a vessel's actions: its name and what -1 and +1 command."""

    name: str
    """Short snake_case name (``rudder``, ``left_thrust``), used in logs, ONNX and ROS topics."""
    meaning: str
    """What the column commands, with units at -1 and +1 (``"rudder angle, -35 .. 35 deg, + to port"``)."""


@dataclasses.dataclass(frozen=True)
class VesselPart:
    """A named rigid mesh of the vessel as a viewer or a sensor sees it.

    A fixed part (``joint`` None) is in the body frame (FLU, origin where the hull has it). A jointed part is
    in its pivot's frame: it sits at ``pivot`` [m, body frame] and turns by -angle about the pivot's z axis,
    where angle [rad] is the boat's row of the state array named ``joint`` (``boom_angle``, ``rudder_angle``,
    ``thruster_angle``...; a 2-D state array is read at column ``joint_column``)."""

    name: str
    mesh: MeshData
    joint: str | None = None
    pivot: tuple[float, float, float] = (0.0, 0.0, 0.0)
    joint_column: int = 0
    material: str = "hull"
    """A material name the viewers know (``hull``, ``sail``, ``foil``, ``metal``, ``dark``)."""


@dataclasses.dataclass(frozen=True)
class PartScaling:
    """Parts a viewer draws at a size of each boat's own (the E-Boat's sail at its reef): part ``parts`` scaled by
    ``scales[level]`` about ``origin`` [m, in the part's pivot frame], level the boat's row of the int32 state array
    named ``level``. A vessel that has such parts says so with a ``part_scaling()`` method (see
    :func:`part_scaling`)."""

    parts: tuple[str, ...]
    level: str
    scales: tuple[float, ...]
    origin: tuple[float, float, float]


def part_scaling(vessel) -> PartScaling | None:
    """The vessel's :class:`PartScaling` (its optional ``part_scaling()``), None where it has none."""
    method = getattr(vessel, "part_scaling", None)
    return method() if callable(method) else None


def sensor_mount(vessel, name: str) -> tuple[float, float, float]:
    """Where ``vessel`` carries a sensor at its place ``name`` (``"masthead"``...): (x, y, z) [m, body frame], from
    the vessel's optional ``sensor_mounts()`` mapping; ``ValueError`` naming the places it has."""
    method = getattr(vessel, "sensor_mounts", None)
    mounts = dict(method()) if callable(method) else {}
    if name not in mounts:
        known = ", ".join(mounts) or "none"
        raise ValueError(f"sensor_mount: the {getattr(vessel, 'name', type(vessel).__name__)} has no sensor place "
                         f"{name!r} (its places: {known})")
    return tuple(float(v) for v in mounts[name])


@dataclasses.dataclass(frozen=True)
class CollisionShape:
    """The horizontal capsule a boat is taken as in contact: from ``stern`` to ``bow`` (body frame [m]) with
    ``radius`` [m]."""

    stern: tuple[float, float, float]
    bow: tuple[float, float, float]
    radius: float

    def __post_init__(self):
        if not (np.all(np.isfinite(self.stern)) and np.all(np.isfinite(self.bow)) and np.isfinite(self.radius)
                and self.radius > 0.0):
            raise ValueError(f"CollisionShape: stern, bow and radius must be finite and radius > 0, got {self!r}")


@runtime_checkable
class VesselSimulator(Protocol):
    """N boats of one vessel on one ocean, boat i in environment i.

    ``state`` names Warp arrays; every vessel's state holds at least ``position`` (N,) vec3 [m],
    ``orientation`` (N,) quat, ``velocity`` (N,) vec6 (Fossen's nu), ``status`` (N,) int32 ``BoatStatus`` bits,
    ``wind_velocity`` (N,) vec3 [m/s], ``wind_mean_speed`` and ``wind_mean_direction`` (N,) [m/s, rad],
    ``readings`` and ``truth`` (N, C) sensor channels (``ocean_warp.sensors``) and ``time`` (1,) [s].
    ``start`` names where a masked reset puts each boat; every vessel's holds at least ``position``,
    ``orientation``, ``velocity``, ``wind_speed``, ``wind_direction``, ``gust_scale``, ``current_speed``,
    ``current_direction`` and ``noise_scale``."""

    count: int
    device: Any
    ocean: Any
    state: Any
    control: Any
    start: Any

    def reset(self, boats=None, **start) -> None:
        """Host path: put the chosen boats at the given start (see each vessel's docstring)."""

    def reset_masked(self, mask, start=None) -> None:
        """Device path: every boat whose ``mask`` (N,) int32 is non-zero goes to its row of ``start``."""

    def launch_actions(self, actions, enabled=None) -> None:
        """Turn ``actions`` (N, A) in [-1, 1] into the simulator's commands (graph-safe launches); ``enabled`` (A,)
        int32 on the device: a zero switches that column off (it commands its neutral value; None: all on)."""

    def launch_step(self) -> None:
        """One ``dt`` of physics, launches only (to embed in a larger graph)."""

    def step(self) -> None:
        """One ``dt`` of physics (captured after the first call)."""

    def rewind(self) -> None:
        """Time and random streams back to their start."""


@runtime_checkable
class Vessel(Protocol):
    """A kind of boat: what it is called, what its actions mean, how it looks and collides, and how to build N
    of them."""

    name: str
    actions: tuple[ActionSpec, ...]
    config: Any
    """The simulator config its boats are built from (its sea, wind, current, sensors and time step: ``ocean``,
    ``wind``, ``dt``, ``capture_graph`` at least)."""

    def simulator(self, count: int, *, device=None, first_boat: int = 0, ocean=None) -> VesselSimulator:
        """``count`` boats of this vessel (boats [first_boat, first_boat + count) of a larger batch)."""

    def parts(self) -> tuple[VesselPart, ...]:
        """The meshes a viewer or a camera sees."""

    def collision_shape(self) -> CollisionShape:
        """The capsule contact takes it as."""


def require_vessel(owner: str, value) -> Vessel:
    """``value`` if it is a :class:`Vessel`, else ``ValueError`` naming ``owner`` and what was given."""
    if not isinstance(value, Vessel) or not isinstance(getattr(value, "actions", None), tuple):
        raise ValueError(f"{owner}: expected a vessel (ocean_warp.vessel.Vessel: name, actions, simulator(), "
                         f"parts(), collision_shape()), got {type(value).__name__} {value!r:.80}")
    return value


def require_actions(owner: str, vessel: Vessel, names) -> tuple[int, ...]:
    """Column indices of the action ``names`` in ``vessel``'s actions; ``ValueError`` naming the first one the
    vessel lacks."""
    known = [spec.name for spec in vessel.actions]
    indices = []
    for name in names:
        if name not in known:
            raise ValueError(f"{owner}: the {vessel.name} has no action {name!r} (its actions: {', '.join(known)})")
        indices.append(known.index(name))
    return tuple(indices)
