"""The camera (ocean_warp.perception.camera, kernels/camera_render.py) against geometry solved here: depth of a
flat calm sea (the plane's intersection along the optical axis), of a sphere buoy, a pile and another boat
(numpy intersections and Scene.cast through the same pixels); the shading's order of brightness (sky over
water, grazing water over water seen from above) and an object's hue; the intrinsics as CameraInfo gives
them; bad configs; a camera whose pose is not finite; the free ViewCamera; and the hook inside a
SailingEnv decision.

Pixel rays are built here from CameraInfo's K (pixel (u, v) -> optical (x, y, 1) = ((u - cx) / fx,
(v - cy) / fy, 1), the link frame x forward, y left, z up = optical (z, -x, -y)) and scipy's rotations of
the mount's Z-Y-X roll, pitch and yaw, not with the module's own kernels."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import torch
import warp as wp
from scipy.spatial.transform import Rotation

from ocean_warp import Ocean, OceanConfig
from ocean_warp.eboat import EBoatVessel, Hydrostatics
from ocean_warp.envs import SailingEnv, WaypointConfig
from ocean_warp.envs.decision_hook import DecisionHook
from ocean_warp.envs.sensors import CameraHook
from ocean_warp.kernels.ray_cast import HIT_BOAT, HIT_NONE, HIT_OBJECT, HIT_WATER
from ocean_warp.perception import Camera, CameraConfig, Scene, SceneObject, ViewCamera, render_view
from ocean_warp.torch_streams import ordered_with_torch
from tests.env_buffers import assert_same_buffers

NONE, WATER, OBJECT, BOAT = int(HIT_NONE), int(HIT_WATER), int(HIT_OBJECT), int(HIT_BOAT)


def calm_sea(device) -> Ocean:
    """Still water: the surface is the plane z = 0."""
    return Ocean(OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.0), device=device)


def boats_in_one_world(ocean: Ocean, positions, yaws, objects=()) -> Scene:
    """Boats at ``positions`` [m] turned by ``yaws`` [rad], all in environment 0 with ``objects``."""
    count, device = len(positions), ocean.device
    quaternions = Rotation.from_euler("z", np.asarray(yaws, np.float64).reshape(-1, 1)).as_quat()
    return Scene(ocean, envs=1, boat_env=np.zeros(count, np.int64),
                 boat_position=wp.array(np.asarray(positions, np.float32), dtype=wp.vec3, device=device),
                 boat_orientation=wp.array(quaternions.astype(np.float32), dtype=wp.quat, device=device),
                 parts=EBoatVessel().parts(hull_detail=1, rudder=False), scaling=EBoatVessel().part_scaling(),
                 joints={"boom_angle": wp.zeros(count, dtype=float, device=device)}, objects=objects)


def camera_rotation(config: CameraConfig, boat_yaw: float) -> Rotation:
    """Link frame -> world of a camera on a level boat of heading ``boat_yaw``."""
    roll, pitch, yaw = config.mount_rpy
    return Rotation.from_euler("z", boat_yaw) * Rotation.from_euler("ZYX", [yaw, pitch, roll])


def pixel_rays(config: CameraConfig, rotation: Rotation) -> tuple[np.ndarray, np.ndarray]:
    """(H, W, 3) unit world directions through the pixel centres and (H, W) each ray's length per metre of
    depth, from CameraInfo's K."""
    k = np.array(config.camera_info()["K"]).reshape(3, 3)
    u, v = np.meshgrid(np.arange(config.width), np.arange(config.height))
    x, y = (u - k[0, 2]) / k[0, 0], (v - k[1, 2]) / k[1, 1]
    link = np.stack([np.ones_like(x), -x, -y], axis=-1)
    stretch = np.linalg.norm(link, axis=-1)
    return rotation.apply((link / stretch[..., None]).reshape(-1, 3)).reshape(link.shape), stretch


def captured(camera: Camera) -> tuple[np.ndarray | None, np.ndarray | None]:
    camera.scene.refresh()
    camera.capture()
    depth = None if camera.depth_array is None else camera.depth_array.numpy().copy()
    rgb = None if camera.rgb_array is None else camera.rgb_array.numpy().copy()
    return depth, rgb


def luminance(rgb: np.ndarray) -> np.ndarray:
    """Rec. 709 luma of 8-bit sRGB pixels (..., 3)."""
    return rgb.astype(np.float64) @ np.array([0.2126, 0.7152, 0.0722])


# --- depth against geometry ---------------------------------------------------------------------------

def test_depth_of_a_calm_sea_is_the_plane_along_the_optical_axis(device, rng):
    """A camera at height h, pitched down: every pixel that looks down sees still water at optical depth
    h / (-dz) (dz the downward part of its ray for unit depth), within 1e-3; above the horizon, or where the
    water lies beyond max_range, nothing (+inf)."""
    height = float(rng.uniform(1.0, 5.0))
    config = CameraConfig(width=40, height=30, horizontal_fov=float(rng.uniform(1.2, 1.8)), min_range=0.0,
                          max_range=60.0, mount=(0.0, 0.0, height),
                          mount_rpy=(float(rng.uniform(-0.1, 0.1)), float(rng.uniform(0.15, 0.35)), 0.0), rgb=False)
    boat_yaw = float(rng.uniform(-math.pi, math.pi))
    camera = Camera(config, boats_in_one_world(calm_sea(device), [(3.0, -2.0, 0.0)], [boat_yaw]))
    depth, _ = captured(camera)
    assert depth.shape == (1, 30, 40) and depth.dtype == np.float32

    directions, stretch = pixel_rays(config, camera_rotation(config, boat_yaw))
    down = -directions[..., 2] * stretch  # descent per metre of depth
    with np.errstate(divide="ignore"):
        expected = np.where(down > 0.0, height / down, np.inf)
    clear = np.abs(expected - config.max_range) > 1e-2 * config.max_range
    sees = (expected <= config.max_range) & clear
    assert sees.sum() > 200 and (~sees & clear).sum() > 100
    np.testing.assert_allclose(depth[0][sees], expected[sees], rtol=1e-3)
    assert np.all(depth[0][~sees & clear] == np.inf)


def sphere_depth(origin, directions, stretch, center, radius) -> np.ndarray:
    """(H, W) optical depth of the nearest hit of each unit ray with the sphere (inf on a miss)."""
    oc = origin - np.asarray(center)
    b = directions @ oc
    disc = b * b - (oc @ oc - radius**2)
    with np.errstate(invalid="ignore"):
        t = -b - np.sqrt(disc)
    return np.where((disc > 0.0) & (t > 0.0), t / stretch, np.inf)


def cylinder_depth(origin, directions, stretch, base, radius, low, high) -> np.ndarray:
    """(H, W) optical depth of the nearest hit with the side of an upright cylinder at ``base`` (x, y), from
    z = ``low`` to ``high`` [m] (inf on a miss; the caps are out of these cameras' sight)."""
    o = origin[:2] - np.asarray(base)
    d = directions[..., :2]
    a = np.sum(d * d, -1)
    b = d @ o
    disc = b * b - a * (o @ o - radius**2)
    with np.errstate(invalid="ignore", divide="ignore"):
        t = (-b - np.sqrt(disc)) / a
    z = origin[2] + t * directions[..., 2]
    return np.where((disc > 0.0) & (t > 0.0) & (z >= low) & (z <= high), t / stretch, np.inf)


def test_depth_of_a_buoy_a_pile_and_a_boat_matches_the_geometry(device, rng):
    """A sphere buoy, a pile and another boat ahead of a level camera: each pixel's depth is Scene.cast's
    distance through the same pixel over the ray's length per metre of depth, and, where the pixel sees the
    buoy or the pile, the numpy intersection's; the camera does not see its own boat; a point inside the
    buoy's upper half, projected with K, falls on a pixel that sees it."""
    buoy_at = np.array([float(rng.uniform(10.0, 14.0)), float(rng.uniform(-2.0, 2.0))])
    pile_at = np.array([float(rng.uniform(16.0, 20.0)), float(rng.uniform(4.0, 6.0))])
    buoy = SceneObject.buoy(buoy_at, radius=1.0)
    pile = SceneObject.pillar(pile_at, radius=0.4, height=6.0)  # from z = -1.5 to 4.5
    config = CameraConfig(width=64, height=48, horizontal_fov=math.radians(90.0), min_range=0.0, max_range=100.0,
                          mount=(0.5, 0.0, 1.5), mount_rpy=(0.0, 0.05, 0.0), rgb=False)
    scene = boats_in_one_world(calm_sea(device), [(0.0, 0.0, 0.0), (15.0, -6.0, 0.0)], [0.0, 1.3], [buoy, pile])
    camera = Camera(config, scene, boats=[0])
    depth, _ = captured(camera)
    depth = depth[0]

    origin = np.array([0.5, 0.0, 1.5])
    np.testing.assert_allclose(camera.position.numpy()[0], origin, atol=1e-6)
    directions, stretch = pixel_rays(config, camera_rotation(config, 0.0))
    cast = scene.cast(np.broadcast_to(origin, directions.shape).reshape(-1, 3), directions.reshape(-1, 3),
                      own_boat=0, t_max=200.0)
    kind = cast["kind"].reshape(depth.shape)
    cast_depth = np.where(kind == NONE, np.inf, cast["distance"].reshape(depth.shape) / stretch)
    for wanted in (WATER, OBJECT, BOAT):
        assert np.sum(kind == wanted) > 10, wanted
    seen = kind != NONE
    np.testing.assert_allclose(depth[seen], cast_depth[seen], rtol=1e-4)  # float32 rays built two ways
    assert np.all(depth[~seen] == np.inf)
    assert not np.any(cast["index"][kind.reshape(-1) == BOAT] == 0)  # never its own boat

    index = cast["index"].reshape(depth.shape)
    for k, expected in ((0, sphere_depth(origin, directions, stretch, (*buoy_at, 0.0), 1.0)),
                        (1, cylinder_depth(origin, directions, stretch, pile_at, 0.4, -1.5, 4.5))):
        pixels = (kind == OBJECT) & (index == k)
        assert pixels.sum() > 5
        np.testing.assert_allclose(depth[pixels], expected[pixels], rtol=1e-3)

    k_matrix = np.array(config.camera_info()["K"]).reshape(3, 3)
    upper = np.array([*buoy_at, 0.6])  # inside the buoy, above the water that hides its lower half
    centre_link = camera_rotation(config, 0.0).inv().apply(upper - origin)
    u, v, w = k_matrix @ np.array([-centre_link[1], -centre_link[2], centre_link[0]])
    row, column = int(round(v / w)), int(round(u / w))
    assert kind[row, column] == OBJECT and index[row, column] == 0


def test_a_camera_whose_pose_is_not_finite_sees_nothing(device):
    """A NaN boat: depth +inf and black pixels, no NaN; the other camera is unaffected."""
    scene = boats_in_one_world(calm_sea(device), [(0.0, 0.0, 0.0), (5.0, 0.0, 0.0)], [0.0, 0.0])
    camera = Camera(CameraConfig(width=8, height=6), scene)
    scene.view.boat_position.assign(np.array([[np.nan, 0.0, 0.0], [5.0, 0.0, 0.0]], np.float32))
    depth, rgb = captured(camera)
    assert np.all(depth[0] == np.inf) and np.all(rgb[0] == 0)
    assert not np.any(np.isnan(depth)) and np.any(np.isfinite(depth[1])) and np.all(rgb[1].max(-1) > 0)


# --- colour -------------------------------------------------------------------------------------------

def test_sky_is_brighter_than_the_sea_and_blue(device):
    """A level camera: the sky above the horizon is brighter than the water below it, blue its strongest
    channel; the sky grows bluer with elevation."""
    config = CameraConfig(width=32, height=32, horizontal_fov=math.radians(90.0), mount=(0.0, 0.0, 2.0),
                          mount_rpy=(0.0, 0.0, 0.0), max_range=500.0)
    camera = Camera(config, boats_in_one_world(calm_sea(device), [(0.0, 0.0, 0.0)], [0.0]))
    depth, rgb = captured(camera)
    sky, water = rgb[0][depth[0] == np.inf], rgb[0][np.isfinite(depth[0])]
    assert len(sky) > 300 and len(water) > 300
    assert luminance(sky).mean() > luminance(water).mean() + 40.0
    assert np.all(sky[:, 2] > sky[:, 1]) and np.all(sky[:, 1] > sky[:, 0])
    top, horizon = rgb[0, 0, 16].astype(int), rgb[0, 14, 16].astype(int)
    assert top[2] - top[0] > horizon[2] - horizon[0]


def test_water_at_grazing_angles_is_brighter_than_seen_from_above(device):
    """Fresnel: a camera pitched 45 degrees down with a 90 degree square view sees the water from straight
    down (bottom row) to the horizon (top row); the reflection brightens the water toward the horizon."""
    config = CameraConfig(width=24, height=24, horizontal_fov=math.radians(90.0), mount=(0.0, 0.0, 3.0),
                          mount_rpy=(0.0, math.radians(45.0), 0.0), max_range=2000.0)
    camera = Camera(config, boats_in_one_world(calm_sea(device), [(0.0, 0.0, 0.0)], [0.0]))
    depth, rgb = captured(camera)
    column = luminance(rgb[0, :, 12])
    assert np.all(np.isfinite(depth[0, 1:, 12]))  # water all the way up to the row below the horizon
    assert column[2] > column[-1] + 60.0
    assert np.all(np.diff(column[1:]) <= 1.0)  # darker, row by row, as the view steepens


@pytest.mark.parametrize("color", [(0.9, 0.1, 0.1), (0.1, 0.8, 0.15)])
def test_an_object_has_its_colour(device, color):
    """A pixel that sees a buoy (its upper half: it floats with its centre on the surface) has its colour's
    strongest channel, well above the others."""
    scene = boats_in_one_world(calm_sea(device), [(0.0, 0.0, 0.0)], [0.0],
                               [SceneObject.buoy((8.0, 0.0), radius=1.5, color=color)])
    config = CameraConfig(width=16, height=16, horizontal_fov=math.radians(40.0), mount=(0.0, 0.0, 1.0),
                          mount_rpy=(0.0, 0.1, 0.0))
    camera = Camera(config, scene)
    _, rgb = captured(camera)
    strongest = int(np.argmax(color))
    pixel = rgb[0, 7, 8].astype(int)
    others = np.delete(pixel, strongest)
    assert pixel[strongest] > 2 * others.max(), pixel


# --- intrinsics and configs ---------------------------------------------------------------------------

@pytest.mark.parametrize("width, height, fov_deg", [(64, 64, 90.0), (640, 480, 60.0), (1280, 720, 75.0), (7, 3, 10.0)])
def test_camera_info_holds_the_pinhole_of_width_height_and_fov(width, height, fov_deg):
    config = CameraConfig(width=width, height=height, horizontal_fov=math.radians(fov_deg))
    info = config.camera_info()
    f = 0.5 * width / math.tan(math.radians(fov_deg) / 2)
    cx, cy = (width - 1) / 2, (height - 1) / 2
    assert (info["width"], info["height"], info["distortion_model"]) == (width, height, "plumb_bob")
    assert info["D"] == [0.0] * 5 and info["R"] == [1.0, 0, 0, 0, 1.0, 0, 0, 0, 1.0]
    np.testing.assert_allclose(info["K"], [f, 0, cx, 0, f, cy, 0, 0, 1], rtol=1e-12)
    np.testing.assert_allclose(info["P"], [f, 0, cx, 0, 0, f, cy, 0, 0, 0, 1, 0], rtol=1e-12)
    assert config.vertical_fov == pytest.approx(2 * math.atan(height / 2 / f))


@pytest.mark.parametrize("field, value", [
    ("width", 0), ("width", 2.5), ("height", -3), ("height", True), ("horizontal_fov", 0.0),
    ("horizontal_fov", math.pi), ("horizontal_fov", math.nan), ("min_range", -0.1), ("min_range", 300.0),
    ("max_range", 0.0), ("max_range", math.inf), ("rate", 0.0), ("rate", math.nan), ("mount", (1.0, 2.0)),
    ("mount", (0.0, math.nan, 1.0)), ("mount_rpy", "up"), ("depth", 1), ("rgb", None), ("haze_distance", -1.0),
])
def test_a_bad_config_names_the_field(field, value):
    with pytest.raises(ValueError, match=rf"^CameraConfig\.{field}"):
        CameraConfig(**{field: value})


def test_a_camera_that_renders_nothing_is_refused():
    with pytest.raises(ValueError, match=r"CameraConfig\.depth and CameraConfig\.rgb"):
        CameraConfig(depth=False, rgb=False)


def test_switched_off_images_are_none(device):
    scene = boats_in_one_world(calm_sea(device), [(0.0, 0.0, 0.0)], [0.0])
    depth_only = Camera(CameraConfig(width=4, height=3, rgb=False), scene)
    rgb_only = Camera(CameraConfig(width=4, height=3, depth=False), scene)
    assert depth_only.rgb is None and tuple(depth_only.depth.shape) == (1, 3, 4)
    assert rgb_only.depth is None and tuple(rgb_only.rgb.shape) == (1, 3, 4, 3) and rgb_only.rgb.dtype == torch.uint8
    with pytest.raises(ValueError, match=r"Camera\.boats"):
        Camera(CameraConfig(), scene, boats=[1])


# --- the free camera ----------------------------------------------------------------------------------

def test_view_camera_looks_at_its_target(device, rng):
    """render_view from an eye above still water toward a target on it: the depth is the plane's, with the
    link frame built here (x toward the target, y level); the target sits at the image's centre."""
    scene = boats_in_one_world(calm_sea(device), [(500.0, 500.0, 0.0)], [0.0])
    eye = np.array([float(rng.uniform(-5, 5)), float(rng.uniform(-5, 5)), float(rng.uniform(2.0, 8.0))])
    target = np.array([eye[0] + float(rng.uniform(10, 20)), eye[1] + float(rng.uniform(-10, 10)), 0.0])
    camera = ViewCamera(scene, 33, 25, math.radians(70.0), max_range=80.0, haze_distance=0.0)
    rgb = render_view(scene, eye, target, 33, 25, math.radians(70.0), camera=camera)
    assert rgb.shape == (25, 33, 3) and rgb.dtype == np.uint8
    depth = camera.depth_image()

    forward = (target - eye) / np.linalg.norm(target - eye)
    left = np.cross([0.0, 0.0, 1.0], forward)
    left /= np.linalg.norm(left)
    rotation = Rotation.from_matrix(np.column_stack([forward, left, np.cross(forward, left)]))
    directions, stretch = pixel_rays(camera.config, rotation)
    with np.errstate(divide="ignore"):
        expected = np.where(directions[..., 2] < 0, eye[2] / (-directions[..., 2] * stretch), np.inf)
    sees = (expected < 0.99 * 80.0)
    np.testing.assert_allclose(depth[sees], expected[sees], rtol=1e-3)
    assert depth[12, 16] == pytest.approx(np.linalg.norm(target - eye), rel=1e-3)
    with pytest.raises(ValueError, match="ViewCamera.env"):
        ViewCamera(scene, 8, 8, 1.0, env=1)


# --- the hook -----------------------------------------------------------------------------------------

def cheap_task(**changes) -> WaypointConfig:
    """The seed waypoint task on four-point buoyancy, a 16 x 16 sea once a step and 3 s episodes."""
    task = WaypointConfig()
    simulator = dataclasses.replace(
        task.simulator, boat=dataclasses.replace(task.simulator.boat, hydrostatics=Hydrostatics.POINTS),
        ocean=OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.3, peak_period=3.0),
        ocean_every_substep=False)
    return dataclasses.replace(task, simulator=simulator, **({"episode_time": 3.0} | changes))


class CapturesByHand(DecisionHook):
    """Refreshes the scene and captures after the given physics steps, keeping copies on the host."""

    def __init__(self, camera: Camera, steps):
        self.camera, self.steps, self.images = camera, set(steps), []

    def after_physics_step(self, env, step: int) -> None:
        if step in self.steps:
            self.images.append(captured(self.camera))


CAMERA_OBJECTS = [SceneObject.buoy((6.0, 1.0), radius=0.8), SceneObject.pillar((9.0, -3.0))]


def test_hook_captures_at_2_hz_and_leaves_the_decision_unchanged(device, rng):
    """A CameraHook at 2 Hz captures after steps 10 and 20 of each decision of 20 steps: its images (the last
    capture, and both recorded) are those a twin environment takes by hand after steps 10 and 20; every
    buffer of the hooked environment equals a plain one's, decision after decision, through the episodes'
    resets."""
    task = cheap_task()
    config = CameraConfig(width=12, height=8, rate=2.0, haze_distance=50.0)
    plain, hooked, twin = (SailingEnv(task, 2, device=device, seed=3) for _ in range(3))
    hook = CameraHook(hooked, config, objects=CAMERA_OBJECTS, record=True)
    hooked.attach(hook)
    assert hook.steps_between_captures == 10 and hook.capture_steps == {9, 19}
    by_hand = CapturesByHand(Camera(config, Scene.for_env(twin, CAMERA_OBJECTS)), steps={9, 19})
    generator = torch.Generator().manual_seed(int(rng.integers(2**31)))
    resets = 0
    for decision in range(4):
        actions = (2.0 * torch.rand(2, 3, generator=generator) - 1.0).to(plain.torch_device)
        plain.step(actions)
        hooked.step(actions)
        assert_same_buffers(hooked.buffers, plain.buffers, f"after decision {decision}")
        resets += int(plain.buffers.done.sum())
        twin.buffers.actions.copy_(actions)
        by_hand.images = []
        with ordered_with_torch(twin.device):
            twin.launch_decision(by_hand)
        (half_depth, half_rgb), (depth, rgb) = by_hand.images
        np.testing.assert_array_equal(hook.camera.depth.cpu().numpy(), depth)
        np.testing.assert_array_equal(hook.camera.rgb.cpu().numpy(), rgb)
        frames = hook.frames()
        assert frames["depth"].shape == (2, 2, 8, 12) and frames["rgb"].shape == (2, 2, 8, 12, 3)
        np.testing.assert_array_equal(frames["depth"], np.stack([half_depth, depth]))
        np.testing.assert_array_equal(frames["rgb"], np.stack([half_rgb, rgb]))
        assert not np.array_equal(half_rgb, rgb)
    assert resets > 0
    assert np.any(np.isfinite(depth)) and np.any(depth == np.inf)


def test_hook_below_the_decision_rate_captures_every_other_decision(device):
    """At 0.5 Hz (every 40 steps: every second decision of 20) the images change after decisions 1 and 3
    only."""
    env = SailingEnv(cheap_task(episode_time=10.0), 1, device=device, seed=1)
    hook = CameraHook(env, CameraConfig(width=8, height=8, rate=0.5, rgb=False), objects=CAMERA_OBJECTS)
    env.attach(hook)
    assert hook.decisions_between_captures == 2 and hook.capture_steps == {19}
    actions = torch.tensor([[0.6, 0.0, 0.3]], device=env.torch_device)
    images = []
    for _ in range(4):
        env.step(actions)
        images.append(hook.camera.depth.cpu().numpy().copy())
    assert not np.array_equal(images[0], np.zeros_like(images[0]))
    assert np.array_equal(images[0], images[1]) and np.array_equal(images[2], images[3])
    assert not np.array_equal(images[1], images[2])


@pytest.mark.parametrize("rate", [3.0, 40.0, 20.0 / 3.0, 0.3])
def test_hook_rate_must_fit_the_steps(device, rate):
    """3 Hz is 6.7 steps of 0.05 s; 40 Hz is faster than the steps; every 3 steps neither divides nor is a
    multiple of the decision's 20; 0.3 Hz is 66.7 steps."""
    env = SailingEnv(cheap_task(), 1, device=device)
    with pytest.raises(ValueError, match=r"CameraConfig\.rate"):
        CameraHook(env, CameraConfig(rate=rate))


def test_frames_need_record(device):
    env = SailingEnv(cheap_task(), 1, device=device)
    with pytest.raises(ValueError, match="record=True"):
        CameraHook(env, CameraConfig()).frames()
    with pytest.raises(ValueError, match="CameraHook.record"):
        CameraHook(env, CameraConfig(), record=1)
