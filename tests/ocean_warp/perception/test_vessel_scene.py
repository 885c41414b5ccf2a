"""The scene of any vessel: a WAM-V's thruster pods, turned by their own angles (``thruster_angle`` columns 0 and
1), are hit where a numpy ray-triangle intersection over the parts posed by hand says."""

from __future__ import annotations

import numpy as np
import pytest
import warp as wp

from ocean_warp.kernels.ray_cast import HIT_BOAT
from ocean_warp.perception import Scene
from ocean_warp.wamv import Wamv, WamvConfig, WamvSimulatorConfig
from ocean_warp.wamv.config import ThrusterLayout
from tests.hull_setups import rotation_matrix
from tests.ocean_warp.perception.test_scene import ray_triangles


def test_turned_thrusters_are_seen_where_their_angles_put_them(device, rng):
    vessel = Wamv(WamvSimulatorConfig(boat=WamvConfig(thrusters=ThrusterLayout.AZIMUTH)))
    sim = vessel.simulator(1, device=device)
    angles = rng.uniform(0.4, 1.2, size=2) * rng.choice([-1.0, 1.0], size=2)
    sim.state.thruster_angle.assign(wp.array(angles[None, :].astype(np.float32), dtype=float, device=device))
    scene = Scene.for_vessel(vessel, sim, [[]], envs=1, boat_env=np.zeros(1, np.int64), water_visible=False)
    position = sim.state.position.numpy()[0].astype(np.float64)
    rotation = rotation_matrix(sim.state.orientation.numpy()[0].astype(np.float64))
    world = []
    for part in vessel.parts():
        points = part.mesh.points
        if part.joint is not None:
            a = -angles[part.joint_column]
            turn = np.array([[np.cos(a), -np.sin(a), 0.0], [np.sin(a), np.cos(a), 0.0], [0.0, 0.0, 1.0]])
            points = points @ turn.T + part.pivot
        world.append((part, points @ rotation.T + position))
    eye = position + rotation @ np.array([-6.0, 0.0, 2.5])  # astern and above: the pods face it
    checked = 0
    for part, points in world:
        if part.joint is None:
            continue
        corners = points[part.mesh.triangles()]
        area = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
        aims = corners[rng.choice(np.flatnonzero(area > 1e-6), size=8, replace=False)].mean(axis=1)
        directions = (aims - eye) / np.linalg.norm(aims - eye, axis=1, keepdims=True)
        hit = scene.cast(np.tile(eye, (len(aims), 1)), directions, t_max=50.0)
        for r in range(len(aims)):
            expected = min(ray_triangles(eye, directions[r], w, p.mesh.triangles()) for p, w in world
                           if not np.isnan(ray_triangles(eye, directions[r], w, p.mesh.triangles())))
            assert hit["kind"][r] == HIT_BOAT
            assert hit["distance"][r] == pytest.approx(expected, abs=2e-3)
            checked += 1
    assert checked == 16
