"""Sensors that see: the ray-cast scene (sea, boats, objects), the lidar and the camera.

- ``scene``: ``Scene`` and ``SceneObject`` (buoys that ride the waves, fixed piles, any mesh trimesh reads).
- ``lidar``: ``LidarConfig``, ``Lidar`` (a lidar on every boat of a scene).
- ``camera``: ``CameraConfig``, ``Camera`` (depth and RGB of a camera on every boat of a scene), ``ViewCamera``
  and ``render_view`` (a free camera).

The hooks that scan and capture inside every decision of a ``SailingEnv`` live above the core, in
``ocean_warp.envs.sensors`` (``LidarHook``, ``CameraHook``).
"""

from .camera import Camera, CameraConfig, ViewCamera, render_view
from .lidar import Lidar
from .lidar_config import BOW_MOUNT, LidarConfig
from .scene import Scene, SceneObject, Shape

__all__ = ["Scene", "SceneObject", "Shape", "LidarConfig", "Lidar", "BOW_MOUNT", "CameraConfig",
           "Camera", "ViewCamera", "render_view"]
