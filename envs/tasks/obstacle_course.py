"""An environment's obstacle course on the device: the layouts drawn at every reset into a scene's free rows,
the contact that flags and pushes the boats, the lidar whose sectors the policy sees, and each boat's gap to
the nearest obstacle (the reward's proximity term): an ``EnvComponent`` (``envs/components.py``) built from
explicit parts. ``SailingEnv`` holds one when its task has ``obstacles``, ``contact`` or a ``lidar``; everything
here is launches only, inside the decision's graph.
"""

from __future__ import annotations

import numpy as np
import warp as wp

from ocean_warp.contact import Contact, ContactConfig, contact_model
from ocean_warp.device_structs import struct_from
from ocean_warp.kernels.contact import object_clearances
from ocean_warp.perception.lidar import Lidar
from ocean_warp.perception.lidar_config import LidarConfig
from ocean_warp.perception.scene import PARKED_DEPTH, Scene
from ocean_warp.vessel import CollisionShape

from ..components import EnvComponent

from .obstacle_kernels import KIND_BUOY, KIND_PILE, LayoutParameters, ObjectRows, append_sectors, draw_layouts
from .obstacle_layout import BUOY_COLOR, PILE_COLOR, ObstacleLayoutConfig
from .task_kernels import PRIVILEGED_OBS

__all__ = ["ObstacleCourse", "OBSTACLE_NONE", "OBSTACLE_BUOY", "OBSTACLE_PILE"]

OBSTACLE_NONE, OBSTACLE_BUOY, OBSTACLE_PILE = 0, int(KIND_BUOY), int(KIND_PILE)
"""The kinds in :attr:`ObstacleCourse.table` (0: an empty row)."""


def _layout_parameters(layout: ObstacleLayoutConfig) -> LayoutParameters:
    return struct_from(
        LayoutParameters, layout, count_low=layout.count[0], count_high=layout.count[1],
        buoy_radius_low=layout.buoy_radius[0], buoy_radius_high=layout.buoy_radius[1],
        pile_radius_low=layout.pile_radius[0], pile_radius_high=layout.pile_radius[1],
        pile_half_height=0.5 * layout.pile_height, along_low=layout.along_track[0],
        along_high=layout.along_track[1], parked_depth=PARKED_DEPTH, buoy_color=wp.vec3(*BUOY_COLOR),
        pile_color=wp.vec3(*PILE_COLOR))


class ObstacleCourse(EnvComponent):
    """The obstacles, contact and lidar of an environment whose task has them, as an
    :class:`~ocean_warp.envs.components.EnvComponent` (its hooks: :meth:`draw`, :meth:`sense`,
    :meth:`append_observation`, :meth:`restart_streams`; its ``force_models``: the contact).

    Args:
        scene: the :class:`~ocean_warp.perception.Scene` of the env's boats (environment i holds boat i, placed
            from its origin), with ``scene.free_slots`` rows per environment for the layouts (the device and the
            environments' count and origins are the scene's).
        layout: the obstacles drawn at every episode start (None: none drawn).
        contact: the contact's law (None: no contact force model, the gap is still measured).
        shape: the vessel's capsule (``Vessel.collision_shape()``), for the contact and the gap.
        clearance: (N,) float array this course writes each boat's gap to the nearest obstacle into [m].
        proximity_range: the gap written where no obstacle is nearer [m].
        lidar: the lidar the policy sees through (None: none) and ``lidar_sectors`` of its beams' minima.
        policy_column: the policy observation's column the lidar's sectors start at.
        critic_column: the critic observation's (None: ``policy_column`` + the sailing tasks' privileged values).
        first_env: the batch's first environment in a larger one (the lidar's noise streams).

    Attributes:
        contact: the :class:`~ocean_warp.contact.Contact` force model (None without).
        lidar: the :class:`~ocean_warp.perception.Lidar` (None without).
        obstacle_count: (N,) obstacles in each environment's current layout.
        table: (N, K) vec4 rows x, y from the environment's origin [m], radius [m], kind (``OBSTACLE_*``).
    """

    def __init__(self, scene: Scene, *, layout: ObstacleLayoutConfig | None, contact: ContactConfig | None,
                 shape: CollisionShape, clearance: wp.array, proximity_range: float, lidar: LidarConfig | None = None,
                 lidar_sectors: int = 0, policy_column: int = 0, critic_column: int | None = None,
                 first_env: int = 0):
        device, n = scene.device, scene.envs
        self.scene, self.device, self.num_envs = scene, device, n
        self.slots = scene.free_slots
        self.first_row = wp.array(scene.first_free_slot.astype(np.int32), dtype=int, device=device)
        view = scene.view
        self.rows = struct_from(ObjectRows, shape=view.object_shape, anchor=scene.anchor,
                                position=view.object_position, orientation=view.object_orientation,
                                size=view.object_size, bound=view.object_bound, color=view.object_color,
                                floats=scene.floats, draft=scene.draft)
        self.layout = None if layout is None else _layout_parameters(layout)
        self.obstacle_count = wp.zeros(n, dtype=int, device=device)
        self.table = wp.zeros((n, max(self.slots, 1)), dtype=wp.vec4, device=device)
        """(N, K) every environment's obstacles: x, y from its origin [m], radius [m], kind (``OBSTACLE_*``;
        a row of zeros: none)."""
        self.contact = None if contact is None else Contact(scene, contact, shape=shape)
        self.force_models = () if self.contact is None else (self.contact,)
        self.clearance = clearance
        self.proximity_range = float(proximity_range)
        self._boat_env = wp.array(np.arange(n, dtype=np.int32), dtype=int, device=device)
        self._clearance_model = self.contact.model if self.contact is not None else contact_model(None, shape)
        """The boats' capsule, for the gap to the obstacles (with or without contact forces)."""
        self.lidar = None if lidar is None else Lidar(lidar, scene, first_index=first_env)
        self._sectors = None if self.lidar is None else self.lidar.downsampled_array(lidar_sectors)
        self._policy_column = policy_column
        self._critic_column = policy_column + PRIVILEGED_OBS if critic_column is None else critic_column

    # --- inside the decision ------------------------------------------------------------------------
    def draw(self, seed: wp.array, first_env: int, mask: wp.array, course) -> None:
        """New layouts for the environments of ``mask`` (after ``draw_starts`` wrote their starts)."""
        if self.layout is None:
            return
        wp.launch(draw_layouts, dim=self.num_envs, device=self.device,
                  inputs=[self.layout, seed, first_env, mask, course, self.first_row, self.rows],
                  outputs=[self.table, self.obstacle_count])

    def sense(self) -> None:
        """The scene refreshed (the sea, the buoys on it), a lidar scan and every boat's gap to the nearest
        obstacle, from the boats' current poses."""
        self.scene.refresh()
        if self.lidar is not None:
            self.lidar.scan()
        wp.launch(object_clearances, dim=self.num_envs, device=self.device,
                  inputs=[self.scene.view, self._clearance_model, self._boat_env, self.proximity_range],
                  outputs=[self.clearance])

    def append_observation(self, policy: wp.array, critic: wp.array) -> None:
        """The lidar's sectors at their columns: after the task's values (policy) and the privileged ones (critic)."""
        if self._sectors is None:
            return
        wp.launch(append_sectors, dim=self._sectors.shape, device=self.device,
                  inputs=[self._sectors, self._policy_column, self._critic_column], outputs=[policy, critic])

    def restart_streams(self) -> None:
        """The lidar's noise from its first draw again (``SailingEnv.reset(seed)``)."""
        if self.lidar is not None:
            self.lidar.restart_stream()
