"""VRX's tasks, batched: N boats of any vessel (the WAM-V by default), one decision per :meth:`VrxEnv.step`.

A step runs, as one replayed graph on the simulator's device: the vessel's action kernel, ``steps_per_decision``
physics steps, the reward and episode-end kernel, VRX's score of the episodes that ended, the observation
kernel (the final observations), a start drawn for every environment that ended, the vessel's masked reset and
the observation kernel again. It reads only the common state of the vessel's simulator
(``ocean_warp.vessel.VesselSimulator``) and so never imports a particular vessel.
"""

from __future__ import annotations

import math

import torch
import warp as wp

from ocean_warp.device_structs import struct_from
from ocean_warp.validation import require_int_in_range

from ..sailing_env import environment_origins
from ..vessel_env import BatchedVesselEnv
from .path_course import PathCourse
from .reward_terms import vrx_reward_terms
from .scoring import VrxScorer
from .task_config import VrxTask, VrxTaskConfig
from .vrx_kernels import (POLICY_BASE, PRIVILEGED, VesselStartRows, VrxCourse, VrxParameters, VrxStartDistribution,
                          vrx_draw_starts, vrx_evaluate_kernel, vrx_observe)

__all__ = ["VrxEnv"]

_SEARCH = 10.0
"""How far the gap to the nearest buoy is looked for [m]."""
_KIND = {VrxTask.STATION_KEEPING: 0, VrxTask.WAYFINDING: 1, VrxTask.FOLLOW_PATH: 2}


class VrxEnv(BatchedVesselEnv):
    """``num_envs`` boats sailing one of VRX's tasks (a :class:`~ocean_warp.envs.vrx.VrxTaskConfig`), batched; it
    implements :class:`~ocean_warp.envs.protocol.BatchedEnv`.

    Example::

        env = VrxEnv(VrxTaskConfig(kind="station_keeping"), 4096, device="cuda:0", seed=1)
        for _ in range(120):
            env.step(policy(env.buffers.policy_obs))
        env.buffers.final_score                        # VRX's score of each env's last ended episode
    """

    def __init__(self, task: VrxTaskConfig, num_envs: int, *, device=None, seed: int = 0, first_env: int = 0):
        if not isinstance(task, VrxTaskConfig):
            raise ValueError(f"VrxEnv: task must be a VrxTaskConfig, got {task!r}")
        self.task = task
        self.num_envs = require_int_in_range("VrxEnv", "num_envs", num_envs, 1, 2**24)
        self.seed = require_int_in_range("VrxEnv", "seed", seed, 0, 2**31 - 1)
        self.first_env = require_int_in_range("VrxEnv", "first_env", first_env, 0, 2**24)
        self.vessel = task.vessel
        self.simulator = self.vessel.simulator(self.num_envs, device=device, first_boat=self.first_env)
        self.device = self.simulator.device
        self.torch_device = torch.device(wp.device_to_torch(self.device))
        self.num_actions = task.num_actions
        self.num_policy_obs = POLICY_BASE + self.num_actions + task.lidar_observations
        self.num_critic_obs = self.num_policy_obs + PRIVILEGED
        self.max_episode_length = task.max_episode_length
        self.decision_period = task.decision_period
        self.steps_per_decision = task.steps_per_decision
        self.parameters = struct_from(VrxParameters, task, task.reward, kind=_KIND[task.kind],
                                      goal_count=task.max_goals, goal_count_low=task.goal_range[0],
                                      num_actions=self.num_actions,
                                      max_episode_length=task.max_episode_length)
        self.start_distribution = _start_distribution(task, self._start_height())

        n, device, goals = self.num_envs, self.device, task.max_goals
        zeros = lambda shape, dtype=float: wp.zeros(shape, dtype=dtype, device=device)  # noqa: E731
        self._seed = wp.array([self.seed], dtype=int, device=device)
        origins = environment_origins(self.first_env + n, self.simulator.ocean.config.tile_size, True)
        self.origin = wp.array(origins[self.first_env:], dtype=wp.vec3, device=device)
        self.route = zeros((n, goals), wp.vec3)
        """(N, G) each environment's goal poses: x, y from its origin [m] and the heading [rad]; the columns from
        ``goal_count`` on repeat the episode's last goal."""
        self.goal_count = wp.full(n, goals, dtype=wp.int32, device=device)
        """(N,) int32 goals (gates) of each environment's episode, drawn at its start in ``task.goal_range``."""
        self._allocate_decision_arrays()
        self.propeller_level = zeros(n, wp.int32)
        """(N,) zeros: VRX's vessels have no propeller levels (the buffer every env has)."""
        enabled = task.enabled_actions()
        self._enabled_actions = None if all(enabled) else wp.array(enabled, dtype=wp.int32, device=device)
        """The vessel's action columns the task uses (None: all of them)."""
        self._course = VrxCourse()
        c = self._course
        c.origin, c.route, c.goal_count, c.target_index = self.origin, self.route, self.goal_count, self.target_index
        c.target_world = self.target_world
        c.previous_error, c.previous_position = zeros(n), zeros(n, wp.vec3)
        c.episode_length, c.episode_return = self.episode_length, self.episode_return
        c.episode_count = self.episode_count
        c.last_action = zeros((n, self.num_actions))
        self._start_rows = struct_from(VesselStartRows, self.simulator.start)
        self.clearance = wp.full(n, _SEARCH, dtype=float, device=device)
        """(N,) each boat's gap to the nearest buoy after the last decision [m] (``_SEARCH`` with none nearer)."""
        self.obstacles = _path_course(task, self.simulator, self.origin, self.clearance, self.first_env)
        """The :class:`~ocean_warp.envs.vrx.path_course.PathCourse` (gates' buoys, obstacles, contact) of the path
        with ``path_course``; None otherwise."""
        self._hold([] if self.obstacles is None else [self.obstacles])
        self.scorer = VrxScorer(self, 0.5 * task.gate_width)
        """What keeps VRX's score of each episode and writes ``final_score`` (``ocean_warp.envs.vrx.scoring``)."""

        obstacles = torch.zeros((n, 0, 4), device=self.torch_device) if self.obstacles is None else \
            wp.to_torch(self.obstacles.table)
        self.buffers = self._bind_buffers(obstacles)
        """torch views of the results, bound once (see :class:`~ocean_warp.envs.protocol.EnvBuffers`); ``target``
        holds the current goal's world x, y and, in column 2, its heading [rad]."""
        self._start_replay()
        self.reset()

    # --- the decision step (``BatchedVesselEnv.step`` replays it) --------------------------------------
    def launch_actions(self) -> None:
        """The vessel's action kernel (launch only)."""
        if self._enabled_actions is None:
            self.simulator.launch_actions(self.actions)
        else:
            self.simulator.launch_actions(self.actions, self._enabled_actions)

    def launch_task(self) -> None:
        """Rewards and episode ends, VRX's scores, the final observations, new episodes for the environments that
        ended, and the observations of the next decision (launch only)."""
        state = self.simulator.state
        self._sense_components()
        wp.launch(vrx_evaluate_kernel(vrx_reward_terms(self.task)), dim=self.num_envs, device=self.device,
                  inputs=[self.parameters, 0.5 * self.task.gate_width, self.actions, state.status, state.position,
                          state.orientation, self._course],
                  outputs=[self.reward, self.terminated, self.time_out, self.done, self.reset_mask, self.final_return,
                           self.final_length, self.final_success, self.final_status, self.final_waypoints])
        self.scorer.launch_finish(self)
        self._observe(self.final_policy_obs, self.final_critic_obs)
        self._start_episodes(self.reset_mask)
        self._sense_components()
        self._observe(self.policy_obs, self.critic_obs)

    def _observe(self, policy: wp.array, critic: wp.array) -> None:
        state = self.simulator.state
        wp.launch(vrx_observe, dim=self.num_envs, device=self.device,
                  inputs=[self.parameters, state.position, state.orientation, state.velocity, state.wind_velocity,
                          self._course], outputs=[policy, critic])
        self._append_component_observations(policy, critic)

    def _start_episodes(self, mask: wp.array) -> None:
        wp.launch(vrx_draw_starts, dim=self.num_envs, device=self.device,
                  inputs=[self.parameters, self.start_distribution, self._seed, self.first_env, mask, self._course,
                          self._start_rows])
        self.scorer.launch_courses(self)
        self._draw_components(mask, self._course)
        self.simulator.reset_masked(mask)

    # --- host calls --------------------------------------------------------------------------------
    def _after_reset(self) -> None:
        self.scorer.launch_reset(self)

    def _after_physics_step(self) -> None:
        self.scorer.launch_sample(self)

    def _start_height(self) -> float:
        rest = getattr(self.simulator, "rest_height", None)
        return float(rest()) if callable(rest) else 0.0


def _path_course(task: VrxTaskConfig, simulator, origin: wp.array, clearance: wp.array,
                 first_env: int) -> PathCourse | None:
    """The buoys, contact and lidar of the path (a task of kind ``follow_path`` with ``path_course``), else None.
    The lidar's sectors follow the task's values and the last actions (policy), and the privileged values
    (critic)."""
    if task.kind is not VrxTask.FOLLOW_PATH or task.path_course is None:
        return None
    column = POLICY_BASE + task.num_actions
    return PathCourse(simulator, origin, task.path_course, gates=task.max_goals,
                      gate_half_width=0.5 * task.gate_width, vessel=task.vessel, clearance=clearance, search=_SEARCH,
                      policy_column=column, critic_column=column + PRIVILEGED, first_env=first_env)


def _start_distribution(task: VrxTaskConfig, start_height: float) -> VrxStartDistribution:
    s, d, rad = task.start, VrxStartDistribution(), math.radians
    d.goal_distance_low, d.goal_distance_high = s.goal_distance
    d.goal_spacing_low, d.goal_spacing_high = s.goal_spacing
    d.goal_bearing_low, d.goal_bearing_high = rad(s.goal_bearing_deg[0]), rad(s.goal_bearing_deg[1])
    d.leg_turn_low, d.leg_turn_high = rad(s.leg_turn_deg[0]), rad(s.leg_turn_deg[1])
    d.wind_speed_low, d.wind_speed_high = s.wind_speed
    d.wind_direction_low, d.wind_direction_high = rad(s.wind_direction_deg[0]), rad(s.wind_direction_deg[1])
    d.gust_scale_low, d.gust_scale_high = s.gust_scale
    d.current_speed_low, d.current_speed_high = s.current_speed
    d.current_direction_low, d.current_direction_high = (rad(s.current_direction_deg[0]),
                                                         rad(s.current_direction_deg[1]))
    d.noise_scale_low, d.noise_scale_high = s.sensor_noise_scale
    d.start_speed_low, d.start_speed_high = s.start_speed
    d.start_height = start_height
    d.gate_half_width = 0.5 * task.gate_width
    buoys = task.path_course if task.kind is VrxTask.FOLLOW_PATH else None
    d.buoy_clearance = 0.0 if buoys is None else buoys.start_clearance + buoys.gate_buoy_radius
    return d
