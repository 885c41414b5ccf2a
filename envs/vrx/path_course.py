"""VRX's follow-the-path course as an environment component (``envs/components.py``): every gate's two buoys
and obstacle buoys among the gates, placed at every episode start, and the vessel's contact with them.

The buoys are rows of a :class:`~ocean_warp.perception.Scene` (they ride the waves); the contact is the
vessel's own capsule (``Vessel.collision_shape()``) against them: a boat that touches one is flagged
``BoatStatus.COLLIDED``, which ends its episode with VRX's task's penalty. ``table`` lists each environment's
buoys as ``EnvBuffers.obstacles`` does.
"""

from __future__ import annotations

import numpy as np
import warp as wp

from ocean_warp.perception.scene import PARKED_DEPTH, Scene

from ..tasks.obstacle_course import ObstacleCourse
from .path_course_config import PathCourseConfig
from .path_course_kernels import PathLayout, draw_path_buoys

__all__ = ["PathCourseConfig", "PathCourse"]


class PathCourse(ObstacleCourse):
    """The follow-the-path course of ``envs`` environments (see the module's docstring): an
    :class:`~ocean_warp.envs.tasks.obstacle_course.ObstacleCourse` (scene rows, contact, the gap to the nearest
    buoy, ``table``) whose :meth:`draw` places the gates' buoys and the obstacles.

    Args:
        simulator: the vessel's simulator (``ocean_warp.vessel.VesselSimulator``: its ocean and boats' poses).
        origins: (N,) vec3 the environments' origins [m].
        config: the buoys and the contact.
        gates: gates per episode; ``gate_half_width``: half the width between a gate's buoys' centres [m].
        vessel: the ``ocean_warp.vessel.Vessel`` sailing it (its parts for rays, its capsule for contact).
        clearance: (N,) float array each boat's gap to the nearest buoy is written into [m].
        search: the gap written where no buoy is nearer [m].
        policy_column, critic_column: where the lidar's sectors (``config.lidar``) go in the observations.
        first_env: the batch's first environment in a larger one (the lidar's noise streams).
    """

    def __init__(self, simulator, origins: wp.array, config: PathCourseConfig, *, gates: int, gate_half_width: float,
                 vessel, clearance: wp.array, search: float = 10.0, policy_column: int = 0, critic_column: int = 0,
                 first_env: int = 0):
        n = simulator.count
        # The scene draws the vessel's own parts for rays; contact and the gaps read the poses and its capsule.
        scene = Scene.for_vessel(vessel, simulator, envs=n, boat_env=np.arange(n), origins=origins.numpy(),
                                 water_visible=True, free_slots=2 * gates + config.obstacles)
        shape = vessel.collision_shape()
        super().__init__(scene, layout=None, contact=config.contact, shape=shape, clearance=clearance,
                         proximity_range=search, lidar=config.lidar, lidar_sectors=config.lidar_observations,
                         policy_column=policy_column, critic_column=critic_column, first_env=first_env)
        self.config = config
        self.path = PathLayout()
        p = self.path
        p.gate_count, p.gate_half_width, p.gate_buoy_radius = gates, float(gate_half_width), config.gate_buoy_radius
        p.obstacle_slots, p.obstacle_radius = config.obstacles, config.obstacle_radius
        p.opening_clearance, p.start_clearance = config.opening_clearance, config.start_clearance
        p.spacing, p.cross_track, p.attempts = config.spacing, config.cross_track, config.attempts
        p.parked_depth = PARKED_DEPTH
        p.port_color, p.starboard_color = wp.vec3(0.8, 0.05, 0.05), wp.vec3(0.05, 0.6, 0.1)
        p.obstacle_color = wp.vec3(0.05, 0.05, 0.05)

    def draw(self, seed: wp.array, first_env: int, mask: wp.array, course) -> None:
        """The buoys of the environments of ``mask`` (after ``vrx_draw_starts`` drew their gates into ``course``,
        a ``VrxCourse``)."""
        wp.launch(draw_path_buoys, dim=self.num_envs, device=self.device,
                  inputs=[self.path, seed, first_env, mask, course, self.first_row, self.rows],
                  outputs=[self.table, self.obstacle_count])
