"""The WAM-V as a vessel: protocol, actions, parts, capsule, config errors and its hydrodynamic database."""

import math

import numpy as np
import pytest

from ocean_warp.vessel import Vessel, VesselSimulator, require_actions, require_vessel
from ocean_warp.wamv import (Wamv, WamvConfig, WamvSimulatorConfig, wamv_boat_type, wamv_hull_mesh,
                             wamv_hydro_database)


def test_wamv_is_a_vessel_and_builds_a_vessel_simulator(device):
    vessel = Wamv()
    assert isinstance(vessel, Vessel) and require_vessel("test", vessel) is vessel
    assert vessel.name == "WAM-V"
    assert [a.name for a in vessel.actions] == ["left_thrust", "right_thrust"]
    sim = vessel.simulator(2, device=device)
    assert isinstance(sim, VesselSimulator) and sim.count == 2
    azimuth = Wamv(WamvSimulatorConfig(boat=WamvConfig(thrusters="azimuth")))
    assert require_actions("test", azimuth, ["left_angle", "right_thrust"]) == (2, 1)
    with pytest.raises(ValueError, match="has no action 'left_angle'"):
        require_actions("test", vessel, ["left_angle"])


def test_thruster_parts_turn_on_their_pivots():
    parts = {part.name: part for part in Wamv().parts()}
    assert {"pontoons", "frame", "left_thruster", "right_thruster"} <= set(parts)
    for column, side in enumerate(("left", "right")):
        part = parts[f"{side}_thruster"]
        assert (part.joint, part.joint_column) == ("thruster_angle", column)
        assert part.pivot[1] == pytest.approx((1.027135, -1.027135)[column])
    assert parts["pontoons"].joint is None


def test_capsule_holds_both_pontoons():
    """Every pontoon vertex lies within the capsule (distance to its axis segment <= its radius)."""
    shape = Wamv().collision_shape()
    stern, bow = np.array(shape.stern), np.array(shape.bow)
    points = wamv_hull_mesh().vertices
    t = np.clip((points - stern) @ (bow - stern) / np.dot(bow - stern, bow - stern), 0.0, 1.0)
    distance = np.linalg.norm(points - (stern + t[:, None] * (bow - stern)), axis=1)
    assert distance.max() <= shape.radius + 1e-9
    assert shape.radius == pytest.approx(1.03 + 0.213, abs=0.005)


@pytest.mark.parametrize("fields, named", [
    (dict(max_forward_thrust=math.nan), "WamvConfig.max_forward_thrust"),
    (dict(max_reverse_thrust=-5.0), "WamvConfig.max_reverse_thrust"),
    (dict(mass=-180.0), "WamvConfig.mass"),
    (dict(profile="gazebo"), "WamvConfig.profile"),
    (dict(thrusters="x"), "WamvConfig.thrusters"),
    (dict(inertia=(120.0, 0.0, 446.0)), "WamvConfig.inertia"),
    (dict(pontoon_spacing=0.3), "WamvConfig.pontoon_spacing"),
])
def test_bad_config_is_one_line_naming_it(fields, named):
    with pytest.raises(ValueError) as error:
        WamvConfig(**fields)
    message = str(error.value)
    assert message.startswith(named) and "\n" not in message


def test_database_matches_the_hull_and_gives_the_added_mass():
    """The shipped database is the default mesh's; a mesh of other sides is refused; the physics boat type takes
    its infinite-frequency added mass, the vrx one VRX's (zero) with VRX's damping."""
    hull = wamv_hull_mesh()
    database = wamv_hydro_database(hull)
    assert database.added_mass_infinite[2, 2] > 0.0
    with pytest.raises(ValueError, match="hydrodynamic database"):
        wamv_hydro_database(wamv_hull_mesh(WamvConfig(pontoon_sides=12)))
    physics = wamv_boat_type(WamvConfig())
    np.testing.assert_allclose(physics.added_mass, database.added_mass_infinite)
    vrx = wamv_boat_type(WamvConfig(profile="vrx"))
    np.testing.assert_array_equal(vrx.added_mass, np.zeros((6, 6)))
    np.testing.assert_array_equal(vrx.linear_damping, [51.3, 40.0, 500.0, 100.0, 100.0, 400.0])
    np.testing.assert_array_equal(vrx.quadratic_damping, [72.4, 0.0, 0.0, 0.0, 0.0, 0.0])
