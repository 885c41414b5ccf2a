"""The state of many boats as device arrays (structure of arrays), readable from torch without copies."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import warp as wp

from .boat_type import BoatType
from .kernels.hull_forces import MAX_HULL_VERTICES, NO_SWEPT_RATE, NO_WAVE_HISTORY, WAVE_POINTS, HullMeshes
from .kernels.radiation import reset_radiation_masked
from .radiation import radiation_states_per_boat, radiation_terms_per_boat
from .resistance import FROUDE_SAMPLES
from .seakeeping.wave_points import WAVE_POINT_INPUTS, rigid_motion_weights, wave_point_grid
from .kernels.rigid_body import (
    STATUS_BAD_INPUT,
    STATUS_CAPSIZED,
    STATUS_COLLIDED,
    STATUS_FLYING,
    STATUS_NONFINITE,
    STATUS_SUNK,
    BodyParameters,
    mat66,
    reset_boats_masked,
    reset_swept_rates_masked,
)
from .kernels.spatial import vec6
from .torch_streams import ordered_with_torch
from .validation import require_indices, require_rows

__all__ = ["Fleet", "FleetModel", "FleetState", "FleetControl", "FleetForces", "FleetTensors", "BoatStatus",
           "END_REASONS", "episode_end"]


class BoatStatus:
    """Bits of ``Fleet.state.status``; a boat is healthy when its status is 0. Flags stay until a reset."""

    NONFINITE = int(STATUS_NONFINITE)
    """Its state turned NaN or infinite; it is frozen at its last finite state."""
    CAPSIZED = int(STATUS_CAPSIZED)
    """Tilted beyond ``SimulatorConfig.max_tilt``."""
    FLYING = int(STATUS_FLYING)
    """Origin above ``SimulatorConfig.max_altitude``."""
    SUNK = int(STATUS_SUNK)
    """Origin below ``-SimulatorConfig.max_depth``."""
    BAD_INPUT = int(STATUS_BAD_INPUT)
    """A force model got a NaN or infinite input (e.g. a rudder command or the wind written from torch);
    set together with NONFINITE, so the boat is frozen too."""
    COLLIDED = int(STATUS_COLLIDED)
    """Touched an object or another boat of its environment (``ocean_warp.contact.Contact``)."""


END_REASONS = ("reached", "capsized", "collided", "flagged", "time-out", "lost")
"""How an episode can end (:func:`episode_end`), in the order of their codes (``ocean-warp ros``'s
``mission_control/episode`` carries the index)."""


def episode_end(success: bool, time_out: bool, status: int) -> str:
    """How an episode ended, one of :data:`END_REASONS`: "capsized" (``BoatStatus.CAPSIZED``), "collided"
    (``BoatStatus.COLLIDED``, not capsized), "flagged" (another ``BoatStatus`` bit), "time-out" (the task's time
    limit), "reached" (every waypoint of the task), else "lost" (healthy, before the time limit, without
    finishing: the task ends an episode when the boat is beyond its lost distance)."""
    status = int(status)
    if status & BoatStatus.CAPSIZED:
        return "capsized"
    if status & BoatStatus.COLLIDED:
        return "collided"
    if status:
        return "flagged"
    return "time-out" if time_out else "reached" if success else "lost"


class FleetTensors(NamedTuple):
    """torch views of the fleet's arrays (no copies: writes go straight to the simulator's memory)."""

    position: object
    """(N, 3) body origin in the world frame [m]."""
    orientation: object
    """(N, 4) body -> world quaternion (x, y, z, w)."""
    velocity: object
    """(N, 6) Fossen's nu: body-frame velocity of the origin [m/s] and angular velocity [rad/s]."""
    status: object
    """(N,) int32 ``BoatStatus`` bits."""
    wrench_world: object
    """(N, 6) external force [N] at the centre of mass and couple [N m], world frame (inputs)."""
    wrench_body: object
    """(N, 6) the same in the body frame (inputs, e.g. foils and propellers)."""
    hydro_wrench: object
    """(N, 6) water's force [N] and moment about the origin [N m], body frame (output)."""


@dataclasses.dataclass(frozen=True)
class FleetModel:
    """What describes the boats, fixed for the fleet's life (Warp arrays and structs on its device)."""

    boat_types: list[BoatType]
    """The fleet's boat types."""
    hull_type: wp.array
    """(N,) int: each boat's index into ``boat_types``."""
    meshes: HullMeshes
    """The boat types' physics meshes, resistance tables and face data, as the hull pass reads them."""
    body: BodyParameters
    """The boat types' mass, inertia, added mass and damping, as the integrator reads them."""
    triangle_offset: wp.array
    """(N,) int: each boat's first row in per-triangle arrays (``FleetState.swept_rate``)."""
    total_triangles: int
    """Hull triangles of all boats together."""
    max_vertex_count: int
    """Vertices of the largest hull (the hull pass's rounds per block)."""
    max_triangle_count: int
    """Triangles of the largest hull."""
    radiation_states: int
    """S, the radiation states of each boat (the most of any type: ``ocean_warp.radiation``)."""
    radiation_terms: int
    """R, the radiation terms of each boat (the most of any type)."""


@dataclasses.dataclass(frozen=True)
class FleetState:
    """What moves, N boats (Warp arrays)."""

    position: wp.array
    """(N,) vec3: body origin in the world frame [m]."""
    orientation: wp.array
    """(N,) quat: body -> world (x, y, z, w)."""
    velocity: wp.array
    """(N,) vec6: Fossen's nu = (u, v, w, p, q, r), body frame [m/s, rad/s]."""
    status: wp.array
    """(N,) int: :class:`BoatStatus` bits."""
    water_velocity: wp.array
    """(N,) vec3: the water's orbital velocity at each boat's origin, body frame [m/s] (computed)."""
    swept_rate: wp.array
    """(total triangles,) float: each hull triangle's last swept rate A_sub |v| for slamming [m^3/s]."""
    wave_velocity: wp.array
    """(N,) vec6: the effective velocity of the water under each hull (orbital plus current, weighted over its wave
    points: ``ocean_warp.seakeeping.wave_points``), linear [m/s] and angular [rad/s], world frame (computed by the
    hull pass, ``kernels.hull_forces.water_motion_under_hull``; first component ``NO_WAVE_HISTORY`` after a
    reset)."""
    wave_acceleration: wp.array
    """(N,) vec6: its rate of change along the boat's path over the last substep, world frame [m/s^2, rad/s^2]."""
    radiation_state: wp.array
    """(S * N,) float: the S radiation states of every boat (``FleetModel.radiation_states``; Cummins' memory,
    ``ocean_warp.kernels.radiation``), state i of boat b at i N + b, in the units of its type's models."""
    radiation_output: wp.array
    """(R * N,) float: each radiation term's output C x [N or N m] for the next substep, term e of boat b at
    e N + b."""


@dataclasses.dataclass(frozen=True)
class FleetControl:
    """What is commanded from outside the simulator's force models, N boats (Warp arrays)."""

    wrench_world: wp.array
    """(N,) vec6: external force at the centre of mass [N] and couple [N m], world frame."""
    wrench_body: wp.array
    """(N,) vec6: the same in the body frame."""


@dataclasses.dataclass(frozen=True)
class FleetForces:
    """What a substep computes before it integrates, N boats (Warp arrays, body frame, about the origin)."""

    hydro_wrench: wp.array
    """(N,) vec6: the water's force [N] and moment [N m] from the hull pass."""
    model_wrench: wp.array
    """(N,) vec6: the sum of the simulator's force models (foils, propellers, ...), zeroed every substep."""


class Fleet:
    """N boats of one or a few :class:`BoatType` on one device: their ``model`` (:class:`FleetModel`, what
    describes them), ``state`` (:class:`FleetState`, what moves), ``control`` (:class:`FleetControl`, the
    external wrenches) and ``forces`` (:class:`FleetForces`, computed every substep).

    ``Fleet(boat_type, 4096)`` gives 4096 boats of one type; ``Fleet([a, b], types=[0, 1, 1, 0])``
    mixes types. All boats start at the origin, upright and at rest: place them with :meth:`reset`.
    """

    def __init__(self, boat_types: BoatType | Sequence[BoatType], count: int | None = None, *,
                 types: Sequence[int] | None = None, device=None):
        boat_types = [boat_types] if isinstance(boat_types, BoatType) else list(boat_types)
        if not boat_types or not all(isinstance(t, BoatType) for t in boat_types):
            raise ValueError("Fleet: boat_types must be a BoatType or a non-empty sequence of them")
        type_of_boat = _type_of_boat(len(boat_types), count, types)
        self.device = wp.get_device(device)
        self.count = len(type_of_boat)
        device = self.device

        vertex_counts = np.array([t.hull.vertex_count for t in boat_types], dtype=np.int64)
        triangle_counts = np.array([t.hull.triangle_count for t in boat_types], dtype=np.int64)
        max_vertex_count = int(vertex_counts.max())
        if max_vertex_count > MAX_HULL_VERTICES:
            raise ValueError(f"Fleet: a hull has {max_vertex_count} vertices; the hull-force pass holds at most "
                             f"{MAX_HULL_VERTICES} per boat in fast memory. Use a coarser physics mesh (Hull(..., "
                             "visual=fine_mesh) keeps the fine one for viewers)")
        boat_triangles = triangle_counts[type_of_boat]
        if boat_triangles.sum() >= 2**31:
            raise ValueError(f"Fleet: {self.count} boats hold more than 2^31 triangles")
        total_triangles = int(boat_triangles.sum())
        self.model = FleetModel(
            boat_types=boat_types, hull_type=wp.array(type_of_boat.astype(np.int32), dtype=int, device=device),
            meshes=_hull_meshes(boat_types, device), body=_body_parameters(boat_types, device),
            triangle_offset=wp.array(_exclusive_sum(boat_triangles), dtype=int, device=device),
            total_triangles=total_triangles, max_vertex_count=max_vertex_count,
            max_triangle_count=int(triangle_counts.max()), radiation_states=radiation_states_per_boat(boat_types),
            radiation_terms=radiation_terms_per_boat(boat_types))
        """What describes the boats (see :class:`FleetModel`)."""

        n = self.count
        upright = np.tile([0.0, 0.0, 0.0, 1.0], (n, 1)).astype(np.float32)
        self.state = FleetState(
            position=wp.zeros(n, dtype=wp.vec3, device=device),
            orientation=wp.array(upright, dtype=wp.quat, device=device),
            velocity=wp.zeros(n, dtype=vec6, device=device), status=wp.zeros(n, dtype=int, device=device),
            water_velocity=wp.zeros(n, dtype=wp.vec3, device=device),
            swept_rate=wp.full(max(total_triangles, 1), NO_SWEPT_RATE, dtype=float, device=device),
            wave_velocity=wp.full(n, vec6(NO_WAVE_HISTORY, 0.0, 0.0, 0.0, 0.0, 0.0), dtype=vec6, device=device),
            wave_acceleration=wp.zeros(n, dtype=vec6, device=device),
            radiation_state=wp.zeros(max(n * self.model.radiation_states, 1), dtype=float, device=device),
            radiation_output=wp.zeros(max(n * self.model.radiation_terms, 1), dtype=float, device=device))
        """What moves (see :class:`FleetState`)."""
        self.control = FleetControl(wrench_world=wp.zeros(n, dtype=vec6, device=device),
                                    wrench_body=wp.zeros(n, dtype=vec6, device=device))
        """The external wrenches (see :class:`FleetControl`)."""
        self.forces = FleetForces(hydro_wrench=wp.zeros(n, dtype=vec6, device=device),
                                  model_wrench=wp.zeros(n, dtype=vec6, device=device))
        """What each substep computes (see :class:`FleetForces`)."""
        self._tensors = None

    # --- torch --------------------------------------------------------------------------------------
    @property
    def tensors(self) -> FleetTensors:
        """torch views of the state and wrench arrays, bound once; no copies."""
        if self._tensors is None:
            self._tensors = FleetTensors(*(wp.to_torch(a) for a in (
                self.state.position, self.state.orientation, self.state.velocity, self.state.status,
                self.control.wrench_world, self.control.wrench_body, self.forces.hydro_wrench)))
        return self._tensors

    # --- resets -------------------------------------------------------------------------------------
    def reset(self, boats=None, *, position, orientation=None, velocity=None) -> None:
        """Place the chosen boats (indices, or None for all) at ``position`` (K, 3) [m] with
        ``orientation`` (K, 4) quaternions x y z w (default upright) and ``velocity`` (K, 6) Fossen nu
        (default at rest); their status flags, external wrenches and slamming history are cleared.
        Single rows broadcast to all K boats."""
        indices = require_indices("Fleet.reset", "boats", boats, self.count)
        k = len(indices)
        position = require_rows("Fleet.reset", "position", position, k, 3).astype(np.float32)
        orientation = require_rows("Fleet.reset", "orientation", [0.0, 0.0, 0.0, 1.0] if orientation is None
                                   else orientation, k, 4).astype(np.float32)
        velocity = require_rows("Fleet.reset", "velocity", np.zeros(6) if velocity is None else velocity,
                                k, 6).astype(np.float32)
        norms = np.linalg.norm(orientation, axis=1)
        if np.any(norms < 1e-6):
            raise ValueError("Fleet.reset: orientation quaternions must not be zero")
        if k == 0:
            return
        # The host path builds a mask and full-length rows and takes the device path: one reset kernel.
        mask = np.zeros(self.count, dtype=np.int32)
        mask[indices] = 1
        rows = {"position": np.zeros((self.count, 3), np.float32),
                "orientation": np.tile(np.array([0.0, 0.0, 0.0, 1.0], np.float32), (self.count, 1)),
                "velocity": np.zeros((self.count, 6), np.float32)}
        rows["position"][indices] = position
        rows["orientation"][indices] = orientation / norms[:, None]
        rows["velocity"][indices] = velocity
        device = self.device
        with ordered_with_torch(device):
            self.reset_masked(wp.array(mask, dtype=wp.int32, device=device),
                              wp.array(rows["position"], dtype=wp.vec3, device=device),
                              wp.array(rows["orientation"], dtype=wp.quat, device=device),
                              wp.array(rows["velocity"], dtype=vec6, device=device))

    def reset_masked(self, mask: wp.array, position: wp.array, orientation: wp.array, velocity: wp.array) -> None:
        """The device path of :meth:`reset`: every boat whose ``mask`` (N,) int32 is non-zero goes to its row
        of ``position`` (N,) vec3 [m], ``orientation`` (N,) quat (unit length) and ``velocity`` (N,)
        vec6; the others are untouched. It only launches kernels (no allocation, no host copy), so it
        may run inside a captured CUDA graph; the caller orders it with torch."""
        device = self.device
        wp.launch(reset_boats_masked, dim=self.count, device=device,
                  inputs=[mask, position, orientation, velocity],
                  outputs=[self.state.position, self.state.orientation, self.state.velocity, self.state.status,
                           self.control.wrench_world, self.control.wrench_body, self.state.water_velocity,
                           self.state.wave_velocity])
        model = self.model
        wp.launch(reset_swept_rates_masked, dim=(self.count, model.max_triangle_count), device=device,
                  inputs=[mask, model.hull_type, model.meshes.triangle_count, model.triangle_offset,
                          float(NO_SWEPT_RATE)],
                  outputs=[self.state.swept_rate])
        if model.radiation_states:
            wp.launch(reset_radiation_masked, dim=(self.count, max(model.radiation_states, model.radiation_terms)),
                      device=device, inputs=[mask], outputs=[self.state.radiation_state, self.state.radiation_output])

    # --- host copies, for inspection and tests --------------------------------------------------------
    def numpy(self) -> dict[str, np.ndarray]:
        """Host copies of position, orientation, velocity, status and hydro_wrench (after torch's
        pending writes to them). Copies even on the CPU, where ``wp.array.numpy()`` is a view."""
        with ordered_with_torch(self.device):
            arrays = {"position": self.state.position, "orientation": self.state.orientation,
                      "velocity": self.state.velocity, "status": self.state.status,
                      "hydro_wrench": self.forces.hydro_wrench}
            return {name: array.numpy().copy() for name, array in arrays.items()}


def _type_of_boat(type_count: int, count, types) -> np.ndarray:
    if types is not None:
        type_of_boat = np.asarray(types)
        if type_of_boat.ndim != 1 or type_of_boat.size == 0 or not np.issubdtype(type_of_boat.dtype, np.integer):
            raise ValueError("Fleet: types must be a non-empty sequence of integer boat-type indices")
        if type_of_boat.min() < 0 or type_of_boat.max() >= type_count:
            raise ValueError(f"Fleet: types must lie in [0, {type_count - 1}]")
        if count is not None and count != type_of_boat.size:
            raise ValueError(f"Fleet: count {count} disagrees with len(types) {type_of_boat.size}")
        return type_of_boat.astype(np.int64)
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
        raise ValueError(f"Fleet: count must be an integer >= 1 (or give types), got {count!r}")
    if type_count != 1:
        raise ValueError("Fleet: with several boat types, say which boat has which with types=[...]")
    return np.zeros(int(count), dtype=np.int64)


def _exclusive_sum(counts: np.ndarray) -> np.ndarray:
    return (np.cumsum(counts) - counts).astype(np.int32)


def _hull_meshes(boat_types: list[BoatType], device) -> HullMeshes:
    hulls = [t.hull for t in boat_types]
    vertex_counts = np.array([h.vertex_count for h in hulls])
    triangle_counts = np.array([h.triangle_count for h in hulls])
    meshes = HullMeshes()
    ordered = [_mesh_by_side_and_height(h) for h in hulls]
    meshes.vertices = wp.array(np.concatenate([v for v, _ in ordered]).astype(np.float32), dtype=wp.vec3,
                               device=device)
    meshes.triangles = wp.array(np.concatenate([t for _, t in ordered]).astype(np.int32), dtype=wp.vec3i,
                                device=device)
    meshes.vertex_start = wp.array(_exclusive_sum(vertex_counts), dtype=int, device=device)
    meshes.vertex_count = wp.array(vertex_counts.astype(np.int32), dtype=int, device=device)
    meshes.triangle_start = wp.array(_exclusive_sum(triangle_counts), dtype=int, device=device)
    meshes.triangle_count = wp.array(triangle_counts.astype(np.int32), dtype=int, device=device)
    meshes.reference_length = wp.array([h.length for h in hulls], dtype=float, device=device)
    meshes.surface_area = wp.array([h.surface_area for h in hulls], dtype=float, device=device)
    meshes.mass = wp.array([t.mass for t in boat_types], dtype=float, device=device)
    _add_residuary_tables(meshes, boat_types, device)
    _add_wave_points(meshes, boat_types, device)
    meshes.seakeeping = wp.array([int(t.seakeeping is not None) for t in boat_types], dtype=int, device=device)
    return meshes


def _add_wave_points(meshes: HullMeshes, boat_types: list[BoatType], device) -> None:
    """Each type's wave points and their weights (``ocean_warp.seakeeping.wave_points``): its database's diffraction
    weights, else the rigid-motion fit of the velocities over its grid."""
    points, weights = [], []
    for boat_type in boat_types:
        fitted = getattr(getattr(boat_type, "seakeeping", None), "diffraction", None)
        grid = fitted.points if fitted is not None else wave_point_grid(boat_type.hull)
        assert len(grid) == WAVE_POINTS and WAVE_POINT_INPUTS == 4
        points.append(grid)
        chosen = fitted.weights if fitted is not None else rigid_motion_weights(grid)
        weights.append(np.transpose(chosen, (1, 2, 0)).reshape(-1, 6))  # point-major, a vec6 per input
    meshes.wave_points = wp.array(np.concatenate(points).astype(np.float32), dtype=wp.vec2, device=device)
    meshes.wave_point_weights = wp.array(np.concatenate(weights).astype(np.float32), dtype=vec6, device=device)


def _add_residuary_tables(meshes: HullMeshes, boat_types: list[BoatType], device) -> None:
    """Each type's residuary-resistance tables (zeros and a length of 0 for a type without one)."""
    none = [0.0] * FROUDE_SAMPLES
    models = [t.residuary for t in boat_types]
    meshes.residuary_length = wp.array([m.waterline_length if m else 0.0 for m in models], dtype=float, device=device)
    meshes.residuary_volume = wp.array([m.displaced_volume if m else 0.0 for m in models], dtype=float, device=device)
    meshes.residuary_center = wp.array(np.array([m.center if m else (0.0, 0.0, 0.0) for m in models]),
                                       dtype=wp.vec3, device=device)
    meshes.residuary_upright = wp.array(np.concatenate([m.upright if m else none for m in models]), dtype=float,
                                        device=device)
    meshes.residuary_heel = wp.array(np.concatenate([m.heel_increase if m else none for m in models]), dtype=float,
                                     device=device)


def _by_side_and_height(points: np.ndarray) -> np.ndarray:
    """The order of ``points`` (N, 3) by side (starboard, centre line, port), then by height within a side."""
    side = np.sign(np.where(np.abs(points[:, 1]) > 1e-6, points[:, 1], 0.0))
    return np.lexsort((points[:, 2], side))


def _mesh_by_side_and_height(hull) -> tuple[np.ndarray, np.ndarray]:
    """The hull's vertices and triangles (indices into the new vertex order), each ordered by side (starboard,
    centre line, port), then by height within a side (a triangle's by its centroid). Neighbouring threads then
    mostly find their vertices all wet or all dry (only a wet one reads the waves' pressure at depth) and their
    triangles too (on an H100 a warp executed 11 of its 32 threads on average with the mesh's own order),
    upright and heeled: with one height order for both sides a heel wets one side and dries the other at the
    same height, while within one side the waterline still follows the height. On sailing E-Boats the triangle
    order took the hull pass from 912 to 801 us (H100, 16 384 boats), the vertex order from 325 to 320 us (H200,
    4 096 boats)."""
    vertex_order = _by_side_and_height(hull.vertices)
    new_index = np.empty_like(vertex_order)
    new_index[vertex_order] = np.arange(len(vertex_order))
    triangles = new_index[hull.triangles]
    triangle_order = _by_side_and_height(hull.vertices[hull.triangles].mean(axis=1))
    return hull.vertices[vertex_order], triangles[triangle_order]


def _body_parameters(boat_types: list[BoatType], device) -> BodyParameters:
    body = BodyParameters()
    body.mass = wp.array([t.mass for t in boat_types], dtype=float, device=device)
    body.center_of_mass = wp.array(np.array([t.center_of_mass for t in boat_types]), dtype=wp.vec3, device=device)
    body.inertia_origin = wp.array(np.array([t.inertia_about_origin for t in boat_types]), dtype=wp.mat33, device=device)
    body.added_mass = wp.array(np.array([t.added_mass for t in boat_types]), dtype=mat66, device=device)
    body.mass_matrix = wp.array(np.array([t.mass_matrix for t in boat_types]), dtype=mat66, device=device)
    body.linear_damping = wp.array(np.array([t.linear_damping for t in boat_types]), dtype=vec6, device=device)
    body.quadratic_damping = wp.array(np.array([t.quadratic_damping for t in boat_types]), dtype=vec6, device=device)
    body.astern_surge_factor = wp.array([t.astern_surge_factor for t in boat_types], dtype=float, device=device)
    return body

