"""Hydrostatics of the per-triangle pressure against Archimedes and ship statics (GM)."""

import math

import numpy as np
import pytest
import warp as wp

import ocean_warp as ow
from ocean_warp.kernels.hull_forces import WaterModel, _submerged_area, triangle_wrench
from ocean_warp.kernels.spatial import vec6
from ocean_warp.kernels.point_buoyancy import circle_segment_area
from tests.hull_setups import calm_ocean, quaternion_about, random_rotations, rotation_matrix

RHO, G = 1025.0, 9.81


def static_wrenches(device, boat_types, positions, orientations, *, type_of_boat=None):
    """The water's wrench on boats held at the given poses in still water (no drag)."""
    count = len(positions)
    fleet = ow.Fleet(boat_types, types=type_of_boat if type_of_boat is not None else [0] * count, device=device)
    fleet.reset(position=positions, orientation=orientations)
    config = ow.SimulatorConfig(hydrodynamics=ow.HydrodynamicsConfig().without_drag())
    simulator = ow.Simulator(calm_ocean(device), fleet, config)
    simulator.compute_hull_wrenches()
    return fleet.forces.hydro_wrench.numpy().astype(np.float64)


def random_box(rng):
    """A box stable upright: beam wide enough for GM > 0 at its draft."""
    length, beam = rng.uniform(2.0, 6.0), rng.uniform(1.0, 2.5)
    height = rng.uniform(0.6, 1.2) * beam * 0.5
    draft = rng.uniform(0.3, 0.5) * height
    return length, beam, height, draft


def test_box_settles_at_archimedes_draft(device, rng):
    boxes = [random_box(rng) for _ in range(3)]
    types = []
    for length, beam, height, draft in boxes:
        mass = RHO * length * beam * draft
        stiffness = RHO * G * length * beam
        critical = 2 * math.sqrt(stiffness * mass)
        types.append(ow.BoatType(hull=ow.Hull.box(length, beam, height), mass=mass,
                                 linear_damping=[0, 0, critical, 0.5 * critical, 0.5 * critical, 0]))
    fleet = ow.Fleet(types, types=[0, 1, 2], device=device)
    start = [[0.0, 20.0 * i, 0.5 * h - d + rng.uniform(-0.2, 0.2) * d] for i, (_, _, h, d) in enumerate(boxes)]
    fleet.reset(position=start, orientation=random_rotations(rng, 3, math.radians(3)))
    simulator = ow.Simulator(calm_ocean(device, tile_size=128.0), fleet, ow.SimulatorConfig(dt=0.02, substeps=4))
    for _ in range(1500):
        simulator.step()
    state = fleet.numpy()
    for i, (_, _, height, draft) in enumerate(boxes):
        settled_draft = 0.5 * height - state["position"][i, 2]
        assert settled_draft == pytest.approx(draft, rel=0.005)
    assert np.all(state["status"] == 0)


@pytest.mark.parametrize("axis", ["roll", "pitch"])
def test_box_restoring_moment_is_rho_g_volume_gm_sin_angle(device, rng, axis):
    length, beam, height, draft = random_box(rng)
    mass = RHO * length * beam * draft
    boat = ow.BoatType(hull=ow.Hull.box(length, beam, height, subdivisions=1), mass=mass)
    # Small enough that the wall-sided box keeps its bottom under and its deck above water.
    half_width = 0.5 * (beam if axis == "roll" else length)
    largest = min(math.radians(4), 0.5 * math.atan(min(draft, height - draft) / half_width))
    angles = rng.uniform(0.25, 1.0, size=4) * largest * rng.choice([-1, 1], size=4)
    rotation_axis = [1.0, 0.0, 0.0] if axis == "roll" else [0.0, 1.0, 0.0]
    orientations = np.array([quaternion_about(rotation_axis, a) for a in angles])
    # Turn about the centre of the waterplane, which stays on the surface: body point (0, 0, draft - h/2).
    waterplane_centre = np.array([0.0, 0.0, draft - 0.5 * height])
    positions = np.array([-rotation_matrix(q) @ waterplane_centre for q in orientations])
    wrenches = static_wrenches(device, boat, positions, orientations)

    volume = length * beam * draft
    metacentric_radius = (beam**2 if axis == "roll" else length**2) / (12 * draft)
    gm = 0.5 * draft + metacentric_radius - 0.5 * height  # KB + BM - KG, centre of mass at the box's centre
    component = 3 if axis == "roll" else 4
    # A wall-sided hull, exactly at any angle that keeps its sides wall-sided: GZ = sin(phi) (GM + BM/2 tan^2(phi)).
    righting_arm = np.sin(angles) * (gm + 0.5 * metacentric_radius * np.tan(angles) ** 2)
    np.testing.assert_allclose(wrenches[:, component], -RHO * G * volume * righting_arm, rtol=1e-3)
    # And the force is rho g V straight up: world z in the body frame.
    up_in_body = np.array([rotation_matrix(q).T @ [0.0, 0.0, 1.0] for q in orientations])
    np.testing.assert_allclose(wrenches[:, :3], RHO * G * volume * up_in_body, rtol=0, atol=1e-4 * RHO * G * volume)


def test_half_submerged_sphere_force_converges_to_archimedes(device, rng):
    radius = float(rng.uniform(0.3, 3.0))
    expected = RHO * G * 2.0 / 3.0 * math.pi * radius**3
    orientation = random_rotations(rng, 1, math.pi)
    errors = []
    for subdivisions in (2, 3, 4, 5):
        boat = ow.BoatType.floating_solid(ow.Hull.sphere(radius, subdivisions=subdivisions))
        wrench = static_wrenches(device, boat, [[0.0, 0.0, 0.0]], orientation)[0]
        up = rotation_matrix(orientation[0]).T @ np.array([0.0, 0.0, 1.0])  # world z in the body frame
        errors.append(abs(wrench[:3] @ up - expected) / expected)
        assert np.linalg.norm(np.cross(wrench[:3], up)) < 1e-4 * expected, "buoyancy must point up"
        if subdivisions >= 3:
            assert errors[-1] < 0.01
    assert all(later < earlier for earlier, later in zip(errors, errors[1:])), errors


def test_fully_submerged_dry_and_capsized_bodies(device, rng):
    centred = ow.Hull.ellipsoid(*rng.uniform(0.4, 1.5, size=3), subdivisions=2)
    # Off the origin, so that the moment of the buoyancy about it is not zero.
    hull = ow.Hull(centred.vertices + rng.uniform(-0.5, 0.5, size=3), centred.triangles)
    boat = ow.BoatType.floating_solid(hull)
    orientations = random_rotations(rng, 3, math.pi)
    depth = rng.uniform(3.0, 10.0)
    positions = [[0.0, 0.0, -depth], [0.0, 10.0, depth], [0.0, 20.0, 0.0]]
    wrenches = static_wrenches(device, boat, positions, orientations)

    up_submerged = rotation_matrix(orientations[0]).T @ np.array([0.0, 0.0, 1.0])
    buoyancy = RHO * G * hull.volume * up_submerged
    np.testing.assert_allclose(wrenches[0, :3], buoyancy, rtol=0, atol=1e-4 * np.linalg.norm(buoyancy))
    # Acting at the centre of volume: the moment about the origin is r_B x F.
    np.testing.assert_allclose(wrenches[0, 3:], np.cross(hull.center_of_volume, buoyancy), rtol=0,
                               atol=1e-4 * np.linalg.norm(buoyancy) * hull.length)
    np.testing.assert_array_equal(wrenches[1], np.zeros(6))  # in the air

    # Turned any way with its centre on the surface: the centrally symmetric mesh is cut into halves
    # of equal volume, so the force is half the buoyancy, straight up.
    centre = rotation_matrix(orientations[2]) @ hull.center_of_volume
    half = static_wrenches(device, boat, [[0.0, 0.0, 0.0] - centre], orientations[2:])[0]
    up_half = rotation_matrix(orientations[2]).T @ np.array([0.0, 0.0, 1.0])
    np.testing.assert_allclose(half[:3], 0.5 * RHO * G * hull.volume * up_half, rtol=0,
                               atol=1e-4 * RHO * G * hull.volume)
    # Upside down and half in: the same.
    capsized = static_wrenches(device, boat, [-hull.center_of_volume * [1, -1, -1]],
                               [quaternion_about([1, 0, 0], math.pi)])[0]
    assert capsized[2] == pytest.approx(-0.5 * RHO * G * hull.volume, rel=1e-4)


def test_waterline_through_vertices_gives_finite_forces(device):
    length, beam, height = 2.0, 1.0, 0.5
    boat = ow.BoatType(hull=ow.Hull.box(length, beam, height), mass=200.0)
    tiny = 1e-7
    positions = [[0.0, 0.0, 0.5 * height], [0.0, 5.0, 0.5 * height - tiny], [0.0, 10.0, 0.0], [0.0, 15.0, 0.0]]
    diagonal = quaternion_about([1.0, 0.0, 0.0], math.atan2(height, beam))  # a bottom edge exactly at the surface
    orientations = [[0, 0, 0, 1], [0, 0, 0, 1], [0, 0, 0, 1], diagonal]
    wrenches = static_wrenches(device, boat, positions, orientations)
    np.testing.assert_array_equal(wrenches[0], np.zeros(6))  # bottom exactly on the surface: depth 0 is dry
    assert 0.0 <= wrenches[1, 2] < RHO * G * length * beam * 10 * tiny
    assert wrenches[2, 2] == pytest.approx(0.5 * RHO * G * length * beam * height, rel=1e-5)
    # Turned onto a bottom edge with its centre on the surface: half the volume, straight up.
    up_diagonal = rotation_matrix(diagonal).T @ np.array([0.0, 0.0, 1.0])
    np.testing.assert_allclose(wrenches[3, :3], 0.5 * RHO * G * length * beam * height * up_diagonal, rtol=0,
                               atol=1e-5 * RHO * G * length * beam * height)


@wp.kernel
def _degenerate_triangle_wrenches(depths: wp.array(dtype=wp.vec3), water: WaterModel, out: wp.array(dtype=vec6)):
    i = wp.tid()
    d = depths[i]
    a = wp.vec3(0.3, -0.2, 0.1)
    b = wp.vec3(1.3, 0.8, 0.6)
    out[i] = triangle_wrench(a, b, 0.5 * (a + b), wp.vec4(d[0], 0.1, 0.0, 0.0), wp.vec4(d[1], 0.0, 0.2, 0.0),
                             wp.vec4(d[2], 0.0, 0.0, -0.1), wp.vec3(1.0, -0.5, 0.3), wp.vec3(0.2, 0.1, -0.4), 0.003,
                             water)


def test_degenerate_triangle_carries_no_force(device, rng):
    from ocean_warp.simulator import _water_model

    depths = rng.uniform(-1.0, 1.0, size=(64, 3))
    depths[:8] = 0.0
    out = wp.zeros(64, dtype=vec6, device=device)
    wp.launch(_degenerate_triangle_wrenches, dim=64, device=device,
              inputs=[wp.array(depths, dtype=wp.vec3, device=device), _water_model(ow.HydrodynamicsConfig(), ow.WaterConfig(), 0.01)],
              outputs=[out])
    result = out.numpy()
    assert np.all(np.isfinite(result))
    np.testing.assert_allclose(result, 0.0, atol=1e-3)  # collinear corners: no area, no force


@wp.kernel
def _submerged_areas(corners: wp.array(dtype=wp.vec3), depths: wp.array(dtype=wp.vec3), out: wp.array(dtype=float)):
    i = wp.tid()
    d = depths[i]
    out[i] = _submerged_area(corners[3 * i], corners[3 * i + 1], corners[3 * i + 2], d[0], d[1], d[2])


def test_submerged_area_matches_polygon_clipping(device, rng):
    from tests.reference_hull import clip_submerged

    count = 200
    corners = rng.uniform(-2, 2, size=(count, 3, 3))
    depths = rng.uniform(-1, 1, size=(count, 3))
    out = wp.zeros(count, dtype=float, device=device)
    wp.launch(_submerged_areas, dim=count, device=device,
              inputs=[wp.array(corners.reshape(-1, 3), dtype=wp.vec3, device=device),
                      wp.array(depths, dtype=wp.vec3, device=device)], outputs=[out])
    for i in range(count):
        points, _, _ = clip_submerged(corners[i], depths[i], np.zeros((3, 3)))
        area = sum(0.5 * np.linalg.norm(np.cross(points[k] - points[0], points[k + 1] - points[0]))
                   for k in range(1, len(points) - 1))
        assert out.numpy()[i] == pytest.approx(area, rel=1e-4, abs=1e-6)


@wp.kernel
def _segment_areas(depths: wp.array(dtype=float), radius: float, out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = circle_segment_area(radius, depths[i])


def test_circle_segment_area_of_the_point_buoyancy(device, rng):
    radius = float(rng.uniform(0.1, 1.0))
    depths = np.concatenate([rng.uniform(0, radius, 20), [0.0, radius, -0.1, 2 * radius]])
    out = wp.zeros(len(depths), dtype=float, device=device)
    wp.launch(_segment_areas, dim=len(depths), device=device,
              inputs=[wp.array(depths, dtype=float, device=device), radius], outputs=[out])
    # The part of the circle within `depth` of its top, integrated numerically (clamped to [0, R]) on a grid
    # that starts at the cut: a grid over the whole diameter cut between two nodes errs by about a chord
    # times the spacing, 1e-3 of a shallow segment's area (seed 17009150335705324369)
    for depth, area in zip(depths, out.numpy()):
        h = min(max(depth, 0.0), radius)
        z = np.linspace(radius - h, radius, 200001)
        expected = np.trapezoid(2 * np.sqrt(np.clip(radius**2 - z**2, 0, None)), z)
        assert area == pytest.approx(expected, rel=1e-3, abs=1e-6)
