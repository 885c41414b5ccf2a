"""How each task is trained: one :class:`TrainConfig` per task id (the Isaac Lab habit of an agents config
beside the task), used by ``ocean-warp train`` and overridable from its command line.

A config names the task the policy is *for* (``task``) and the config it is trained *on*
(``train_task``): the mission policy, for one, practises single legs of every bearing to the wind and
then sails the six-waypoint mission, whose observations (toward the current waypoint) are the same.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

from ocean_warp.validation import require_in_range, require_int_in_range, require_positive, require_range_pair

from ..registration import make_task_config
from ..vrx.task_config import VrxTaskConfig
from ..task_specs import TASK_SPECS, task_spec
from ..tasks.task_configs import (
    AvoidConfig,
    AvoidSailConfig,
    MissionConfig,
    MissionSailConfig,
    StartConfig,
    TaskConfig,
    WaypointPlusConfig,
)

__all__ = ["PpoConfig", "CurriculumConfig", "TrainConfig", "AGENT_CONFIGS", "agent_config", "mission_practice",
           "TRAINING_REEF_RANDOM", "with_training_reef", "waypoint_agent", "waypoint_plus_agent", "mission_agent",
           "mission_sail_agent", "avoid_agent", "avoid_sail_agent"]

TRAINING_REEF_RANDOM = 0.25
"""Probability per training episode that the reef level is drawn uniformly instead of by the task's rule
(``ReefRule.random_level``), so that a policy meets every rig in every wind it trains in; evaluation and the
tasks' defaults keep 0."""


def with_training_reef(task: TaskConfig) -> TaskConfig:
    """``task`` with its reef rule's ``random_level`` at :data:`TRAINING_REEF_RANDOM` (a task without a rule:
    as it is)."""
    if task.reef is None:
        return task
    return dataclasses.replace(task, reef=dataclasses.replace(task.reef, random_level=TRAINING_REEF_RANDOM))


@dataclasses.dataclass(frozen=True)
class PpoConfig:
    """rsl-rl's PPO and its actor-critic networks (MLPs)."""

    hidden_dims: tuple[int, ...] = (64, 64)
    """Hidden layer widths of the actor and of the critic."""
    activation: str = "elu"
    init_std: float = 0.8
    """Initial standard deviation of the Gaussian actions (actions live in [-1, 1])."""
    obs_normalization: bool = True
    """Normalise observations with running statistics (kept in the checkpoint)."""
    learning_rate: float = 1e-3
    schedule: str = "adaptive"
    """"adaptive": the learning rate follows ``desired_kl``; "fixed"."""
    desired_kl: float = 0.01
    num_learning_epochs: int = 5
    num_mini_batches: int = 4
    gamma: float = 0.99
    """Discount per decision."""
    lam: float = 0.95
    clip_param: float = 0.2
    entropy_coef: float = 0.005
    value_loss_coef: float = 1.0
    max_grad_norm: float = 1.0
    privileged_critic: bool = True
    """The critic sees the policy's observation and privileged truth (distance, bearing, velocities, attitude,
    true wind, progress; the env's ``critic`` group); False: the policy's observation only."""

    def __post_init__(self):
        owner = "PpoConfig"
        if not isinstance(self.privileged_critic, bool):
            raise ValueError(f"{owner}.privileged_critic must be True or False, got {self.privileged_critic!r}")
        dims = tuple(self.hidden_dims)
        if not dims or any(not isinstance(d, int) or isinstance(d, bool) or not 1 <= d <= 4096 for d in dims):
            raise ValueError(f"{owner}.hidden_dims must be a non-empty sequence of widths 1..4096, got "
                             f"{self.hidden_dims!r}")
        object.__setattr__(self, "hidden_dims", dims)
        for name, allowed in (("activation", ("elu", "relu", "tanh", "selu", "leaky_relu")),
                              ("schedule", ("adaptive", "fixed"))):
            if getattr(self, name) not in allowed:
                raise ValueError(f"{owner}.{name} must be one of {', '.join(allowed)}, got {getattr(self, name)!r}")
        for name in ("init_std", "learning_rate", "desired_kl", "clip_param", "max_grad_norm", "value_loss_coef"):
            require_positive(owner, name, getattr(self, name))
        for name in ("gamma", "lam"):
            require_in_range(owner, name, getattr(self, name), 0.0, 1.0)
        require_in_range(owner, "entropy_coef", self.entropy_coef, 0.0, 1.0)
        require_int_in_range(owner, "num_learning_epochs", self.num_learning_epochs, 1, 100)
        require_int_in_range(owner, "num_mini_batches", self.num_mini_batches, 1, 4096)

    def actor_config(self) -> dict[str, Any]:
        return {"class_name": "MLPModel", "hidden_dims": list(self.hidden_dims), "activation": self.activation,
                "obs_normalization": self.obs_normalization,
                "distribution_cfg": {"class_name": "GaussianDistribution", "init_std": self.init_std}}

    def critic_config(self) -> dict[str, Any]:
        return {"class_name": "MLPModel", "hidden_dims": list(self.hidden_dims), "activation": self.activation,
                "obs_normalization": self.obs_normalization}

    def runner_config(self, steps_per_env: int) -> dict[str, Any]:
        """The dict rsl-rl's ``OnPolicyRunner`` takes (5.x layout)."""
        return {
            "num_steps_per_env": steps_per_env,
            "save_interval": 10**9,  # checkpoints are written by ocean_warp's trainer, atomically
            "obs_groups": {"actor": ["policy"], "critic": ["critic" if self.privileged_critic else "policy"]},
            "actor": self.actor_config(),
            "critic": self.critic_config(),
            "algorithm": {"class_name": "PPO", "learning_rate": self.learning_rate, "schedule": self.schedule,
                          "desired_kl": self.desired_kl, "num_learning_epochs": self.num_learning_epochs,
                          "num_mini_batches": self.num_mini_batches, "gamma": self.gamma, "lam": self.lam,
                          "clip_param": self.clip_param, "entropy_coef": self.entropy_coef,
                          "value_loss_coef": self.value_loss_coef, "max_grad_norm": self.max_grad_norm},
            "logger": "tensorboard",
        }


@dataclasses.dataclass(frozen=True)
class CurriculumConfig:
    """Sea, wind and legs grow with success. At level k the boats train in ``sea_states[k]`` (Hs [m]), with
    the true wind drawn per episode in ``wind_speeds[k]`` (low, high) [m/s] and the waypoint at a distance in
    ``waypoint_distances[k]`` (low, high) [m]; each of the three may be empty (the task's own throughout) or
    hold one entry per level. The trainer moves up a level when the success rate of the episodes that ended
    over the last ``window`` iterations reaches ``promote_success``. With ``randomize``, each iteration draws
    Hs uniformly in [0, the level's Hs] (domain randomisation of the sea state: one sea per rollout, every
    boat in it). All three empty: no curriculum."""

    sea_states: tuple[float, ...] = ()
    promote_success: float = 0.8
    window: int = 5
    randomize: bool = True
    wind_speeds: tuple[tuple[float, float], ...] = ()
    waypoint_distances: tuple[tuple[float, float], ...] = ()

    def __post_init__(self):
        owner = "CurriculumConfig"
        states = tuple(float(h) for h in self.sea_states)
        if any(not math.isfinite(h) or h < 0.0 for h in states) or list(states) != sorted(states):
            raise ValueError(f"{owner}.sea_states must be increasing wave heights >= 0 [m], got {self.sea_states!r}")
        object.__setattr__(self, "sea_states", states)
        for name, high in (("wind_speeds", 40.0), ("waypoint_distances", 10_000.0)):
            ranges = tuple(require_range_pair(owner, f"{name}[{k}]", pair, 0.0, high)
                           for k, pair in enumerate(getattr(self, name)))
            object.__setattr__(self, name, ranges)
        lengths = {len(v) for v in (self.sea_states, self.wind_speeds, self.waypoint_distances) if v}
        if len(lengths) > 1:
            raise ValueError(f"{owner}: sea_states, wind_speeds and waypoint_distances must each be empty or hold "
                             f"one entry per level, got {len(self.sea_states)}, {len(self.wind_speeds)} and "
                             f"{len(self.waypoint_distances)} entries")
        require_in_range(owner, "promote_success", self.promote_success, 0.0, 1.0)
        require_int_in_range(owner, "window", self.window, 1, 10_000)

    @property
    def levels(self) -> int:
        """Levels of the curriculum (0: none)."""
        return max(len(self.sea_states), len(self.wind_speeds), len(self.waypoint_distances))

    def start(self, base: StartConfig, level: int) -> StartConfig:
        """``base`` with the wind and waypoint-distance ranges of ``level`` (where this curriculum sets them)."""
        changes = {}
        if self.wind_speeds:
            changes["wind_speed"] = self.wind_speeds[level]
        if self.waypoint_distances:
            changes["waypoint_distance"] = self.waypoint_distances[level]
        return dataclasses.replace(base, **changes) if changes else base


@dataclasses.dataclass(frozen=True)
class TrainConfig:
    """Everything ``ocean-warp train`` needs for one task; every field can be set from the command line
    (``--set ppo.learning_rate=3e-4``)."""

    task: str
    """The task id the policy is for (its observations and actions)."""
    train_task: Any
    """The config it is trained on (the task itself, or practice for it): a ``TaskConfig`` or a ``VrxTaskConfig``."""
    num_envs_cpu: int = 256
    """Environments when training on the CPU."""
    num_envs_cuda: int = 4096
    """Environments when training on a GPU."""
    steps_per_env: int = 24
    """Decisions per environment per PPO iteration."""
    iterations: int = 300
    save_interval: int = 50
    """Iterations between checkpoints; every environment restarts from a seeded reset at each multiple,
    which is what lets ``--resume`` continue bit for bit."""
    ppo: PpoConfig = dataclasses.field(default_factory=PpoConfig)
    curriculum: CurriculumConfig = dataclasses.field(default_factory=CurriculumConfig)
    random_episode_start: bool = True
    """Start every segment with random episode lengths, so time-outs do not come in lockstep."""

    def __post_init__(self):
        owner = "TrainConfig"
        if not isinstance(self.train_task, (TaskConfig, VrxTaskConfig)):
            raise ValueError(f"{owner}.train_task must be a TaskConfig or a VrxTaskConfig, got {self.train_task!r}")
        require_int_in_range(owner, "num_envs_cpu", self.num_envs_cpu, 1, 2**24)
        require_int_in_range(owner, "num_envs_cuda", self.num_envs_cuda, 1, 2**24)
        require_int_in_range(owner, "steps_per_env", self.steps_per_env, 1, 100_000)
        require_int_in_range(owner, "iterations", self.iterations, 1, 10**9)
        require_int_in_range(owner, "save_interval", self.save_interval, 1, 10**9)
        for name, kind in (("ppo", PpoConfig), ("curriculum", CurriculumConfig)):
            if not isinstance(getattr(self, name), kind):
                raise ValueError(f"{owner}.{name} must be a {kind.__name__}, got {getattr(self, name)!r}")

    def num_envs(self, device_is_cuda: bool) -> int:
        return self.num_envs_cuda if device_is_cuda else self.num_envs_cpu


def mission_practice(base: MissionConfig | None = None, wind_speed: tuple[float, float] = (8.0, 12.0)) -> MissionConfig:
    """Single legs for the mission ``base`` (default ``MissionConfig()``; ``MissionSailConfig()`` for the
    sail-only one): from rest or under way, any heading, to one waypoint 50-150 m away at any bearing to a
    gusty wind of ``wind_speed`` (low, high) [m/s] (the mission's legs are 100 and 141 m, reached, run and
    beaten), on the mission's boat and sea, with the boat's mass and foils varied by 5 % and the reef level
    drawn at random a quarter of the time (:func:`with_training_reef`)."""
    base = base if base is not None else MissionConfig()
    start = StartConfig(heading_deg=(-180.0, 180.0), heading_step_deg=0.0, wind_speed=wind_speed,
                        wind_direction_deg=(-180.0, 180.0), wind_direction_step_deg=0.0, gust_scale=(0.5, 1.5),
                        waypoint_distance=(50.0, 150.0), waypoint_bearing_deg=(-180.0, 180.0), position_jitter=1.0,
                        surge_speed=(0.0, 1.5), sheet_deg=(0.0, 90.0), foil_variation=0.05)
    simulator = dataclasses.replace(base.simulator, mass_variation=0.05)
    return with_training_reef(dataclasses.replace(base, simulator=simulator, route=None, episode_time=400.0,
                                                  start=start))


VRX_SEA = CurriculumConfig(sea_states=(0.72,), randomize=True)
"""VRX 2023's seas: each iteration draws Hs uniformly in [0, 0.72] m (calm to VRX's gain 0.8 at 6 s)."""


def _wamv_agent(task_id: str) -> TrainConfig:
    """A VRX task's training on the WAM-V: 0.5 s decisions, 32 a segment, 4096 envs on a GPU, VRX's seas."""
    return TrainConfig(task=task_id, train_task=make_task_config(task_id), num_envs_cpu=256, num_envs_cuda=4096,
                       steps_per_env=32, iterations=300, save_interval=50,
                       ppo=PpoConfig(hidden_dims=(64, 64), entropy_coef=0.002), curriculum=VRX_SEA)


def wamv_station_keeping_agent() -> TrainConfig:
    """WamvStationKeeping-v0's training: the task itself."""
    return _wamv_agent("WamvStationKeeping-v0")


def wamv_wayfinding_agent() -> TrainConfig:
    """WamvWayfinding-v0's training: the task itself."""
    return _wamv_agent("WamvWayfinding-v0")


def wamv_follow_path_agent() -> TrainConfig:
    """WamvFollowPath-v0's training: the task itself."""
    return _wamv_agent("WamvFollowPath-v0")


def waypoint_agent() -> TrainConfig:
    """EBoatWaypoint-v0's training: the task itself, 400 iterations."""
    return TrainConfig(task="EBoatWaypoint-v0", train_task=make_task_config("EBoatWaypoint-v0"),
                       num_envs_cpu=256, num_envs_cuda=4096, steps_per_env=24, iterations=400, save_interval=50)


def waypoint_plus_agent() -> TrainConfig:
    """EBoatWaypointPlus-v0's training: the task with the training reef, 128-wide networks."""
    return TrainConfig(task="EBoatWaypointPlus-v0", train_task=with_training_reef(WaypointPlusConfig()),
                       num_envs_cpu=256, num_envs_cuda=4096, steps_per_env=24, iterations=400, save_interval=50,
                       ppo=PpoConfig(hidden_dims=(128, 128)))


def mission_agent() -> TrainConfig:
    """EBoatMission-v0's training: single legs (:func:`mission_practice`) in a sea that grows with
    success."""
    return TrainConfig(task="EBoatMission-v0", train_task=mission_practice(), num_envs_cpu=256, num_envs_cuda=4096,
                       steps_per_env=32, iterations=250, save_interval=50,
                       curriculum=CurriculumConfig(sea_states=(0.1, 0.3, 0.5), promote_success=0.75))


SAIL_PRACTICE_WIND = (3.0, 12.0)
"""True wind [m/s] of the sail-only mission's practice legs: every wind its missions are sailed in, and more."""
SAIL_CURRICULUM = CurriculumConfig(sea_states=(0.1, 0.3, 0.5), promote_success=0.75,
                                   wind_speeds=((4.0, 8.0), SAIL_PRACTICE_WIND, SAIL_PRACTICE_WIND),
                                   waypoint_distances=((30.0, 80.0), (50.0, 150.0), (50.0, 150.0)))
"""The sail-only mission's curriculum: short legs in moderate wind and a low sea first, then every wind, leg
and sea."""


def mission_sail_agent() -> TrainConfig:
    """EBoatMissionSail-v0's training: as the mission's, with the sail-only curriculum."""
    return dataclasses.replace(mission_agent(), task="EBoatMissionSail-v0", curriculum=SAIL_CURRICULUM,
                               train_task=mission_practice(MissionSailConfig(), wind_speed=SAIL_PRACTICE_WIND))


def avoid_agent() -> TrainConfig:
    """EBoatAvoid-v0's training: the task with the training reef, 128-wide networks."""
    return TrainConfig(task="EBoatAvoid-v0", train_task=with_training_reef(AvoidConfig()), num_envs_cpu=256,
                       num_envs_cuda=4096, steps_per_env=32, iterations=300, save_interval=50,
                       ppo=PpoConfig(hidden_dims=(128, 128)))


def avoid_sail_agent() -> TrainConfig:
    """EBoatAvoidSail-v0's training: as the avoidance task's, under sail alone."""
    return dataclasses.replace(avoid_agent(), task="EBoatAvoidSail-v0",
                               train_task=with_training_reef(AvoidSailConfig()))


AGENT_CONFIGS: dict[str, Callable[[], TrainConfig]] = {spec.id: spec.make_agent_config for spec in TASK_SPECS}
"""The default training config of each task id (factories; ``task_specs.TASK_SPECS``)."""


def agent_config(task: str) -> TrainConfig:
    """The default :class:`TrainConfig` of a task id (with or without the "ocean_warp/" prefix): its spec's
    (``task_specs.task_spec``).

    Raises:
        ValueError: an unknown task id (one line naming the known ones).
    """
    return task_spec(task).make_agent_config()
