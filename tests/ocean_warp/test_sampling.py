"""Sampling the surface: the choppy inversion, heights, normals and rates against numpy on the grid."""

import math

import numpy as np
import pytest
import warp as wp

from ocean_warp import Ocean, OceanConfig
from ocean_warp.kernels.ocean_surface import (OceanSurface, local_inversion, undisplaced_position,
                                              undisplaced_position_local, undisplaced_position_near)


def numpy_bilinear(field: np.ndarray, xy: np.ndarray, cell: float) -> np.ndarray:
    """Periodic bilinear interpolation of a (n, n) [iy, ix] grid at world points, written for the test."""
    n = field.shape[0]
    g = xy / cell
    g0 = np.floor(g)
    t = g - g0
    ix0, iy0 = g0[:, 0].astype(int) % n, g0[:, 1].astype(int) % n
    ix1, iy1 = (ix0 + 1) % n, (iy0 + 1) % n
    lower = (1 - t[:, 0]) * field[iy0, ix0] + t[:, 0] * field[iy0, ix1]
    upper = (1 - t[:, 0]) * field[iy1, ix0] + t[:, 0] * field[iy1, ix1]
    return (1 - t[:, 1]) * lower + t[:, 1] * upper


def choppy_ocean(rng, device, choppiness=1.0, min_wavelength_cells=0.0):
    tile = float(rng.uniform(150, 400))
    config = OceanConfig(tile_size=tile, resolution=128, significant_wave_height=float(rng.uniform(1, 3)),
                         peak_period=float(rng.uniform(6, 10)), choppiness=choppiness, spreading=8.0,
                         direction=float(rng.uniform(-math.pi, math.pi)), seed=int(rng.integers(2**31)),
                         min_wavelength=min_wavelength_cells * tile / 128)
    ocean = Ocean(config, device=device)
    ocean.update(float(rng.uniform(0, 1000)))
    return ocean


def test_choppy_sample_lands_on_asked_point(device, rng):
    ocean = choppy_ocean(rng, device)
    cell = ocean.config.cell_size
    points = rng.uniform(-1000, 1000, size=(500, 2))
    sample = ocean.sample(points)
    q = sample.grid_position.astype(np.float64)
    displaced = q + ocean.config.choppiness * np.stack(
        [numpy_bilinear(ocean.field_numpy(f"displacement_{axis}"), q, cell) for axis in "xy"], 1)
    np.testing.assert_allclose(displaced, points, atol=0.01)
    # The displacement really moved things: the inversion is not the identity.
    assert np.abs(q - points).max() > 0.1
    # float32 positions ~1 km from the origin are good to ~1e-4 m, on slopes up to ~1.
    np.testing.assert_allclose(sample.height, numpy_bilinear(ocean.field_numpy("height"), q, cell), atol=2e-4)


def test_normal_is_normal_to_sampled_surface(device, rng):
    # A steep choppy sea (where the tilt of the displaced surface differs from the plain slope by
    # degrees) of waves at least 16 cells long, so that bilinear heights resolve them and their
    # finite differences are the surface's slope.
    config = OceanConfig(tile_size=200.0, resolution=256, significant_wave_height=3.0, peak_period=5.0, choppiness=0.9,
                         min_wavelength=25.0, direction=float(rng.uniform(-math.pi, math.pi)), seed=int(rng.integers(2**31)))
    ocean = Ocean(config, device=device)
    ocean.update(float(rng.uniform(0, 1000)))
    points = rng.uniform(0, ocean.config.tile_size, size=(300, 2))
    step = 0.02 * ocean.config.cell_size
    height = lambda p: ocean.sample(p).height.astype(np.float64)  # noqa: E731
    dh_dx = (height(points + [step, 0]) - height(points - [step, 0])) / (2 * step)
    dh_dy = (height(points + [0, step]) - height(points - [0, step])) / (2 * step)
    expected = np.stack([-dh_dx, -dh_dy, np.ones_like(dh_dx)], 1)
    expected /= np.linalg.norm(expected, axis=1, keepdims=True)
    normal = ocean.sample(points).normal
    np.testing.assert_allclose(np.linalg.norm(normal, axis=1), 1.0, atol=1e-5)
    angle = np.degrees(np.arccos(np.clip(np.sum(normal * expected, axis=1), -1, 1)))
    assert np.median(angle) < 0.2 and angle.max() < 3.0


def test_rates_are_time_derivatives(device, rng):
    config = OceanConfig(tile_size=200.0, resolution=64, significant_wave_height=2.0, peak_period=7.0,
                         depth=float(rng.uniform(8, 40)), seed=int(rng.integers(2**31)))
    ocean = Ocean(config, device=device)
    t, dt = float(rng.uniform(0, 500)), 1e-2

    def fields_at(time):
        ocean.update(time)
        return {name: ocean.field_numpy(name).astype(np.float64) for name in
                ("height", "displacement_x", "displacement_y", "vertical_velocity", "velocity_x", "velocity_y")}

    before, now, after = fields_at(t - dt), fields_at(t), fields_at(t + dt)
    for position, rate in (("height", "vertical_velocity"), ("displacement_x", "velocity_x"),
                           ("displacement_y", "velocity_y")):
        numeric = (after[position] - before[position]) / (2 * dt)
        scale = np.abs(now[rate]).max()
        assert np.abs(numeric - now[rate]).max() < 2e-3 * scale, rate


def test_slopes_are_space_derivatives(device, rng):
    ocean = choppy_ocean(rng, device)
    height = ocean.field_numpy("height").astype(np.float64)
    n, cell = ocean.config.resolution, ocean.config.cell_size
    k = 2 * math.pi * np.fft.fftfreq(n, d=cell)
    spectrum = np.fft.fft2(height)
    for axis, name in ((1, "slope_x"), (0, "slope_y")):
        wavenumber = k[None, :] if axis == 1 else k[:, None]
        expected = np.fft.ifft2(1j * wavenumber * spectrum).real
        np.testing.assert_allclose(ocean.field_numpy(name), expected, atol=1e-5 * np.abs(expected).max() + 1e-7)


def test_sample_rejects_bad_points(device):
    ocean = Ocean(OceanConfig(resolution=16, tile_size=50.0), device=device)
    with pytest.raises(ValueError, match=r"shape \(M, 2\)"):
        ocean.sample(np.zeros((4, 3)))
    with pytest.raises(ValueError, match="NaN"):
        ocean.sample([[0.0, np.nan]])


@wp.kernel
def _invert_near(surface: OceanSurface, points: wp.array(dtype=wp.vec2), anchor: wp.vec2,
                 grid_positions: wp.array(dtype=wp.vec2)):
    """Each point's grid position, started from the solution at ``anchor`` as the hull pass does."""
    i = wp.tid()
    shift = anchor - undisplaced_position(surface, anchor)
    grid_positions[i] = undisplaced_position_near(surface, points[i], shift)


def test_inversion_started_near_matches_the_full_one(device, rng):
    """Points within a boat's reach (2 m) of an anchor, started from the anchor's solution, land on the asked
    points to 5 mm on a steep choppy sea (choppiness 1, Hs up to 3 m at Tp 6 s, where each iteration shrinks
    the error only about 3-fold: two fixed iterations left up to 9 cm, so the iteration must run to its
    1 mm tolerance)."""
    ocean = choppy_ocean(rng, device)
    assert ocean.config.inversion_tolerance == 1e-3
    anchors = rng.uniform(-300, 300, size=(20, 2))
    cell = ocean.config.cell_size
    for anchor in anchors:
        points = anchor + rng.uniform(-2.0, 2.0, size=(64, 2))
        near = wp.zeros(len(points), dtype=wp.vec2, device=device)
        wp.launch(_invert_near, dim=len(points), device=device,
                  inputs=[ocean.surface, wp.array(points.astype(np.float32), dtype=wp.vec2, device=device),
                          wp.vec2(*map(float, anchor))], outputs=[near])
        q = near.numpy().astype(np.float64)
        displaced = q + ocean.config.choppiness * np.stack(
            [numpy_bilinear(ocean.field_numpy(f"displacement_{axis}"), q, cell) for axis in "xy"], 1)
        np.testing.assert_allclose(displaced, points, atol=5e-3)


@wp.kernel
def _invert_local(surface: OceanSurface, points: wp.array(dtype=wp.vec2), anchor: wp.vec2,
                  grid_positions: wp.array(dtype=wp.vec2), starts: wp.array(dtype=wp.vec2)):
    """Each point's grid position from the anchor's first-order estimate, as the hull pass does, and the estimate."""
    i = wp.tid()
    local = local_inversion(surface, anchor)
    grid_positions[i] = undisplaced_position_local(surface, points[i], local)
    starts[i] = local.grid + local.inverse_jacobian * (points[i] - anchor)


@pytest.mark.parametrize("choppiness", [0.5, 1.0])
def test_inversion_from_the_local_estimate_lands_on_the_points(device, rng, choppiness):
    """Points within a boat's reach (2 m) of an anchor, started from the first-order estimate about the anchor and
    stopped by its contraction, land on the asked points within 5 mm on choppy seas of Hs 1-3 m (as
    :func:`test_inversion_started_near_matches_the_full_one`; the contraction found at the anchor may be smaller 2 m
    away, where the steps then stop a little early); the estimate itself is closer than the anchor's shift alone
    (the median error under two thirds of it)."""
    ocean = choppy_ocean(rng, device, choppiness=choppiness)
    cell = ocean.config.cell_size
    start_errors, shift_errors = [], []
    for anchor in rng.uniform(-300, 300, size=(20, 2)):
        points = anchor + rng.uniform(-2.0, 2.0, size=(64, 2))
        grid = wp.zeros(len(points), dtype=wp.vec2, device=device)
        starts = wp.zeros(len(points), dtype=wp.vec2, device=device)
        wp.launch(_invert_local, dim=len(points), device=device,
                  inputs=[ocean.surface, wp.array(points.astype(np.float32), dtype=wp.vec2, device=device),
                          wp.vec2(*map(float, anchor))], outputs=[grid, starts])
        displacement = lambda q: choppiness * np.stack(  # noqa: E731
            [numpy_bilinear(ocean.field_numpy(f"displacement_{axis}"), q, cell) for axis in "xy"], 1)
        q = grid.numpy().astype(np.float64)
        np.testing.assert_allclose(q + displacement(q), points, atol=5e-3)
        anchor_grid = np.asarray(anchor, dtype=np.float64)
        for _ in range(50):  # the anchor's own grid position, by numpy's fixed-point iteration
            anchor_grid = anchor - displacement(anchor_grid[None])[0]
        start = starts.numpy().astype(np.float64)
        start_errors.append(np.abs(start + displacement(start) - points).max(axis=1))
        shifted = points - (anchor - anchor_grid)
        shift_errors.append(np.abs(shifted + displacement(shifted) - points).max(axis=1))
    start_error, shift_error = np.concatenate(start_errors), np.concatenate(shift_errors)
    assert np.median(start_error) * 1.5 < np.median(shift_error)
