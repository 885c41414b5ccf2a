"""Sensors that see: the ray-cast scene (sea, boats, objects), the lidar and the camera.

- ``scene``: ``Scene`` and ``SceneObject`` (buoys that ride the waves, fixed piles, any mesh trimesh reads).
"""

from .scene import Scene, SceneObject, Shape

__all__ = ["Scene", "SceneObject", "Shape"]
