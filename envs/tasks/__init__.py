"""Tasks: what a boat is asked to do and how it is scored.

- ``task_configs``: the task configs (``WaypointConfig``, the seed paper's; ``WaypointPlusConfig``;
  ``MissionConfig``, the six-waypoint BCDACA mission; ``MissionSailConfig``, the mission under sail alone),
  with their starts, rewards and observation sets. Re-exported here.
- ``task_kernels``: the Warp kernels of a decision's task side: actions to commands, observations, rewards,
  terminations and the masked resets.
"""

from .task_configs import *  # noqa: F401,F403
from .task_configs import __all__  # noqa: F401
