"""VRX's tasks (station keeping, wayfinding, following a path) as batched RL tasks on any vessel."""

from .path_course_config import PathCourseConfig
from .task_config import VrxRewardConfig, VrxStartConfig, VrxTask, VrxTaskConfig, wamv_vessel
from .vrx_env import VrxEnv

__all__ = ["VrxTask", "VrxTaskConfig", "VrxRewardConfig", "VrxStartConfig", "VrxEnv", "wamv_vessel",
           "PathCourseConfig"]
