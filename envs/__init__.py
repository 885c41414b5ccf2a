"""Reinforcement-learning environments on the E-Boat simulator (installed as ``ocean_warp.envs``).

At the top: ``BatchedEnv`` and ``EnvBuffers`` (``protocol``: the face of a batch of environments that
training, evaluation and the adapters use), ``SailingEnv`` (``sailing_env``: N boats, one task, one captured
decision step with same-step resets; it implements the protocol, as ``parallel``'s ``ShardedSailingEnv``
does), the task ids (``registration``) and their specs (``task_specs``: one per task). By role, in
subpackages (each ``__init__`` says what it holds):

- ``tasks``: ``WaypointConfig`` (the seed paper's), ``WaypointPlusConfig`` (ours), ``MissionConfig`` (the
  six-waypoint "BCDACA" mission), ``MissionSailConfig`` (the mission with the propeller off),
  ``AvoidConfig`` and ``AvoidSailConfig`` (a waypoint through buoys and piles, with a lidar), and their
  kernels.
- ``interfaces``: ``RslRlVecEnv`` (rsl-rl), ``SailingVectorEnv`` and ``SailingEnvSingle`` (gymnasium, with the
  ids ``ocean_warp/EBoatWaypoint-v0``, ``ocean_warp/EBoatWaypointPlus-v0``, ``ocean_warp/EBoatMission-v0``,
  ``ocean_warp/EBoatMissionSail-v0``, ``ocean_warp/EBoatAvoid-v0`` and ``ocean_warp/EBoatAvoidSail-v0``),
  ``Sb3VecEnv`` (stable-baselines3, an optional extra:
  ``ocean_warp.envs.interfaces.sb3_env``).
- ``parallel``: environments over CPU worker processes. ``controllers``: ``SailingAutopilot``, a classical
  sailing autopilot that runs any task in place of a policy. ``training``: PPO, checkpoints, the shipped
  policies. ``evaluation``: controllers sailing a task's runs, their results and files. ``apps``:
  ``ocean-warp eval``, ``demo`` and ``export-usd``. ``sensors``: the lidar and camera hooks (``LidarHook``,
  ``CameraHook``) that scan inside every decision. ``ros``: ``ocean-warp ros``, the MCAP log of an env and
  ``ocean-warp export-policy``. ``vrx``: VRX's tasks on any vessel.
"""

from .registration import TASK_IDS, make_task_config, register_envs

# The other public names, each with the module that holds it, imported on first use (PEP 562): the
# command line's parsers import light modules of this package without loading Warp and torch.
_PUBLIC = {
    "BatchedEnv": "protocol", "EnvBuffers": "protocol",
    "SailingEnv": "sailing_env", "environment_origins": "sailing_env",
    **{name: "tasks.task_configs" for name in (
        "AvoidConfig", "AvoidSailConfig", "BCDACA_ROUTE", "MISSION_WAYPOINTS", "MissionConfig", "MissionSailConfig",
        "ObservationSet", "ObstacleLayoutConfig", "ReefRule", "RewardConfig", "StartConfig", "TaskConfig",
        "WaypointConfig", "WaypointPlusConfig")},
    "SailingEnvSingle": "interfaces.gym_env", "SailingVectorEnv": "interfaces.gym_env",
    "RslRlVecEnv": "interfaces.rsl_rl_env",
}

__all__ = ["BatchedEnv", "SailingEnv", "EnvBuffers", "environment_origins", "TaskConfig", "WaypointConfig",
           "WaypointPlusConfig", "MissionConfig", "MissionSailConfig", "AvoidConfig", "AvoidSailConfig",
           "ObstacleLayoutConfig", "StartConfig", "RewardConfig", "ReefRule", "ObservationSet", "BCDACA_ROUTE",
           "MISSION_WAYPOINTS", "RslRlVecEnv", "SailingVectorEnv", "SailingEnvSingle", "TASK_IDS",
           "make_task_config", "register_envs"]


from ocean_warp.lazy_names import lazy_attributes  # noqa: E402

__getattr__, __dir__ = lazy_attributes(__name__, _PUBLIC)


register_envs()
