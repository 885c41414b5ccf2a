"""Sensors that see: the ray-cast scene (sea, boats, objects), the lidar and the camera.

- ``scene``: ``Scene`` and ``SceneObject`` (buoys that ride the waves, fixed piles, any mesh trimesh reads).
- ``lidar``: ``LidarConfig``, ``Lidar`` (a lidar on every boat of a scene) and ``LidarHook`` (scans inside
  every decision of a ``SailingEnv``).
- ``camera``: ``CameraConfig``, ``Camera`` (depth and RGB of a camera on every boat of a scene), ``CameraHook``
  (captures inside every decision of a ``SailingEnv``), ``ViewCamera`` and ``render_view`` (a free camera).
"""

from .camera import Camera, CameraConfig, CameraHook, ViewCamera, render_view
from .lidar import Lidar, LidarHook
from .lidar_config import BOW_MOUNT, MASTHEAD_MOUNT, LidarConfig
from .scene import Scene, SceneObject, Shape

__all__ = ["Scene", "SceneObject", "Shape", "LidarConfig", "Lidar", "LidarHook", "BOW_MOUNT", "MASTHEAD_MOUNT",
           "CameraConfig", "Camera", "CameraHook", "ViewCamera", "render_view"]
