"""The lidar (ocean_warp.perception.lidar) against scenes the test solves itself: a flat calm sea (range = height /
sin(depression)), spheres and piles (ray-sphere and ray-cylinder in numpy), another boat's hull (a numpy
ray-triangle intersection over the same meshes), a regular wave (the Airy heights), the sea switched off,
environments that do not see each other; noise, dropouts and the seeded stream; the down-sampled
observation; bad configs; and the hook inside a SailingEnv decision.

Beam directions are built here from the docstring's definition (azimuth from -pi every 2 pi / B, channels
evenly from elevation_min to elevation_max, the mount's Z-Y-X roll, pitch, yaw) with scipy's rotations,
not with the module's own tables."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import torch
import warp as wp
from scipy.spatial.transform import Rotation

from ocean_warp import Ocean, OceanConfig
from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig, EBoatVessel, Hydrostatics
from ocean_warp.eboat.parts import eboat_parts
from ocean_warp.envs import SailingEnv, WaypointConfig
from ocean_warp.envs.decision_hook import DecisionHook
from ocean_warp.envs.sensors import LidarHook
from ocean_warp.kernels.ray_cast import HIT_BOAT, HIT_NONE, HIT_OBJECT, HIT_WATER
from ocean_warp.meshes import concatenate
from ocean_warp.perception import Lidar, LidarConfig, Scene, SceneObject, Shape
from ocean_warp.torch_streams import ordered_with_torch
from ocean_warp.vessel import sensor_mount
from tests.env_buffers import assert_same_buffers

NONE, WATER, OBJECT, BOAT = int(HIT_NONE), int(HIT_WATER), int(HIT_OBJECT), int(HIT_BOAT)


# --- scenes and rays built here ------------------------------------------------------------------------

def calm_ocean(device) -> Ocean:
    return Ocean(OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.0), device=device)


def random_quaternions(rng, count: int, tilt: float) -> np.ndarray:
    """(count, 4) x y z w: any yaw, roll and pitch within +-``tilt`` [rad]."""
    angles = np.column_stack([rng.uniform(-math.pi, math.pi, count), rng.uniform(-tilt, tilt, count),
                              rng.uniform(-tilt, tilt, count)])
    return Rotation.from_euler("ZYX", angles).as_quat()


SENSOR_PARTS = EBoatVessel().parts(hull_detail=1, rudder=False)
"""The E-Boat as the lidar sees it in a SailingEnv (hull, keel and mast at the physics detail, boom and sail)."""


def boat_scene(ocean, positions, quaternions, *, objects=(), boat_env=None, envs=None, origins=None) -> Scene:
    """A scene of boats at the given poses; by default each boat in an environment of its own."""
    count = len(positions)
    boat_env = np.arange(count) if boat_env is None else np.asarray(boat_env)
    device = ocean.device
    position = wp.array(np.asarray(positions, np.float32), dtype=wp.vec3, device=device)
    orientation = wp.array(np.asarray(quaternions, np.float32), dtype=wp.quat, device=device)
    boom = wp.zeros(count, dtype=float, device=device)
    return Scene(ocean, envs=envs or count, boat_env=boat_env, boat_position=position, boat_orientation=orientation,
                 parts=SENSOR_PARTS, joints={"boom_angle": boom}, scaling=EBoatVessel().part_scaling(), objects=objects,
                 origins=origins)


def scanned(lidar: Lidar) -> tuple[np.ndarray, np.ndarray]:
    lidar.scan()
    return lidar.range_array.numpy().copy(), lidar.kind_array.numpy().copy()


def beam_rays(config: LidarConfig, positions, quaternions) -> tuple[np.ndarray, np.ndarray]:
    """(N, 3) sensor origins and (N, C * B, 3) unit beam directions, world frame."""
    fov = config.horizontal_fov
    azimuth = (-math.pi + np.arange(config.beams) * 2 * math.pi / config.beams if fov == 2 * math.pi
               else np.linspace(-0.5 * fov, 0.5 * fov, config.beams))
    elevation = (np.linspace(config.elevation_min, config.elevation_max, config.channels) if config.channels > 1
                 else np.array([0.5 * (config.elevation_min + config.elevation_max)]))
    az, el = np.meshgrid(azimuth, elevation)  # (C, B): channel-major
    sensor = np.stack([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)], -1).reshape(-1, 3)
    roll, pitch, yaw = config.mount_rpy
    mount = Rotation.from_euler("ZYX", [yaw, pitch, roll])
    origins, directions = [], []
    for position, quaternion in zip(np.asarray(positions, np.float64), np.asarray(quaternions, np.float64)):
        body = Rotation.from_quat(quaternion)
        origins.append(position + body.apply(config.mount))
        directions.append((body * mount).apply(sensor))
    return np.array(origins), np.array(directions)


def sea_distance(origins, directions) -> np.ndarray:
    """(N, R) distance along each ray to the still-water plane z = 0 (inf when it does not go down)."""
    dz = directions[..., 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(dz < 0.0, -origins[:, None, 2] / dz, np.inf)
    return t


def sphere_distance(origins, directions, center, radius) -> tuple[np.ndarray, np.ndarray]:
    """(N, R) nearest positive distance to a sphere (inf on a miss) and whether the ray is clear of grazing."""
    oc = origins[:, None, :] - center
    b = np.sum(oc * directions, -1)
    disc = b * b - (np.sum(oc * oc, -1) - radius**2)
    with np.errstate(invalid="ignore"):
        t = -b - np.sqrt(disc)
    t = np.where((disc >= 0.0) & (t > 0.0), t, np.inf)
    return t, np.abs(disc) > 1e-2 * radius**2


def cylinder_distance(origins, directions, center, radius, half_height) -> tuple[np.ndarray, np.ndarray]:
    """(N, R) nearest positive distance to a closed upright cylinder and whether the hit is clear of its rims
    and of grazing the side."""
    o = origins[:, None, :] - center
    d = directions
    a = d[..., 0] ** 2 + d[..., 1] ** 2
    b = o[..., 0] * d[..., 0] + o[..., 1] * d[..., 1]
    c = o[..., 0] ** 2 + o[..., 1] ** 2 - radius**2
    disc = b * b - a * c
    with np.errstate(invalid="ignore", divide="ignore"):
        side = (-b - np.sqrt(disc)) / a
        side_z = o[..., 2] + side * d[..., 2]
        side = np.where((disc >= 0) & (side > 0) & (np.abs(side_z) <= half_height), side, np.inf)
        best = side
        for cap in (half_height, -half_height):
            t = (cap - o[..., 2]) / d[..., 2]
            x, y = o[..., 0] + t * d[..., 0], o[..., 1] + t * d[..., 1]
            best = np.where((t > 0) & (x * x + y * y <= radius**2) & (t < best), t, best)
    point = o + np.where(np.isfinite(best), best, 0.0)[..., None] * d
    rim = (np.abs(np.hypot(point[..., 0], point[..., 1]) - radius) < 2e-3) & \
        (np.abs(np.abs(point[..., 2]) - half_height) < 2e-3)
    # either side of tangency: a float32 ray can touch a side float64 just misses (and the reverse)
    grazing = np.abs(disc) < 1e-2 * a * radius**2
    return best, ~(rim | grazing)


def ray_mesh_distance(origins, directions, triangles) -> np.ndarray:
    """(R,) nearest positive distance from each ray to a set of (T, 3, 3) triangles (Moller-Trumbore), inf
    on a miss; float64."""
    v0, e1, e2 = triangles[:, 0], triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]
    best = np.full(len(origins), np.inf)
    for r, (origin, direction) in enumerate(zip(origins, directions)):
        p = np.cross(direction, e2)
        det = np.sum(e1 * p, 1)
        ok = np.abs(det) > 1e-12
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        s = origin - v0
        u = np.sum(s * p, 1) * inv
        q = np.cross(s, e1)
        v = (q @ direction) * inv
        t = np.sum(e2 * q, 1) * inv
        hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 1e-9)
        if hit.any():
            best[r] = t[hit].min()
    return best


# --- geometry -----------------------------------------------------------------------------------------

def test_flat_calm_sea_range_is_height_over_sine_of_depression(device, rng):
    """Downward beams meet still water at height / sin(depression); beams above the horizon (or whose
    water lies beyond max_range) return nothing at max_range. A boat with a NaN pose reports nothing; the
    hit points lie on the water."""
    count = 6
    positions = np.column_stack([rng.uniform(-20, 20, (count, 2)), rng.uniform(-0.1, 0.3, count)])
    quaternions = random_quaternions(rng, count, 0.25)
    config = LidarConfig(channels=8, beams=24, elevation_min=float(rng.uniform(-1.3, -0.8)),
                         elevation_max=float(rng.uniform(0.2, 0.5)), min_range=0.3, max_range=30.0,
                         mount=(float(rng.uniform(0.5, 1.2)), float(rng.uniform(-0.1, 0.1)), float(rng.uniform(1.0, 3.0))),
                         mount_rpy=tuple(rng.uniform(-0.2, 0.2, 3)))
    positions[-1] = np.nan  # a boat whose pose went wrong
    lidar = Lidar(config, boat_scene(calm_ocean(device), positions, quaternions))
    ranges, kinds = scanned(lidar)

    origins, directions = beam_rays(config, positions, quaternions)
    depression = -np.arcsin(directions[..., 2])
    with np.errstate(divide="ignore", invalid="ignore"):
        expected = np.where(depression > 0, origins[:, None, 2] / np.sin(depression), np.inf)
    seen = (expected >= config.min_range) & (expected <= config.max_range)
    clear = np.abs(expected - config.max_range) > 1e-2
    good = slice(0, count - 1)
    assert seen[good].sum() > 100 and (~seen[good]).sum() > 100
    check = seen[good] & clear[good]
    np.testing.assert_allclose(ranges[good][check], expected[good][check], rtol=1e-3)
    assert np.all(kinds[good][check] == WATER)
    unseen = ~seen[good] & clear[good]
    assert np.all(kinds[good][unseen] == NONE) and np.all(ranges[good][unseen] == config.max_range)
    assert np.all(kinds[-1] == NONE) and np.all(ranges[-1] == config.max_range)  # the NaN boat

    points = lidar.points()
    assert points.shape == (count, config.beam_count, 3)
    assert np.all(np.isnan(points[kinds == NONE]))
    np.testing.assert_allclose(points[kinds == WATER][:, 2], 0.0, atol=1e-3)


def object_scene(rng, device, count: int, *, envs_apart: float = 200.0):
    """``count`` boats near their environments' origins, each environment holding a sphere and a pile at
    random places around its boat; returns the scene, the boats' poses and the objects' world geometry."""
    origins = np.column_stack([np.arange(count) * envs_apart, rng.uniform(-50, 50, count), np.zeros(count)])
    positions = origins + np.column_stack([rng.uniform(-2, 2, (count, 2)), rng.uniform(0.0, 0.2, count)])
    quaternions = random_quaternions(rng, count, 0.1)
    objects, geometry = [], []
    for k in range(count):
        bearings = rng.uniform(-math.pi, math.pi) + np.array([0.0, rng.uniform(1.5, 4.5)])
        distances = rng.uniform(4.0, 12.0, 2)
        places = positions[k, :2] + distances[:, None] * np.column_stack([np.cos(bearings), np.sin(bearings)])
        sphere = SceneObject(Shape.SPHERE, position=(*(places[0] - origins[k, :2]), float(rng.uniform(0.3, 1.2))),
                             radius=float(rng.uniform(0.4, 1.0)))
        pile = SceneObject.pillar(places[1] - origins[k, :2], radius=float(rng.uniform(0.2, 0.6)),
                                  height=float(rng.uniform(3.0, 6.0)))
        objects.append([sphere, pile])
        geometry.append({"sphere": (origins[k] + sphere.position, sphere.radius),
                         "pile": (origins[k] + pile.position, pile.radius, 0.5 * pile.height)})
    scene = boat_scene(calm_ocean(device), positions, quaternions, objects=objects, origins=origins)
    return scene, positions, quaternions, geometry


def analytic_objects(origins, directions, geometry, *, water: bool):
    """Per boat the nearest distance and kind among its sphere, its pile and (``water``) the sea, and whether
    each ray is clear of grazing an object."""
    nearest, kinds, clear = [], [], []
    for k, shapes in enumerate(geometry):
        o, d = origins[k:k + 1], directions[k:k + 1]
        sphere, sphere_clear = sphere_distance(o, d, *shapes["sphere"])
        pile, pile_clear = cylinder_distance(o, d, *shapes["pile"])
        sea = sea_distance(o, d) if water else np.full_like(sphere, np.inf)
        objects = np.minimum(sphere, pile)
        nearest.append(np.minimum(objects, sea)[0])
        kinds.append(np.where(objects <= sea, OBJECT, WATER)[0])
        clear.append((sphere_clear & pile_clear)[0])
    return np.array(nearest), np.array(kinds), np.array(clear)


def test_sphere_buoy_and_pile_at_known_places(device, rng):
    """A sphere and a pile (closed cylinder) around each boat: the range to the analytic surface and
    HIT_OBJECT, the sea where they are not in the way."""
    scene, positions, quaternions, geometry = object_scene(rng, device, 4)
    config = LidarConfig(channels=9, beams=180, elevation_min=-0.35, elevation_max=0.35, max_range=30.0,
                         mount=(0.3, 0.0, 1.0))
    ranges, kinds = scanned(Lidar(config, scene))
    origins, directions = beam_rays(config, positions, quaternions)
    expected, expected_kind, clear = analytic_objects(origins, directions, geometry, water=True)
    hit = np.isfinite(expected) & (expected <= config.max_range - 1e-2) & clear
    assert (hit & (expected_kind == OBJECT)).sum() > 40
    np.testing.assert_allclose(ranges[hit], expected[hit], rtol=1e-4, atol=1e-4)
    np.testing.assert_array_equal(kinds[hit], expected_kind[hit])
    missed = ~np.isfinite(expected) & clear
    assert missed.sum() > 50 and np.all(kinds[missed] == NONE)


def test_water_returns_off_beams_pass_the_sea(device, rng):
    """Without water returns the beams that would meet the sea go through it: on open water they report
    nothing (max_range, HIT_NONE); those that meet a pile below the waterline report the pile."""
    scene, positions, quaternions, geometry = object_scene(rng, device, 3)
    config = LidarConfig(channels=12, beams=240, elevation_min=-0.6, elevation_max=-0.05, max_range=25.0,
                         mount=(0.3, 0.0, 1.0), water_returns=False)
    ranges, kinds = scanned(Lidar(config, scene))
    origins, directions = beam_rays(config, positions, quaternions)
    expected, _, clear = analytic_objects(origins, directions, geometry, water=False)
    hit = np.isfinite(expected) & (expected <= config.max_range - 1e-2) & clear
    below_waterline = hit & (origins[:, None, 2] + expected * directions[..., 2] < 0.0)
    assert below_waterline.sum() > 5
    assert not np.any(kinds == WATER)
    np.testing.assert_allclose(ranges[hit], expected[hit], rtol=1e-4, atol=1e-4)
    assert np.all(kinds[hit] == OBJECT)
    open_water = ~np.isfinite(expected) & clear
    sea = sea_distance(origins, directions)
    assert (open_water & (sea < config.max_range)).sum() > 100  # would have been water returns
    assert np.all(kinds[open_water] == NONE) and np.all(ranges[open_water] == config.max_range)


def test_environments_do_not_see_each_other(device, rng):
    """Two environments at the same origin: only the first holds a sphere. Its boat sees the sphere and not
    the other environment's boat 5 m ahead, facing it; that boat sees neither (the sea, yes)."""
    heading = float(rng.uniform(-math.pi, math.pi))
    ahead, port = np.array([math.cos(heading), math.sin(heading), 0.0]), np.array([-math.sin(heading), math.cos(heading), 0.0])
    positions = np.array([[0.0, 0.0, 0.0], 5.0 * ahead])
    quaternions = Rotation.from_euler("z", [[heading], [heading + math.pi]]).as_quat()
    sphere = SceneObject(Shape.SPHERE, position=tuple(4.0 * port + (0.0, 0.0, 0.8)), radius=0.8)
    scene = boat_scene(calm_ocean(device), positions, quaternions, objects=[[sphere], []], boat_env=[0, 1], envs=2)
    config = LidarConfig(channels=4, beams=72, elevation_min=-0.1, elevation_max=0.3)
    ranges, kinds = scanned(Lidar(config, scene))
    assert np.sum(kinds[0] == OBJECT) > 3 and not np.any(kinds[0] == BOAT)
    assert not np.any(np.isin(kinds[1], [OBJECT, BOAT])) and np.any(kinds[1] == WATER)
    # In one environment the same boats see each other.
    together = boat_scene(calm_ocean(device), positions, quaternions, objects=[sphere], boat_env=[0, 0], envs=1)
    _, kinds = scanned(Lidar(config, together))
    assert np.any(kinds[0] == BOAT) and np.any(kinds[1] == BOAT) and np.any(kinds[1] == OBJECT)


def test_another_boats_hull_at_a_known_pose(device, rng):
    """Two E-Boats in one environment: the first's lidar, turned toward the second, sees it (HIT_BOAT) at the
    ranges a numpy ray-triangle intersection finds over the same meshes (hull, keel, mast; boom and sail)."""
    sim = EBoatSimulator(EBoatSimulatorConfig(boat=EBoatConfig(hydrostatics=Hydrostatics.POINTS)), 2, device=device)
    bearing, distance = float(rng.uniform(-math.pi, math.pi)), float(rng.uniform(5.0, 8.0))
    headings = rng.uniform(-math.pi, math.pi, 2)
    sim.reset(position=[[0.0, 0.0, 0.0], [distance * math.cos(bearing), distance * math.sin(bearing), 0.0]],
              heading=headings)
    scene = Scene.for_simulator(sim, vessel=EBoatVessel(sim.config), parts=SENSOR_PARTS)
    config = LidarConfig(channels=24, beams=64, horizontal_fov=1.0, elevation_min=-0.35, elevation_max=0.45,
                         max_range=20.0, mount=(0.0, 0.0, 1.2), mount_rpy=(0.0, 0.0, float(bearing - headings[0])))
    ranges, kinds = scanned(Lidar(config, scene))

    position, quaternion = sim.state.position.numpy(), sim.state.orientation.numpy()
    parts = eboat_parts(sim.config.boat, hull_detail=1)
    body, boom = concatenate(parts.hull, parts.keel, parts.mast), concatenate(parts.spar, parts.sail)
    boom_angle = float(sim.state.boom_angle.numpy()[1])
    pose = Rotation.from_quat(quaternion[1])
    world_body = pose.apply(body.points) + position[1]
    world_boom = pose.apply(Rotation.from_euler("z", -boom_angle).apply(boom.points) + parts.boom_pivot) + position[1]
    triangles = np.concatenate([world_body[body.triangles()], world_boom[boom.triangles()]])
    origins, directions = beam_rays(config, position[:1], quaternion[:1])
    boat = ray_mesh_distance(np.repeat(origins, len(directions[0]), 0), directions[0], triangles)
    sea = sea_distance(origins, directions)[0]
    expected_kind = np.where((boat < sea) & (boat <= config.max_range), BOAT,
                             np.where(sea <= config.max_range, WATER, NONE))
    sees_boat = expected_kind == BOAT
    assert sees_boat.sum() > 20
    assert np.mean(kinds[0] == expected_kind) > 0.98  # a beam grazing a triangle's edge may differ
    both = sees_boat & (kinds[0] == BOAT)
    assert both.sum() > 0.95 * sees_boat.sum()
    np.testing.assert_allclose(ranges[0][both], boat[both], atol=2e-3)


def test_regular_wave_crest_where_airy_theory_puts_it(device, rng):
    """Straight-down beams from sensors along the wave's direction read the heights a cos(k x - w t + phase):
    the deep-water wave of the test's own dispersion, the crest where the theory puts it."""
    tile, wavelength = 64.0, 32.0
    k = 2 * math.pi / wavelength
    omega = math.sqrt(9.81 * k)
    amplitude, phase = float(rng.uniform(0.3, 1.0)), float(rng.uniform(-math.pi, math.pi))
    ocean = Ocean(OceanConfig(spectrum="regular", tile_size=tile, resolution=64, amplitude=amplitude,
                              period=2 * math.pi / omega, direction=0.0, phase=phase), device=device)
    t = float(rng.uniform(0.0, 100.0))
    ocean.update(t)
    x = np.arange(0.0, wavelength, 0.5) + rng.uniform(-100, 100)
    height = 5.0
    positions = np.column_stack([x, np.full_like(x, rng.uniform(-50, 50)), np.full_like(x, height)])
    scene = boat_scene(ocean, positions, np.tile([0.0, 0.0, 0.0, 1.0], (len(x), 1)))
    scene.refresh()
    config = LidarConfig(beams=1, horizontal_fov=0.1, elevation_min=-math.pi / 2, elevation_max=-math.pi / 2,
                         mount=(0.0, 0.0, 0.0), max_range=20.0)
    ranges, kinds = scanned(Lidar(config, scene))
    assert np.all(kinds == WATER)
    measured = height - ranges[:, 0]
    theory = amplitude * np.cos(k * x - omega * t + phase)
    np.testing.assert_allclose(measured, theory, atol=0.02 * amplitude)
    crest = math.remainder(x[np.argmax(measured)] - x[np.argmax(theory)], wavelength)
    assert abs(crest) <= 0.5 + 1e-9  # the sampling step


@pytest.mark.parametrize("choppiness", [0.0, 0.7])
def test_sea_is_the_one_the_scene_casts_through(device, rng, choppiness):
    """Slanted beams over a JONSWAP sea against ``Scene.cast`` (ray_cast's march through the same fields) from
    the same origins: without choppiness the same surface (ranges within 1 mm); with it the lidar's height
    map is exact at the grid nodes and bilinear between them, so the two agree to about a centimetre in
    height."""
    hs = float(rng.uniform(0.5, 1.5))
    ocean = Ocean(OceanConfig(tile_size=48.0, resolution=32, significant_wave_height=hs, peak_period=4.0,
                              choppiness=choppiness, seed=int(rng.integers(2**31))), device=device)
    ocean.update(float(rng.uniform(0.0, 100.0)))
    count = 6
    positions = np.column_stack([rng.uniform(-60, 60, (count, 2)), rng.uniform(0.0, 1.0, count)])
    quaternions = random_quaternions(rng, count, 0.2)
    scene = boat_scene(ocean, positions, quaternions)
    scene.refresh()
    config = LidarConfig(channels=8, beams=60, elevation_min=-1.2, elevation_max=0.1, max_range=40.0,
                         mount=(0.5, 0.0, 1.5))
    ranges, kinds = scanned(Lidar(config, scene))
    origins, directions = beam_rays(config, positions, quaternions)
    beams = config.beam_count
    cast = scene.cast(np.repeat(origins, beams, 0), directions.reshape(-1, 3), envs=np.repeat(np.arange(count), beams),
                      own_boat=np.repeat(np.arange(count), beams), t_min=config.min_range, t_max=config.max_range)
    cast_kinds, cast_ranges = cast["kind"].reshape(count, beams), cast["distance"].reshape(count, beams)
    water = (kinds == WATER) & (cast_kinds == WATER)
    assert water.sum() > 0.5 * kinds.size
    height_error = np.abs((ranges - cast_ranges) * directions[..., 2])[water]
    if choppiness == 0.0:  # but for a beam grazing a crest, which the march may step over
        assert np.mean(kinds == cast_kinds) > 0.995
        assert np.mean(np.abs(ranges - cast_ranges)[water] < 1e-3) > 0.995
    else:
        assert np.mean(kinds == cast_kinds) > 0.99  # a beam grazing a crest may differ
        assert np.median(height_error) < 0.01 * hs and np.percentile(height_error, 95) < 0.06 * hs


# --- noise, the stream, the observation ------------------------------------------------------------------

def noisy_flat_scan(device, rng, config: LidarConfig, count: int = 64):
    positions = np.column_stack([rng.uniform(-20, 20, (count, 2)), np.zeros(count)])
    scene = boat_scene(calm_ocean(device), positions, random_quaternions(rng, count, 0.05))
    exact = Lidar(dataclasses.replace(config, range_noise_std=0.0, dropout=0.0), scene)
    return Lidar(config, scene), scanned(exact)[0]


def test_range_noise_and_dropouts_have_the_configured_statistics(device, rng):
    std, dropout = float(rng.uniform(0.02, 0.08)), float(rng.uniform(0.05, 0.2))
    config = LidarConfig(channels=4, beams=64, elevation_min=-1.2, elevation_max=-0.6, range_noise_std=std,
                         dropout=dropout, seed=int(rng.integers(2**31)))
    lidar, truth = noisy_flat_scan(device, rng, config)
    ranges, kinds = scanned(lidar)
    lost = kinds == NONE
    assert np.all(ranges[lost] == config.max_range)
    assert lost.mean() == pytest.approx(dropout, abs=0.01)  # 16 384 beams: 4 standard errors
    error = ranges[~lost] - truth[~lost]
    assert error.std() == pytest.approx(std, rel=0.05)
    assert abs(error.mean()) < 0.05 * std


def test_same_seed_same_scans_and_each_scan_draws_anew(device, rng):
    config = LidarConfig(channels=2, beams=32, elevation_min=-1.0, elevation_max=-0.5, range_noise_std=0.05,
                         dropout=0.1, seed=int(rng.integers(2**31)))
    state = rng.bit_generator.state
    first, _ = noisy_flat_scan(device, rng, config, count=8)
    rng.bit_generator.state = state  # the same boats
    twin, _ = noisy_flat_scan(device, rng, config, count=8)
    scan = scanned(first)
    np.testing.assert_array_equal(scan[0], scanned(twin)[0])
    second = scanned(first)
    assert not np.array_equal(scan[0], second[0])
    first.restart_stream()
    np.testing.assert_array_equal(scanned(first)[0], scan[0])
    rng.bit_generator.state = state
    other, _ = noisy_flat_scan(device, rng, dataclasses.replace(config, seed=config.seed ^ 1), count=8)
    assert not np.array_equal(scanned(other)[0], scan[0])


def test_downsampled_is_the_nearest_return_per_sector(device, rng):
    scene, positions, quaternions, _ = object_scene(rng, device, 3)
    config = LidarConfig(channels=3, beams=72, elevation_min=0.0, elevation_max=0.2, max_range=15.0)
    lidar = Lidar(config, scene)
    lidar.scan()
    sectors = 12
    observation = lidar.downsampled(sectors)
    assert isinstance(observation, torch.Tensor) and observation.shape == (3, sectors)
    assert lidar.downsampled(sectors).data_ptr() == observation.data_ptr()  # the same tensor

    def expected():
        ranges = lidar.ranges.cpu().numpy().reshape(3, config.channels, sectors, config.beams // sectors)
        return ranges.min(axis=(1, 3)) / config.max_range

    np.testing.assert_allclose(observation.cpu().numpy(), expected(), rtol=1e-6)
    assert observation.min() < 0.9 and observation.max() == 1.0
    # Turned boats: the next scan refills the same tensor.
    turned = (Rotation.from_quat(quaternions) * Rotation.from_euler("z", 1.0)).as_quat()
    scene.view.boat_orientation.assign(turned.astype(np.float32))
    before = observation.cpu().numpy().copy()
    lidar.scan()
    np.testing.assert_allclose(observation.cpu().numpy(), expected(), rtol=1e-6)
    assert not np.array_equal(before, observation.cpu().numpy())
    with pytest.raises(ValueError, match="sectors"):
        lidar.downsampled(7)


# --- configs --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("changes, field", [
    ({"beams": 0}, "LidarConfig.beams"),
    ({"channels": 0}, "LidarConfig.channels"),
    ({"min_range": 60.0, "max_range": 50.0}, "LidarConfig.min_range"),
    ({"max_range": math.nan}, "LidarConfig.max_range"),
    ({"mount": (1.0, math.nan, 0.5)}, "LidarConfig.mount"),
    ({"mount": (1.0, 0.5)}, "LidarConfig.mount"),
    ({"mount_rpy": (0.0, math.inf, 0.0)}, "LidarConfig.mount_rpy"),
    ({"rate": 0.0}, "LidarConfig.rate"),
    ({"rate": -10.0}, "LidarConfig.rate"),
    ({"horizontal_fov": 7.0}, "LidarConfig.horizontal_fov"),
    ({"channels": 4, "elevation_min": 0.2, "elevation_max": 0.2}, "LidarConfig.elevation_max"),
    ({"elevation_min": -2.0}, "LidarConfig.elevation_min"),
    ({"dropout": 1.0}, "LidarConfig.dropout"),
    ({"range_noise_std": -0.1}, "LidarConfig.range_noise_std"),
    ({"water_returns": 1}, "LidarConfig.water_returns"),
    ({"seed": -1}, "LidarConfig.seed"),
])
def test_bad_config_is_a_value_error_naming_the_field(changes, field):
    with pytest.raises(ValueError, match=field.replace(".", r"\.")):
        LidarConfig(**changes)


def test_presets():
    scan = LidarConfig.scan_2d()
    assert (scan.channels, scan.beams, scan.beam_count, scan.horizontal_fov) == (1, 360, 360, 2 * math.pi)
    azimuth = scan.azimuths()
    assert azimuth[0] == -math.pi and azimuth[180] == 0.0 and np.allclose(np.diff(azimuth), math.radians(1.0))
    masthead = sensor_mount(EBoatVessel(), "masthead")
    vlp = LidarConfig.multi_channel(16, mount=masthead)
    assert (vlp.channels, vlp.max_range) == (16, 100.0)
    np.testing.assert_allclose(np.degrees(vlp.elevations()), np.arange(-15.0, 16.0, 2.0), atol=1e-12)
    assert LidarConfig.multi_channel(16, mount=masthead, beams=1800).beam_count == 28_800
    # The sheet's mast joint, 0.595 m forward and 0.153 m below the hull link (0.2106 m up), plus the 3.55 m mast.
    np.testing.assert_allclose(vlp.mount, (0.595, 0.0, 0.2106 - 0.153 + 3.55), atol=1e-9)
    with pytest.raises(ValueError, match=r"the E-Boat has no sensor place 'keel' \(its places: masthead\)"):
        sensor_mount(EBoatVessel(), "keel")


# --- inside a SailingEnv decision -------------------------------------------------------------------------

def cheap_task(**changes) -> WaypointConfig:
    """The seed waypoint task on four-point hydrostatics and a 32 x 32 sea, 3 s episodes, noisy sensors."""
    base = WaypointConfig()
    simulator = dataclasses.replace(
        base.simulator, boat=dataclasses.replace(base.simulator.boat, hydrostatics=Hydrostatics.POINTS),
        ocean=OceanConfig(tile_size=64.0, resolution=32, significant_wave_height=0.3, peak_period=3.0),
        ocean_every_substep=False)
    return dataclasses.replace(base, simulator=simulator, **({"episode_time": 3.0} | changes))


class ScansByHand(DecisionHook):
    """Refreshes the scene, scans and reads the scan to the host after every ``every`` physics steps."""

    def __init__(self, lidar: Lidar, every: int):
        self.lidar, self.every, self.scans = lidar, every, []

    def after_physics_step(self, env, step: int) -> None:
        if (step + 1) % self.every == 0:
            self.lidar.scene.refresh()
            self.scans.append(scanned(self.lidar))


def test_hook_scans_at_the_rate_and_leaves_the_decision_unchanged(device, rng):
    """A LidarHook at 5 Hz (every 4 of the 20 steps) records 5 scans a decision: the scans a twin environment
    takes by hand after steps 4, 8, ..., 20; every buffer of the hooked environment equals a plain one's,
    decision after decision, through a time-out's reset."""
    task = cheap_task()
    objects = [SceneObject.buoy((6.0, 2.0)), SceneObject.pillar((-3.0, 7.0)), SceneObject.pillar((2.0, -6.0))]
    config = LidarConfig(channels=2, beams=36, elevation_min=-0.3, elevation_max=0.0, rate=5.0,
                         range_noise_std=0.02, dropout=0.05, seed=int(rng.integers(2**31)))
    plain = SailingEnv(task, 3, device=device, seed=4)
    hooked = SailingEnv(task, 3, device=device, seed=4)
    hook = LidarHook(hooked, config, objects=objects, sectors=6, record=True)
    hooked.attach(hook)
    twin = SailingEnv(task, 3, device=device, seed=4)
    by_hand = ScansByHand(Lidar(config, Scene.for_env(twin, objects)), every=4)
    assert hook.period == 4 and hook.scans_per_decision == 5
    generator = torch.Generator().manual_seed(int(rng.integers(2**31)))
    resets = 0
    for decision in range(4):
        actions = (2.0 * torch.rand(3, 3, generator=generator) - 1.0).to(plain.torch_device)
        plain.step(actions)
        hooked.step(actions)
        assert_same_buffers(hooked.buffers, plain.buffers, f"after decision {decision}")
        resets += int(plain.buffers.done.sum())
        twin.buffers.actions.copy_(actions)
        by_hand.scans = []
        with ordered_with_torch(twin.device):
            twin.launch_decision(by_hand)  # eagerly, the probe reading every scan on the host
        expected = by_hand.scans
        frames = hook.frames()
        assert frames["ranges"].shape == (5, 3, 72)
        for f, (ranges, kinds) in enumerate(expected):
            np.testing.assert_array_equal(frames["ranges"][f], ranges)
            np.testing.assert_array_equal(frames["kinds"][f], kinds)
        np.testing.assert_array_equal(hook.lidar.range_array.numpy(), expected[-1][0])
        np.testing.assert_array_equal(frames["sensor_position"][-1], by_hand.lidar.sensor_position.numpy())
        np.testing.assert_allclose(hook.observation.cpu().numpy(),
                                   expected[-1][0].reshape(3, 2, 6, 6).min(axis=(1, 3)) / config.max_range)
    assert resets > 0
    assert np.any(frames["kinds"] == OBJECT) and np.any(frames["kinds"] == WATER)


def test_hook_rate_must_fit_the_steps(device):
    env = SailingEnv(cheap_task(), 1, device=device)
    with pytest.raises(ValueError, match=r"LidarConfig\.rate"):
        LidarHook(env, LidarConfig(rate=7.0))  # 1 / (7 x 0.05) = 2.86 steps
    with pytest.raises(ValueError, match=r"LidarConfig\.rate"):
        LidarHook(env, LidarConfig(rate=40.0))  # faster than the 20 Hz steps
    with pytest.raises(ValueError, match=r"LidarConfig\.rate"):
        LidarHook(env, LidarConfig(rate=20.0 / 3.0))  # every 3 steps does not divide 20
    with pytest.raises(ValueError, match="record=True"):
        LidarHook(env, LidarConfig()).frames()
