"""The spectral ocean: a periodic sea surface evaluated on a grid by tiled inverse FFTs in Warp."""

from __future__ import annotations

import dataclasses
import math
from typing import NamedTuple

import numpy as np
import warp as wp

from .kernels.ocean_spectrum import (
    FIELD_COUNT,
    FIELD_DISPLACEMENT,
    FIELD_HEIGHT,
    FIELD_SLOPE,
    FIELD_PRESSURE_LOWER,
    FIELD_PRESSURE_UPPER,
    FIELD_VELOCITY,
    FIELD_VELOCITY_BELOW,
    PACKED_QUADS,
    fields_along_x_kernel,
    packed_spectra,
    spectra_along_y_kernel,
    spectrum_cell,
)
from .kernels.field_slots import advance_cursor, copy_slot_fields
from .kernels.ocean_surface import OceanSurface, sample_surface_kernel
from . import spectra
from .ocean_config import OceanConfig, Spectrum, require_significant_wave_height
from .wave_grid import CELL_LAYOUT, RegularWave, build_wave_grid

__all__ = ["Ocean", "FftPlan", "SurfaceSample"]


@dataclasses.dataclass(frozen=True)
class FftPlan:
    """How the two FFT passes are launched (one block per grid row). :meth:`for_device` gives the
    defaults measured in ``benchmarks/RESULTS.md``; other values are for benchmarking."""

    block_dim: int
    """Threads per block (1 on the CPU, where a block runs on one thread)."""

    @staticmethod
    def for_device(resolution: int, device) -> "FftPlan":
        if wp.get_device(device).is_cpu:
            return FftPlan(block_dim=1)
        # cuFFTDx wants at least two elements per thread; four was fastest on an H100.
        return FftPlan(block_dim=max(resolution // 4, 1))


class SurfaceSample(NamedTuple):
    """The ocean surface above a set of world points, as numpy arrays on the host."""

    height: np.ndarray
    """(M,) surface height [m] above each point (z up, still water at 0)."""
    normal: np.ndarray
    """(M, 3) unit upward normal of the surface."""
    velocity: np.ndarray
    """(M, 3) water velocity at the surface [m/s] (linear orbital velocity)."""
    grid_position: np.ndarray
    """(M, 2) the undisplaced grid position [m] whose choppy displacement lands on the point."""

DEEP_WATER = 1.0e30
"""The water depth [m] the spectrum kernel is given for deep water: its depth factors are then e^{k z}."""

CELL_OMEGA = CELL_LAYOUT.index("omega")
"""Where a spectrum cell holds its wave's angular frequency [rad/s]."""


def exact_time_limit(max_omega: float) -> float:
    """The largest |t| [s] at which the phase omega t [rad] of the fastest wave, ``max_omega`` [rad/s], is
    still exact to the float32 the fields are computed in. ``evolve_amplitude`` reduces omega t to [0, 2 pi)
    in float64, with a rounding error up to omega |t| eps64 [rad]; the float32 phase near 2 pi is spaced
    2^-21 rad. The error stays below that spacing while |t| <= spacing / (eps64 omega) = 2^31 / omega:
    about ten years for a grid whose fastest wave has 6.6 rad/s. Infinite for a sea without waves."""
    if max_omega <= 0.0:
        return math.inf
    spacing = float(np.spacing(np.float32(2.0 * math.pi)))
    return spacing / (float(np.finfo(np.float64).eps) * max_omega)


class Ocean:
    """A periodic patch of ocean surface (it tiles the whole plane) from one wave spectrum.

    ``update(t)`` evaluates, on the device, the height, horizontal displacement, slopes and water
    velocity on the grid at time t [s]; ``sample(xy)`` reads the surface above world points; kernels
    read it through :attr:`surface` and the ``wp.func`` lookups of ``ocean_warp.kernels.ocean_surface``.

    Example::

        ocean = Ocean(OceanConfig(significant_wave_height=2.0, peak_period=8.0), device="cuda:0")
        ocean.update(12.5)
        sample = ocean.sample([[10.0, -3.0], [250.0, 40.0]])
        sample.height, sample.normal, sample.velocity
    """

    def __init__(self, config: OceanConfig | None = None, *, device=None, fft_plan: FftPlan | None = None,
                 depth_fields: bool = True):
        self.config = config if config is not None else OceanConfig()
        if not isinstance(self.config, OceanConfig):
            raise TypeError(f"Ocean expects an OceanConfig, got {type(self.config).__name__}")
        self.device = wp.get_device(device)
        n = self.config.resolution
        self.fft_plan = fft_plan if fft_plan is not None else FftPlan.for_device(n, self.device)

        self.wave_grid = build_wave_grid(self.config)
        """The sea as the config lays it on the grid (the amplitudes before any
        :meth:`set_significant_wave_height`)."""
        cells_x_major = np.ascontiguousarray(self.wave_grid.cells.transpose(1, 0, 2))
        self._base_cells = cells_x_major
        self._cells = wp.array(cells_x_major, dtype=spectrum_cell, device=self.device)
        self._amplitude_scale = 1.0
        self.time = wp.zeros(1, dtype=wp.float64, device=self.device)
        """(1,) float64 time [s] of a standalone ocean's fields (``update(t)`` sets it; kernels may advance it
        inside a captured graph). A :class:`~ocean_warp.Simulator` evaluates its ocean at its own clock."""
        # Pass 1 writes packed_spectra (n, n); pass 2 reads the same bytes as vec4f (n, PACKED_QUADS n).
        self._spectra_quads = wp.zeros((n, PACKED_QUADS * n), dtype=wp.vec4f, device=self.device)
        self._spectra = wp.array(ptr=self._spectra_quads.ptr, dtype=packed_spectra, shape=(n, n), device=self.device)
        self._field_rows = wp.zeros((FIELD_COUNT * n, n), dtype=wp.vec2f, device=self.device)
        self.fields = self._field_rows.reshape((FIELD_COUNT, n, n))
        """(4, n, n) vec2f field pairs, index [field, iy, ix]; see ``ocean_warp.kernels.ocean_spectrum``."""

        self.surface = OceanSurface()
        """The struct kernels take to read this ocean."""
        self.surface.fields = self.fields
        self.surface.inv_cell_size = 1.0 / self.config.cell_size
        self.surface.index_mask = n - 1
        self.surface.choppiness = self.config.choppiness
        choppy = self.config.choppiness > 0
        self.surface.inversion_iterations = self.config.inversion_iterations if choppy else 0
        self.surface.inversion_tolerance_sq = self.config.inversion_tolerance**2
        depths = self.config.pressure_depths
        self.surface.pressure_depths = wp.vec3(-depths[0], -depths[1], -depths[2])
        water_depth = self.config.depth if math.isfinite(self.config.depth) else DEEP_WATER
        self._levels = wp.vec4f(-depths[0], -depths[1], -depths[2], water_depth)

        self.time_limit = exact_time_limit(float(np.max(self._base_cells[..., CELL_OMEGA])))
        """Largest |t| [s] :meth:`update` accepts: beyond it the float64 phase omega t of the grid's fastest
        wave is no longer exact to the float32 the fields are computed in (:func:`exact_time_limit`)."""
        self._loop_period = wp.float64(self.config.loop_period or 0.0)
        if not isinstance(depth_fields, bool):
            raise ValueError(f"Ocean: depth_fields must be True or False, got {depth_fields!r}")
        self.depth_fields = depth_fields
        """Whether the ocean evaluates fields 4-6, the pressure at depth and the water's motion below, which the
        mesh hull and seakeeping read (False: they stay zero; a four-point hull reads only the surface)."""
        self._along_y = spectra_along_y_kernel(n, depth_fields)
        self._along_x = fields_along_x_kernel(n, depth_fields)
        self._slots: tuple[wp.array, wp.array] | None = None
        self.update(0.0)

    # --- evaluation -----------------------------------------------------------------------------
    def update(self, t: float | None = None, *, out: wp.array | None = None, clock: wp.array | None = None) -> None:
        """Evaluate all fields at time ``t`` [s] (None: at the time held in ``clock``, a (1,) float64 array
        [s] such as a simulator's, else in :attr:`time`). With ``config.loop_period`` the fields repeat
        exactly: t is taken modulo the loop period. ``out``: a (FIELD_COUNT * n, n) vec2f array to write
        the fields into instead of this ocean's own (the evaluating side of :meth:`read_fields_from`).

        An ocean that reads its fields from slots (:meth:`read_fields_from`) copies the next slot instead.

        Asynchronous on CUDA. Inside a captured graph pass None and advance :attr:`time` with a
        kernel: a Python ``t`` would be frozen into the graph."""
        if self._slots is not None and out is None:
            if t is not None:
                raise ValueError(f"Ocean.update: this ocean reads its fields from slots evaluated elsewhere, so it "
                                 f"cannot evaluate t = {t!r}; update it without a time")
            slots, cursor = self._slots
            wp.launch(copy_slot_fields, dim=self._field_rows.shape[0], device=self.device,
                      inputs=[slots, cursor], outputs=[self._field_rows])
            wp.launch(advance_cursor, dim=1, device=self.device, inputs=[cursor])
            return
        if t is not None:
            if isinstance(t, bool) or not isinstance(t, (int, float, np.floating, np.integer)) or not math.isfinite(t):
                raise ValueError(f"Ocean.update: t must be a finite time in seconds, got {t!r}")
            if abs(t) > self.time_limit:
                raise ValueError(f"Ocean.update: t must be within +-{self.time_limit:.4g} s (beyond it the phase of "
                                 "the grid's fastest wave is no longer exact in float32), got {t!r}")
            self.time.fill_(float(t))
            clock = None
        n = self.config.resolution
        block_dim = self.fft_plan.block_dim
        wp.launch_tiled(self._along_y, dim=[n], inputs=[self._cells, self.time if clock is None else clock,
                                                         self._loop_period, self._levels],
                        outputs=[self._spectra], block_dim=block_dim, device=self.device)
        if out is None:
            out = self._field_rows
        elif out.shape != self._field_rows.shape or out.dtype != wp.vec2f or out.device != self.device:
            raise ValueError(f"Ocean.update: out must be a {self._field_rows.shape} vec2f array on {self.device}, "
                             f"got {out.shape} {wp.types.type_repr(out.dtype)} on {out.device}")
        wp.launch_tiled(self._along_x, dim=[n], inputs=[self._spectra_quads], outputs=[out],
                        block_dim=block_dim, device=self.device)

    def read_fields_from(self, slots: wp.array, cursor: wp.array) -> None:
        """From now on, take the fields from ``slots`` instead of evaluating them: each :meth:`update`
        copies ``slots[cursor[0]]`` into this ocean's fields and adds 1 to ``cursor[0]``.

        For many oceans of one config that would each evaluate the same fields (the workers of
        ``ocean_warp.envs.parallel.sharded``): one evaluates them into the slots with ``update(out=slots[k])``,
        the others copy them, bit for bit the same, at a fraction of the cost. The cursor lives on the
        device, so a captured graph reads whichever slot the cursor names when it is replayed.

        Args:
            slots: (K, FIELD_COUNT * n, n) vec2f, K sets of fields of this ocean's grid.
            cursor: (1,) int32, the slot the next update reads.
        """
        shape = self._field_rows.shape
        if slots.ndim != 3 or slots.shape[1:] != shape or slots.dtype != wp.vec2f or slots.device != self.device:
            raise ValueError(f"Ocean.read_fields_from: slots must be a (K, {shape[0]}, {shape[1]}) vec2f array on "
                             f"{self.device}, got {slots.shape} {wp.types.type_repr(slots.dtype)} on {slots.device}")
        if cursor.shape != (1,) or cursor.dtype != wp.int32 or cursor.device != self.device:
            raise ValueError(f"Ocean.read_fields_from: cursor must be a (1,) int32 array on {self.device}, got "
                             f"{cursor.shape} {wp.types.type_repr(cursor.dtype)} on {cursor.device}")
        self._slots = (slots, cursor)

    # --- sea state ------------------------------------------------------------------------------
    @property
    def spectrum_significant_wave_height(self) -> float:
        """Hs [m] of the spectrum the sea is drawn from now: the config's (for a Pierson-Moskowitz sea given by
        ``wind_speed``, the Hs of that wind's sea), or the last :meth:`set_significant_wave_height`.
        0 for a "regular" ocean."""
        return self._spectrum_hs() * self._amplitude_scale

    def _spectrum_hs(self) -> float:
        config = self.config
        if config.spectrum is Spectrum.REGULAR:
            return 0.0
        if config.spectrum is Spectrum.PIERSON_MOSKOWITZ and config.wind_speed is not None:
            return spectra.pierson_moskowitz_wind_sea_state(config.wind_speed, config.water.gravity)[0]
        return config.significant_wave_height

    def set_significant_wave_height(self, hs: float) -> None:
        """Change the sea state to a significant wave height of ``hs`` [m] (0 to
        ``MAX_SIGNIFICANT_WAVE_HEIGHT``; 0 gives a flat sea), keeping its shape: the same spectrum shape, peak
        period, directions and phases, with every complex amplitude times ``hs / Hs0``, Hs0 the config's
        spectral Hs (see :attr:`spectrum_significant_wave_height`). So every field is exactly that multiple of
        the config's sea at the same time, and ``hs`` means what ``OceanConfig.significant_wave_height``
        means (the grid holds a little less, see :attr:`significant_wave_height`).

        For domain randomisation between rollouts (one sea per ocean; every boat on it shares it). The
        amplitudes are written into the existing device array (no reallocation), so a captured CUDA
        graph that updates this ocean stays valid; the fields change at the next :meth:`update`. Scaled
        from the config's amplitudes every time, so repeated calls do not accumulate rounding.
        Asynchronous copy on CUDA; call it outside a graph capture.

        Raises ``ValueError`` for a bad ``hs``, for a "regular" ocean (one wave of a given amplitude,
        not a spectrum: build an Ocean with another ``amplitude`` instead), and for a config with no
        waves (Hs 0: there is no spectrum to scale; build it with the largest Hs you will use and
        scale down)."""
        owner = "Ocean.set_significant_wave_height"
        hs = require_significant_wave_height(f"{owner}: hs", hs)
        if self.config.spectrum is Spectrum.REGULAR:
            raise ValueError(f"{owner}: a \"regular\" ocean is one wave of OceanConfig.amplitude, not a spectrum "
                             "with a significant wave height; build an Ocean with another amplitude instead")
        base = self._spectrum_hs()
        if base <= 0.0:
            raise ValueError(f"{owner}: this ocean was built with significant_wave_height 0, so it has no spectrum "
                             "to scale; build it with a non-zero Hs (e.g. the largest you will use) and scale that")
        scale = float(hs) / base
        cells = self._base_cells.copy()
        cells[..., :4] = (self._base_cells[..., :4].astype(np.float64) * scale).astype(np.float32)
        self._cells.assign(cells)
        self._amplitude_scale = scale

    # --- reading --------------------------------------------------------------------------------
    def sample(self, xy) -> SurfaceSample:
        """The surface above world points ``xy`` (M, 2) [m] at the last update: height, unit normal and
        water velocity, on the host. Periodic bilinear interpolation; the choppy displacement is
        inverted so the height is the one above the asked point."""
        points = np.asarray(xy, dtype=np.float64)
        if points.ndim == 1 and points.shape == (2,):
            points = points[None, :]
        if points.ndim != 2 or points.shape[1] != 2:
            raise ValueError(f"Ocean.sample: xy must have shape (M, 2) [m], got {points.shape}")
        if not np.all(np.isfinite(points)):
            raise ValueError("Ocean.sample: xy holds NaN or infinite coordinates")
        m = points.shape[0]
        device = self.device
        points_wp = wp.array(points.astype(np.float32), dtype=wp.vec2, device=device)
        heights = wp.empty(m, dtype=float, device=device)
        normals = wp.empty(m, dtype=wp.vec3, device=device)
        velocities = wp.empty(m, dtype=wp.vec3, device=device)
        grid_positions = wp.empty(m, dtype=wp.vec2, device=device)
        if m:
            wp.launch(
                sample_surface_kernel,
                dim=m,
                inputs=[self.surface, points_wp],
                outputs=[heights, normals, velocities, grid_positions],
                device=device,
            )
        return SurfaceSample(heights.numpy(), normals.numpy(), velocities.numpy(), grid_positions.numpy())

    def field_numpy(self, name: str) -> np.ndarray:
        """One real field on the grid as a host array (n, n), index [iy, ix]: "height" [m],
        "vertical_velocity" [m/s], "displacement_x"/"displacement_y" [m] (before choppiness),
        "slope_x"/"slope_y", "velocity_x"/"velocity_y" [m/s]; below the surface, at the depths
        ``config.pressure_depths`` (1, 2, 3): "pressure_head_1/2/3" (dynamic pressure / (rho g)) [m], and at the
        second depth "vertical_velocity_2", "velocity_x_2"/"velocity_y_2" [m/s]."""
        layout = {
            "height": (FIELD_HEIGHT, 0),
            "vertical_velocity": (FIELD_HEIGHT, 1),
            "displacement_x": (FIELD_DISPLACEMENT, 0),
            "displacement_y": (FIELD_DISPLACEMENT, 1),
            "slope_x": (FIELD_SLOPE, 0),
            "slope_y": (FIELD_SLOPE, 1),
            "velocity_x": (FIELD_VELOCITY, 0),
            "velocity_y": (FIELD_VELOCITY, 1),
            "pressure_head_1": (FIELD_PRESSURE_UPPER, 0),
            "pressure_head_2": (FIELD_PRESSURE_UPPER, 1),
            "pressure_head_3": (FIELD_PRESSURE_LOWER, 0),
            "vertical_velocity_2": (FIELD_PRESSURE_LOWER, 1),
            "velocity_x_2": (FIELD_VELOCITY_BELOW, 0),
            "velocity_y_2": (FIELD_VELOCITY_BELOW, 1),
        }
        if name not in layout:
            raise ValueError(f"Ocean.field_numpy: unknown field {name!r}; choose one of {', '.join(layout)}")
        field, component = layout[name]
        return self.fields.numpy()[field, :, :, component]

    def grid_axis(self) -> np.ndarray:
        """World coordinates [m] of the grid nodes along x (and y): (n,)."""
        return np.arange(self.config.resolution) * self.config.cell_size

    @property
    def regular_wave(self) -> RegularWave | None:
        """The wave of a "regular" ocean as laid on the grid (wavevector, frequency), else None."""
        return self.wave_grid.regular_wave

    @property
    def significant_wave_height(self) -> float:
        """4 sqrt(variance) [m] of the sea this grid holds now: the spectrum's Hs
        (:attr:`spectrum_significant_wave_height`) less what falls outside the grid's band (longer than
        the tile, shorter than two cells or ``min_wavelength``). Follows
        :meth:`set_significant_wave_height`."""
        return 4.0 * math.sqrt(self.wave_grid.variance) * self._amplitude_scale
