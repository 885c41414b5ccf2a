"""The WAM-V floats where two horizontal cylinders carrying its 180 kg float, by hand and by its mesh."""

import numpy as np
import pytest
from scipy.optimize import brentq

from ocean_warp.wamv import WamvConfig, wamv_hull_mesh

from .helpers import run, simulator

DENSITY = 1025.0  # the default sea water [kg/m^3]


def hand_draft(mass, radius, length):
    """Draft [m] of two horizontal cylinders of ``radius`` and ``length`` [m] carrying ``mass`` [kg]: each
    displaces a circular segment of area m / (2 rho L)."""
    area = mass / (2.0 * DENSITY * length)

    def segment(h):
        return radius**2 * np.arccos((radius - h) / radius) - (radius - h) * np.sqrt(2.0 * radius * h - h * h) - area

    return brentq(segment, 0.0, 2.0 * radius)


@pytest.mark.parametrize("profile", ["vrx", "physics"])
def test_draft_at_rest_matches_two_cylinders(device, profile):
    """Dropped from 6.5 cm above its rest, the boat settles with the pontoons' axes R - draft above still water."""
    config = WamvConfig()
    draft = hand_draft(config.mass, config.pontoon_radius, config.pontoon_length)
    sim = simulator(1, device, profile=profile)
    sim.reset(position=(0.0, 0.0, 0.2))
    state = run(sim, 12.0)
    height = state["position"][0, 2]
    assert height == pytest.approx(config.pontoon_radius - draft, abs=3e-3)
    assert np.abs(state["velocity"][0]).max() < 0.05  # VRX damps pitch lightly (mQ 100 N m s on 393 kg m^2)
    assert sim.state.status.numpy()[0] == 0


def polygon_area_below(points, level):
    """Area of the closed polygon ``points`` (K, 2) (y, z) below z = ``level`` (clipped by hand, shoelace)."""
    kept = []
    for a, b in zip(points, np.roll(points, -1, axis=0)):
        if a[1] <= level:
            kept.append(a)
        if (a[1] - level) * (b[1] - level) < 0.0:
            kept.append(a + (level - a[1]) / (b[1] - a[1]) * (b - a))
    y, z = np.asarray(kept).T
    return 0.5 * abs(np.dot(y, np.roll(z, -1)) - np.dot(z, np.roll(y, -1)))


def test_mesh_displaces_the_mass_at_the_rest_height(device):
    """The pontoons' 16-sided sections (area of the round one, a vertex at the keel) cut at the simulated
    waterline hold the boat's mass of water (within 1 %)."""
    config = WamvConfig()
    sim = simulator(1, device)
    sim.reset(position=(0.0, 0.0, 0.2))
    height = float(run(sim, 12.0)["position"][0, 2])
    n = config.pontoon_sides
    circumradius = config.pontoon_radius * np.sqrt(2.0 * np.pi / (n * np.sin(2.0 * np.pi / n)))
    angles = -0.5 * np.pi + 2.0 * np.pi * np.arange(n) / n
    section = circumradius * np.column_stack([np.cos(angles), np.sin(angles)])
    assert polygon_area_below(section, 1.0) == pytest.approx(np.pi * config.pontoon_radius**2, rel=1e-9)
    volume = 2.0 * config.pontoon_length * polygon_area_below(section, -height)
    assert DENSITY * volume == pytest.approx(config.mass, rel=0.01)
    assert wamv_hull_mesh(config).volume == pytest.approx(2.0 * config.pontoon_length * np.pi
                                                          * config.pontoon_radius**2, rel=1e-9)
