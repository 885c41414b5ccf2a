"""The vrx profile's lumped damping: the steady speed under constant thrust solves T = Xu u + Xuu u |u|."""

import numpy as np
import pytest

from .helpers import run, simulator, vrx_thrust

X_U, X_UU = 51.3, 72.4  # VRX's wamv_gazebo_dynamics_plugin.xacro [N s/m, N s^2/m^2]


@pytest.mark.parametrize("command", [0.4, 1.0])
def test_steady_speed_under_constant_thrust(device, command):
    thrust = 2.0 * float(vrx_thrust(command))
    speed = (-X_U + np.sqrt(X_U**2 + 4.0 * X_UU * thrust)) / (2.0 * X_UU)
    sim = simulator(1, device)
    sim.reset(position=(0.0, 0.0, 0.135))
    sim.control.thrust_command.fill_(command)
    velocity = run(sim, 40.0)["velocity"][0]
    assert velocity[0] == pytest.approx(speed, rel=0.01)
    assert abs(velocity[1]) < 1e-3 and abs(velocity[5]) < 1e-3
