"""The E-Boat preset: composite mass properties against the data sheet, the hull, floating at rest (the real
boat's figures against the sheet's CAD measurements: ``test_real_eboat``)."""

import math

import numpy as np
import pytest

import ocean_warp as ow
from ocean_warp.eboat import EBoat, EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.eboat.hull_shape import HullShape
from ocean_warp.eboat.mass_properties import eboat_mass_properties
from ocean_warp.eboat.sheet import LINKS, Version
from ocean_warp.eboat.urdf_links import urdf_links
from tests import reference_hull
from tests.hull_setups import assert_afloat_upright, rotation_matrix, settled_heights

# The sheet's link table (the procedural boat's), typed in again: mass [kg] of every link of eboat4 (V-B, V-C).
SHEET_MASSES = {"hull": 83.69, "keel": 40.04, "mast": 12.5, "boom": 2.41, "sail": 2.22, "rudder": 1.60, "deck": 4.66,
                "electric leg": 3.63, "engine base": 0.89, "bow": 1.10, "rack port": 1.73, "rack starboard": 1.73,
                "camera": 2.07}


def test_composite_mass_properties_match_the_link_table():
    composite = eboat_mass_properties(Version.C)
    assert {link.name: link.mass for link in LINKS} == SHEET_MASSES
    assert composite.mass == pytest.approx(sum(SHEET_MASSES.values()), rel=1e-12)
    assert composite.mass == pytest.approx(158.4, rel=0.002)  # the sheet's stated total for eboat4
    assert eboat_mass_properties(Version.A).mass == pytest.approx(154.2, rel=0.002)
    # The sheet's hull link: 83.69 kg at (-0.198, 0, -0.060) in a frame 0.2106 m above the waterline.
    hull = next(link for link in LINKS if link.name == "hull")
    np.testing.assert_allclose(hull.center_of_mass, [-0.198, 0.0, 0.2106 - 0.060])
    assert hull.inertia == (7.794, 42.817, 47.147, 1.267)


@pytest.mark.parametrize("table", ["sheet", "urdf"])
def test_composite_inertia_is_the_parallel_axis_sum(table):
    links = LINKS if table == "sheet" else urdf_links()
    composite = eboat_mass_properties(Version.C, links)
    masses = np.array([link.mass for link in links])
    positions = np.array([link.center_of_mass for link in links])
    center = (masses[:, None] * positions).sum(axis=0) / masses.sum()
    np.testing.assert_allclose(composite.center_of_mass, center, atol=1e-12)
    # Each link as its own inertia plus, in the test's own words, m (|d|^2 1 - d d^T) with d its offset.
    expected = np.zeros((3, 3))
    from ocean_warp.eboat.mass_properties import link_inertia

    for link, mass, position in zip(links, masses, positions):
        d = position - center
        expected += link_inertia(link)
        expected[0, 0] += mass * (d[1] ** 2 + d[2] ** 2)
        expected[1, 1] += mass * (d[0] ** 2 + d[2] ** 2)
        expected[2, 2] += mass * (d[0] ** 2 + d[1] ** 2)
        expected[0, 1] -= mass * d[0] * d[1]
        expected[0, 2] -= mass * d[0] * d[2]
        expected[1, 2] -= mass * d[1] * d[2]
    expected[1, 0], expected[2, 0], expected[2, 1] = expected[0, 1], expected[0, 2], expected[1, 2]
    np.testing.assert_allclose(composite.inertia, expected, rtol=1e-10, atol=1e-10)
    if table == "urdf":  # a URDF link whose chain does not turn keeps the URDF's tensor: the hull link
        np.testing.assert_allclose(link_inertia(links[0]), [[7.79423, -0.000716745, 1.26709],
                                                            [-0.000716745, 42.8173, -0.00040264],
                                                            [1.26709, -0.00040264, 47.1467]])
        return
    # The links' own inertias, from the sheet's figures and shapes, written out here.
    by_name = {link.name: link_inertia(link) for link in LINKS}
    np.testing.assert_allclose(by_name["hull"], [[7.794, 0, 1.267], [0, 42.817, 0], [1.267, 0, 47.147]])
    mast_across = 12.5 * (3 * 0.05**2 + 3.55**2) / 12  # cylinder r 0.05 m, 3.55 m long, about its middle
    np.testing.assert_allclose(by_name["mast"], np.diag([mast_across, mast_across, 12.5 * 0.05**2 / 2]))
    np.testing.assert_allclose(np.diag(by_name["boom"])[1:], [2.41 * 1.8**2 / 12] * 2)  # rod 1.8 m along x
    np.testing.assert_allclose(by_name["rudder"], 1.60 / 12 * np.diag([0.015**2 + 0.608**2, 0.189**2 + 0.608**2,
                                                                         0.189**2 + 0.015**2]))  # box


@pytest.mark.parametrize("hull", ["real", "procedural"])
def test_boat_type_carries_the_composite_and_the_sheet_hydrodynamics(hull):
    eboat = EBoat(EBoatConfig(hull=hull))
    composite = eboat_mass_properties(Version.C, LINKS if hull == "procedural" else eboat.geometry.links)
    assert eboat.boat_type.mass == pytest.approx(composite.mass)
    np.testing.assert_allclose(eboat.boat_type.center_of_mass, composite.center_of_mass)
    np.testing.assert_allclose(eboat.boat_type.inertia, composite.inertia)
    np.testing.assert_allclose(np.diag(eboat.boat_type.added_mass), [0, 124, 148, 0, 0, 0])  # sheet: X, Y, Z
    # Mesh hydrostatics: the hull damps surge, sway and heave; the sheet's roll and pitch terms stay (V-C: 25);
    # the physics profile's keel, rudder and hull damp yaw (no N_r), the seed profile keeps the sheet's 120.
    np.testing.assert_allclose(eboat.boat_type.linear_damping, [0, 0, 0, 25, 25, 0])
    assert eboat.boat_type.seakeeping is None
    if hull == "real":
        # With seakeeping from potential flow: the database's A_inf is the added mass, radiation damps the hull,
        # and the sheet's linear terms, which stood in for that, are gone; so are the linear cross-flow drag terms.
        eboat = EBoat(EBoatConfig(hull=hull, seakeeping=True))
        database = eboat.boat_type.seakeeping
        np.testing.assert_allclose(eboat.boat_type.added_mass, database.added_mass_infinite)
        assert 300.0 < database.added_mass_infinite[2, 2] < 900.0  # heave: a flat bottom's large added mass
        np.testing.assert_allclose(eboat.boat_type.linear_damping, [0, 0, 0, 0, 0, 0])
        assert eboat.hydrodynamics.pressure_drag_linear == 0.0 and eboat.hydrodynamics.suction_linear == 0.0
        assert eboat.hydrodynamics.pressure_drag_quadratic > 0.0
    seed_mesh = EBoat(EBoatConfig(hull=hull, profile="seed", hydrostatics="mesh")).boat_type
    np.testing.assert_allclose(seed_mesh.linear_damping, [0, 0, 0, 25, 25, 120])
    points = EBoat(EBoatConfig(hull=hull, version="V-A", hydrostatics="points")).boat_type
    np.testing.assert_allclose(points.linear_damping, [5, 8, 50, 5, 5, 40])  # sheet, V-A column
    np.testing.assert_allclose(points.quadratic_damping[:2], [7.4, 160])
    assert points.astern_surge_factor == 1.3


def test_procedural_hull_is_a_sailboat_hull_within_the_sheets_box():
    hull = EBoat(EBoatConfig(hull="procedural")).hull
    extents = np.ptp(hull.vertices, axis=0)
    assert extents[0] == pytest.approx(2.5, abs=0.01)  # length overall
    assert extents[1] <= 1.0 + 1e-9 and extents[2] <= 0.63  # within the collision box 2.7 x 1.0 x 0.63 m
    assert 1500 <= hull.triangle_count <= 2500
    # Not a box: a pointed bow, and less volume than the bounding box.
    bow = hull.vertices[hull.vertices[:, 0] > hull.vertices[:, 0].max() - 0.05]
    assert np.abs(bow[:, 1]).max() < 0.1
    assert hull.volume < 0.7 * extents.prod()


def mesh_equilibrium_height(eboat, turn):
    """Height [m] of the body origin at which the numpy reference's buoyancy on the hull, held at the
    orientation ``turn``, carries the boat's weight in still water (bisection), less the buoyancy of what the
    real boat's keel, bulb and rudder displace outside the mesh (under water, straight up)."""
    hydro, water = eboat.hydrodynamics.without_drag(), ow.WaterConfig()
    vertices = eboat.hull.vertices
    weight = (eboat.boat_type.mass - water.density * eboat.geometry.appendage_volume) * water.gravity

    def buoyancy(height):
        depth = -((vertices @ turn.T)[:, 2] + height)
        wrench = reference_hull.hull_wrench(vertices, eboat.hull.triangles, depth, np.zeros_like(vertices), np.zeros(6),
                                            hydro, np.zeros(3), water)
        return (turn @ wrench[:3])[2]

    low, high = -0.3, 0.3
    for _ in range(30):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if buoyancy(middle) > weight else (low, middle)
    return 0.5 * (low + high)


def points_equilibrium_depth(eboat):
    """Depth [m] of the four points when each carries a quarter of the weight: rho g (L/2) S(R, h) = m g / 4,
    with the circle segment S written out here."""
    radius, length = eboat.vrx.hull_radius, eboat.vrx.hull_length
    target = eboat.boat_type.mass / (2.0 * EBoatSimulatorConfig().water.density * length)
    low, high = 0.0, radius
    for _ in range(50):
        h = 0.5 * (low + high)
        segment = radius**2 * math.acos((radius - h) / radius) - (radius - h) * math.sqrt(2 * radius * h - h * h)
        low, high = (low, h) if segment > target else (h, high)
    return 0.5 * (low + high)


@pytest.mark.parametrize("hull", ["real", "procedural"])
def test_rest_height_is_where_the_reference_buoyancy_carries_the_weight(hull):
    eboat = EBoat(EBoatConfig(hull=hull))
    assert eboat.rest_height() == pytest.approx(mesh_equilibrium_height(eboat, np.eye(3)), abs=2e-4)


@pytest.mark.parametrize("hull", ["real", "procedural"])
@pytest.mark.parametrize("hydrostatics", ["mesh", "points"])
def test_floats_upright_at_its_equilibrium_draft(device, hydrostatics, hull):
    eboat = EBoat(EBoatConfig(hydrostatics=hydrostatics, hull=hull))
    sim = EBoatSimulator(EBoatSimulatorConfig(boat=eboat.config, wind=ow.WindConfig(speed=0.0)), 2, device=device)
    sim.reset(position=[[0.0, 0.0, 0.1], [10.0, 0.0, -0.1]])
    height = settled_heights(sim, 500, average_over=100)
    state = sim.fleet.numpy()
    assert_afloat_upright(state)
    turn = rotation_matrix(state["orientation"][0])
    if hydrostatics == "mesh":
        # Archimedes by an independent implementation; the procedural canoe about 5 cm above the source's waterline.
        np.testing.assert_allclose(height, mesh_equilibrium_height(eboat, turn), atol=1e-3)
    else:
        # The points' mean depth (the trim tilts them about x = 0) is the analytic one, to the segment's curvature.
        # They sit at the base frame's height: the real boat's body frame lies 0.094 m above it (sheet).
        points = np.array(eboat.vrx.points) + [0.0, 0.0, -0.094 if hull == "real" else 0.0]
        mean_depth = -(height[0] + (points @ turn.T)[:, 2]).mean()
        assert mean_depth == pytest.approx(points_equilibrium_depth(eboat), abs=1e-3)


def test_bad_eboat_config_is_refused():
    with pytest.raises(ValueError, match="EBoatConfig.version must be one of 'V-A', 'V-B', 'V-C'"):
        EBoatConfig(version="V-D")
    with pytest.raises(ValueError, match="EBoatConfig.hydrostatics must be one of 'mesh', 'points'"):
        EBoatConfig(hydrostatics="strips")
    with pytest.raises(ValueError, match="EBoatConfig.hull_shape shapes the procedural hull"):
        EBoatConfig(hull_shape=HullShape(keel_z=-0.3))
    with pytest.raises(ValueError, match="EBoatConfig.hull_shape must be a HullShape"):
        EBoatConfig(hull_shape="canoe")
    with pytest.raises(ValueError, match="HullShape.bow_x must lie forward of stern_x"):
        HullShape(bow_x=-1.5)
    with pytest.raises(ValueError, match=r"HullShape.widest_at must be in \[0.05, 0.95\]"):
        HullShape(widest_at=1.0)


def test_bad_eboat_resets_are_refused(device):
    sim = EBoatSimulator(None, 3, device=device)
    with pytest.raises(ValueError, match="EBoatSimulator.reset.sheet holds NaN"):
        sim.reset(sheet=[0.2, np.nan, 0.3])
    with pytest.raises(ValueError, match="EBoatSimulator.reset.heading must be one number or 3"):
        sim.reset(heading=[0.1, 0.2])
    with pytest.raises(ValueError, match=r"EBoatSimulator.reset.boats: indices must lie in \[0, 2\]"):
        sim.reset([3])
    with pytest.raises(ValueError, match="EBoatSimulator.reset.wind_speed must be >= 0"):
        sim.reset(wind_speed=-2.0)


@pytest.mark.parametrize("fields", [dict(seakeeping=1), dict(seakeeping=True, hull="procedural"),
                                    dict(seakeeping=True, profile="seed"), dict(seakeeping=True, hydrostatics="points")])
def test_seakeeping_is_the_real_meshed_hulls_and_a_switch(fields):
    with pytest.raises(ValueError, match="EBoatConfig.seakeeping"):
        EBoatConfig(**fields)
