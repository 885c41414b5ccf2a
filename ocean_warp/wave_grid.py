"""The sea state laid on the FFT grid: initial complex amplitudes h0(k), frequencies and the per-cell
constants that the spectrum kernel reads (host side, numpy float64, done once per ocean).

Fields are sums over the grid's wavevectors k = 2 pi (n_x, n_y) / L, with n in FFT order:

    h(x, t) = sum_k h^(k, t) exp(i k.x),   h^(k, t) = h0(k) exp(-i w t) + conj(h0(-k)) exp(+i w t)

(Tessendorf's evolution, signed so that the energy placed at h0(k) travels towards +k). The second term
keeps h^(-k) = conj(h^(k)), so every field is real. E|h0(k)|^2 = S2(k) dk^2 / 2, with S2 the
wavenumber spectrum over the plane, so the field's variance is the integral of the spectrum.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np

from . import spectra
from .ocean_config import OceanConfig, Spectrum

__all__ = ["RegularWave", "WaveGrid", "build_wave_grid", "loop_frequencies", "CELL_LAYOUT"]

CELL_LAYOUT = ("h0_re", "h0_im", "h0m_re", "h0m_im", "omega", "kx", "ky", "horizontal_gain")
"""Meaning of the 8 float32 values the spectrum kernel reads per cell: h0(k), conj(h0(-k)), omega [rad/s],
k [rad/m], and coth(k d) / |k| [m], the gain from slope to horizontal displacement."""


@dataclasses.dataclass(frozen=True)
class RegularWave:
    """The one Airy wave of a "regular" ocean, after snapping its wavevector to the grid."""

    amplitude: float
    """[m]"""
    wavevector: tuple[float, float]
    """(kx, ky) [rad/m] on the grid."""
    omega: float
    """Angular frequency [rad/s] of that wavevector by the dispersion relation."""
    phase: float
    """[rad], h = a cos(k.x - omega t + phase)."""

    @property
    def wavenumber(self) -> float:
        return math.hypot(*self.wavevector)

    @property
    def period(self) -> float:
        return 2.0 * math.pi / self.omega

    @property
    def direction(self) -> float:
        return math.atan2(self.wavevector[1], self.wavevector[0])


@dataclasses.dataclass(frozen=True)
class WaveGrid:
    """Everything the ocean computes once from its config."""

    cells: np.ndarray
    """(n, n, 8) float32, layout :data:`CELL_LAYOUT`, array index [iy, ix]."""
    h0: np.ndarray
    """(n, n) complex128 initial amplitudes [m]."""
    omega: np.ndarray
    """(n, n) angular frequency of each cell [rad/s], as the fields evolve with it: the dispersion
    relation's, or with ``OceanConfig.loop_period`` its multiple of 2 pi / loop_period."""
    variance: float
    """Variance of the height field [m^2] that the spectrum puts on this grid: the expectation over
    seeds of the spatial variance (exact for "regular")."""
    regular_wave: RegularWave | None


def loop_frequencies(omega, loop_period: float | None) -> np.ndarray:
    """Angular frequencies [rad/s] that repeat every ``loop_period`` [s]: each ``omega`` [rad/s] moved to the
    nearest whole multiple of 2 pi / loop_period, and to one multiple at least where omega > 0 (a wave
    longer than 2 loop_period would otherwise stand still). omega = 0 (the mean) stays 0. None returns
    ``omega`` unchanged. Each omega moves by at most pi / loop_period, a relative error of at most
    T_w / (2 loop_period) for a wave of period T_w; only waves longer than 2 loop_period, raised to one
    cycle per loop, move further."""
    omega = np.asarray(omega, dtype=np.float64)
    if loop_period is None:
        return omega
    quantum = 2.0 * math.pi / loop_period
    multiples = np.maximum(np.rint(omega / quantum), 1.0)
    return np.where(omega > 0.0, multiples * quantum, 0.0)


def _wavevectors(config: OceanConfig) -> tuple[np.ndarray, np.ndarray]:
    n = config.resolution
    k_axis = 2.0 * math.pi * np.fft.fftfreq(n, d=config.cell_size)
    kx, ky = np.meshgrid(k_axis, k_axis, indexing="xy")  # kx varies along columns (x), ky along rows (y)
    return kx, ky


def _excluded_cells(config: OceanConfig, kx: np.ndarray, ky: np.ndarray) -> np.ndarray:
    """Cells that carry no wave: the mean, the Nyquist row and column (they have no Hermitian partner,
    so a derivative there would not be real), and waves shorter than ``min_wavelength``."""
    n = config.resolution
    excluded = np.zeros((n, n), dtype=bool)
    excluded[0, 0] = True
    excluded[n // 2, :] = True
    excluded[:, n // 2] = True
    if config.min_wavelength > 0.0:
        excluded |= np.hypot(kx, ky) > 2.0 * math.pi / config.min_wavelength
    return excluded


def _ring_normalised(weights: np.ndarray, ring: np.ndarray, distance_to_ray: np.ndarray | None, max_distance: float):
    """Scale directional weights so that each ring of cells (|k| within half a grid step of r dk) sums
    to one: the discrete directional distribution then conserves each ring's energy however few cells
    the spread covers. For a long-crested sea, a ring whose weights are all zero (the ray crosses it
    between cell centres) gives its energy to its cell nearest the ray, if one lies within
    ``max_distance`` of it; rings the ray never reaches on the grid stay empty."""
    n_rings = int(ring.max()) + 1
    sums = np.bincount(ring.ravel(), weights=weights.ravel(), minlength=n_rings)
    if distance_to_ray is not None:
        flat_distance = distance_to_ray.ravel()
        flat_ring = ring.ravel()
        for r in np.flatnonzero(sums[1:] == 0.0) + 1:
            members = np.flatnonzero((flat_ring == r) & (flat_distance >= 0.0) & (flat_distance <= max_distance))
            if members.size:
                weights.ravel()[members[np.argmin(flat_distance[members])]] = 1.0
        sums = np.bincount(flat_ring, weights=weights.ravel(), minlength=n_rings)
    safe = np.where(sums > 0.0, sums, 1.0)
    return weights / safe[ring]


def _directional_weights(config: OceanConfig, kx: np.ndarray, ky: np.ndarray, excluded: np.ndarray) -> np.ndarray:
    """Share of each cell in the energy of its wavenumber ring (sums to 1 over each ring)."""
    dk = 2.0 * math.pi / config.tile_size
    k = np.hypot(kx, ky)
    ring = np.rint(k / dk).astype(np.int64)
    along = kx * math.cos(config.direction) + ky * math.sin(config.direction)
    if config.long_crested:
        # A tent of one grid step across the ray: exact (a single line of cells) for grid-aligned
        # directions, the nearest cells otherwise.
        across = np.abs(-kx * math.sin(config.direction) + ky * math.cos(config.direction))
        weights = np.where((along > 0.0) & ~excluded, np.maximum(0.0, 1.0 - across / dk), 0.0)
        distance = np.where((along > 0.0) & ~excluded, across, -1.0)
        return _ring_normalised(weights, ring, distance, max_distance=1.5 * dk)
    theta = np.arctan2(ky, kx)
    weights = np.where(excluded, 0.0, spectra.cos2s_spreading(theta, config.direction, config.spreading))
    return _ring_normalised(weights, ring, None, max_distance=0.0)


def _frequency_spectrum(config: OceanConfig, omega: np.ndarray) -> np.ndarray:
    if config.spectrum is Spectrum.JONSWAP:
        return spectra.jonswap(omega, config.significant_wave_height, config.peak_period, config.gamma)
    if config.wind_speed is not None:
        return spectra.pierson_moskowitz_wind(omega, config.wind_speed, config.water.gravity)
    return spectra.pierson_moskowitz(omega, config.significant_wave_height, config.peak_period)


def _spectral_h0(config: OceanConfig, kx, ky, omega, excluded) -> tuple[np.ndarray, np.ndarray]:
    """Random amplitudes h0 [m] and their expected squares E|h0|^2 [m^2]."""
    dk = 2.0 * math.pi / config.tile_size
    k = np.hypot(kx, ky)
    safe_k = np.where(k > 0.0, k, 1.0)
    # Wavenumber spectrum along |k|: S_k(k) = S(omega(k)) d omega / dk [m^3].
    s_k = _frequency_spectrum(config, omega) * spectra.dispersion_domega_dk(safe_k, config.depth, config.water.gravity)
    ring_share = _directional_weights(config, kx, ky, excluded)
    # The ring of radius k and width dk holds S_k dk of variance; each cell takes its share, and the
    # pair h0(k), conj(h0(-k)) splits a cell's variance in two: E|h0|^2 = S_k dk share / 2.
    mean_square = np.where(excluded, 0.0, 0.5 * s_k * dk * ring_share)
    rng = np.random.Generator(np.random.Philox(config.seed))
    gaussian = rng.standard_normal((2,) + k.shape)
    return np.sqrt(mean_square) * (gaussian[0] + 1j * gaussian[1]) / math.sqrt(2.0), mean_square


def _regular_h0(config: OceanConfig, kx, ky, excluded) -> tuple[np.ndarray, RegularWave]:
    n = config.resolution
    dk = 2.0 * math.pi / config.tile_size
    omega_target = 2.0 * math.pi / config.period
    k_target = float(spectra.wavenumber_from_omega(omega_target, config.depth, config.water.gravity))
    n_x = round(k_target * math.cos(config.direction) / dk)
    n_y = round(k_target * math.sin(config.direction) / dk)
    if (n_x, n_y) == (0, 0):
        raise ValueError(
            f"OceanConfig.period {config.period} s gives a wavelength of {2 * math.pi / k_target:.1f} m, "
            f"longer than tile_size {config.tile_size} m: enlarge the tile"
        )
    if max(abs(n_x), abs(n_y)) >= n // 2:
        raise ValueError(
            f"OceanConfig.period {config.period} s gives a wavelength of {2 * math.pi / k_target:.3f} m, "
            f"too short for the grid spacing {config.cell_size} m: raise resolution or the period"
        )
    ix, iy = n_x % n, n_y % n
    if excluded[iy, ix]:
        raise ValueError(
            f"OceanConfig.min_wavelength {config.min_wavelength} m removes the regular wave "
            f"(wavelength {2 * math.pi / k_target:.3f} m)"
        )
    wavevector = (float(kx[iy, ix]), float(ky[iy, ix]))
    k_grid = math.hypot(*wavevector)
    dispersion = float(spectra.dispersion_omega(k_grid, config.depth, config.water.gravity))
    omega = float(loop_frequencies(dispersion, config.loop_period))
    if abs(omega / dispersion - 1.0) > 0.01:
        warnings.warn(
            f"regular wave: period {2 * math.pi / omega:.4f} s instead of {2 * math.pi / dispersion:.4f} s, so that it "
            f"repeats every OceanConfig.loop_period ({config.loop_period} s); a longer loop_period brings it closer",
            stacklevel=3,
        )
    direction_error = abs(math.remainder(math.atan2(wavevector[1], wavevector[0]) - config.direction, 2 * math.pi))
    if abs(k_grid / k_target - 1.0) > 0.01 or direction_error > math.radians(1.0):
        warnings.warn(
            f"regular wave snapped to the grid: period {2 * math.pi / dispersion:.4f} s and direction "
            f"{math.degrees(math.atan2(wavevector[1], wavevector[0])):.2f} deg instead of {config.period} s and "
            f"{math.degrees(config.direction):.2f} deg; make tile_size a multiple of the wavelength "
            f"({2 * math.pi / k_target:.3f} m) along x and y to avoid this",
            stacklevel=3,
        )
    h0 = np.zeros((n, n), dtype=np.complex128)
    h0[iy, ix] = 0.5 * config.amplitude * np.exp(1j * config.phase)
    return h0, RegularWave(config.amplitude, wavevector, omega, config.phase)


def build_wave_grid(config: OceanConfig) -> WaveGrid:
    """Lay ``config``'s sea state on its grid: amplitudes, frequencies and the kernel's cell constants."""
    kx, ky = _wavevectors(config)
    k = np.hypot(kx, ky)
    omega = spectra.dispersion_omega(k, config.depth, config.water.gravity)
    excluded = _excluded_cells(config, kx, ky)
    regular_wave = None
    if config.spectrum is Spectrum.REGULAR:
        h0, regular_wave = _regular_h0(config, kx, ky, excluded)
        variance = 0.5 * config.amplitude**2
    else:
        # The amplitudes follow the dispersion relation's omega; only the time evolution uses the loop's.
        h0, mean_square = _spectral_h0(config, kx, ky, omega, excluded)
        variance = 2.0 * float(mean_square.sum())  # each cell's pair h0(k), conj(h0(-k))
    omega = loop_frequencies(omega, config.loop_period)
    # conj(h0(-k)): index -i of an FFT-ordered axis is (n - i) mod n.
    h0_mirror = np.conj(np.roll(np.flip(h0, axis=(0, 1)), shift=(1, 1), axis=(0, 1)))
    safe_k = np.where(k > 0.0, k, 1.0)
    if math.isinf(config.depth):
        horizontal_gain = 1.0 / safe_k
    else:
        horizontal_gain = 1.0 / (safe_k * np.tanh(safe_k * config.depth))
    horizontal_gain = np.where(k > 0.0, horizontal_gain, 0.0)
    cells = np.stack(
        [h0.real, h0.imag, h0_mirror.real, h0_mirror.imag, omega, kx, ky, horizontal_gain], axis=-1
    ).astype(np.float32)
    return WaveGrid(cells=cells, h0=h0, omega=omega, variance=variance, regular_wave=regular_wave)
