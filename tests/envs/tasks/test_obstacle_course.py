"""Obstacle courses (issue 22): the layouts drawn per environment at every reset, the scene rows they fill,
the lidar's sectors in the observation, and the reward's collision and proximity terms.

Every number is checked against one the test works out itself: the layout's geometry (``ObstacleLayoutConfig``'s
docstring) in numpy from the boat's start and waypoint, ray hits and lidar returns as analytic ray-sphere and
ray-cylinder intersections, the gap between the boat's capsule (``boat_capsule``) and an obstacle as an exact
segment-segment or point-segment distance, and the reward from ``RewardConfig``'s docstring. Contact against
analytic cases (a boat stops outside a pile, boats meeting head-on are flagged) is in
``tests/ocean_warp/test_contact.py``.

Fast settings: the four-point hydrostatics and a coarse sea (the layouts, the lidar and the reward do not depend
on the hull model), few environments and decisions.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import torch
import warp as wp

import ocean_warp as ow
from ocean_warp.contact import ContactConfig, boat_capsule
from ocean_warp.device_structs import struct_from
from ocean_warp.eboat import Hydrostatics
from ocean_warp.eboat.parts import eboat_parts
from ocean_warp.envs import SailingEnv
from ocean_warp.envs.tasks.task_configs import (
    AvoidConfig,
    AvoidSailConfig,
    ObstacleLayoutConfig,
    RewardConfig,
    StartConfig,
    avoid_lidar,
)
from ocean_warp.kernels.ray_cast import HIT_OBJECT, SHAPE_CYLINDER, SHAPE_SPHERE, SceneView, cast_rays
from ocean_warp.ocean_config import OceanConfig
from ocean_warp.perception.scene import PARKED_DEPTH
from tests.hull_setups import rotation_matrix

STERN, BOW, CAPSULE_RADIUS = boat_capsule(eboat_parts(hull_detail=1).hull.points)
"""The boat's capsule in its body frame (the contact's and the proximity term's, ``ContactConfig.radius`` None)."""
SEED_OBS, SECTORS, PRIVILEGED = 5, 24, 12
AHEAD = SEED_OBS + 1
"""Policy values before the lidar's sectors: the seed's five and the reef level (the avoidance tasks' reef rule)."""
"""The seed observation's values, the avoidance task's lidar sectors, the critic's extra values."""
BUOY, PILE = 1, 2
"""Kinds in ``env.buffers.obstacles``."""


def cheap(task, **changes):
    """``task`` on the four-point hydrostatics and a coarse sea (fast on the CPU), with ``changes``."""
    simulator = dataclasses.replace(
        task.simulator, boat=dataclasses.replace(task.simulator.boat, hydrostatics=Hydrostatics.POINTS),
        ocean=OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.3, peak_period=3.0),
        ocean_every_substep=False)
    return dataclasses.replace(task, simulator=simulator, **changes)


def one_decision_episodes(task):
    """``task`` with 0.05 s decisions (one physics step) and episodes one decision long: every step ends every
    episode, so every step draws new layouts."""
    return cheap(task, decision_period=0.05, episode_time=0.05)


def table(env) -> np.ndarray:
    """(N, K, 4) numpy copy of the layouts: x, y from the origin [m], radius [m], kind."""
    return env.buffers.obstacles.cpu().numpy().copy()


def start_and_waypoint(env) -> tuple[np.ndarray, np.ndarray]:
    """(N, 2) each boat's start and (N, 2) its first waypoint, from its origin [m]: read right after a reset."""
    b = env.buffers
    start = (b.position - b.origin)[:, :2].cpu().numpy().astype(np.float64)
    return start, b.route[:, 0, :2].cpu().numpy().astype(np.float64)


def segment_distance(p1, q1, p2, q2) -> float:
    """Least distance between segments p1-q1 and p2-q2 (3D): |r + s d1 - t d2|^2 is convex on [0, 1]^2, so its
    minimum is the unconstrained one when inside, else on an edge, where it is the clamped 1-D minimum."""
    p1, q1, p2, q2 = (np.asarray(v, dtype=np.float64) for v in (p1, q1, p2, q2))
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a, e, b, c, f = d1 @ d1, d2 @ d2, d1 @ d2, d1 @ r, d2 @ r
    candidates = []
    denominator = a * e - b * b
    if denominator > 1e-12 * a * e:
        s, t = (b * f - c * e) / denominator, (a * f - b * c) / denominator
        if 0.0 <= s <= 1.0 and 0.0 <= t <= 1.0:
            candidates.append((s, t))
    candidates += [(s, np.clip((f + s * b) / e, 0.0, 1.0)) for s in (0.0, 1.0)]
    candidates += [(np.clip((t * b - c) / a, 0.0, 1.0), t) for t in (0.0, 1.0)]
    return min(float(np.linalg.norm(r + s * d1 - t * d2)) for s, t in candidates)


def point_segment_distance(point, a, b) -> float:
    point, a, b = (np.asarray(v, dtype=np.float64) for v in (point, a, b))
    t = np.clip((point - a) @ (b - a) / ((b - a) @ (b - a)), 0.0, 1.0)
    return float(np.linalg.norm(point - (a + t * (b - a))))


def capsule_axis(position, orientation) -> tuple[np.ndarray, np.ndarray]:
    """World ends of a boat's capsule axis at a pose."""
    rotation = rotation_matrix(orientation)
    position = np.asarray(position, dtype=np.float64)
    return position + rotation @ STERN, position + rotation @ BOW


def obstacle_gaps(env, layouts: np.ndarray, pile_height: float, positions, orientations, which) -> np.ndarray:
    """(N,) the gap [m] of each boat of ``which`` (a boolean mask) to the nearest obstacle of ``layouts`` (its
    environment's table), from its capsule at the given poses; inf for the others and where there is none. A
    pile is an upright cylinder standing from pile_height / 4 below still water, a buoy a sphere about (table x,
    y, the sea's height there, as the scene floats it now: ``which`` must hold only environments whose layout
    is still ``layouts``); the gap is the centre-to-axis distance less the radii, at least 0."""
    origins = env.buffers.origin.cpu().numpy().astype(np.float64)
    floated = env.obstacles.scene.view.object_position.numpy().astype(np.float64)
    first_row = env.obstacles.first_row.numpy()
    gaps = np.full(env.num_envs, np.inf)
    for e in np.flatnonzero(which):
        a, b = capsule_axis(positions[e], orientations[e])
        for k, (x, y, radius, kind) in enumerate(layouts[e].astype(np.float64)):
            if kind == PILE:
                base = origins[e] + (x, y, -pile_height / 4.0)
                centre_distance = segment_distance(a, b, base, base + (0.0, 0.0, pile_height))
            elif kind == BUOY:
                centre = floated[first_row[e] + k]
                np.testing.assert_allclose(centre[:2], origins[e, :2] + (x, y), atol=1e-4)  # it floats where drawn
                centre_distance = point_segment_distance(centre, a, b)
            else:
                continue
            gaps[e] = min(gaps[e], max(centre_distance - CAPSULE_RADIUS - radius, 0.0))
    return gaps


def cast_without_water(scene, envs, origins, directions, t_max: float = 200.0) -> dict[str, np.ndarray]:
    """``Scene.cast`` with the sea invisible (rays see only the objects and boats): "distance", "kind",
    "index"."""
    device, count = scene.device, len(origins)
    view = struct_from(SceneView, scene.view, water_visible=0)
    directions = np.asarray(directions, dtype=np.float64)
    directions = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    out = {name: wp.zeros(count, dtype=dtype, device=device)
           for name, dtype in (("distance", float), ("kind", int), ("index", int), ("normal", wp.vec3))}
    wp.launch(cast_rays, dim=count, device=device,
              inputs=[view, wp.array(np.asarray(envs, np.int32), dtype=int, device=device),
                      wp.array(np.asarray(origins, np.float32), dtype=wp.vec3, device=device),
                      wp.array(directions.astype(np.float32), dtype=wp.vec3, device=device),
                      wp.array(np.full(count, -1, np.int32), dtype=int, device=device), 0.0, t_max],
              outputs=[out["distance"], out["kind"], out["index"], out["normal"]])
    return {name: out[name].numpy() for name in ("distance", "kind", "index")}


# --- layouts -------------------------------------------------------------------------------------------


def test_layouts_replay_from_the_seed_in_every_shard(device, rng):
    """Two batches with one seed draw bit-identical layouts at construction and at every reset after an
    episode ends; each reset draws a new layout; another seed draws others; ``reset(seed)`` draws the first
    again; a shard (``first_env`` = 10) draws rows 10.. of the whole batch's."""
    task = one_decision_episodes(AvoidConfig())
    seed = int(rng.integers(1 << 30))
    first, twin = SailingEnv(task, 16, device=device, seed=seed), SailingEnv(task, 16, device=device, seed=seed)
    shard = SailingEnv(task, 6, device=device, seed=seed, first_env=10)
    other = SailingEnv(task, 16, device=device, seed=seed + 1)
    initial = table(first)
    assert initial.shape == (16, 12, 4) and np.all(initial[:, :6, 3] > 0)  # 6-12 obstacles each
    np.testing.assert_array_equal(table(twin), initial)
    np.testing.assert_array_equal(table(shard), initial[10:])
    assert not np.array_equal(table(other), initial)
    layouts = [initial]
    for _ in range(2):
        actions = torch.from_numpy(rng.uniform(-1.0, 1.0, (16, 3)).astype(np.float32)).to(first.torch_device)
        for env in (first, twin, other):
            env.step(actions)
        shard.step(actions[10:])
        assert bool(first.buffers.done.all()) and bool(shard.buffers.done.all())
        layouts.append(table(first))
        np.testing.assert_array_equal(table(twin), layouts[-1])
        np.testing.assert_array_equal(table(shard), layouts[-1][10:])
        assert not np.array_equal(table(other), layouts[-1])
        assert not np.any(np.all(layouts[-1] == layouts[-2], axis=(1, 2))), "every environment gets a new layout"
    first.reset(seed=seed)
    np.testing.assert_array_equal(table(first), initial)


def check_layouts(env, layout: ObstacleLayoutConfig) -> tuple[np.ndarray, np.ndarray]:
    """Every environment's layout (read right after a reset) against ``layout``'s rules, worked out in numpy
    from the boat's start S and first waypoint W: the kept obstacles fill the first rows, the rest are zeros;
    kinds and radii within their ranges; each centre at S + t (W - S) + c n with t in ``along_track`` and
    |c| <= ``cross_track``; surfaces at least ``start_clearance`` from S, ``waypoint_clearance`` from W and
    ``spacing`` from each other. Returns (N,) obstacles kept, and (M, 2) each kept obstacle's surface distance
    from S and from W."""
    eps = 1e-3  # [m] float32 positions of up to a few hundred metres
    layouts = table(env)
    start, waypoint = start_and_waypoint(env)
    kept = (layouts[:, :, 3] != 0).sum(axis=1)
    np.testing.assert_array_equal(env.obstacles.obstacle_count.numpy(), kept)
    surface_distances = []
    for e in range(env.num_envs):
        rows = layouts[e, :kept[e]].astype(np.float64)
        assert np.all(layouts[e, kept[e]:] == 0.0), f"env {e}: empty rows after the kept ones"
        assert np.all(np.isin(rows[:, 3], (BUOY, PILE)))
        buoy, pile = rows[:, 3] == BUOY, rows[:, 3] == PILE
        assert np.all((rows[buoy, 2] >= layout.buoy_radius[0] - 1e-6) & (rows[buoy, 2] <= layout.buoy_radius[1] + 1e-6))
        assert np.all((rows[pile, 2] >= layout.pile_radius[0] - 1e-6) & (rows[pile, 2] <= layout.pile_radius[1] + 1e-6))
        centres, radii = rows[:, :2], rows[:, 2]
        leg = waypoint[e] - start[e]
        length = np.linalg.norm(leg)
        along = leg / length
        normal = np.array([-along[1], along[0]])
        t = (centres - start[e]) @ along / length
        c = (centres - start[e]) @ normal
        assert np.all((t >= layout.along_track[0] - eps / length) & (t <= layout.along_track[1] + eps / length)), t
        assert np.all(np.abs(c) <= layout.cross_track + eps), c
        from_start = np.linalg.norm(centres - start[e], axis=1) - radii
        from_waypoint = np.linalg.norm(centres - waypoint[e], axis=1) - radii
        assert np.all(from_start >= layout.start_clearance - eps), (e, from_start)
        assert np.all(from_waypoint >= layout.waypoint_clearance - eps), (e, from_waypoint)
        gaps = np.linalg.norm(centres[:, None] - centres[None], axis=2) - radii[:, None] - radii[None]
        np.fill_diagonal(gaps, np.inf)
        assert np.all(gaps >= layout.spacing - eps), (e, gaps.min())
        surface_distances += list(zip(from_start, from_waypoint))
    return kept, np.array(surface_distances)


def test_avoid_layouts_never_cover_the_start_or_the_waypoint(device, rng):
    """The avoidance task's layouts (64 environments, 4 resets): the rules of ``check_layouts``; the counts
    6-12 (none of the 12 slots is left empty for want of room on a 100-200 m leg, rejection being rare);
    about 40 % piles."""
    task = cheap(AvoidConfig())
    layout = task.obstacles
    env = SailingEnv(task, 64, device=device, seed=int(rng.integers(1 << 30)))
    counts, kinds = [], []
    for _ in range(4):
        kept, _ = check_layouts(env, layout)
        counts.append(kept)
        kinds.append(table(env)[:, :, 3])
        env.reset()
    counts, kinds = np.concatenate(counts), np.concatenate(kinds)
    assert counts.min() >= layout.count[0] and counts.max() <= layout.count[1]
    assert set(counts.tolist()) == set(range(6, 13)), "every count of the range is drawn"
    piles = np.sum(kinds == PILE) / np.sum(kinds != 0)
    assert abs(piles - layout.pile_fraction) < 0.06, piles  # ~2300 obstacles: 5 standard deviations


def test_crowded_layouts_leave_slots_empty_rather_than_break_a_rule(device, rng):
    """A band too small for the count asked (24 obstacles 3 m apart in a band 4 m wide, on a 60-80 m leg with
    15-25 m clearances at each end: 10-50 m of it left): slots are left empty (a few of the 24 are kept), never
    filled against a rule, and the obstacles pack right up to the clearances (so the rules were what stopped
    them)."""
    layout = ObstacleLayoutConfig(count=(24, 24), pile_fraction=0.5, along_track=(0.0, 1.0), cross_track=2.0,
                                  start_clearance=float(rng.uniform(15.0, 20.0)),
                                  waypoint_clearance=float(rng.uniform(20.0, 25.0)), spacing=3.0, attempts=8)
    start = dataclasses.replace(AvoidConfig().start, waypoint_distance=(60.0, 80.0))
    env = SailingEnv(cheap(AvoidConfig(), obstacles=layout, start=start), 32, device=device,
                     seed=int(rng.integers(1 << 30)))
    kept, surfaces = check_layouts(env, layout)
    env.reset()
    kept_again, surfaces_again = check_layouts(env, layout)
    kept, surfaces = np.concatenate([kept, kept_again]), np.concatenate([surfaces, surfaces_again])
    assert kept.max() < 24 and kept.min() >= 1, kept
    assert surfaces[:, 0].min() < layout.start_clearance + 1.0, "packed up to the start's clearance"
    assert surfaces[:, 1].min() < layout.waypoint_clearance + 1.0, "and up to the waypoint's"


def test_scene_rows_hold_the_table_and_empty_rows_are_never_hit(device, rng):
    """Each kept obstacle is in its scene row (shape, radius, place; a pile from a quarter of its height below
    still water, a buoy floating on the sea), and rays cast at it hit it where the analytic ray-cylinder or
    ray-sphere intersection says. After a new layout with fewer obstacles, the dropped ones' rows are parked
    ``PARKED_DEPTH`` below the origin with radius 0 (a row left where it stood, even of radius 0, would still
    touch a boat's capsule and count in its clearance), and rays cast where they stood hit nothing of theirs."""
    pile_height = float(rng.uniform(4.0, 8.0))
    layout = ObstacleLayoutConfig(count=(1, 12), pile_height=pile_height)
    env = SailingEnv(cheap(AvoidConfig(), obstacles=layout), 16, device=device, seed=int(rng.integers(1 << 30)))
    scene, first_row = env.obstacles.scene, env.obstacles.first_row.numpy()
    origins = env.buffers.origin.cpu().numpy().astype(np.float64)

    def rays_at(layouts, floated):
        """One ray at every kept obstacle of ``layouts`` (buoys where ``floated``, the scene's object positions
        then, put them): (envs, rows, ray origins, directions, expected t)."""
        envs, rows, starts, directions, expected = [], [], [], [], []
        for e in range(env.num_envs):
            for k, (x, y, radius, kind) in enumerate(layouts[e].astype(np.float64)):
                if kind == 0:
                    continue
                centre = origins[e] + (x, y, 0.0)
                if kind == PILE:  # horizontal, at a random height on the pile, off its axis by less than r
                    bearing, distance = rng.uniform(0.0, 2 * math.pi), radius + rng.uniform(0.5, 1.5)
                    offset = rng.uniform(-0.8, 0.8) * radius
                    towards = -np.array([math.cos(bearing), math.sin(bearing), 0.0])
                    side = np.array([-towards[1], towards[0], 0.0])
                    start = centre + distance * -towards + offset * side + (0.0, 0.0, rng.uniform(0.2, 2.0))
                    along = distance  # the ray's start is 'distance' back along 'towards', 'offset' aside
                    t = along - math.sqrt(radius**2 - offset**2)
                    direction = towards
                else:  # down onto a buoy, off its centre by less than r
                    centre = floated[first_row[e] + k].astype(np.float64)
                    offset = rng.uniform(0.0, 0.8) * radius
                    angle = rng.uniform(0.0, 2 * math.pi)
                    start = centre + (offset * math.cos(angle), offset * math.sin(angle), 3.0)
                    t = 3.0 - math.sqrt(radius**2 - offset**2)
                    direction = np.array([0.0, 0.0, -1.0])
                envs.append(e), rows.append(first_row[e] + k), starts.append(start), directions.append(direction)
                expected.append(t)
        return np.array(envs), np.array(rows), np.array(starts), np.array(directions), np.array(expected)

    old = table(env)
    shape = scene.view.object_shape.numpy()
    size = scene.view.object_size.numpy()
    position = scene.view.object_position.numpy()
    for e in range(env.num_envs):
        for k, (x, y, radius, kind) in enumerate(old[e]):
            row = first_row[e] + k
            if kind == 0:
                assert size[row, 0] == 0.0 and position[row, 2] == pytest.approx(origins[e, 2] - PARKED_DEPTH)
                continue
            assert shape[row] == (SHAPE_CYLINDER if kind == PILE else SHAPE_SPHERE)
            assert size[row, 0] == pytest.approx(radius, abs=1e-6)
            np.testing.assert_allclose(position[row, :2], origins[e, :2] + (x, y), atol=1e-4)
            if kind == PILE:
                assert size[row, 1] == pytest.approx(pile_height / 2, rel=1e-6)  # half height
                assert position[row, 2] == pytest.approx(pile_height / 4, rel=1e-6)  # from -h/4 to 3h/4
            else:
                assert abs(position[row, 2]) < 0.5  # on the sea (Hs 0.3 m)
    envs, rows, starts, directions, expected = rays_at(old, position)
    hits = cast_without_water(scene, envs, starts, directions)
    np.testing.assert_array_equal(hits["kind"], HIT_OBJECT)
    np.testing.assert_array_equal(hits["index"], rows)
    np.testing.assert_allclose(hits["distance"], expected, atol=2e-4)

    stale, old_position = 0, position
    for _ in range(3):  # new layouts, some with fewer obstacles than the last
        env.reset()
        new = table(env)
        dropped = (old[:, :, 3] != 0) & (new[:, :, 3] == 0)
        stale += int(dropped.sum())
        for e, k in zip(*np.nonzero(dropped)):  # parked deep, with nothing left of the old obstacle
            row = first_row[e] + k
            assert scene.view.object_size.numpy()[row, 0] == 0.0 and scene.view.object_bound.numpy()[row] == 0.0
            np.testing.assert_allclose(scene.view.object_position.numpy()[row],
                                       origins[e] - (0.0, 0.0, PARKED_DEPTH), atol=1e-3)
        envs, rows, starts, directions, _ = rays_at(np.where(dropped[:, :, None], old, 0.0), old_position)
        if len(envs):
            hits = cast_without_water(scene, envs, starts, directions)
            kept_rows = {first_row[e] + k for e in range(env.num_envs) for k in range(12) if new[e, k, 3] != 0}
            assert not set(hits["index"][hits["kind"] == HIT_OBJECT].tolist()) - kept_rows, "an empty row was hit"
            # A ray that finds nothing where the obstacle stood runs on (up to 200 m) and may meet a boat,
            # whose hit carries a boat's index: only object hits name rows.
            assert not np.any(np.isin(hits["index"][hits["kind"] == HIT_OBJECT], rows))
        old, old_position = new, scene.view.object_position.numpy()
    assert stale >= 5, "the layouts dropped obstacles, whose rows the rays then looked for"


# --- the observation --------------------------------------------------------------------------------


def pile_course(**changes) -> AvoidConfig:
    """Piles within lidar range of a still boat: the waypoint 40 m away, 2 piles 8-32 m down the leg within
    6 m of it, the boat heading within 30 deg of the waypoint; calm air; then ``changes``."""
    start = StartConfig(heading_deg=(-30.0, 30.0), heading_step_deg=0.0, heading_toward_waypoint=True,
                        wind_speed=(0.0, 0.0), wind_direction_step_deg=0.0, gust_scale=(0.0, 0.0),
                        waypoint_distance=(40.0, 40.0), waypoint_bearing_deg=(-180.0, 180.0))
    obstacles = ObstacleLayoutConfig(count=(2, 2), pile_fraction=1.0, along_track=(0.2, 0.8), cross_track=6.0,
                                     start_clearance=5.0, waypoint_clearance=5.0, spacing=2.0)
    return cheap(AvoidConfig(), **({"start": start, "obstacles": obstacles} | changes))


def test_lidar_sectors_in_the_observation_against_analytic_returns(device, rng):
    """At a reset (boats level, at known poses) every lidar beam's range is the analytic hit of a level ray from
    the bow mount on the environment's piles (upright circles in the plane of the scan), or 50 m; the policy's
    values 5-28 and the critic's 17-40 are the nearest return of each 15-degree sector over 50 m, worked out
    from those ranges, and are ``lidar.downsampled(24)``; piles 8-32 m off make some sectors read below 1."""
    env = SailingEnv(pile_course(), 8, device=device, seed=int(rng.integers(1 << 30)))
    lidar, config = env.obstacles.lidar, env.task.lidar
    assert config.beams == 360 and config.max_range == 50.0 and not config.water_returns
    b = env.buffers
    positions = b.position.cpu().numpy().astype(np.float64)
    orientations = b.orientation.cpu().numpy().astype(np.float64)
    origins = b.origin.cpu().numpy().astype(np.float64)
    layouts = table(env).astype(np.float64)
    ranges = lidar.ranges.cpu().numpy()
    azimuths = config.azimuths()
    for e in range(env.num_envs):
        rotation = rotation_matrix(orientations[e])
        assert rotation[2, 2] == pytest.approx(1.0, abs=1e-6), "level at a reset"
        sensor = (positions[e] + rotation @ np.array(config.mount))[:2]
        heading = math.atan2(rotation[1, 0], rotation[0, 0])
        directions = np.stack([np.cos(heading + azimuths), np.sin(heading + azimuths)], axis=1)
        expected = np.full(config.beams, config.max_range)
        certain = np.ones(config.beams, dtype=bool)
        for x, y, radius, kind in layouts[e]:
            assert kind == PILE
            offset = sensor - (origins[e, :2] + (x, y))
            half_b = directions @ offset
            discriminant = half_b**2 - (offset @ offset - radius**2)
            t = -half_b - np.sqrt(np.maximum(discriminant, 0.0))
            hit = (discriminant >= 0.0) & (t >= config.min_range) & (t <= config.max_range)
            expected = np.where(hit, np.minimum(expected, t), expected)
            # Near grazing, t moves by d(disc) / (2 sqrt(disc)), so float32's rounding of the scene's positions
            # moves such a beam by over 1 mm (seed 3560529043: one beam 1.2 mm off): beams whose half chord
            # sqrt(disc) is under 0.1 m may read either way
            certain &= np.abs(discriminant) > 1e-2
        np.testing.assert_allclose(ranges[e][certain], expected[certain], atol=1e-3)
    nearest = ranges.reshape(env.num_envs, SECTORS, -1).min(axis=2) / config.max_range
    policy, critic = b.policy_obs.cpu().numpy(), b.critic_obs.cpu().numpy()
    assert policy.shape == (8, AHEAD + SECTORS) and critic.shape == (8, AHEAD + PRIVILEGED + SECTORS)
    np.testing.assert_allclose(policy[:, AHEAD:], nearest, rtol=1e-6)
    np.testing.assert_array_equal(policy[:, AHEAD:], lidar.downsampled(SECTORS).cpu().numpy())
    np.testing.assert_array_equal(critic[:, AHEAD + PRIVILEGED:], policy[:, AHEAD:])
    np.testing.assert_array_equal(critic[:, :AHEAD], policy[:, :AHEAD])
    assert np.all(policy[:, AHEAD:].min(axis=1) < 36.0 / 50.0), "every boat sees a pile"
    assert np.all(policy[:, AHEAD:].max(axis=1) == 1.0), "and open water elsewhere"


@pytest.mark.parametrize("config", [AvoidConfig, AvoidSailConfig])
def test_avoid_task_observations_carry_the_lidar_sectors(device, rng, config):
    """The registered tasks as they are (mesh hull, default layouts), two decisions of random actions: the
    policy's observation is the seed's 5 values and the reef level, then the lidar's 24 sectors, the critic's
    the same 6, the 12 privileged values, then the same 24 sectors; each sector in [0, 1]."""
    env = SailingEnv(config(episode_time=1.0), 4, device=device, seed=int(rng.integers(1 << 30)))
    for _ in range(2):
        env.step(torch.from_numpy(rng.uniform(-1.0, 1.0, (4, 3)).astype(np.float32)).to(env.torch_device))
        b = env.buffers
        sectors = env.obstacles.lidar.downsampled(SECTORS)
        assert b.policy_obs.shape == (4, AHEAD + SECTORS)
        assert torch.equal(b.policy_obs[:, AHEAD:], sectors)
        assert torch.equal(b.critic_obs[:, AHEAD + PRIVILEGED:], sectors)
        assert torch.equal(b.critic_obs[:, :AHEAD], b.policy_obs[:, :AHEAD])
        levels = env.simulator.state.reef_level.numpy()  # the rule's, from each run's 3-8 m/s: 0 or 1 (2 at 8)
        np.testing.assert_array_equal(b.policy_obs[:, SEED_OBS].cpu().numpy(), levels / 2.0)
        assert bool(((sectors >= 0.0) & (sectors <= 1.0)).all())
        assert bool(b.done.all())  # one-decision episodes: a new layout, start and scan every step
    assert b.obstacles.shape == (4, 12, 4)


# --- the reward ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("pushed", [False, True], ids=["flag_only", "pushed"])
def test_a_collision_ends_the_episode_with_the_collision_penalty(device, rng, pushed):
    """A pile of radius 1 m on the line 12 m ahead, the boat under full propeller steering at the waypoint: it
    hits the pile; that decision's boat is flagged COLLIDED, its reward is exactly -collision_penalty (not
    -flagged_penalty, no progress or proximity term), its episode is terminated, not timed out, and the
    episode log counts a collision. With a contact that only flags (no force) the boat sails on into the pile,
    so at the decision's end its capsule overlaps it (gap 0, worked out from its pose); with the task's
    contact force it bounces off (within the decision) but ends it within 1 m of the pile."""
    collision, flagged = float(rng.uniform(1.5, 5.0)), float(rng.uniform(0.1, 0.9))
    reward = RewardConfig(collision_penalty=collision, flagged_penalty=flagged, proximity_cost=0.2,
                          proximity_range=5.0)
    obstacles = ObstacleLayoutConfig(count=(1, 1), pile_fraction=1.0, pile_radius=(1.0, 1.0),
                                     along_track=(0.4, 0.4), cross_track=0.0, start_clearance=5.0,
                                     waypoint_clearance=5.0)
    start = StartConfig(heading_deg=(0.0, 0.0), heading_step_deg=0.0, heading_toward_waypoint=True,
                        wind_speed=(0.0, 0.0), wind_direction_step_deg=0.0, gust_scale=(0.0, 0.0),
                        waypoint_distance=(30.0, 30.0), waypoint_bearing_deg=(-180.0, 180.0),
                        surge_speed=(1.0, 1.5))
    contact = ContactConfig() if pushed else ContactConfig(stiffness=0.0, damping=0.0)
    task = cheap(AvoidConfig(), start=start, obstacles=obstacles, reward=reward, contact=contact, episode_time=30.0)
    env = SailingEnv(task, 4, device=device, seed=int(rng.integers(1 << 30)))
    b = env.buffers
    hit = np.zeros(4, dtype=bool)
    for _ in range(12):
        actions = torch.zeros(4, 3, device=env.torch_device)
        actions[:, 0] = 1.0
        actions[:, 2] = torch.clamp(3.0 * b.policy_obs[:, 1], -1.0, 1.0)  # obs 1: the bearing / 180 deg
        layouts = table(env)  # the episode's (a collision ends it, and the reset draws the next)
        env.step(actions)
        done, status, rewards = b.done.cpu().numpy(), b.final_status.cpu().numpy(), b.reward.cpu().numpy()
        collided = done & ((status & ow.BoatStatus.COLLIDED) != 0)
        assert not np.any(done & ~collided), "no episode ends any other way"
        gaps = obstacle_gaps(env, layouts, obstacles.pile_height, b.final_position.cpu().numpy(),
                             b.final_orientation.cpu().numpy(), np.ones(4, dtype=bool))
        if collided.any():
            np.testing.assert_array_equal(rewards[collided], np.float32(-collision))
            assert b.terminated.cpu().numpy()[collided].all() and not b.time_out.cpu().numpy()[collided].any()
            if pushed:
                assert np.all(gaps[collided] < 1.0), gaps
            else:
                np.testing.assert_array_equal(gaps[collided], 0.0)
            log = env.episode_log()
            assert log["/episode/collided_rate"].tolist() == [1.0] * int(collided.sum())
            assert log["/episode/capsized_rate"].tolist() == [0.0] * int(collided.sum())
        assert np.all(gaps[~collided] > 0.0), "a boat clear of the pile at the decision's end was not flagged"
        assert np.all(rewards[~collided] > -0.5 * collision)  # sailing on: progress less a small cost
        hit |= collided
    assert hit.all(), "every boat hit its pile"


def test_the_proximity_cost_against_hand_computation(device, rng):
    """Random actions among buoys and piles, the proximity cost large and its range 30 m (every decision
    counts it): each decision that ends unflagged and in no other way earns RewardConfig's progress term from
    the distances to the waypoint before and after (the level int(5 a0)), minus proximity_cost
    max(0, 1 - g / range) with g the gap from the boat's capsule to the nearest obstacle worked out from its
    pose (``obstacle_gaps``), minus smoothness sum((a - a_prev)^2), the time cost and the motor's energy
    energy_cost (|level| / 5)^1.5 decision_period; ``env.clearance`` is that g."""
    reward = RewardConfig(proximity_cost=float(rng.uniform(0.5, 2.0)), proximity_range=30.0,
                          smoothness=float(rng.uniform(0.01, 0.1)), time_cost=float(rng.uniform(0.001, 0.01)),
                          collision_penalty=2.0, energy_cost=float(rng.uniform(0.01, 0.05)))
    obstacles = ObstacleLayoutConfig(count=(3, 4), pile_fraction=0.5, along_track=(0.1, 0.6), cross_track=5.0,
                                     start_clearance=4.0, waypoint_clearance=5.0, spacing=2.0)
    start = StartConfig(heading_deg=(-60.0, 60.0), heading_step_deg=0.0, heading_toward_waypoint=True,
                        wind_speed=(3.0, 6.0), wind_direction_step_deg=0.0, waypoint_distance=(40.0, 40.0),
                        waypoint_bearing_deg=(-180.0, 180.0), surge_speed=(0.0, 1.5), sheet_deg=(20.0, 60.0))
    task = pile_course(start=start, obstacles=obstacles, reward=reward, episode_time=30.0)
    n = 8
    env = SailingEnv(task, n, device=device, seed=int(rng.integers(1 << 30)))
    b = env.buffers
    last = np.zeros((n, 3))
    checked, proximity_seen, kinds_seen = 0, [], set()
    for _ in range(6):
        targets = b.target.cpu().numpy().astype(np.float64)
        before = np.linalg.norm((targets - b.position.cpu().numpy())[:, :2], axis=1)
        actions = rng.uniform(-1.2, 1.2, (n, 3)).astype(np.float32)
        layouts = table(env)
        env.step(torch.from_numpy(actions).to(env.torch_device))
        positions, orientations = b.final_position.cpu().numpy(), b.final_orientation.cpu().numpy()
        after = np.linalg.norm((targets - positions)[:, :2], axis=1)
        done = b.done.cpu().numpy()
        sailing = ~done  # neither reached, lost, flagged nor timed out (the clearance of one that ended is its
        # new start's, and a buoy of its old layout no longer floats in the scene)
        gaps = obstacle_gaps(env, layouts, obstacles.pile_height, positions, orientations, sailing)
        clipped = np.clip(actions.astype(np.float64), -1.0, 1.0)
        level = np.abs(np.trunc(5.0 * clipped[:, 0]))
        progress = (before - after) / reward.progress_scale
        progress = np.where(progress > 0.0, progress * (1.0 - reward.propeller_gain * level / 5.0),
                            progress - reward.propeller_cost * level)
        proximity = reward.proximity_cost * np.maximum(1.0 - gaps / reward.proximity_range, 0.0)
        energy = reward.energy_cost * task.decision_period * (level / 5.0) ** 1.5
        expected = (progress - proximity - reward.smoothness * np.sum((clipped - last) ** 2, axis=1)
                    - reward.time_cost - energy)
        np.testing.assert_allclose(b.reward.cpu().numpy()[sailing], expected[sailing], rtol=0, atol=2e-5)
        np.testing.assert_allclose(env.clearance.numpy()[sailing], np.minimum(gaps, reward.proximity_range)[sailing],
                                   atol=2e-4)
        checked += int(sailing.sum())
        proximity_seen += list(proximity[sailing])
        kinds_seen |= set(layouts[sailing][:, :, 3].ravel().tolist())
        last = np.where(done[:, None], 0.0, clipped)
    assert checked >= 40, checked
    assert {BUOY, PILE} <= kinds_seen, "buoys and piles were both in play"
    assert min(proximity_seen) > 0.2 * reward.proximity_cost, "the term counted in every decision checked"


# --- configs --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("field, value", [
    ("count", (5, 3)), ("count", (0, 0)), ("count", (1, 65)), ("count", (-1, 3)), ("count", (1.5, 3)), ("count", 4),
    ("pile_fraction", 1.5), ("pile_fraction", -0.1),
    ("buoy_radius", (0.0, 1.0)), ("buoy_radius", (1.0, 0.5)), ("buoy_radius", 1.0),
    ("pile_radius", (-0.3, 1.0)), ("pile_radius", (0.3, 60.0)),
    ("pile_height", 0.0), ("pile_height", float("nan")),
    ("along_track", (0.6, 0.4)), ("along_track", (0.0, 1.2)), ("along_track", (-0.1, 0.5)),
    ("cross_track", -1.0), ("start_clearance", -0.5), ("waypoint_clearance", -2.0), ("spacing", -1.0),
    ("attempts", 0), ("attempts", 1001), ("attempts", 2.5),
])
def test_bad_layout_configs_name_the_field(field, value):
    with pytest.raises(ValueError, match=rf"ObstacleLayoutConfig\.{field}\b"):
        ObstacleLayoutConfig(**{field: value})


def test_layout_config_defaults_and_task_config_checks():
    """The avoidance tasks' defaults as documented; obstacles need a contact, lidar sectors must divide the
    beams, and the new fields must be of their kinds."""
    layout = ObstacleLayoutConfig()
    assert layout.slots == 12 and ObstacleLayoutConfig(count=(0, 3)).slots == 3
    avoid, sail = AvoidConfig(), AvoidSailConfig()
    assert avoid.obstacle_slots == 12 and avoid.lidar_observations == 24 and avoid.propeller is True
    assert sail.propeller is False and sail.obstacles == avoid.obstacles and sail.lidar == avoid.lidar
    assert (avoid.reward.collision_penalty, avoid.reward.proximity_cost) == (2.0, 0.02)
    with pytest.raises(ValueError, match=r"AvoidConfig\.contact must be a ContactConfig when obstacles"):
        AvoidConfig(contact=None)
    for sectors in (7, 0, 361, True, 24.0):
        with pytest.raises(ValueError, match=r"AvoidSailConfig\.lidar_sectors must be a whole divisor"):
            AvoidSailConfig(lidar_sectors=sectors)
    assert AvoidConfig(lidar_sectors=36).lidar_observations == 36
    assert AvoidConfig(lidar=avoid_lidar(beams=72), lidar_sectors=72).lidar_observations == 72
    for field, value in (("obstacles", {"count": (1, 2)}), ("contact", 5.0e4), ("lidar", "2d")):
        with pytest.raises(ValueError, match=rf"AvoidConfig\.{field} must be a"):
            AvoidConfig(**{field: value})
    assert AvoidConfig(obstacles=None, contact=ContactConfig()).obstacle_slots == 0
