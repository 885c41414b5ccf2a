"""The WAM-V's thrusters: VRX's curve, the cut out of the water, the turning sense, azimuth and actions."""

import numpy as np
import pytest
import warp as wp

from ocean_warp.fleet import BoatStatus
from ocean_warp.torch_streams import ordered_with_torch

from .helpers import run, simulator, vrx_thrust

REST_HEIGHT = 0.135  # about where the pontoons' axes float [m]


def test_thrust_follows_vrx_curve(device):
    """41 boats, commands -1.2 .. 1.2 (clamped): each boat's thrust is VRX's mapping of its command."""
    commands = np.linspace(-1.2, 1.2, 41).astype(np.float32)
    commands[20] = 0.005  # inside the dead band
    sim = simulator(len(commands), device)
    sim.reset(position=(0.0, 0.0, REST_HEIGHT))
    sim.control.thrust_command.assign(np.column_stack([commands, commands]))
    sim.step()
    thrust = sim.state.thrust.numpy()
    expected = vrx_thrust(commands)
    np.testing.assert_allclose(thrust[:, 0], expected, rtol=1e-4, atol=1e-3)
    np.testing.assert_allclose(thrust[:, 1], expected, rtol=1e-4, atol=1e-3)
    assert thrust[-1, 0] == pytest.approx(242.67, abs=0.01) and thrust[0, 0] == pytest.approx(-100.0)


def test_no_thrust_out_of_the_water(device):
    """A boat held 1 m up (propellers 0.8 m above the water) gets no thrust; one afloat gets VRX's."""
    sim = simulator(2, device)
    sim.reset(position=[(0.0, 0.0, 1.0), (10.0, 0.0, REST_HEIGHT)])
    sim.control.thrust_command.fill_(1.0)
    sim.step()
    thrust = sim.state.thrust.numpy()
    np.testing.assert_array_equal(thrust[0], [0.0, 0.0])
    np.testing.assert_allclose(thrust[1], vrx_thrust([1.0, 1.0]), rtol=1e-4)


@pytest.mark.parametrize("profile", ["vrx", "physics"])
def test_left_thruster_alone_turns_to_starboard(device, profile):
    """FLU: the left (port) thruster ahead alone yaws the boat clockwise (r < 0); the right alone, r > 0."""
    sim = simulator(2, device, profile=profile)
    sim.reset(position=[(0.0, 0.0, REST_HEIGHT), (20.0, 0.0, REST_HEIGHT)])
    sim.control.thrust_command.assign(np.array([[0.8, 0.0], [0.0, 0.8]], dtype=np.float32))
    velocity = run(sim, 3.0)["velocity"]
    assert velocity[0, 5] < -0.05 and velocity[1, 5] > 0.05
    assert velocity[0, 0] > 0.1 and velocity[1, 0] > 0.1


def test_azimuth_angle_is_clamped_and_turns_to_port(device):
    """Azimuth thrusters at +0.3 rad (both ahead) turn the boat to port; 3 rad is held at the pi/2 limit."""
    sim = simulator(2, device, thrusters="azimuth")
    sim.reset(position=[(0.0, 0.0, REST_HEIGHT), (20.0, 0.0, REST_HEIGHT)])
    sim.control.thrust_command.fill_(0.8)
    sim.control.angle_command.assign(np.array([[0.3, 0.3], [3.0, -3.0]], dtype=np.float32))
    velocity = run(sim, 3.0)["velocity"]
    angles = sim.state.thruster_angle.numpy()
    np.testing.assert_allclose(angles, [[0.3, 0.3], [np.pi / 2, -np.pi / 2]], rtol=1e-6)
    assert velocity[0, 5] > 0.05


def test_actions_scale_to_commands_and_nan_flags_the_boat(device):
    """launch_actions: thrust = clamp(action), angle = action x limit, a column switched off commands 0; NaN flags
    BAD_INPUT, others sail on."""
    sim = simulator(3, device, thrusters="azimuth", max_thruster_angle=0.5)
    sim.reset(position=(0.0, 0.0, REST_HEIGHT))
    actions = np.array([[0.5, -2.0, 0.4, -1.0], [0.0, 1.0, 0.0, 0.0], [np.nan, 0.0, 0.0, 0.0]], dtype=np.float32)
    enabled = wp.array(np.array([1, 0, 1, 1], dtype=np.int32), device=device)
    with ordered_with_torch(sim.device):
        sim.launch_actions(wp.array(actions, dtype=float, device=device), enabled)
    command = sim.control.thrust_command.numpy()
    np.testing.assert_allclose(command[0], [0.5, 0.0])  # the right thruster switched off
    np.testing.assert_allclose(sim.control.angle_command.numpy()[0], [0.2, -0.5], rtol=1e-6)
    np.testing.assert_array_equal(command[1], [0.0, 0.0])
    with ordered_with_torch(sim.device):
        sim.launch_actions(wp.array(actions, dtype=float, device=device))
    np.testing.assert_allclose(sim.control.thrust_command.numpy()[:2], [[0.5, -1.0], [0.0, 1.0]])
    sim.step()
    status = sim.state.status.numpy()
    assert status[2] & BoatStatus.BAD_INPUT and status[0] == 0 and status[1] == 0
    with pytest.raises(ValueError, match=r"actions must be \(3, 4\)"):
        sim.launch_actions(wp.zeros((3, 2), dtype=float, device=device))
