"""The ocean update as a user would write it without ocean_warp: the same eight fields from the same
spectrum, through torch.fft (CPU or CUDA) or numpy.fft, in single precision."""

from __future__ import annotations

import math

import numpy as np


class TorchOceanReference:
    """All fields of ``ocean_warp.Ocean`` via ``torch.fft.ifft2``; ``fields`` is (4, n, n) complex64,
    the same field pairs as the Warp ocean. ``time`` is a 0-d float64 tensor, so a CUDA graph of
    :meth:`update` replays at whatever time it holds."""

    def __init__(self, cells: np.ndarray, device: str):
        import torch

        self.torch = torch
        c = torch.as_tensor(cells, device=device)
        scale = float(cells.shape[0] * cells.shape[1])  # undo ifft2's 1/n^2 once, in the amplitudes
        self.h0 = torch.complex(c[..., 0], c[..., 1]) * scale
        self.h0_mirror = torch.complex(c[..., 2], c[..., 3]) * scale
        self.omega = c[..., 4]
        self.omega_f64 = c[..., 4].double()
        self.i_k = torch.complex(-c[..., 6], c[..., 5])  # i kx - ky
        self.gain = c[..., 7]
        self.time = torch.zeros((), dtype=torch.float64, device=device)
        n = cells.shape[0]
        self.fields = torch.empty((4, n, n), dtype=torch.complex64, device=device)

    def update(self) -> None:
        torch = self.torch
        phase = torch.remainder(self.omega_f64 * self.time, 2 * math.pi).float()
        rotation = torch.polar(torch.ones_like(phase), -phase)  # e^{-i w t}
        forward = self.h0 * rotation
        backward = self.h0_mirror * rotation.conj()
        height = forward + backward
        rate = 1j * self.omega * (backward - forward)
        spectra = torch.stack([height + 1j * rate, self.gain * self.i_k * height, self.i_k * height,
                               self.gain * self.i_k * rate])
        self.fields.copy_(torch.fft.ifft2(spectra))


class NumpyOceanReference:
    """The same with numpy.fft, kept in complex64 throughout (no silent complex128 promotion)."""

    def __init__(self, cells: np.ndarray):
        scale = cells.shape[0] * cells.shape[1]  # undo ifft2's 1/n^2 once, in the amplitudes
        self.h0 = (scale * (cells[..., 0] + 1j * cells[..., 1])).astype(np.complex64)
        self.h0_mirror = (scale * (cells[..., 2] + 1j * cells[..., 3])).astype(np.complex64)
        self.omega_f64 = cells[..., 4].astype(np.float64)
        self.i_omega = (1j * cells[..., 4]).astype(np.complex64)
        self.i_k = (-cells[..., 6] + 1j * cells[..., 5]).astype(np.complex64)
        self.gain_i_k = (cells[..., 7] * self.i_k).astype(np.complex64)
        self.time = 0.0
        self.rotation = np.empty(cells.shape[:2], dtype=np.complex64)
        self.spectra = np.empty((4,) + cells.shape[:2], dtype=np.complex64)
        self.fields = None

    def update(self) -> None:
        phase = np.remainder(self.omega_f64 * self.time, 2 * math.pi).astype(np.float32)
        self.rotation.real = np.cos(phase)
        self.rotation.imag = -np.sin(phase)  # e^{-i w t}
        forward = self.h0 * self.rotation
        backward = self.h0_mirror * np.conj(self.rotation)
        height = forward + backward
        rate = self.i_omega * (backward - forward)
        self.spectra[0] = height + np.complex64(1j) * rate
        np.multiply(self.gain_i_k, height, out=self.spectra[1])
        np.multiply(self.i_k, height, out=self.spectra[2])
        np.multiply(self.gain_i_k, rate, out=self.spectra[3])
        self.fields = np.fft.ifft2(self.spectra)
