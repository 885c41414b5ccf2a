"""The scene the sensors and the camera see: the sea, the boats at their poses and the objects of every
environment, on the device (kernels in ``ocean_warp.kernels.ray_cast``).

Every environment holds its own boats and objects; a ray cast in an environment sees only those and the
sea (which all share), so thousands of environments side by side on one ocean do not see each other.

Example::

    scene = Scene.for_env(env, objects=[SceneObject.buoy((30.0, 5.0)), SceneObject.pillar((60.0, -10.0))])
    scene.refresh()          # after the physics: the water band and the floating objects (launches only)
"""

from __future__ import annotations

import dataclasses
import enum
import math
from collections.abc import Sequence

import numpy as np
import warp as wp

from ..device_structs import struct_from
from ..kernels.ray_cast import (
    SHAPE_CYLINDER,
    SHAPE_MESH,
    SHAPE_SPHERE,
    SceneView,
    cast_rays,
    float_objects,
    resample_heights,
    water_band,
)
from ..mesh_files import read_mesh_file
from ..meshes import MeshData
from ..ocean import Ocean
from ..validation import require_finite, require_positive
from ..vessel import PartScaling, VesselPart, part_scaling, require_vessel

__all__ = ["Shape", "SceneObject", "Scene", "PARKED_DEPTH"]

JOINT_ARRAYS = 3
"""How many distinct joint state arrays a scene's vessel may turn its parts with (``SceneView.joint_0..2``)."""

PARKED_DEPTH = 1000.0
"""How far below its environment's origin an empty object row is parked [m] (``Scene.free_slots``)."""


class Shape(str, enum.Enum):
    SPHERE = "sphere"
    CYLINDER = "cylinder"
    MESH = "mesh"


_SHAPE_CODES = {Shape.SPHERE: int(SHAPE_SPHERE), Shape.CYLINDER: int(SHAPE_CYLINDER), Shape.MESH: int(SHAPE_MESH)}


@dataclasses.dataclass(frozen=True)
class SceneObject:
    """An object placed in an environment. Invalid values raise ``ValueError`` naming the field."""

    shape: Shape = Shape.SPHERE
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """Its frame's place from the environment's origin [m] (a floating object takes z from the sea)."""
    yaw: float = 0.0
    """Turn of its frame about z [rad]."""
    radius: float = 0.5
    """Of a sphere or a cylinder [m]."""
    height: float = 1.0
    """Of a cylinder [m] (its frame is at mid-height)."""
    mesh: MeshData | None = None
    """Of a ``Shape.MESH`` object, in its frame [m]."""
    floats: bool = False
    """Rides the sea: its frame sits ``draft`` below the surface at its x, y and tilts with the surface."""
    draft: float = 0.0
    """[m]"""
    color: tuple[float, float, float] = (0.95, 0.45, 0.1)
    """Linear RGB in 0-1, for the camera."""

    def __post_init__(self):
        owner = "SceneObject"
        try:
            object.__setattr__(self, "shape", Shape(self.shape))
        except ValueError:
            raise ValueError(f"{owner}.shape must be one of {[s.value for s in Shape]}, got {self.shape!r}") from None
        position = tuple(require_finite(owner, "position", float(v)) for v in np.asarray(self.position).reshape(-1))
        if len(position) != 3:
            raise ValueError(f"{owner}.position must be (x, y, z) [m], got {self.position!r}")
        object.__setattr__(self, "position", position)
        object.__setattr__(self, "yaw", require_finite(owner, "yaw", self.yaw))
        object.__setattr__(self, "radius", require_positive(owner, "radius", self.radius, unit=" [m]"))
        object.__setattr__(self, "height", require_positive(owner, "height", self.height, unit=" [m]"))
        object.__setattr__(self, "draft", require_finite(owner, "draft", self.draft))
        if not isinstance(self.floats, bool):
            raise ValueError(f"{owner}.floats must be True or False, got {self.floats!r}")
        color = tuple(float(c) for c in np.asarray(self.color, dtype=np.float64).reshape(-1))
        if len(color) != 3 or not all(0.0 <= c <= 1.0 for c in color):
            raise ValueError(f"{owner}.color must be (r, g, b) in [0, 1], got {self.color!r}")
        object.__setattr__(self, "color", color)
        if self.shape is Shape.MESH:
            if not isinstance(self.mesh, MeshData) or len(self.mesh.face_counts) == 0:
                raise ValueError(f"{owner}.mesh must be a MeshData with faces for a mesh object, got {self.mesh!r}")
            if not np.all(np.isfinite(self.mesh.points)):
                raise ValueError(f"{owner}.mesh has non-finite vertices")

    @classmethod
    def buoy(cls, position, radius: float = 0.5, *, color=(0.95, 0.45, 0.1)) -> SceneObject:
        """A floating spherical buoy, its centre on the surface, at ``position`` (x, y) [m]."""
        x, y = position[:2]
        return cls(Shape.SPHERE, (x, y, 0.0), radius=radius, floats=True, draft=0.0, color=color)

    @classmethod
    def pillar(cls, position, radius: float = 0.5, height: float = 6.0, *, color=(0.45, 0.42, 0.4)) -> SceneObject:
        """A fixed upright cylinder (a pile, a rock) standing from ``height`` / 4 below still water."""
        x, y = position[:2]
        return cls(Shape.CYLINDER, (x, y, height / 4.0), radius=radius, height=height, color=color)

    @classmethod
    def from_file(cls, path, position=(0.0, 0.0, 0.0), *, yaw: float = 0.0, scale: float = 1.0,
                  floats: bool = False, draft: float = 0.0, color=(0.5, 0.5, 0.55)) -> SceneObject:
        """A mesh file (OBJ, STL, PLY, OFF, GLB or GLTF: ``ocean_warp.mesh_files``), times ``scale``, placed
        at ``position`` [m]."""
        loaded = read_mesh_file("SceneObject.from_file", path)
        scale = require_positive("SceneObject.from_file", "scale", scale)
        mesh = MeshData(np.asarray(loaded.vertices, dtype=np.float64) * scale, np.full(len(loaded.faces), 3, np.int32),
                        np.asarray(loaded.faces, dtype=np.int32).reshape(-1))
        return cls(Shape.MESH, tuple(position), yaw=yaw, mesh=mesh, floats=floats, draft=draft, color=color)

    @property
    def bound(self) -> float:
        """Radius of a sphere about its frame's origin that holds it [m]."""
        if self.shape is Shape.SPHERE:
            return self.radius
        if self.shape is Shape.CYLINDER:
            return math.hypot(self.radius, 0.5 * self.height)
        return float(np.linalg.norm(self.mesh.points, axis=1).max())


def _wp_mesh(mesh: MeshData, device) -> wp.Mesh:
    return wp.Mesh(points=wp.array(mesh.points.astype(np.float32), dtype=wp.vec3, device=device),
                   indices=wp.array(mesh.triangles().reshape(-1), dtype=int, device=device))


class Scene:
    """The boats, objects and sea of ``envs`` environments on ``ocean``'s device, as :class:`SceneView`.

    Args:
        ocean: the sea (its current fields are what rays see; :meth:`refresh` after it changes).
        envs: number of environments.
        boat_env: (B,) the environment of each boat (-1: not drawn).
        boat_position, boat_orientation: the boats' (B,) Warp arrays (vec3 [m], quat), read by every cast (bound,
            not copied).
        parts: the :class:`~ocean_warp.vessel.VesselPart` s every boat is drawn with (``Vessel.parts()``; the scene
            knows no vessel of its own: :meth:`for_vessel` reads them from one).
        joints: the boats' joint state arrays by name (``{"boom_angle": state.boom_angle}``: (B,) or (B, C)
            float32 Warp arrays [rad], bound too), one for each ``joint`` of ``parts``.
        scaling: which parts are drawn at a size of each boat's own (``Vessel.part_scaling()``; None: none).
        reef_level: the boats' (B,) int32 Warp array of levels of ``scaling`` (``EBoatState.reef_level``), bound
            too: each scaled part is drawn scaled about its origin by its level's factor; None: level 0 on every
            boat.
        objects: one sequence of :class:`SceneObject` for every environment (placed from each origin), or
            a sequence of ``envs`` such sequences, one per environment.
        origins: (envs, 3) world origin of each environment [m] (default: all at 0).
        water_visible: whether rays see the sea.
        free_slots: rows each environment keeps after its objects for objects placed on the device later
            (an obstacle layout drawn at every reset: ``ocean_warp.envs.tasks.obstacle_course``). A free slot
            holds nothing until a kernel writes it: a sphere of radius 0 parked ``PARKED_DEPTH`` below its
            environment's origin, which no ray, camera or boat reaches.
    """

    def __init__(self, ocean: Ocean, *, envs: int, boat_env, boat_position: wp.array, boat_orientation: wp.array,
                 parts: Sequence[VesselPart], joints: dict | None = None, objects: Sequence = (), origins=None,
                 water_visible: bool = True, free_slots: int = 0, reef_level: wp.array | None = None,
                 scaling: PartScaling | None = None):
        if not isinstance(ocean, Ocean):
            raise ValueError(f"Scene: ocean must be an ocean_warp Ocean, got {type(ocean).__name__}")
        if isinstance(envs, bool) or not isinstance(envs, int) or envs < 1:
            raise ValueError(f"Scene.envs must be a whole number >= 1, got {envs!r}")
        if isinstance(free_slots, bool) or not isinstance(free_slots, int) or not 0 <= free_slots <= 1024:
            raise ValueError(f"Scene.free_slots must be a whole number in [0, 1024], got {free_slots!r}")
        if not isinstance(water_visible, bool):
            raise ValueError(f"Scene.water_visible must be True or False, got {water_visible!r}")
        self.ocean, self.envs, self.device = ocean, envs, ocean.device
        device = self.device
        boat_env = np.asarray(boat_env, dtype=np.int64).reshape(-1)
        if boat_env.size != boat_position.shape[0] or np.any(boat_env >= envs) or np.any(boat_env < -1):
            raise ValueError(f"Scene.boat_env must give each of the {boat_position.shape[0]} boats an environment "
                             f"in [0, {envs}) or -1")
        origins = np.zeros((envs, 3)) if origins is None else np.asarray(origins, dtype=np.float64)
        if origins.shape != (envs, 3) or not np.all(np.isfinite(origins)):
            raise ValueError(f"Scene.origins must be ({envs}, 3) finite [m], got shape {origins.shape}")
        per_env = _objects_per_env(objects, envs)
        self.objects = per_env
        self.boat_env = boat_env.copy()
        """(B,) int64 numpy: the environment each boat is drawn in (-1: not drawn)."""

        count = boat_position.shape[0]
        boat_parts = _PartTable(parts, dict(joints or {}), scaling, count, device)
        self._meshes = list(boat_parts.meshes)
        if reef_level is None:
            reef_level = wp.zeros(count, dtype=int, device=device)
        elif reef_level.shape[0] != count:
            raise ValueError(f"Scene.reef_level must hold one level for each of the {count} boats, "
                             f"got {reef_level.shape[0]}")
        self.reef_level = reef_level
        """(B,) int32: each boat's level of its scaled parts (bound, not copied), e.g. the E-Boat's reef."""
        self.reef_scale = wp.array(np.array(boat_parts.scales, dtype=np.float32), dtype=float, device=device)
        """(levels,) the linear factor on the scaled parts of each level (``PartScaling.scales``; [1]: none)."""
        self.parts = tuple(parts)
        """The vessel's parts every boat is drawn with."""

        flat = [(env, item) for env in range(envs) for item in per_env[env] + [None] * free_slots]
        mesh_ids: dict[int, wp.Mesh] = {}
        for _, item in flat:
            if item is not None and item.shape is Shape.MESH and id(item.mesh) not in mesh_ids:
                mesh_ids[id(item.mesh)] = _wp_mesh(item.mesh, device)
        self._meshes += list(mesh_ids.values())
        count = max(len(flat), 1)  # Warp arrays of length 0 cannot be read; a dummy row is never cast against
        anchor = np.zeros((count, 3), np.float32)
        quats = np.tile(np.array([0.0, 0.0, 0.0, 1.0], np.float32), (count, 1))
        rows = {"shape": np.zeros(count, np.int32), "size": np.zeros((count, 3), np.float32),
                "mesh": np.zeros(count, np.uint64), "bound": np.zeros(count, np.float32),
                "color": np.zeros((count, 3), np.float32), "floats": np.zeros(count, np.int32),
                "draft": np.zeros(count, np.float32)}
        for k, (env, item) in enumerate(flat):
            if item is None:
                anchor[k] = origins[env] - (0.0, 0.0, PARKED_DEPTH)
                continue
            anchor[k] = origins[env] + np.asarray(item.position)
            quats[k] = (0.0, 0.0, math.sin(0.5 * item.yaw), math.cos(0.5 * item.yaw))
            rows["shape"][k] = _SHAPE_CODES[item.shape]
            rows["size"][k] = (item.radius, 0.5 * item.height, 0.0)
            rows["mesh"][k] = mesh_ids[id(item.mesh)].id if item.shape is Shape.MESH else 0
            rows["bound"][k] = item.bound
            rows["color"][k] = item.color
            rows["floats"][k], rows["draft"][k] = int(item.floats), item.draft
        starts = np.zeros(envs + 1, np.int32)
        starts[1:] = np.cumsum([len(items) + free_slots for items in per_env])
        order = np.argsort(np.where(boat_env < 0, envs, boat_env), kind="stable")
        order = order[boat_env[order] >= 0]
        boat_start = np.zeros(envs + 1, np.int32)
        boat_start[1:] = np.cumsum(np.bincount(boat_env[boat_env >= 0], minlength=envs))

        array = lambda values, dtype: wp.array(values, dtype=dtype, device=device)  # noqa: E731
        self.anchor = array(anchor, wp.vec3)
        """(M,) where each object stands, world frame [m] (a floating one's x, y)."""
        self.floats, self.draft = array(rows["floats"], int), array(rows["draft"], float)
        """(M,) 1 where an object rides the sea, and how far its frame sits below the surface [m]."""
        self.free_slots = free_slots
        self.first_free_slot = starts[1:] - free_slots
        """(envs,) numpy: the first of each environment's ``free_slots`` rows (they run to the next
        environment's first row)."""
        grid = ocean.config.resolution
        self.heights = wp.zeros((grid, grid), dtype=float, device=device)
        """(n, n) the sea's height above every grid node at the last :meth:`refresh` [m]."""
        self.band = wp.zeros(2, dtype=float, device=device)
        """(2,) the lowest and highest of ``heights`` [m] (see ``ray_cast.water_band``)."""
        self.view = struct_from(
            SceneView, surface=ocean.surface, heights=self.heights, water_band=self.band,
            water_visible=int(water_visible),
            object_start=array(starts, int), object_shape=array(rows["shape"], int),
            object_position=array(anchor, wp.vec3), object_orientation=array(quats, wp.quat),
            object_size=array(rows["size"], wp.vec3), object_mesh=array(rows["mesh"], wp.uint64),
            object_bound=array(rows["bound"], float), object_color=array(rows["color"], wp.vec3),
            boat_start=array(boat_start, int), boat_list=array(order.astype(np.int32), int),
            boat_position=boat_position, boat_orientation=boat_orientation, reef_level=reef_level,
            reef_scale=self.reef_scale, boat_bound=boat_parts.bound, **boat_parts.view_fields())
        """What the kernels take (:class:`~ocean_warp.kernels.ray_cast.SceneView`)."""
        self._band_start = array(np.array([1.0e30, -1.0e30], np.float32), float)
        self.object_count = len(flat)
        self.refresh()

    # --- constructors -------------------------------------------------------------------------------
    @classmethod
    def for_env(cls, env, objects: Sequence = (), *, water_visible: bool = True, free_slots: int = 0) -> Scene:
        """The scene of an environment of ``ocean_warp.envs`` (``SailingEnv``, ``VrxEnv``: its ``vessel`` and
        ``simulator``): environment i holds boat i, its objects are placed from its origin (and ``free_slots``
        rows each for objects placed later on the device)."""
        return cls.for_vessel(env.vessel, env.simulator, objects, envs=env.num_envs, boat_env=np.arange(env.num_envs),
                              origins=env.origin.numpy(), water_visible=water_visible, free_slots=free_slots)

    @classmethod
    def for_simulator(cls, sim, objects: Sequence = (), *, vessel, water_visible: bool = True, parts=None) -> Scene:
        """One environment with every boat of ``sim``, a simulator of ``vessel`` (a fleet that sees itself), its
        objects placed from the world origin; ``parts`` as :meth:`for_vessel`'s."""
        return cls.for_vessel(vessel, sim, [objects], envs=1, boat_env=np.zeros(sim.count, np.int64),
                              water_visible=water_visible, parts=parts)

    @classmethod
    def for_vessel(cls, vessel, sim, objects: Sequence = (), *, parts=None, **options) -> Scene:
        """The boats of ``sim``, a simulator of ``vessel`` (any ``ocean_warp.vessel.Vessel``), drawn with its parts
        (``parts``: some of them, or at another detail, e.g. ``vessel.parts(hull_detail=1)``; None: ``parts()``)
        posed by its state's joint arrays and scaled per its ``part_scaling()``; ``options``: the constructor's
        ``envs``, ``boat_env``, ``origins``, ``water_visible`` and ``free_slots``."""
        vessel = require_vessel("Scene.for_vessel", vessel)
        parts = vessel.parts() if parts is None else tuple(parts)
        scaling = part_scaling(vessel)
        joints = {}
        for name in {part.joint for part in parts if part.joint is not None}:
            joints[name] = _state_array(vessel, sim, name)
        level = _state_array(vessel, sim, scaling.level) if scaling is not None else None
        return cls(sim.ocean, boat_position=sim.state.position, boat_orientation=sim.state.orientation,
                   objects=objects, parts=parts, joints=joints, scaling=scaling, reef_level=level, **options)

    # --- per frame ----------------------------------------------------------------------------------
    def refresh(self) -> None:
        """The sea's height map and band from its current fields, and the floating objects on it. Launches
        only (graph-safe): call it after the ocean's fields change, before casting."""
        device = self.device
        wp.launch(resample_heights, dim=self.heights.shape, device=device, inputs=[self.ocean.surface],
                  outputs=[self.heights])
        wp.copy(self.band, self._band_start)
        wp.launch(water_band, dim=self.heights.shape[0], device=device, inputs=[self.heights, self.band])
        if self.object_count:
            wp.launch(float_objects, dim=self.object_count, device=device,
                      inputs=[self.ocean.surface, self.floats, self.draft, self.anchor],
                      outputs=[self.view.object_position, self.view.object_orientation])


    def cast(self, origins, directions, *, envs=None, own_boat=None, t_min: float = 0.0,
             t_max: float = 200.0) -> dict[str, np.ndarray]:
        """Cast R rays from the host (for tests and tools): ``origins`` and ``directions`` (R, 3) world [m]
        (directions normalised here), in environments ``envs`` (R,) (default 0), ignoring boats
        ``own_boat`` (R,) (default none). Returns numpy "distance" [m] (t_max where nothing is hit),
        "kind" (``ray_cast.HIT_*``), "index" and "normal" (R, 3)."""
        origins = np.asarray(origins, dtype=np.float32).reshape(-1, 3)
        directions = np.asarray(directions, dtype=np.float32).reshape(-1, 3)
        count = len(origins)
        if directions.shape != origins.shape or count == 0:
            raise ValueError(f"Scene.cast: origins and directions must both be (R, 3) with R >= 1, got "
                             f"{origins.shape} and {directions.shape}")
        if np.any(np.linalg.norm(directions, axis=1) == 0.0) or not np.all(np.isfinite(directions)) \
                or not np.all(np.isfinite(origins)):
            raise ValueError("Scene.cast: origins must be finite and directions finite and non-zero")
        t_min = require_finite("Scene.cast", "t_min", t_min)
        t_max = require_positive("Scene.cast", "t_max", t_max, unit=" [m]")
        envs = np.zeros(count, np.int32) if envs is None else np.broadcast_to(np.asarray(envs, np.int32), count)
        if np.any(envs < 0) or np.any(envs >= self.envs):
            raise ValueError(f"Scene.cast: envs must lie in [0, {self.envs})")
        own = np.full(count, -1, np.int32) if own_boat is None \
            else np.broadcast_to(np.asarray(own_boat, np.int32), count)
        device = self.device
        out = {name: wp.zeros(count, dtype=dtype, device=device)
               for name, dtype in (("distance", float), ("kind", int), ("index", int), ("normal", wp.vec3))}
        wp.launch(cast_rays, dim=count, device=device,
                  inputs=[self.view, wp.array(envs, dtype=int, device=device),
                          wp.array(origins, dtype=wp.vec3, device=device),
                          wp.array(directions, dtype=wp.vec3, device=device), wp.array(own, dtype=int, device=device),
                          t_min, t_max],
                  outputs=[out["distance"], out["kind"], out["index"], out["normal"]])
        return {name: array.numpy().copy() for name, array in out.items()}


def _objects_per_env(objects: Sequence, envs: int) -> list[list[SceneObject]]:
    items = list(objects)
    if all(isinstance(item, SceneObject) for item in items):
        return [items for _ in range(envs)]
    if len(items) == envs and all(not isinstance(group, SceneObject) and all(isinstance(o, SceneObject) for o in group)
                                  for group in items):
        return [list(group) for group in items]
    raise ValueError(f"Scene.objects must be SceneObjects (for every environment) or {envs} sequences of them "
                     "(one per environment)")


def _state_array(vessel, sim, name: str) -> wp.array:
    array = getattr(sim.state, name, None)
    if not isinstance(array, wp.array):
        raise ValueError(f"Scene: the {vessel.name}'s parts read the state array {name!r}, which its simulator "
                         f"({type(sim).__name__}) does not have")
    return array


_LOOKS = {"sail": 1, "metal": 1}
"""``SceneView.part_look`` of each material the camera draws in a sail's colour (every other: a hull's)."""


class _PartTable:
    """A vessel's parts as the ``SceneView.part_*`` and ``joint_*`` rows, their Warp meshes and the boats'
    bound."""

    def __init__(self, parts, joints: dict, scaling: PartScaling | None, count: int, device):
        parts = tuple(parts)
        if not parts or not all(isinstance(part, VesselPart) for part in parts):
            raise ValueError(f"Scene.parts must be one or more ocean_warp.vessel.VesselParts, got {parts!r:.120}")
        scaled = set(scaling.parts) if scaling is not None else set()
        self.scales = tuple(scaling.scales) if scaling is not None else (1.0,)
        if not self.scales or not all(math.isfinite(v) and v > 0.0 for v in self.scales):
            raise ValueError(f"Scene.scaling.scales must be finite factors > 0, got {self.scales!r}")
        names = list(dict.fromkeys(part.joint for part in parts if part.joint is not None))
        if len(names) > JOINT_ARRAYS:
            raise ValueError(f"Scene: a vessel's parts may turn with at most {JOINT_ARRAYS} joint state arrays, got "
                             f"{len(names)} ({', '.join(names)})")
        self.joints = []
        for name in names:
            array = joints.get(name)
            if not isinstance(array, wp.array) or array.dtype != wp.float32 or array.ndim not in (1, 2) \
                    or array.shape[0] != count:
                raise ValueError(f"Scene.joints[{name!r}] must be a ({count},) or ({count}, C) float32 Warp array "
                                 f"(the parts turn with it), got {array!r:.80}")
            self.joints.append(array.reshape((count, 1)) if array.ndim == 1 else array)
        self.meshes, rows, self.bound = [], [], 0.0
        for part in parts:
            origin = np.asarray(scaling.origin if part.name in scaled else (0.0, 0.0, 0.0), dtype=np.float64)
            points = np.asarray(part.mesh.points, dtype=np.float64) - origin
            joint = names.index(part.joint) if part.joint is not None else -1
            if joint >= 0 and not 0 <= part.joint_column < self.joints[joint].shape[1]:
                raise ValueError(f"Scene: part {part.name!r} reads column {part.joint_column} of {part.joint!r}, "
                                 f"which has {self.joints[joint].shape[1]}")
            self.meshes.append(_wp_mesh(MeshData(points, part.mesh.face_counts, part.mesh.face_indices), device))
            largest = max(self.scales) if part.name in scaled else 1.0
            self.bound = max(self.bound, float(np.linalg.norm(part.pivot)) + float(np.linalg.norm(origin))
                             + largest * float(np.linalg.norm(points, axis=1).max()))
            rows.append((part.pivot, origin, joint, part.joint_column, int(part.name in scaled),
                         _LOOKS.get(part.material, 0)))
        self._rows, self._device = rows, device

    def view_fields(self) -> dict:
        device = self._device
        pivot, origin, joint, column, scaled, look = zip(*self._rows)
        unused = wp.zeros((1, 1), dtype=float, device=device)
        joints = self.joints + [unused] * (JOINT_ARRAYS - len(self.joints))
        ints = lambda values: wp.array(np.array(values, np.int32), dtype=int, device=device)  # noqa: E731
        return dict(part_mesh=wp.array(np.array([mesh.id for mesh in self.meshes], np.uint64), dtype=wp.uint64,
                                       device=device),
                    part_pivot=wp.array(np.array(pivot, np.float32), dtype=wp.vec3, device=device),
                    part_origin=wp.array(np.array(origin, np.float32), dtype=wp.vec3, device=device),
                    part_joint=ints(joint), part_column=ints(column), part_scaled=ints(scaled), part_look=ints(look),
                    joint_0=joints[0], joint_1=joints[1], joint_2=joints[2])
