"""The E-Boat preset: composite mass properties against the data sheet, the hull, floating at rest."""

import math

import numpy as np
import pytest

import ocean_warp as ow
from ocean_warp.eboat import EBoat, EBoatConfig, EBoatSimulator
from ocean_warp.eboat.mass_properties import eboat_mass_properties
from ocean_warp.eboat.sheet import LINKS, Version
from ocean_warp.frames import roll_pitch_yaw

# The sheet's link table, typed in again: mass [kg] of every link of eboat4 (V-B, V-C).
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


def test_composite_inertia_is_the_parallel_axis_sum():
    composite = eboat_mass_properties(Version.C)
    masses = np.array([link.mass for link in LINKS])
    positions = np.array([link.center_of_mass for link in LINKS])
    center = (masses[:, None] * positions).sum(axis=0) / masses.sum()
    np.testing.assert_allclose(composite.center_of_mass, center, atol=1e-12)
    # Each link as its own inertia plus, in the test's own words, m (|d|^2 1 - d d^T) with d its offset.
    expected = np.zeros((3, 3))
    from ocean_warp.eboat.mass_properties import link_inertia

    for link, mass, position in zip(LINKS, masses, positions):
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
    # The mast alone, a 12.5 kg cylinder 3.55 m long of radius 0.05 m: m (3 r^2 + L^2) / 12 about its middle.
    mast = next(link for link in LINKS if link.name == "mast")
    assert link_inertia(mast)[0, 0] == pytest.approx(12.5 * (3 * 0.05**2 + 3.55**2) / 12)


def test_boat_type_carries_the_composite_and_the_sheet_hydrodynamics():
    eboat = EBoat()
    composite = eboat_mass_properties(Version.C)
    assert eboat.boat_type.mass == pytest.approx(composite.mass)
    np.testing.assert_allclose(eboat.boat_type.inertia, composite.inertia)
    np.testing.assert_allclose(np.diag(eboat.boat_type.added_mass), [0, 124, 148, 0, 0, 0])  # sheet: X, Y, Z added mass
    points = EBoat(EBoatConfig(version="V-A", hydrostatics="points")).boat_type
    np.testing.assert_allclose(points.linear_damping, [5, 8, 50, 5, 5, 40])  # sheet, V-A column
    np.testing.assert_allclose(points.quadratic_damping[:2], [7.4, 160])
    assert points.astern_surge_factor == 1.3


def test_hull_is_a_sailboat_hull_within_the_sheets_box():
    hull = EBoat().hull
    extents = np.ptp(hull.vertices, axis=0)
    assert extents[0] == pytest.approx(2.5, abs=0.01)  # length overall
    assert extents[1] <= 1.0 + 1e-9 and extents[2] <= 0.63  # within the collision box 2.7 x 1.0 x 0.63 m
    assert 1500 <= hull.triangle_count <= 2500
    # Not a box: a pointed bow, and less volume than the bounding box.
    bow = hull.vertices[hull.vertices[:, 0] > hull.vertices[:, 0].max() - 0.05]
    assert np.abs(bow[:, 1]).max() < 0.1
    assert hull.volume < 0.7 * extents.prod()


@pytest.mark.parametrize("hydrostatics", ["mesh", "points"])
def test_floats_upright_at_a_sensible_draft(device, hydrostatics):
    sim = EBoatSimulator(2, eboat=EBoat(EBoatConfig(hydrostatics=hydrostatics)), wind=ow.WindConfig(speed=0.0),
                         device=device)
    sim.reset(position=[[0.0, 0.0, 0.1], [10.0, 0.0, -0.1]])
    for _ in range(400):
        sim.step()
    state = sim.fleet.numpy()
    roll, pitch, _ = roll_pitch_yaw(state["orientation"]).T
    assert np.all(np.abs(np.degrees(roll)) < 1.0) and np.all(np.abs(np.degrees(pitch)) < 2.0)
    # The source's base frame sits at the waterline: the hull floats within a few centimetres of it (the
    # original four points, set at that height, sink 9 cm to carry the boat).
    assert np.all(np.abs(state["position"][:, 2]) < (0.08 if hydrostatics == "mesh" else 0.12))
    assert np.all(state["status"] == 0)


def test_bad_eboat_config_is_refused():
    with pytest.raises(ValueError, match="EBoatConfig.version must be one of 'V-A', 'V-B', 'V-C'"):
        EBoatConfig(version="V-D")
    with pytest.raises(ValueError, match="EBoatConfig.hydrostatics must be one of 'mesh', 'points'"):
        EBoatConfig(hydrostatics="strips")
    with pytest.raises(ValueError, match="EBoatConfig.water_density must be > 0"):
        EBoatConfig(water_density=-1.0)
    assert math.isfinite(EBoat().rest_height())
