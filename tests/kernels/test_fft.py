"""The tiled inverse-FFT kernels against numpy.fft, and the whole ocean update against numpy."""

import numpy as np
import pytest
import warp as wp

from ocean_warp import FftPlan, Ocean, OceanConfig
from ocean_warp.kernels.fft import ifft_rows_kernel


def _relative_error(actual, expected):
    return np.linalg.norm(actual - expected) / np.linalg.norm(expected)


@pytest.mark.parametrize("n", [64, 128, 256, 512])
def test_inverse_fft_2d_matches_numpy(device, rng, n):
    plan = FftPlan.for_device(n, device)
    spectrum = (rng.standard_normal((n, n)) + 1j * rng.standard_normal((n, n))).astype(np.complex64)
    src = wp.array(spectrum.view(np.float32).reshape(n, n, 2), dtype=wp.vec2f, device=device)
    along_rows = wp.full((n, n), wp.vec2f(np.nan, np.nan), dtype=wp.vec2f, device=device)
    result = wp.full((n, n), wp.vec2f(np.nan, np.nan), dtype=wp.vec2f, device=device)
    kernel = ifft_rows_kernel(n)
    wp.launch_tiled(kernel, dim=[n], inputs=[src], outputs=[along_rows], block_dim=plan.block_dim, device=device)
    # Second pass over the transposed view: its rows are the columns of the first pass's output.
    wp.launch_tiled(kernel, dim=[n], inputs=[along_rows.transpose()], outputs=[result], block_dim=plan.block_dim,
                    device=device)
    actual = result.numpy().view(np.complex64)[..., 0]
    # Warp's inverse transform is unnormalised, and the result comes out transposed.
    expected = (np.fft.ifft2(spectrum.astype(np.complex128)) * n * n).T
    assert np.all(np.isfinite(actual)), "some outputs were never written"
    assert _relative_error(actual, expected) < 1e-5


def _numpy_fields(ocean: Ocean, t: float) -> dict[str, np.ndarray]:
    """All eight fields straight from linear wave theory, with numpy's FFT in float64."""
    cells = ocean.wave_grid.cells.astype(np.float64)
    h0 = cells[..., 0] + 1j * cells[..., 1]
    h0_mirror = cells[..., 2] + 1j * cells[..., 3]
    omega, kx, ky, gain = cells[..., 4], cells[..., 5], cells[..., 6], cells[..., 7]
    forward, backward = h0 * np.exp(-1j * omega * t), h0_mirror * np.exp(1j * omega * t)
    height = forward + backward
    rate = -1j * omega * forward + 1j * omega * backward
    n = ocean.config.resolution

    def to_space(spectrum):
        field = np.fft.ifft2(spectrum) * n * n
        assert np.abs(field.imag).max() <= 1e-9 * max(np.abs(field.real).max(), 1e-30), "spectrum not Hermitian"
        return field.real

    return {
        "height": to_space(height),
        "vertical_velocity": to_space(rate),
        "displacement_x": to_space(1j * kx * gain * height),
        "displacement_y": to_space(1j * ky * gain * height),
        "slope_x": to_space(1j * kx * height),
        "slope_y": to_space(1j * ky * height),
        "velocity_x": to_space(1j * kx * gain * rate),
        "velocity_y": to_space(1j * ky * gain * rate),
    }


@pytest.mark.parametrize("n", [64, 256])
def test_ocean_update_matches_numpy(device, rng, n):
    config = OceanConfig(
        tile_size=float(rng.uniform(50.0, 400.0)),
        resolution=n,
        significant_wave_height=float(rng.uniform(0.5, 4.0)),
        peak_period=float(rng.uniform(4.0, 10.0)),
        direction=float(rng.uniform(-np.pi, np.pi)),
        depth=float(rng.choice([np.inf, rng.uniform(5.0, 50.0)])),
        seed=int(rng.integers(2**31)),
    )
    ocean = Ocean(config, device=device)
    t = float(rng.uniform(0.0, 5000.0))
    ocean.update(t)
    for name, expected in _numpy_fields(ocean, t).items():
        actual = ocean.field_numpy(name)
        assert _relative_error(actual, expected) < 1e-4, name


def test_captured_update_replays_at_device_time(device, rng):
    ocean = Ocean(OceanConfig(resolution=128, tile_size=300.0, seed=int(rng.integers(2**31))), device=device)
    ocean.update(0.0)
    with wp.ScopedCapture(device=device) as capture:
        ocean.update()  # reads the time from the device array
    times = rng.uniform(1.0, 1000.0, size=3)
    for t in times:
        ocean.time.fill_(float(t))
        wp.capture_launch(capture.graph)
        replayed = ocean.field_numpy("height").copy()
        ocean.update(float(t))
        np.testing.assert_array_equal(replayed, ocean.field_numpy("height"))
    assert not np.allclose(replayed, Ocean(ocean.config, device=device).field_numpy("height"))


def test_an_ocean_reading_slots_copies_what_another_evaluated(device, rng):
    """One ocean evaluates two times into slots; a second of the same config reads them in the cursor's
    order, bit for bit what it evaluates itself, inside a captured graph too; it refuses a time of its own."""
    config = OceanConfig(resolution=64, tile_size=200.0, significant_wave_height=2.0, choppiness=0.5,
                         seed=int(rng.integers(2**31)))
    source, reader = Ocean(config, device=device), Ocean(config, device=device)
    times = rng.uniform(0.0, 500.0, size=2)
    rows = source.fields.shape[0] * source.fields.shape[1]
    slots = wp.zeros((2, rows, config.resolution), dtype=wp.vec2f, device=device)
    for slot, t in enumerate(times):
        source.update(float(t), out=slots[slot])
    expected = []
    for t in times:
        reader.update(float(t))
        expected.append(reader.field_numpy("height").copy())
    cursor = wp.zeros(1, dtype=wp.int32, device=device)
    reader.read_fields_from(slots, cursor)
    with wp.ScopedCapture(device=device) as capture:
        reader.update()
    for slot in (0, 1):
        wp.capture_launch(capture.graph)
        np.testing.assert_array_equal(reader.field_numpy("height"), expected[slot])
    assert cursor.numpy()[0] == 2
    assert not np.array_equal(expected[0], expected[1])
    with pytest.raises(ValueError, match="cannot evaluate t = 1.0"):
        reader.update(1.0)
    with pytest.raises(ValueError, match=rf"slots must be a \(K, {rows}, 64\) vec2f array"):
        reader.read_fields_from(wp.zeros((2, 64, 64), dtype=wp.vec2f, device=device), cursor)
    with pytest.raises(ValueError, match=rf"out must be a \({rows}, 64\) vec2f array"):
        source.update(0.0, out=wp.zeros((64, 64), dtype=wp.vec2f, device=device))
