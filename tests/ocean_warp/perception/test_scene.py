"""The ray-cast scene against analytic geometry and an independent numpy ray-triangle intersection."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh
import warp as wp

from ocean_warp.eboat import EBoatVessel
from ocean_warp.eboat.parts import eboat_parts
from ocean_warp.frames import quaternion_from_roll_pitch_yaw
from ocean_warp.kernels.ray_cast import HIT_BOAT, HIT_NONE, HIT_OBJECT, HIT_WATER
from ocean_warp.meshes import concatenate
from ocean_warp.perception import Scene, SceneObject
from tests.hull_setups import calm_ocean, rotation_matrix
from tests.ocean_warp.test_regular_wave import regular_ocean


def boats(device, poses=(), envs=None):
    """Warp arrays of boats at ``poses`` [(x, y, z, heading, boom)], and their environments."""
    poses = np.asarray(poses, dtype=np.float64).reshape(-1, 5)
    count = max(len(poses), 1)
    position = np.zeros((count, 3), np.float32)
    orientation = np.tile(np.array([0.0, 0.0, 0.0, 1.0], np.float32), (count, 1))
    boom = np.zeros(count, np.float32)
    if len(poses):
        position[:] = poses[:, :3]
        orientation[:] = quaternion_from_roll_pitch_yaw(np.column_stack([0 * poses[:, 3], 0 * poses[:, 3], poses[:, 3]]))
        boom[:] = poses[:, 4]
    env_of = np.zeros(count, np.int64) if envs is None else np.asarray(envs)
    if not len(poses):
        env_of = np.full(count, -1)
    vessel = EBoatVessel()
    return dict(boat_env=env_of, boat_position=wp.array(position, dtype=wp.vec3, device=device),
                boat_orientation=wp.array(orientation, dtype=wp.quat, device=device),
                parts=vessel.parts(hull_detail=1, rudder=False), scaling=vessel.part_scaling(),
                joints={"boom_angle": wp.array(boom, dtype=float, device=device)})


def test_flat_sea_range_is_height_over_sine_of_depression(device, rng):
    scene = Scene(calm_ocean(device), envs=1, **boats(device))
    count = 64
    height = rng.uniform(1.0, 8.0, size=count)
    depression = rng.uniform(math.radians(3.0), math.radians(89.0), size=count)
    azimuth = rng.uniform(-math.pi, math.pi, size=count)
    xy = rng.uniform(-100.0, 100.0, size=(count, 2))
    origins = np.column_stack([xy, height])
    directions = np.column_stack([np.cos(depression) * np.cos(azimuth), np.cos(depression) * np.sin(azimuth),
                                  -np.sin(depression)])
    hit = scene.cast(origins, directions, t_max=500.0)
    np.testing.assert_allclose(hit["distance"], height / np.sin(depression), rtol=1e-4)
    assert np.all(hit["kind"] == HIT_WATER)
    np.testing.assert_allclose(hit["normal"], np.tile([0.0, 0.0, 1.0], (count, 1)), atol=1e-5)
    upward = scene.cast(origins, directions * np.array([1.0, 1.0, -1.0]), t_max=80.0)
    assert np.all(upward["kind"] == HIT_NONE) and np.all(upward["distance"] == 80.0)


def test_water_can_be_made_invisible(device, rng):
    scene = Scene(calm_ocean(device), envs=1, water_visible=False, **boats(device))
    origins = np.column_stack([rng.uniform(-50, 50, size=(8, 2)), rng.uniform(1, 5, size=8)])
    hit = scene.cast(origins, np.tile([0.3, 0.0, -1.0], (8, 1)), t_max=40.0)
    assert np.all(hit["kind"] == HIT_NONE)


def sphere_distance(origin, direction, center, radius):
    """Nearest positive root of |o + t d - c| = r, unit d (NaN on a miss)."""
    oc = origin - center
    b = np.sum(oc * direction, axis=1)
    c = np.sum(oc * oc, axis=1) - radius**2
    disc = b * b - c
    return np.where(disc >= 0, -b - np.sqrt(np.maximum(disc, 0)), np.nan)


def test_buoys_and_piles_at_known_places(device, rng):
    """A floating buoy on still water (centre at the surface) and a pile, at random places: the ranges of rays
    aimed at them against the analytic sphere and cylinder; a pile's side normal is horizontal."""
    buoy_xy, pile_xy = rng.uniform(10.0, 40.0, size=2) * [1, -1], rng.uniform(-40.0, -10.0, size=2)
    radius, pile_radius, pile_height = rng.uniform(0.4, 1.5), rng.uniform(0.3, 1.0), rng.uniform(3.0, 8.0)
    scene = Scene(calm_ocean(device), envs=1, objects=[SceneObject.buoy(buoy_xy, radius=radius),
                                                       SceneObject.pillar(pile_xy, radius=pile_radius,
                                                                          height=pile_height)], **boats(device))
    count = 40
    eye = np.tile([0.0, 0.0, 0.5 * radius], (count, 1))
    # At the buoy's upper half: the rays reach it before they could reach the water.
    aim = np.array([buoy_xy[0], buoy_xy[1], 0.0]) + rng.uniform([-0.4, -0.4, 0.05], [0.4, 0.4, 0.4],
                                                                size=(count, 3)) * radius
    directions = (aim - eye) / np.linalg.norm(aim - eye, axis=1, keepdims=True)
    hit = scene.cast(eye, directions)
    expected = sphere_distance(eye, directions, np.array([*buoy_xy, 0.0]), radius)
    seen = ~np.isnan(expected)
    assert seen.sum() > count // 2
    np.testing.assert_allclose(hit["distance"][seen], expected[seen], rtol=1e-4)
    assert np.all(hit["kind"][seen] == HIT_OBJECT) and np.all(hit["index"][seen] == 0)

    level = rng.uniform(0.2, 2.0)  # a level ray at this height hits the pile's side
    toward = np.array([pile_xy[0], pile_xy[1]]) / np.linalg.norm(pile_xy)
    hit = scene.cast([[0.0, 0.0, level]], [[toward[0], toward[1], 0.0]])
    assert hit["kind"][0] == HIT_OBJECT and hit["index"][0] == 1
    assert hit["distance"][0] == pytest.approx(np.linalg.norm(pile_xy) - pile_radius, rel=1e-4)
    np.testing.assert_allclose(hit["normal"][0], [-toward[0], -toward[1], 0.0], atol=1e-3)
    over = scene.cast([[0.0, 0.0, pile_height]], [[toward[0], toward[1], 0.0]], t_max=100.0)  # above its top
    assert over["kind"][0] == HIT_NONE


def test_a_mesh_object_read_from_a_file(device, tmp_path, rng):
    """A box written as STL and read back by trimesh, placed and turned: a ray meets its near face."""
    half = rng.uniform(0.5, 2.0, size=3)
    trimesh.creation.box(extents=2 * half).export(tmp_path / "box.stl")
    place, yaw = np.array([rng.uniform(20, 40), rng.uniform(-5, 5), 1.0]), rng.uniform(-0.5, 0.5)
    box = SceneObject.from_file(tmp_path / "box.stl", place, yaw=yaw)
    scene = Scene(calm_ocean(device), envs=1, objects=[box], **boats(device))
    # Aim along the box's own -x axis from outside: the face at +half[0] is met first.
    axis = np.array([math.cos(yaw), math.sin(yaw), 0.0])
    start = place + (half[0] + 10.0) * axis
    hit = scene.cast([start], [-axis])
    assert hit["kind"][0] == HIT_OBJECT
    assert hit["distance"][0] == pytest.approx(10.0, abs=1e-4)
    np.testing.assert_allclose(hit["normal"][0], axis, atol=1e-4)
    with pytest.raises(FileNotFoundError, match="SceneObject.from_file: no such file"):
        SceneObject.from_file(tmp_path / "missing.obj")


def ray_triangles(origin, direction, vertices, triangles):
    """Nearest t > 0 of one ray against triangles (Moller-Trumbore, numpy), NaN on a miss."""
    a, b, c = (vertices[triangles[:, i]] for i in range(3))
    e1, e2 = b - a, c - a
    p = np.cross(direction, e2)
    det = np.sum(e1 * p, axis=1)
    ok = np.abs(det) > 1e-12
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = origin - a
    u = np.sum(s * p, axis=1) * inv
    q = np.cross(s, e1)
    v = (q @ direction) * inv
    t = np.sum(e2 * q, axis=1) * inv
    hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 1e-9)
    return t[hit].min() if hit.any() else np.nan


def test_another_boat_at_a_known_pose(device, rng):
    """Two boats in one environment: rays from boat 0's masthead region toward boat 1 hit boat 1 where a
    numpy ray-triangle intersection over the same parts (hull, keel and mast; boom and sail at the boom
    angle) says, and never boat 0 itself."""
    heading, boom = rng.uniform(-math.pi, math.pi), rng.uniform(-0.8, 0.8)
    other = np.array([rng.uniform(8.0, 15.0), rng.uniform(-3.0, 3.0), 0.0])
    scene = Scene(calm_ocean(device), envs=1, water_visible=False,
                  **boats(device, [(0, 0, 0, 0.3, 0.0), (*other, heading, boom)], envs=[0, 0]))
    parts = eboat_parts(hull_detail=1)
    rotation = rotation_matrix(quaternion_from_roll_pitch_yaw(np.array([[0.0, 0.0, heading]]))[0])
    body = concatenate(parts.hull, parts.keel, parts.mast)
    sail = concatenate(parts.spar, parts.sail)
    boom_turn = rotation_matrix(quaternion_from_roll_pitch_yaw(np.array([[0.0, 0.0, -boom]]))[0])
    world_body = body.points @ rotation.T + other
    world_sail = (sail.points @ boom_turn.T + parts.boom_pivot) @ rotation.T + other
    eye = np.array([0.0, 0.0, 1.5])
    # Half the rays aim at the centroids of random triangles of boat 1 (a ray through a triangle's interior
    # must hit boat 1, maybe nearer); half at random points about it, which may miss (a thin mast and sail
    # fill little of any box, so a count of random hits is no premise to assert).
    corners = np.concatenate([world_body[body.triangles()], world_sail[sail.triangles()]])
    area = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    aimed = corners[rng.choice(np.flatnonzero(area > 1e-6), size=12, replace=False)].mean(axis=1)
    targets = np.concatenate([aimed, other + rng.uniform([-1.2, -0.4, -0.3], [1.2, 0.4, 3.0], size=(12, 3))])
    count = len(targets)
    directions = (targets - eye) / np.linalg.norm(targets - eye, axis=1, keepdims=True)
    hit = scene.cast(np.tile(eye, (count, 1)), directions, own_boat=0)
    checked = 0
    for r in range(count):
        expected = np.fmin(ray_triangles(eye, directions[r], world_body, body.triangles()),
                           ray_triangles(eye, directions[r], world_sail, sail.triangles()))
        if np.isnan(expected):
            assert r >= len(aimed) and hit["kind"][r] == HIT_NONE
            continue
        checked += 1
        assert hit["kind"][r] == HIT_BOAT and hit["index"][r] == 1
        assert hit["distance"][r] == pytest.approx(expected, abs=1e-3)
    assert checked >= len(aimed)
    inside = scene.cast([[0.0, 0.0, 0.5]], [[1.0, 0.0, 0.0]], own_boat=0, t_max=2.0)  # from within boat 0
    assert inside["kind"][0] == HIT_NONE


def test_each_environment_sees_only_its_own_objects(device, rng):
    x = rng.uniform(10.0, 30.0)
    scene = Scene(calm_ocean(device), envs=2, objects=[[], [SceneObject.pillar((x, 0.0), radius=1.0)]],
                  **boats(device))
    hit = scene.cast([[0.0, 0.0, 1.0]] * 2, [[1.0, 0.0, 0.0]] * 2, envs=[0, 1], t_max=60.0)
    assert list(hit["kind"]) == [HIT_NONE, HIT_OBJECT]
    assert hit["distance"][1] == pytest.approx(x - 1.0, rel=1e-5)


def test_a_regular_wave_is_seen_where_theory_puts_it(device, rng):
    """Straight-down rays over a regular Airy wave meet a cos(k.x - omega t + phase); a floating buoy's
    centre rides at that height."""
    ocean, a, k_vec, omega, phase = regular_ocean(rng, device, math.inf)
    t = float(rng.uniform(0.0, 600.0))
    ocean.update(t)
    xy = rng.uniform(-200.0, 200.0, size=(50, 2))
    buoy = SceneObject.buoy(xy[0], radius=0.3)
    scene = Scene(ocean, envs=1, objects=[buoy], **boats(device))
    origins = np.column_stack([xy[1:], np.full(49, 5.0)])
    hit = scene.cast(origins, np.tile([0.0, 0.0, -1.0], (49, 1)))
    theory = a * np.cos(xy[1:] @ k_vec - omega * t + phase)
    np.testing.assert_allclose(5.0 - hit["distance"], theory, atol=5e-3 * a + 1e-3)
    assert np.all(hit["kind"] == HIT_WATER)
    band = scene.band.numpy()
    assert band[0] == pytest.approx(-a, abs=2e-3 * a) and band[1] == pytest.approx(a, abs=2e-3 * a)
    centre = scene.view.object_position.numpy()[0]
    assert centre[2] == pytest.approx(a * math.cos(xy[0] @ k_vec - omega * t + phase), abs=5e-3 * a + 1e-3)


@pytest.mark.parametrize("field,value,message", [
    ("radius", 0.0, r"SceneObject\.radius must be > 0"),
    ("height", -1.0, r"SceneObject\.height must be > 0"),
    ("shape", "cone", r"SceneObject\.shape must be one of"),
    ("position", (0.0, math.nan, 0.0), r"SceneObject\.position must be finite"),
    ("color", (1.5, 0.0, 0.0), r"SceneObject\.color must be \(r, g, b\) in \[0, 1\]"),
    ("shape", "mesh", r"SceneObject\.mesh must be a MeshData"),
])
def test_bad_objects_name_the_field(field, value, message):
    with pytest.raises(ValueError, match=message):
        SceneObject(**{field: value})


def test_bad_scenes_and_casts_are_clear_errors(device):
    ocean = calm_ocean(device)
    with pytest.raises(ValueError, match="Scene.objects must be SceneObjects"):
        Scene(ocean, envs=2, objects=[[SceneObject()]], **boats(device))
    with pytest.raises(ValueError, match="Scene.envs must be a whole number"):
        Scene(ocean, envs=0, **boats(device))
    scene = Scene(ocean, envs=1, **boats(device))
    with pytest.raises(ValueError, match="directions finite and non-zero"):
        scene.cast([[0, 0, 1]], [[0, 0, 0]])
    with pytest.raises(ValueError, match=r"envs must lie in \[0, 1\)"):
        scene.cast([[0, 0, 1]], [[1, 0, 0]], envs=[3])


def test_a_reefed_sail_is_hit_where_its_scaled_triangles_are(device, rng):
    """Boat 1 at reef level 0, 1 or 2 (a random boom angle and heading): rays from boat 0 toward it hit it where
    a numpy ray-triangle intersection over the hull, keel and mast, the spar and the sail scaled by s =
    sqrt(A_k / 3.188) about its tack says; rays at the full sail's head, above a reef's, miss a reefed boat's
    sail. The scene reads the levels from the boats' array (bound, not copied): the same scene redrawn."""
    heading, boom = rng.uniform(-math.pi, math.pi), rng.uniform(-0.8, 0.8)
    other = np.array([rng.uniform(8.0, 15.0), rng.uniform(-3.0, 3.0), 0.0])
    levels = wp.zeros(2, dtype=int, device=device)
    scene = Scene(calm_ocean(device), envs=1, water_visible=False, reef_level=levels,
                  **boats(device, [(0, 0, 0, 0.3, 0.0), (*other, heading, boom)], envs=[0, 0]))
    parts = eboat_parts(hull_detail=1)
    rotation = rotation_matrix(quaternion_from_roll_pitch_yaw(np.array([[0.0, 0.0, heading]]))[0])
    boom_turn = rotation_matrix(quaternion_from_roll_pitch_yaw(np.array([[0.0, 0.0, -boom]]))[0])
    body = concatenate(parts.hull, parts.keel, parts.mast)
    world_body = body.points @ rotation.T + other
    world_spar = (parts.spar.points @ boom_turn.T + parts.boom_pivot) @ rotation.T + other
    full_sail = (parts.sail.points @ boom_turn.T + parts.boom_pivot) @ rotation.T + other
    eye = np.array([0.0, 0.0, 1.5])
    for level, area in enumerate((3.188, 2.0, 1.15)):
        levels.assign(np.array([0, level], dtype=np.int32))
        s = math.sqrt(area / 3.188)
        tack = parts.sail_tack
        sail = ((tack + s * (parts.sail.points - tack)) @ boom_turn.T + parts.boom_pivot) @ rotation.T + other
        triangles = parts.sail.triangles()
        # At the centroids of the reefed sail's triangles and of the full sail's, and about the boat.
        targets = np.concatenate([sail[triangles].mean(axis=1), full_sail[triangles].mean(axis=1),
                                  other + rng.uniform([-1.2, -0.4, 0.5], [1.2, 0.4, 3.0], size=(12, 3))])
        directions = (targets - eye) / np.linalg.norm(targets - eye, axis=1, keepdims=True)
        hit = scene.cast(np.tile(eye, (len(targets), 1)), directions, own_boat=0)
        for r in range(len(targets)):
            expected = np.nanmin([ray_triangles(eye, directions[r], world_body, body.triangles()),
                                  ray_triangles(eye, directions[r], world_spar, parts.spar.triangles()),
                                  ray_triangles(eye, directions[r], sail, triangles), np.inf])
            if not np.isfinite(expected):
                assert hit["kind"][r] == HIT_NONE, (level, r)
                continue
            assert hit["kind"][r] == HIT_BOAT and hit["index"][r] == 1, (level, r)
            assert hit["distance"][r] == pytest.approx(expected, abs=1e-3), (level, r)
        if level > 0:  # the full sail's head region is empty air at a reef (or the mast, behind)
            head = full_sail[np.argmax(full_sail[:, 2])] + np.array([0.0, 0.0, -0.3])
            direction = (head - eye) / np.linalg.norm(head - eye)
            reached = ray_triangles(eye, direction, full_sail, triangles)
            assert np.isfinite(reached) and np.isnan(ray_triangles(eye, direction, sail, triangles))
            seen = scene.cast(eye[None, :], direction[None, :], own_boat=0)
            assert seen["kind"][0] == HIT_NONE or abs(seen["distance"][0] - reached) > 0.01
