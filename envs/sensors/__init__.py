"""Sensors inside an environment's decisions: the core's lidar and camera (``ocean_warp.perception``) on every
boat of a ``SailingEnv``, driven by decision hooks (``env.attach(hook)``).

- ``lidar_hook``: ``LidarHook`` (scans every ``LidarConfig.rate`` inside each decision, sectors for a policy).
- ``camera_hook``: ``CameraHook`` (depth and RGB captured at ``CameraConfig.rate`` inside each decision).
"""

from .camera_hook import CameraHook
from .lidar_hook import LidarHook

__all__ = ["CameraHook", "LidarHook"]
