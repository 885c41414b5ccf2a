"""The batched sailing environment: N E-Boats, one task, one decision per :meth:`SailingEnv.step`.

A step runs, on the simulator's device: the actions to actuator commands, ``steps_per_decision``
physics steps, the reward and episode-end kernel, the observation kernel (the final observations),
a start drawn for every environment that ended, the simulator's masked reset of exactly those, and the
observation kernel again (what the policy sees next). All of it is one captured graph, on CUDA and on
the CPU (``ocean_warp.replay``); nothing in it allocates or waits for the host. The results are Warp
arrays that torch reads through views bound in the constructor (``env.buffers``).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import torch
import warp as wp

from ocean_warp.device_structs import struct_from
from ocean_warp.eboat import EBoatSimulator, EBoatVessel, Hydrostatics
from ocean_warp.perception.scene import Scene
from ocean_warp.validation import require_int_in_range

from .tasks.task_kernels import (
    POLICY_OBS,
    BoatView,
    Course,
    EpisodeEnds,
    StartRows,
    PRIVILEGED_OBS,
    StartDistribution,
    TaskParameters,
    draw_starts,
    evaluate_kernel_for,
    observe_kernel_for,
    policy_observation_count,
)
from .decision_hook import DecisionHook
from .tasks.obstacle_course import ObstacleCourse
from .vessel_env import BatchedVesselEnv
from .tasks.task_configs import ObservationSet, TaskConfig

__all__ = ["SailingEnv", "DecisionHook", "environment_origins"]


def environment_origins(count: int, tile_size: float, spread: bool) -> np.ndarray:
    """(count, 3) origins spread evenly over the periodic ocean tile [m] (a low-discrepancy R2 sequence,
    so any number of environments covers the tile without clumps); zeros when not ``spread``."""
    if not spread:
        return np.zeros((count, 3), dtype=np.float32)
    plastic = 1.324717957244746  # x^3 = x + 1: the R2 sequence's generator
    steps = np.arange(count, dtype=np.float64)[:, None] * np.array([1.0 / plastic, 1.0 / plastic**2])
    xy = np.mod(0.5 + steps, 1.0) * tile_size
    return np.column_stack([xy, np.zeros(count)]).astype(np.float32)


class SailingEnv(BatchedVesselEnv):
    """``num_envs`` E-Boats sailing one task (a :class:`~ocean_warp.envs.tasks.TaskConfig`), batched.

    Example::

        env = SailingEnv(WaypointConfig(), 4096, device="cuda:0", seed=1)
        obs = env.buffers.policy_obs                   # torch view, updated in place by step()
        for _ in range(1000):
            env.step(policy(obs))
            env.buffers.reward, env.buffers.done       # views, too

    It implements :class:`~ocean_warp.envs.protocol.BatchedEnv`, the face training, evaluation and the
    adapters use; ``simulator`` (the :class:`~ocean_warp.eboat.EBoatSimulator`) is there for recorders and
    tests that look inside one decision (:class:`DecisionHook`).
    """

    num_actions = 3

    def __init__(self, task: TaskConfig, num_envs: int, *, device=None, seed: int = 0, first_env: int = 0):
        """``first_env``: this batch is environments [first_env, first_env + num_envs) of a larger one with
        the same task and seed, and sails exactly as they would there: their origins, start draws, mass
        variants, gusts and sensor noise (a shard of a batch; ``ocean_warp.envs.parallel.sharded`` runs one per
        process)."""
        if not isinstance(task, TaskConfig):
            raise ValueError(f"SailingEnv: task must be a TaskConfig (WaypointConfig, ...), got {task!r}")
        self.task = task
        self.num_envs = require_int_in_range("SailingEnv", "num_envs", num_envs, 1, 2**24)
        self.seed = require_int_in_range("SailingEnv", "seed", seed, 0, 2**31 - 1)
        self.first_env = require_int_in_range("SailingEnv", "first_env", first_env, 0, 2**24)
        self.vessel = EBoatVessel(task.simulator)
        """The E-Boat of the task (what builds the boats, and what the scene, the stage and the topics draw)."""
        self.simulator = self.vessel.simulator(self.num_envs, device=device, first_boat=self.first_env)
        self.device = self.simulator.device
        self.torch_device = torch.device(wp.device_to_torch(self.device))
        # The policy sees its observation set's values, its reef level (a task with a reef rule), its lidar's sectors.
        lidar_column = POLICY_OBS[ObservationSet(task.observation).value] + task.reef_observations
        self.num_policy_obs = policy_observation_count(task)
        self.num_critic_obs = self.num_policy_obs + PRIVILEGED_OBS
        self.max_episode_length = task.max_episode_length
        self.decision_period = task.decision_period
        self.steps_per_decision = task.steps_per_decision
        self.parameters = _task_parameters(task)
        self.start_distribution = _start_distribution(task, self._start_height(), self.device)

        n, device = self.num_envs, self.device
        zeros = lambda shape, dtype=float: wp.zeros(shape, dtype=dtype, device=device)  # noqa: E731
        self._seed = wp.array([self.seed], dtype=int, device=device)
        origins = environment_origins(self.first_env + n, task.simulator.ocean.tile_size, task.ocean_spacing)
        self.origin = wp.array(origins[self.first_env:], dtype=wp.vec3, device=device)
        route = np.zeros((n, task.route_length, 3), dtype=np.float32)
        if task.route is not None:
            route[:, :, :2] = np.array(task.route, dtype=np.float32)
        self.route = wp.array(route, dtype=wp.vec3, device=device)
        """(N, R) waypoints of each environment, from its origin [m]."""
        self._allocate_decision_arrays()
        self.last_action = zeros((n, 3))
        self.leg_start = zeros(n, wp.vec3)
        self.previous_distance = zeros(n)
        self.propeller_level = zeros(n, self.simulator.control.propeller.dtype)
        """(N,) the propeller level the last decision applied (copied before a reset stops the motor)."""
        self._enabled_actions = wp.array([1 if task.propeller else 0, 1, 1], dtype=wp.int32, device=device)
        """The vessel's action columns the task uses: the propeller's is off under sail alone."""
        self.clearance = wp.full(n, task.reward.proximity_range, dtype=float, device=device)
        """(N,) each boat's gap to the nearest obstacle after the last decision [m] (the reward's proximity
        range on open water)."""
        self.obstacles = _obstacle_course(task, self.simulator, self.origin, self.first_env, self.clearance,
                                          lidar_column)
        """The :class:`~ocean_warp.envs.tasks.obstacle_course.ObstacleCourse` (layouts, contact, lidar) of a
        task with ``obstacles``, ``contact`` or a ``lidar``; None otherwise."""
        self._hold([] if self.obstacles is None else [self.obstacles])

        self._course = struct_from(Course, self)
        """The task's per-environment arrays, grouped as the kernels take them."""
        self._ends = struct_from(EpisodeEnds, self)
        self._boats = struct_from(BoatView, self.simulator.state)
        self._start_rows = struct_from(StartRows, self.simulator.start)

        self.buffers = self._bind_buffers(self._obstacle_view())
        """torch views of the results, bound once (see :class:`~ocean_warp.envs.protocol.EnvBuffers`)."""
        self._start_replay()
        self.reset()

    def _obstacle_view(self) -> torch.Tensor:
        if self.obstacles is None or self.obstacles.slots == 0:
            return torch.zeros((self.num_envs, 0, 4), device=self.torch_device)
        return wp.to_torch(self.obstacles.table)

    # --- the decision step (``BatchedVesselEnv.step`` replays it) --------------------------------------
    def launch_actions(self) -> None:
        """The environment layer before the physics: actions to actuator commands, and the propeller level
        they apply (launch only)."""
        self.simulator.launch_actions(self.actions, self._enabled_actions)
        wp.copy(self.propeller_level, self.simulator.control.propeller)

    def launch_task(self) -> None:
        """The environment layer after the physics: rewards and episode ends, the final observations, new
        episodes for the environments that ended, and the observations of the next decision (launch only)."""
        state = self.simulator.state
        self._sense_components()
        wp.launch(evaluate_kernel_for(self.task), dim=self.num_envs, device=self.device,
                  inputs=[self.parameters, self.actions, state.status, state.position, self.clearance, self._course,
                          self._ends])
        self._observe(self.final_policy_obs, self.final_critic_obs)
        self._start_episodes(self.reset_mask)
        self._sense_components()
        self._observe(self.policy_obs, self.critic_obs)

    def _observe(self, policy: wp.array, critic: wp.array) -> None:
        wp.launch(observe_kernel_for(self.task), dim=self.num_envs, device=self.device,
                  inputs=[self.parameters, self._boats, self._course],
                  outputs=[policy, critic])
        self._append_component_observations(policy, critic)

    def _start_episodes(self, mask: wp.array) -> None:
        wp.launch(draw_starts, dim=self.num_envs, device=self.device,
                  inputs=[self.parameters, self.start_distribution, self._seed, self.first_env, mask, self._course,
                          self._start_rows])
        self._draw_components(mask, self._course)
        self.simulator.reset_masked(mask)

    # --- host calls --------------------------------------------------------------------------------
    def _after_reset(self) -> None:
        wp.copy(self.propeller_level, self.simulator.control.propeller)

    def set_start(self, start) -> None:
        """Draw the episodes that start from now on from ``start`` (a ``StartConfig``: a training curriculum's
        wind and leg ranges); the decision's graph is captured anew at the next step. Episodes under way are
        not touched."""
        self.task = dataclasses.replace(self.task, start=start)
        self.start_distribution = _start_distribution(self.task, self.start_distribution.start_height,
                                                      self.device)
        self._recapture()

    def _start_height(self) -> float:
        if self.task.start_height is not None:
            return self.task.start_height
        if self.task.simulator.boat.hydrostatics is Hydrostatics.POINTS:
            return 0.0
        return self.simulator.eboat.rest_height("cpu", self.task.simulator.water)


def _obstacle_course(task: TaskConfig, simulator: EBoatSimulator, origin: wp.array, first_env: int,
                     clearance: wp.array, lidar_column: int) -> ObstacleCourse | None:
    """The obstacle course of a task with ``obstacles``, ``contact`` or a ``lidar`` (None otherwise): the scene of
    the E-Boats, environment i holding boat i from its ``origin`` (N,) [m], with the task's free rows."""
    if task.obstacles is None and task.lidar is None and task.contact is None:
        return None
    n = simulator.count
    vessel = EBoatVessel(task.simulator)
    # The parts the sensors have always seen: the physics hull's detail, no rudder.
    scene = Scene.for_vessel(vessel, simulator, parts=vessel.parts(hull_detail=1, rudder=False), envs=n,
                             boat_env=np.arange(n), origins=origin.numpy(), water_visible=True,
                             free_slots=task.obstacle_slots)
    return ObstacleCourse(scene, layout=task.obstacles, contact=task.contact,
                          shape=vessel.collision_shape(), clearance=clearance,
                          proximity_range=task.reward.proximity_range, lidar=task.lidar,
                          lidar_sectors=task.lidar_sectors, policy_column=lidar_column, first_env=first_env)


def _task_parameters(task: TaskConfig) -> TaskParameters:
    return struct_from(TaskParameters, task, task.reward, reef_levels=task.simulator.boat.reef_levels)


def _start_distribution(task: TaskConfig, start_height: float, device) -> StartDistribution:
    s, d = task.start, StartDistribution()
    rad = math.radians
    d.heading_low, d.heading_high = rad(s.heading_deg[0]), rad(s.heading_deg[1])
    d.heading_step = rad(s.heading_step_deg)
    d.heading_toward_waypoint = int(s.heading_toward_waypoint)
    d.wind_speed_low, d.wind_speed_high = s.wind_speed
    d.wind_direction_low, d.wind_direction_high = rad(s.wind_direction_deg[0]), rad(s.wind_direction_deg[1])
    d.wind_direction_step = rad(s.wind_direction_step_deg)
    d.gust_scale_low, d.gust_scale_high = s.gust_scale
    d.waypoint_distance_low, d.waypoint_distance_high = s.waypoint_distance
    d.waypoint_bearing_low = rad(s.waypoint_bearing_deg[0])
    d.waypoint_bearing_high = rad(s.waypoint_bearing_deg[1])
    d.random_waypoint = int(task.route is None)
    d.start_point = wp.vec3(task.start_point[0], task.start_point[1], 0.0)
    d.position_jitter = task.start.position_jitter
    d.start_height = start_height
    d.surge_low, d.surge_high = s.surge_speed
    d.sheet_low, d.sheet_high = rad(s.sheet_deg[0]), rad(s.sheet_deg[1])
    d.foil_variation = s.foil_variation
    d.noise_scale_low, d.noise_scale_high = s.sensor_noise_scale
    current = task.simulator.current
    if s.current_speed is None:  # the config's current, every episode
        d.current_speed_low = d.current_speed_high = current.speed
        d.current_direction_low = d.current_direction_high = current.direction
    else:
        d.current_speed_low, d.current_speed_high = s.current_speed
        d.current_direction_low = rad(s.current_direction_deg[0])
        d.current_direction_high = rad(s.current_direction_deg[1])
    reef = task.reef
    d.reef_rule = int(reef is not None)
    thresholds = () if reef is None else reef.thresholds
    d.reef_thresholds = wp.array(np.array(thresholds or (0.0,), dtype=np.float32), dtype=float, device=device)
    d.reef_threshold_count = len(thresholds)
    d.reef_fixed_level = -1 if reef is None or reef.level is None else reef.level
    d.reef_random = 0.0 if reef is None else reef.random_level
    d.reef_levels = task.simulator.boat.reef_levels
    return d
