"""Tasks: what a boat is asked to do and how it is scored.

- ``task_configs``: the task configs (``WaypointConfig``, the seed paper's; ``WaypointPlusConfig``;
  ``MissionConfig``, the six-waypoint BCDACA mission; ``MissionSailConfig``, the mission under sail alone;
  ``AvoidConfig`` and ``AvoidSailConfig``, a waypoint through buoys and piles seen with a lidar), with their
  starts, rewards and observation sets. Re-exported here.
- ``task_kernels``: the Warp kernels of a decision's task side: rewards and terminations, observations (built per
  task from the terms and blocks it selects: ``evaluate_kernel_for(task)``, ``observe_kernel_for(task)``) and the
  masked resets; ``task_structs``: the structs they take.
- ``reward_terms``: each term of the reward as a device function, and the terms a task selects
  (``reward_terms(task)``).
- ``observation_blocks``: the name and the scale and unit of every value of a task's policy observation
  (``policy_layout(task)``), which the exported policies carry, each block next to the device function that writes
  it.
- ``obstacle_layout`` (``ObstacleLayoutConfig``), ``obstacle_kernels`` and ``obstacle_course``
  (``ObstacleCourse``): the obstacles drawn at every reset, the contact, the lidar and the proximity gap of a
  task with ``obstacles`` or a ``lidar``.
"""

from .task_configs import *  # noqa: F401,F403
from .task_configs import __all__  # noqa: F401
