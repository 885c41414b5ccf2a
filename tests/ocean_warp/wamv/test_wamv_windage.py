"""The wind on the WAM-V against VRX's law worked out by hand: X = c_x w_x |w_x|, Y = c_y w_y |w_y|,
N = -2 c_z w_x w_y on the apparent wind in the body frame."""

import math

import numpy as np
import warp as wp

from ocean_warp.kernels.lumped_windage import lumped_windage
from ocean_warp.kernels.spatial import vec6
from ocean_warp.ocean_config import OceanConfig
from ocean_warp.wamv import WamvConfig, WamvSimulator, WamvSimulatorConfig
from ocean_warp.wind import WindConfig


def test_windage_wrench_is_vrx_law_on_the_apparent_wind(device, rng):
    n = 6
    coefficients = (0.5, 0.5, 0.33)
    yaw = rng.uniform(-math.pi, math.pi, n)
    wind = np.column_stack([rng.uniform(-8, 8, (n, 2)), np.zeros(n)])
    nu = np.column_stack([rng.uniform(-2, 2, (n, 2)), np.zeros((n, 4))])
    q = np.column_stack([np.zeros(n), np.zeros(n), np.sin(yaw / 2), np.cos(yaw / 2)])
    wrench = wp.zeros(n, dtype=vec6, device=device)
    wp.launch(lumped_windage, dim=n, device=device,
              inputs=[wp.vec3(*coefficients), wp.array(wind, dtype=wp.vec3, device=device),
                      wp.array(q, dtype=wp.quat, device=device), wp.array(nu, dtype=vec6, device=device)],
              outputs=[wrench])
    # by hand: the true wind turned into the yawed frame, less the boat's own velocity
    wx = np.cos(yaw) * wind[:, 0] + np.sin(yaw) * wind[:, 1] - nu[:, 0]
    wy = -np.sin(yaw) * wind[:, 0] + np.cos(yaw) * wind[:, 1] - nu[:, 1]
    expected = np.zeros((n, 6))
    expected[:, 0] = 0.5 * wx * np.abs(wx)
    expected[:, 1] = 0.5 * wy * np.abs(wy)
    expected[:, 5] = -2 * 0.33 * wx * wy
    np.testing.assert_allclose(wrench.numpy(), expected, rtol=1e-5, atol=1e-5)


def test_a_steady_beam_wind_drifts_the_boat_downwind_at_the_damping_balance(device):
    """In still water, a 10 m/s wind toward +y on a boat heading +x: it drifts toward +y until VRX's sway damping
    (40 N s/m, no quadratic term) balances c_y (10 - v)^2: v = root of 40 v = 0.5 (10 - v)^2 (about 1.56 m/s)."""
    still = OceanConfig(significant_wave_height=0.0, tile_size=64.0, resolution=16)  # still: a small grid serves
    config = WamvSimulatorConfig(boat=WamvConfig(profile="vrx"), ocean=still,
                                 wind=WindConfig(speed=10.0, direction=math.pi / 2))
    sim = WamvSimulator(config, 1, device=device)
    sim.reset(position=(0.0, 0.0, sim.rest_height()), heading=0.0)
    for _ in range(int(30.0 / config.dt)):  # the sway time constant, (180 + 0) kg / 40 N s/m, is 4.5 s
        sim.step()
    v = float(sim.state.velocity.numpy()[0, 1])
    expected = np.roots([0.5, -(10.0 + 40.0), 50.0])  # 0.5 v^2 - 50 v + 50 = 0 from 40 v = 0.5 (10 - v)^2
    root = float(min(r for r in expected.real if 0 < r < 10))
    assert abs(v - root) < 0.05 * root, (v, root)
