"""The physics profile's wave-making resistance: the pontoon's offsets against its 16-sided section cut by hand
at the waterline that holds the boat's mass, the table's scale against the boat's own figures, and the
simulator's steady speed against the thrust that friction and the table together take."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from ocean_warp.sensors import SensorConfig
from ocean_warp.wamv import WamvConfig, WamvSimulator, WamvSimulatorConfig, wamv_boat_type
from ocean_warp.wamv.wave_resistance import pontoon_offsets, wamv_wave_resistance

from .helpers import run, vrx_thrust

DENSITY, G = 1025.0, 9.81


def section_half_width(config):
    """Half-width [m] of the pontoon's regular polygon (the round section's area, a vertex at the keel) at a
    height z [m] above its axis: the polygon's starboard chain, keel to top, is monotone in z."""
    n = config.pontoon_sides
    radius = config.pontoon_radius * math.sqrt(2.0 * math.pi / (n * math.sin(2.0 * math.pi / n)))
    angles = -0.5 * math.pi + 2.0 * math.pi * np.arange(n // 2 + 1) / n
    return lambda z: np.interp(z, radius * np.sin(angles), radius * np.cos(angles)), radius


def test_pontoon_offsets_are_its_section_at_the_floating_waterline():
    config = WamvConfig()
    width, radius = section_half_width(config)

    def displaced(level):  # both pontoons below z = level [m^3]
        z = np.linspace(-radius, level, 20001)
        return 2.0 * config.pontoon_length * 2.0 * np.trapezoid(width(z), z)

    waterline = brentq(lambda level: displaced(level) - config.mass / DENSITY, -radius, 0.0, xtol=1e-10)
    offsets = pontoon_offsets(config)
    assert offsets.depths[-1] == 0.0
    assert offsets.depths[0] == pytest.approx(-radius - waterline, abs=1e-5)
    half = 0.5 * config.pontoon_length
    assert offsets.stations[[0, 1, -2, -1]] == pytest.approx(config.pontoon_center_x + np.array([-half, -half,
                                                                                                half, half]))
    middle = offsets.half_breadth[len(offsets.stations) // 2]
    np.testing.assert_allclose(middle, width(offsets.depths + waterline), atol=2e-5)
    assert not offsets.half_breadth[0].any() and not offsets.half_breadth[-1].any()
    assert 2.0 * offsets.volume == pytest.approx(config.mass / DENSITY, rel=2e-3)


def test_table_scales_with_the_boats_displacement_and_length():
    config = WamvConfig()
    table = wamv_wave_resistance(config)
    assert table.waterline_length == pytest.approx(config.pontoon_length)
    assert table.displaced_volume == pytest.approx(config.mass / DENSITY, rel=1e-4)
    assert table.center[:2] == pytest.approx((config.pontoon_center_x, 0.0), abs=1e-9)
    assert table.upright[0] == 0.0 and min(table.upright[1:]) > 0.0
    assert wamv_boat_type(config).residuary == table
    assert wamv_boat_type(WamvConfig(wave_resistance=False)).residuary is None
    assert wamv_boat_type(WamvConfig(profile="vrx")).residuary is None


def steady(config, commands, device):
    sim = WamvSimulator(WamvSimulatorConfig(boat=config, sensors=SensorConfig.noise_free()), len(commands),
                        device=device)
    sim.reset(position=(0.0, 0.0, sim.rest_height()))
    sim.control.thrust_command.assign(np.repeat(np.asarray(commands, dtype=np.float32)[:, None], 2, axis=1))
    return run(sim, 50.0)["velocity"][:, 0]


def test_steady_speed_takes_friction_plus_the_table(device):
    """At command 0.4 the boat settles where both thrusters' 91 N (VRX's curve) meet the friction the same
    boat without wave resistance has at that speed (interpolated between its own steady runs) plus
    rho g V r(Fn) of the table."""
    command = 0.4
    table = wamv_wave_resistance()
    speed = steady(WamvConfig(), [command], device)[0]
    commands = np.array([0.24, 0.27, 0.30, 0.33])
    without = steady(WamvConfig(wave_resistance=False), commands, device)
    assert without[0] < speed < without[-1]
    friction = np.interp(speed, without, 2.0 * vrx_thrust(commands))
    froude = speed / math.sqrt(G * table.waterline_length)
    wave = DENSITY * G * table.displaced_volume * np.interp(froude, 0.05 * np.arange(16), table.upright)
    assert 2.0 * vrx_thrust(command) == pytest.approx(friction + wave, rel=0.01)
