"""A "regular" ocean is one Airy wave: heights, velocities and phase speed against linear wave theory.

The expected wavenumber comes from the test's own root-finding of omega^2 = g k tanh(k h); the tile is
chosen so that the wave fits it exactly.
"""

import math

import numpy as np
import pytest
import warp as wp
from scipy.optimize import brentq

from ocean_warp import Ocean, OceanConfig
from ocean_warp.kernels.ocean_surface import OceanSurface, height_velocity_at_grid, pressure_head, undisplaced_position

GRAVITY = 9.81


def airy_wavenumber(period: float, depth: float) -> float:
    omega = 2 * math.pi / period
    if math.isinf(depth):
        return omega**2 / GRAVITY
    return brentq(lambda k: GRAVITY * k * math.tanh(k * depth) - omega**2, 1e-9, 10 * omega**2 / GRAVITY + 10)


def regular_ocean(rng, device, depth, grid_steps=(3, 2)):
    """A regular wave whose wavevector is grid_steps * (2 pi / tile)."""
    period = float(rng.uniform(3.0, 9.0))
    k = airy_wavenumber(period, depth)
    tile = math.hypot(*grid_steps) * 2 * math.pi / k
    amplitude = float(rng.uniform(0.1, 1.5))
    phase = float(rng.uniform(-math.pi, math.pi))
    direction = math.atan2(grid_steps[1], grid_steps[0])
    config = OceanConfig(spectrum="regular", tile_size=tile, resolution=512, amplitude=amplitude, period=period,
                         direction=direction, phase=phase, depth=depth)
    wavevector = k * np.array([math.cos(direction), math.sin(direction)])
    return Ocean(config, device=device), amplitude, wavevector, 2 * math.pi / period, phase


@pytest.mark.parametrize("depth", [math.inf, 12.0, 4.0])
def test_regular_wave_heights_and_velocities(device, rng, depth):
    ocean, a, k_vec, omega, phase = regular_ocean(rng, device, depth)
    k = np.linalg.norm(k_vec)
    depth_factor = 1.0 if math.isinf(depth) else 1.0 / math.tanh(k * depth)
    for t in rng.uniform(0.0, 3600.0, size=3):
        ocean.update(float(t))
        points = rng.uniform(-500.0, 500.0, size=(200, 2))
        sample = ocean.sample(points)
        theta = points @ k_vec - omega * t + phase
        np.testing.assert_allclose(sample.height, a * np.cos(theta), atol=1e-3 * a, rtol=0)
        # Linear theory at the surface: w = a omega sin(theta), horizontal u = a omega coth(k h) cos(theta).
        np.testing.assert_allclose(sample.velocity[:, 2], a * omega * np.sin(theta), atol=2e-3 * a * omega, rtol=0)
        horizontal = a * omega * depth_factor * np.cos(theta)[:, None] * k_vec / k
        np.testing.assert_allclose(sample.velocity[:, :2], horizontal, atol=2e-3 * a * omega * depth_factor, rtol=0)
        normal = np.stack([a * k_vec[0] * np.sin(theta), a * k_vec[1] * np.sin(theta), np.ones_like(theta)], 1)
        normal /= np.linalg.norm(normal, axis=1, keepdims=True)
        np.testing.assert_allclose(sample.normal, normal, atol=2e-3)


@pytest.mark.parametrize("depth", [math.inf, 6.0])
def test_regular_wave_phase_speed_obeys_dispersion(device, rng, depth):
    ocean, a, k_vec, omega, _ = regular_ocean(rng, device, depth, grid_steps=(4, 0))
    k = np.linalg.norm(k_vec)
    expected_speed = math.sqrt(GRAVITY / k * math.tanh(k * depth)) if math.isfinite(depth) else math.sqrt(GRAVITY / k)
    # Track the phase of the wave along its direction of travel between two times.
    x = np.linspace(0.0, 2 * math.pi / k, 64, endpoint=False)
    points = np.stack([x, np.full_like(x, rng.uniform(0, 100))], 1)

    def phase_at(t):
        ocean.update(t)
        heights = ocean.sample(points).height
        return np.angle(np.sum(heights * np.exp(-1j * k * x)))

    t0 = float(rng.uniform(0, 100))
    dt = 0.2 * 2 * math.pi / omega  # a fifth of a period: no phase wrap ambiguity
    shift = math.remainder(phase_at(t0) - phase_at(t0 + dt), 2 * math.pi)
    measured_speed = shift / k / dt
    assert measured_speed == pytest.approx(expected_speed, rel=1e-3)


def test_regular_wave_snaps_to_grid_with_warning(device):
    config = OceanConfig(spectrum="regular", tile_size=100.0, resolution=64, period=5.3, direction=0.3)
    with pytest.warns(UserWarning, match="snapped to the grid"):
        ocean = Ocean(config, device=device)
    wave = ocean.regular_wave
    dk = 2 * math.pi / 100.0
    assert wave.wavevector[0] / dk == pytest.approx(round(wave.wavevector[0] / dk), abs=1e-9)
    assert wave.omega**2 == pytest.approx(GRAVITY * wave.wavenumber, rel=1e-12)


@pytest.mark.parametrize("depth", [math.inf, 3.0])
def test_wave_pressure_and_motion_decay_with_depth_as_airy_says(device, rng, depth):
    """Below the surface the dynamic pressure head is a cosh(k (z + h)) / cosh(k h) cos(theta) (e^{k z} in deep
    water), and the orbital velocity at the middle depth decays likewise: the ocean's depth fields on the grid
    against linear wave theory, at depths drawn at random."""
    period = float(rng.uniform(0.9, 2.5))
    k = airy_wavenumber(period, depth)
    tile = math.hypot(3, 2) * 2 * math.pi / k
    depths = tuple(np.sort(rng.uniform(0.02, 0.6, size=3)))
    a, phase, direction = float(rng.uniform(0.02, 0.1)), float(rng.uniform(-math.pi, math.pi)), math.atan2(2, 3)
    ocean = Ocean(OceanConfig(spectrum="regular", tile_size=tile, resolution=64, amplitude=a, period=period,
                              direction=direction, phase=phase, depth=depth, pressure_depths=depths), device=device)
    omega = 2 * math.pi / period
    k_vec = k * np.array([math.cos(direction), math.sin(direction)])
    t = float(rng.uniform(0.0, 600.0))
    ocean.update(t)
    x, y = np.meshgrid(ocean.grid_axis(), ocean.grid_axis())
    theta = x * k_vec[0] + y * k_vec[1] - omega * t + phase

    def factor(d):
        return math.exp(-k * d) if math.isinf(depth) else math.cosh(k * (depth - d)) / math.cosh(k * depth)

    for index, d in enumerate(depths, start=1):
        expected = a * factor(d) * np.cos(theta)
        np.testing.assert_allclose(ocean.field_numpy(f"pressure_head_{index}"), expected, atol=2e-3 * a, rtol=0)
    speed = a * omega * factor(depths[1])
    horizontal = speed * (1.0 if math.isinf(depth) else 1.0 / math.tanh(k * depth))
    np.testing.assert_allclose(ocean.field_numpy("vertical_velocity_2"), speed * np.sin(theta),
                               atol=2e-3 * speed + (0.0 if math.isinf(depth) else 0.05 * speed), rtol=0)
    np.testing.assert_allclose(ocean.field_numpy("velocity_x_2"), horizontal * math.cos(direction) * np.cos(theta),
                               atol=2e-3 * horizontal, rtol=0)


@pytest.mark.parametrize("depths", [(0.1, 0.1, 0.3), (0.0, 0.1, 0.2), (0.1, 0.2), "deep", (0.1, 0.2, math.inf)])
def test_pressure_depths_are_checked(depths):
    with pytest.raises(ValueError, match="OceanConfig.pressure_depths must be three depths"):
        OceanConfig(pressure_depths=depths)


@wp.kernel
def _pressure_heads(surface: OceanSurface, points: wp.array(dtype=wp.vec3), heads: wp.array(dtype=float)):
    i = wp.tid()
    p = points[i]
    q = undisplaced_position(surface, wp.vec2(p[0], p[1]))
    heads[i] = pressure_head(surface, q, p[2], height_velocity_at_grid(surface, q)[0])


def test_the_pressure_a_hull_feels_is_airys_between_the_depths(device, rng):
    """p / (rho g) at random points under a regular wave: -z + a e^{k z} cos(theta) (deep water) at the ocean's
    depths, linear in z between them and the surface, held below the deepest; above still water hydrostatic
    up to the surface."""
    period = float(rng.uniform(1.0, 2.0))
    k = airy_wavenumber(period, math.inf)
    tile = 4 * 2 * math.pi / k
    a = float(rng.uniform(0.03, 0.08))
    depths = (0.05, 0.15, 0.35)
    ocean = Ocean(OceanConfig(spectrum="regular", tile_size=tile, resolution=256, amplitude=a, period=period,
                              direction=0.0, pressure_depths=depths), device=device)
    t = float(rng.uniform(0.0, 100.0))
    ocean.update(t)
    count = 400
    x = rng.uniform(0.0, tile, size=count)
    z = rng.uniform(-0.5, 0.1, size=count)
    points = wp.array(np.column_stack([x, np.zeros(count), z]).astype(np.float32), dtype=wp.vec3, device=device)
    heads = wp.zeros(count, dtype=float, device=device)
    wp.launch(_pressure_heads, dim=count, inputs=[ocean.surface, points, heads], device=device)
    phase = np.cos(k * x - 2 * math.pi / period * t)
    levels = np.array([0.0, -depths[0], -depths[1], -depths[2]])
    at_levels = a * np.exp(k * levels)[None, :] * phase[:, None]
    dynamic = np.array([np.interp(-zi, -levels, row) for zi, row in zip(z, at_levels)])  # held below the deepest
    expected = np.where(z >= 0.0, a * phase - z, dynamic - z)
    np.testing.assert_allclose(heads.numpy(), expected, atol=3e-3 * a, rtol=0)
