"""Cameras that see the ray-cast scene: depth and RGB images of every boat's camera at once, and a free
camera for pictures and videos (kernels in ``ocean_warp.kernels.camera_render``, which says how the
frames, the depth and the shading are defined).

Example::

    camera = Camera(CameraConfig(width=64, height=64, rgb=False), scene)   # one on every boat of the scene
    scene.refresh()                        # after the sea moved
    camera.capture()
    camera.depth                           # torch (N, 64, 64) float32 [m]

A camera that captures inside every decision of an environment: ``ocean_warp.envs.sensors.CameraHook``.

A camera is mounted in its boat's body frame (x forward, y left, z up): its *link* frame (the same axes:
x the viewing direction) sits at ``CameraConfig.mount`` [m], turned by ``mount_rpy`` (roll, pitch, yaw
[rad], Z-Y-X as ``ocean_warp.frames``; pitch > 0 looks down). The default is a bow camera 1.2 m forward of
the body origin and 0.6 m above it (just behind the stem, 0.2 m over the deck), looking ahead and 10 degrees
down. The images are in the optical frame (z forward, x right, y down), as ROS has them.
"""

from __future__ import annotations

import dataclasses
import math
from numbers import Integral

import numpy as np
import warp as wp

from ..frames import quaternion_from_roll_pitch_yaw
from ..kernels.camera_render import CameraLens, look_at_poses, mounted_camera_poses, render_cameras
from ..validation import require_finite, require_in_range, require_int_in_range, require_non_negative, require_positive
from .scene import Scene

__all__ = ["CameraConfig", "Camera", "ViewCamera", "render_view"]

MAX_PIXELS_A_SIDE = 8192


@dataclasses.dataclass(frozen=True)
class CameraConfig:
    """A pinhole camera (no distortion, square pixels). Invalid values raise ``ValueError`` naming the field."""

    width: int = 64
    """Image columns [px]."""
    height: int = 64
    """Image rows [px]."""
    horizontal_fov: float = math.radians(90.0)
    """Horizontal field of view [rad], in (0, pi); the vertical one follows from the aspect ratio."""
    min_range: float = 0.1
    """Depth below which a hit reads -inf [m] (REP 117: too close)."""
    max_range: float = 200.0
    """Depth beyond which nothing is seen [m] (+inf in the depth image)."""
    rate: float = 2.0
    """Captures per second of simulated time [Hz] under a ``CameraHook`` (``ocean_warp.envs.sensors``); the
    physics rate divided by it must be a whole number of steps that divides a decision's steps or is a multiple
    of them."""
    mount: tuple[float, float, float] = (1.2, 0.0, 0.6)
    """Position of the camera's link frame in the boat's body frame [m] (x forward, y left, z up)."""
    mount_rpy: tuple[float, float, float] = (0.0, math.radians(10.0), 0.0)
    """Roll, pitch, yaw of the link frame in the body frame [rad] (Z-Y-X; pitch > 0 looks down)."""
    depth: bool = True
    """Render the depth image."""
    rgb: bool = True
    """Render the RGB image."""
    haze_distance: float = 0.0
    """Distance over which haze takes 63 % of a colour [m]; 0: no haze."""

    def __post_init__(self):
        owner = "CameraConfig"
        for name in ("width", "height"):
            require_int_in_range(owner, name, getattr(self, name), 1, MAX_PIXELS_A_SIDE)
        fov = require_finite(owner, "horizontal_fov", self.horizontal_fov)
        if not 0.0 < fov < math.pi:
            raise ValueError(f"{owner}.horizontal_fov must be in (0, pi) [rad], got {self.horizontal_fov!r}")
        object.__setattr__(self, "horizontal_fov", fov)
        object.__setattr__(self, "max_range", require_positive(owner, "max_range", self.max_range, unit=" [m]"))
        object.__setattr__(self, "min_range", require_in_range(owner, "min_range", self.min_range, 0.0,
                                                               self.max_range, unit=" [m] (below max_range)"))
        object.__setattr__(self, "rate", require_positive(owner, "rate", self.rate, unit=" [Hz]"))
        object.__setattr__(self, "mount", _three_finite(owner, "mount", self.mount, "(x, y, z) [m]"))
        object.__setattr__(self, "mount_rpy", _three_finite(owner, "mount_rpy", self.mount_rpy,
                                                            "(roll, pitch, yaw) [rad]"))
        for name in ("depth", "rgb"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"{owner}.{name} must be True or False, got {getattr(self, name)!r}")
        if not (self.depth or self.rgb):
            raise ValueError(f"{owner}.depth and {owner}.rgb are both False: the camera would render nothing")
        object.__setattr__(self, "haze_distance", require_non_negative(owner, "haze_distance", self.haze_distance,
                                                                       unit=" [m]"))

    @property
    def focal_length(self) -> float:
        """fx = fy [px]: (width / 2) / tan(horizontal_fov / 2)."""
        return 0.5 * self.width / math.tan(0.5 * self.horizontal_fov)

    @property
    def vertical_fov(self) -> float:
        """Vertical field of view [rad]: 2 atan((height / 2) / fy)."""
        return 2.0 * math.atan(0.5 * self.height / self.focal_length)

    @property
    def principal_point(self) -> tuple[float, float]:
        """(cx, cy) [px]: the image's centre, ((width - 1) / 2, (height - 1) / 2), pixel centres at integers."""
        return 0.5 * (self.width - 1), 0.5 * (self.height - 1)

    def lens(self) -> CameraLens:
        """The kernel's :class:`~ocean_warp.kernels.camera_render.CameraLens`."""
        lens = CameraLens()
        lens.fx = lens.fy = self.focal_length
        lens.cx, lens.cy = self.principal_point
        lens.min_range, lens.max_range, lens.haze_distance = self.min_range, self.max_range, self.haze_distance
        return lens

    def camera_info(self) -> dict:
        """The fields of ROS's ``sensor_msgs/CameraInfo`` (ROS 1 names; ROS 2 spells D, K, R, P lowercase)
        for this camera: no distortion ("plumb_bob", D all zero), R the identity, K and P row-major with
        fx = fy = :attr:`focal_length` and (cx, cy) = :attr:`principal_point`."""
        f = self.focal_length
        cx, cy = self.principal_point
        return {"width": self.width, "height": self.height, "distortion_model": "plumb_bob", "D": [0.0] * 5,
                "K": [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0], "R": [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
                "P": [f, 0.0, cx, 0.0, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0], "binning_x": 0, "binning_y": 0,
                "roi": {"x_offset": 0, "y_offset": 0, "height": 0, "width": 0, "do_rectify": False}}


def _three_finite(owner: str, field: str, value, meaning: str) -> tuple[float, float, float]:
    try:
        numbers = np.asarray(value, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        numbers = np.array([])
    if numbers.size != 3 or not np.all(np.isfinite(numbers)):
        raise ValueError(f"{owner}.{field} must be three finite numbers {meaning}, got {value!r}")
    return tuple(float(v) for v in numbers)


class _CameraBatch:
    """Cameras that share a config and a scene: their link-frame poses, environments and images, all
    allocated once, and the render launch."""

    def __init__(self, config: CameraConfig, scene: Scene, envs: np.ndarray, own_boats: np.ndarray, owner: str):
        if not isinstance(config, CameraConfig):
            raise ValueError(f"{owner}: config must be a CameraConfig, got {config!r}")
        if not isinstance(scene, Scene):
            raise ValueError(f"{owner}: scene must be an ocean_warp Scene, got {scene!r}")
        self.config, self.scene, self.device = config, scene, scene.device
        self.count = len(envs)
        """Number of cameras."""
        device, n, shape = self.device, self.count, (self.count, config.height, config.width)
        self.lens = config.lens()
        self.env = wp.array(np.asarray(envs, np.int32), dtype=int, device=device)
        """(N,) the environment each camera sees."""
        self.own_boat = wp.array(np.asarray(own_boats, np.int32), dtype=int, device=device)
        """(N,) the boat each camera cannot see (its own; -1: none)."""
        self.position = wp.zeros(n, dtype=wp.vec3, device=device)
        """(N,) world position of each camera's link frame [m], written by each render."""
        self.orientation = wp.zeros(n, dtype=wp.quat, device=device)
        """(N,) link frame (x forward, y left, z up) -> world."""
        self.gate = wp.zeros(1, dtype=int, device=device)
        """(1,) the render writes only while this holds 0 (``CameraHook`` counts decisions in it)."""
        self.depth_array = wp.zeros(shape, dtype=float, device=device) if config.depth else None
        """(N, H, W) float32 depth [m] along the optical axis (+inf: nothing, -inf: too near); None when off."""
        self.rgb_array = wp.zeros(shape + (3,), dtype=wp.uint8, device=device) if config.rgb else None
        """(N, H, W, 3) uint8 sRGB; None when off."""
        self.depth = wp.to_torch(self.depth_array) if config.depth else None
        """torch view of :attr:`depth_array` (bound once)."""
        self.rgb = wp.to_torch(self.rgb_array) if config.rgb else None
        """torch view of :attr:`rgb_array` (bound once)."""
        # The kernel takes both images; a switched-off one is a placeholder it never writes.
        self._depth_target = self.depth_array if config.depth else wp.zeros((1, 1, 1), dtype=float, device=device)
        self._rgb_target = self.rgb_array if config.rgb else wp.zeros((1, 1, 1, 3), dtype=wp.uint8, device=device)

    def camera_info(self) -> dict:
        """ROS ``sensor_msgs/CameraInfo`` fields (:meth:`CameraConfig.camera_info`)."""
        return self.config.camera_info()

    def _launch_render(self) -> None:
        config = self.config
        wp.launch(render_cameras, dim=(self.count, config.height, config.width), device=self.device,
                  inputs=[self.scene.view, self.lens, self.position, self.orientation, self.env, self.own_boat,
                          self.gate, int(config.depth), int(config.rgb)],
                  outputs=[self._depth_target, self._rgb_target])


class Camera(_CameraBatch):
    """One camera on each of ``boats`` (indices into the scene's boats; default every boat the scene draws,
    in order: for ``Scene.for_env`` camera i rides boat i of environment i), all with ``config``. Each sees
    its boat's environment and not its own boat.

    :meth:`capture` renders into :attr:`depth_array` (N, H, W) and :attr:`rgb_array` (N, H, W, 3), which
    torch reads through :attr:`depth` and :attr:`rgb` (views bound here). It reads the scene as it is:
    ``scene.refresh()`` first after the sea moved (``ocean_warp.envs.sensors.CameraHook`` does both).
    """

    def __init__(self, config: CameraConfig, scene: Scene, boats=None):
        if not isinstance(scene, Scene):
            raise ValueError(f"Camera: scene must be an ocean_warp Scene, got {scene!r}")
        environments = scene.boat_env
        if boats is None:
            boats = np.flatnonzero(environments >= 0)
        boats = np.asarray(boats).reshape(-1)
        if boats.size == 0 or not np.issubdtype(boats.dtype, np.integer) or boats.min() < 0 \
                or boats.max() >= environments.size:
            raise ValueError(f"Camera.boats must be one or more boat indices in [0, {environments.size}), "
                             f"got {boats!r}")
        if np.any(environments[boats] < 0):
            raise ValueError(f"Camera.boats: boats {boats[environments[boats] < 0].tolist()} are in no environment "
                             "of the scene")
        super().__init__(config, scene, environments[boats], boats, "Camera")
        self.boats = wp.array(boats.astype(np.int32), dtype=int, device=self.device)
        """(N,) the boat each camera rides."""
        self._mount_position = wp.vec3(*config.mount)
        self._mount_orientation = wp.quat(*quaternion_from_roll_pitch_yaw(config.mount_rpy)[0])

    def capture(self) -> None:
        """The cameras' poses from their boats' and the images (launches only, graph-safe)."""
        view = self.scene.view
        wp.launch(mounted_camera_poses, dim=self.count, device=self.device,
                  inputs=[view.boat_position, view.boat_orientation, self.boats, self._mount_position,
                          self._mount_orientation], outputs=[self.position, self.orientation])
        self._launch_render()


class ViewCamera(_CameraBatch):
    """A free camera over environment ``env`` of ``scene`` (it sees every boat there): a picture or a video's
    frames from any place. Its pose, images and the look-at inputs are allocated once; :meth:`render` is
    launch-only (graph-safe), reading the eye and target from :attr:`eye` and :attr:`target`, which
    :meth:`look_at` sets from the host or a kernel writes on the device (``camera_render.follow_boat``).

    Args:
        width, height: image size [px].
        horizontal_fov: [rad], in (0, pi).
        max_range: depth beyond which the camera sees sky or, below the horizon, haze [m].
        haze_distance: [m] (0: none); a few hundred metres hides the end of the range.
    """

    def __init__(self, scene: Scene, width: int, height: int, horizontal_fov: float, *, env: int = 0,
                 max_range: float = 2000.0, haze_distance: float = 500.0):
        if isinstance(env, bool) or not isinstance(env, Integral) or not 0 <= env < getattr(scene, "envs", 0):
            raise ValueError(f"ViewCamera.env must be an environment of the scene, in [0, "
                             f"{getattr(scene, 'envs', 0)}), got {env!r}")
        config = CameraConfig(width=width, height=height, horizontal_fov=horizontal_fov, min_range=0.0,
                              max_range=max_range, haze_distance=haze_distance)
        super().__init__(config, scene, np.array([env]), np.array([-1]), "ViewCamera")
        self.eye = wp.zeros(1, dtype=wp.vec3, device=self.device)
        """(1,) where the camera is [m], world frame."""
        self.target = wp.array([wp.vec3(1.0, 0.0, 0.0)], dtype=wp.vec3, device=self.device)
        """(1,) the point it looks at [m] (level, no roll)."""

    def look_at(self, eye, target) -> None:
        """Place the camera at ``eye`` looking at ``target`` ((x, y, z) [m], world frame; from the host)."""
        eye = _three_finite("ViewCamera.look_at", "eye", eye, "[m]")
        target = _three_finite("ViewCamera.look_at", "target", target, "[m]")
        self.eye.fill_(wp.vec3(*eye))
        self.target.fill_(wp.vec3(*target))

    def render(self) -> None:
        """The pose from :attr:`eye` and :attr:`target`, and the images (launches only)."""
        wp.launch(look_at_poses, dim=1, device=self.device, inputs=[self.eye, self.target],
                  outputs=[self.position, self.orientation])
        self._launch_render()

    def image(self) -> np.ndarray:
        """(H, W, 3) uint8 sRGB of the last render, on the host."""
        return self.rgb_array.numpy()[0]

    def depth_image(self) -> np.ndarray:
        """(H, W) float32 depth of the last render [m], on the host."""
        return self.depth_array.numpy()[0]


def render_view(scene: Scene, eye, target, width: int, height: int, fov: float, env: int = 0, *,
                camera: ViewCamera | None = None, **options) -> np.ndarray:
    """One RGB frame (H, W, 3) uint8 of environment ``env`` of ``scene`` seen from ``eye`` looking at
    ``target`` ((x, y, z) [m], world) with horizontal field of view ``fov`` [rad]. ``camera``: a
    :class:`ViewCamera` of that size, field of view and environment to render into (its arrays, allocated
    once, are reused: frame after frame); None makes one (``options``: its ``max_range``,
    ``haze_distance``). The scene is read as it is (``scene.refresh()`` after the sea moved)."""
    if camera is None:
        camera = ViewCamera(scene, width, height, fov, env=env, **options)
    elif (camera.scene is not scene or (camera.config.width, camera.config.height) != (width, height)
          or camera.config.horizontal_fov != fov or camera.env.numpy()[0] != env):
        raise ValueError("render_view: camera must be a ViewCamera of this scene, size, fov and env")
    camera.look_at(eye, target)
    camera.render()
    return camera.image()
