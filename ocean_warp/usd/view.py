"""A camera and lights for the stage, so that a viewer or an importer that opens it (Blender's, for one)
has something to look through and the sun to see by.

- The camera (:data:`~ocean_warp.usd.paths.CAMERA`) looks from the south and above at the centre of an
  area (xmin, xmax, ymin, ymax) [m], far enough back that the whole area fits in its field of view.
- The sun (:data:`~ocean_warp.usd.paths.SUN`) is a DistantLight shining down from the south-east; the sky
  (:data:`~ocean_warp.usd.paths.SKY`) a DomeLight of a uniform pale blue.
"""

from __future__ import annotations

import math

import numpy as np
from pxr import Gf, UsdGeom, UsdLux

from .paths import CAMERA, LIGHTS, SKY, SUN

__all__ = ["define_camera", "define_lights", "look_at", "CAMERA_ELEVATION_DEG"]

CAMERA_ELEVATION_DEG = 35.0
"""The camera looks down at this angle below the horizon [deg]."""
FOCAL_LENGTH = 0.35
"""A 35 mm lens on a 36 x 24 mm aperture (54 by 38 degrees), in USD's camera unit, a tenth of a scene unit
(the stage's metre): 35 mm = 0.35."""
APERTURE = (0.36, 0.24)
SUN_ELEVATION_DEG, SUN_AZIMUTH_DEG = 50.0, -45.0
"""Where the sun is: 50 degrees above the horizon, towards the south-east (azimuth from +x, ccw) [deg]."""
SUN_INTENSITY = 1.0
"""DistantLight intensity (usdview's default light is 1; Blender 5.0's importer makes it a sun of strength
4 W/m^2). Renderers differ in their light units: raise it for one that expects physical values."""
SKY_COLOR = (0.55, 0.70, 0.90)
SKY_INTENSITY = 0.6
"""DomeLight intensity: a dim uniform sky, for the shadows (Blender's importer makes the world this colour
at this strength when the scene has a world)."""


def look_at(eye, target, up=(0.0, 0.0, 1.0)) -> Gf.Matrix4d:
    """The local-to-world matrix (USD's row-vector convention) of a camera or light at ``eye`` [m] whose
    -z axis points at ``target`` [m] and whose +y axis is as close to ``up`` as it can be."""
    eye, target = np.asarray(eye, dtype=np.float64), np.asarray(target, dtype=np.float64)
    forward = target - eye
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, np.asarray(up, dtype=np.float64))
    if np.linalg.norm(right) < 1e-9:  # looking straight along ``up``
        right = np.cross(forward, (0.0, 1.0, 0.0))
    right /= np.linalg.norm(right)
    above = np.cross(right, forward)
    rows = np.zeros((4, 4))
    rows[0, :3], rows[1, :3], rows[2, :3], rows[3, :3], rows[3, 3] = right, above, -forward, eye, 1.0
    return Gf.Matrix4d(*rows.reshape(-1).tolist())


def define_camera(stage, area, *, height: float = 0.0) -> UsdGeom.Camera:
    """A camera at :data:`~ocean_warp.usd.paths.CAMERA` framing ``area`` (xmin, xmax, ymin, ymax) [m] at
    ``height`` [m]: it looks at the area's centre from the south, :data:`CAMERA_ELEVATION_DEG` above the
    horizon, back far enough that a sphere around the whole area fits inside the narrower of its two
    fields of view."""
    xmin, xmax, ymin, ymax = map(float, area)
    centre = np.array([0.5 * (xmin + xmax), 0.5 * (ymin + ymax), float(height)])
    radius = 0.5 * math.hypot(xmax - xmin, ymax - ymin) + 2.0  # plus a little water around it
    half_fov = math.atan(0.5 * min(APERTURE) / FOCAL_LENGTH)  # the vertical field of view's half
    distance = radius / math.sin(half_fov)
    elevation = math.radians(CAMERA_ELEVATION_DEG)
    eye = centre + distance * np.array([0.0, -math.cos(elevation), math.sin(elevation)])
    camera = UsdGeom.Camera.Define(stage, CAMERA)
    camera.AddTransformOp().Set(look_at(eye, centre))
    camera.CreateProjectionAttr(UsdGeom.Tokens.perspective)
    camera.CreateFocalLengthAttr(FOCAL_LENGTH)
    camera.CreateHorizontalApertureAttr(APERTURE[0])
    camera.CreateVerticalApertureAttr(APERTURE[1])
    camera.CreateClippingRangeAttr(Gf.Vec2f(0.1, float(2.0 * (distance + radius))))
    return camera


def define_lights(stage) -> None:
    """The sun (a DistantLight at :data:`~ocean_warp.usd.paths.SUN`, shining from
    :data:`SUN_ELEVATION_DEG` above the horizon towards the north-west) and the sky (a DomeLight at
    :data:`~ocean_warp.usd.paths.SKY`)."""
    UsdGeom.Xform.Define(stage, LIGHTS)
    sun = UsdLux.DistantLight.Define(stage, SUN)
    elevation, azimuth = math.radians(SUN_ELEVATION_DEG), math.radians(SUN_AZIMUTH_DEG)
    towards_sun = np.array([math.cos(elevation) * math.cos(azimuth), math.cos(elevation) * math.sin(azimuth),
                            math.sin(elevation)])
    # A DistantLight shines along its -z axis: point -z away from the sun.
    sun.AddTransformOp().Set(look_at(towards_sun, np.zeros(3)).SetTranslateOnly(Gf.Vec3d(0.0, 0.0, 0.0)))
    sun.CreateIntensityAttr(SUN_INTENSITY)
    sun.CreateAngleAttr(0.53)  # the sun's apparent diameter [deg]
    sun.CreateColorAttr(Gf.Vec3f(1.0, 0.96, 0.90))
    sky = UsdLux.DomeLight.Define(stage, SKY)
    sky.CreateIntensityAttr(SKY_INTENSITY)
    sky.CreateColorAttr(Gf.Vec3f(*SKY_COLOR))
