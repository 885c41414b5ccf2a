"""State-space models of a hull's radiation memory, identified from its frequency-domain coefficients.

Cummins' equation keeps the wave radiation of a hull moving with velocity nu in a convolution,

    (M + A_inf) dnu/dt + mu + ... = tau,    mu(t) = integral of K(t - s) nu(s) ds,

whose kernel's transform is, for each pair of degrees of freedom (row, col),

    K(jw) = B(w) + jw (A(w) - A_inf)

with A(w), B(w) the added mass and damping and A_inf the added mass at infinite frequency. Following Perez and
Fossen (2008, 2009; the MSS FDI toolbox's method, written afresh here) each significant K is fitted in the
frequency domain by a rational function P(s)/Q(s) of order n (2 to 6) that is

- strictly proper with relative degree one (deg P = n - 1), as K decays like 1/w at high frequency;
- zero at s = 0 (P(0) = 0), as a steady velocity radiates no wave: K(0) = B(0) = 0;
- stable: the linearised least squares of Sanathanan and Koerner gives Q, poles in the right half-plane are
  reflected into the left, and P is then refitted to the data by linear least squares.

The fit is realised as a balanced state-space block (a, b, c): dx/dt = a x + b nu[col], mu[row] += c x. The
order is the lowest one whose error (the RMS of |K_fit - K| over the fitted frequencies, relative to the RMS of
|K|) is within ``tolerance``, else the lowest one within 5 % of the best order's error; orders whose poles lie
far outside the fitted frequencies (slower than half the lowest, faster than twenty times the highest), which
no data constrain, are passed over where another order qualifies.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

__all__ = ["KernelFit", "RadiationFit", "DOF_NAMES", "retardation_kernels", "kernel_response", "fit_kernel",
           "significant_terms", "fit_radiation"]

DOF_NAMES = ("surge", "sway", "heave", "roll", "pitch", "yaw")
"""The six rigid degrees of freedom, in the order of the database's rows and columns."""
ORDERS = (2, 3, 4, 5, 6)
"""The orders tried by default."""
DEFAULT_TOLERANCE = 0.02
"""Relative RMS error of K(jw) that an order must reach to be chosen."""
DIAGONAL_THRESHOLD = 1e-3
"""A diagonal kernel is fitted where its largest |K| is at least this fraction of the largest translational one
(times length^2 for rotations, length the cube root of the displaced volume): smaller is numerical noise (a
sphere's yaw, say)."""
COUPLING_THRESHOLD = 0.05
"""A coupling (row != col) is fitted where its largest |K| is at least this fraction of sqrt(max|K_rr| max|K_cc|)."""
SLOWEST_POLE = 0.5
"""A fit's poles must be at least this fraction of the lowest fitted frequency (in magnitude) ..."""
FASTEST_POLE = 20.0
"""... and at most this multiple of the highest, where an order meets that; else every order is a candidate."""
_SK_ITERATIONS = 40


@dataclasses.dataclass(frozen=True)
class KernelFit:
    """One fitted kernel: its state-space block and how well it fits."""

    row: int
    col: int
    a: np.ndarray
    """(n, n) [1/s]: every eigenvalue has a negative real part."""
    b: np.ndarray
    """(n,)."""
    c: np.ndarray
    """(n,): K(jw) = c (jw I - a)^-1 b in the units of B[row, col]."""
    error: float
    """RMS of |K_fit - K| over the fitted frequencies relative to the RMS of |K|."""
    errors_by_order: dict
    """Order tried -> its error."""

    @property
    def order(self) -> int:
        return len(self.b)

    @property
    def name(self) -> str:
        """"heave" for a diagonal term, "sway-roll" for a coupling."""
        return DOF_NAMES[self.row] if self.row == self.col else f"{DOF_NAMES[self.row]}-{DOF_NAMES[self.col]}"


@dataclasses.dataclass(frozen=True)
class RadiationFit:
    """Every significant kernel of a database, fitted."""

    fits: tuple
    """:class:`KernelFit` per (row, col) term, couplings once per pair and per direction (K is symmetric)."""
    band: tuple
    """(low, high) [rad/s]: the frequencies the fits were made over."""

    def describe(self) -> str:
        """One line per fitted term: its order and error."""
        lines = []
        for fit in self.fits:
            if fit.row <= fit.col:
                lines.append(f"  {fit.name:<12} order {fit.order}  error {100 * fit.error:5.2f} %")
        return "\n".join(lines)


def retardation_kernels(frequencies, added_mass, damping, added_mass_infinite) -> np.ndarray:
    """(F, 6, 6) complex K(jw) = B(w) + jw (A(w) - A_inf) from ``frequencies`` (F,) [rad/s], ``added_mass`` and
    ``damping`` (F, 6, 6) and ``added_mass_infinite`` (6, 6)."""
    w = np.asarray(frequencies, dtype=np.float64)[:, None, None]
    return np.asarray(damping) + 1j * w * (np.asarray(added_mass) - np.asarray(added_mass_infinite)[None])


def kernel_response(a, b, c, frequencies) -> np.ndarray:
    """(F,) complex c (jw I - a)^-1 b of one state-space block at ``frequencies`` (F,) [rad/s]."""
    a, b, c = (np.asarray(v, dtype=np.float64) for v in (a, b, c))
    w = np.asarray(frequencies, dtype=np.float64)
    resolvent = 1j * w[:, None, None] * np.eye(len(b))[None] - a[None]
    return np.linalg.solve(resolvent, np.broadcast_to(b, (len(w), len(b)))[..., None])[..., 0] @ c


def _relative_error(model: np.ndarray, data: np.ndarray) -> float:
    return float(np.sqrt(np.sum(np.abs(model - data) ** 2) / max(np.sum(np.abs(data) ** 2), 1e-300)))


def _powers(s: np.ndarray, degree: int) -> np.ndarray:
    """(F, degree + 1) s^0 .. s^degree."""
    return s[:, None] ** np.arange(degree + 1)[None, :]


def _real_rows(matrix: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A complex least-squares problem in real unknowns, as real rows (real parts over imaginary parts)."""
    return np.vstack([matrix.real, matrix.imag]), np.concatenate([rhs.real, rhs.imag])


def _denominator(s: np.ndarray, data: np.ndarray, order: int) -> np.ndarray:
    """Monic Q (coefficients q_0 .. q_n, q_n = 1) by Sanathanan-Koerner iterations on P - K Q = 0, with
    P = p_1 s + ... + p_{n-1} s^(n-1)."""
    powers = _powers(s, order)
    q = np.zeros(order + 1)
    q[-1] = 1.0
    weight = np.ones(len(s))
    for _ in range(_SK_ITERATIONS):
        numerator_columns = powers[:, 1:order]
        denominator_columns = -data[:, None] * powers[:, :order]
        matrix = np.hstack([numerator_columns, denominator_columns]) / weight[:, None]
        rhs = data * powers[:, order] / weight
        rows, values = _real_rows(matrix, rhs)
        scale = np.linalg.norm(rows, axis=0)
        scale[scale == 0] = 1.0
        solution = np.linalg.lstsq(rows / scale, values, rcond=None)[0] / scale
        new_q = np.append(solution[order - 1:], 1.0)
        new_weight = np.abs(powers @ new_q)
        if not np.all(np.isfinite(new_weight)) or new_weight.min() == 0.0:
            break
        change = np.max(np.abs(new_q - q)) / max(np.max(np.abs(new_q)), 1e-300)
        q, weight = new_q, new_weight
        if change < 1e-10:
            break
    return q


def _stable_denominator(q: np.ndarray) -> np.ndarray:
    """Q with its right-half-plane poles reflected into the left half-plane (and poles on the imaginary axis
    moved a little into it)."""
    poles = np.roots(q[::-1])
    size = max(np.max(np.abs(poles)), 1e-12)
    real = -np.abs(poles.real)
    real = np.minimum(real, -1e-3 * np.maximum(np.abs(poles), 1e-3 * size))
    stable = real + 1j * poles.imag
    return np.real(np.poly(stable))[::-1]


def _numerator(s: np.ndarray, data: np.ndarray, q: np.ndarray) -> np.ndarray:
    """p_0 .. p_{n-1} (p_0 = 0) minimising sum |P/Q - K|^2 for the fixed denominator q."""
    order = len(q) - 1
    powers = _powers(s, order)
    denominator = powers @ q
    rows, values = _real_rows(powers[:, 1:order] / denominator[:, None], data)
    solution = np.linalg.lstsq(rows, values, rcond=None)[0]
    return np.concatenate([[0.0], solution])


def _companion(p: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The controllable companion form of P/Q (q monic, deg p < deg q)."""
    order = len(q) - 1
    a = np.zeros((order, order))
    a[:-1, 1:] = np.eye(order - 1)
    a[-1, :] = -q[:order]
    b = np.zeros(order)
    b[-1] = 1.0
    return a, b, np.asarray(p[:order], dtype=np.float64)


def _lyapunov(a: np.ndarray, q: np.ndarray) -> np.ndarray:
    """X with a X + X a^T + q = 0 (a stable), by the Kronecker form (n is at most a dozen)."""
    n = len(a)
    identity = np.eye(n)
    operator = np.kron(identity, a) + np.kron(a, identity)
    x = np.linalg.solve(operator, -q.reshape(-1, order="F")).reshape(n, n, order="F")
    return 0.5 * (x + x.T)


def _square_root(matrix: np.ndarray) -> np.ndarray:
    """L with L L^T = matrix (symmetric, positive semi-definite up to round-off)."""
    values, vectors = np.linalg.eigh(matrix)
    return vectors * np.sqrt(np.clip(values, 0.0, None))[None, :]


def balanced(a, b, c) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The balanced realisation of a stable (a, b, c) (equal, diagonal controllability and observability
    Gramians), with states whose Hankel singular value is below 1e-9 of the largest truncated."""
    a, b, c = (np.asarray(v, dtype=np.float64) for v in (a, b, c))
    controllability = _lyapunov(a, np.outer(b, b))
    observability = _lyapunov(a.T, np.outer(c, c))
    lc, lo = _square_root(controllability), _square_root(observability)
    u, hankel, vt = np.linalg.svd(lo.T @ lc)
    keep = hankel > 1e-9 * hankel[0]
    u, hankel, v = u[:, keep], hankel[keep], vt[keep].T
    root = np.sqrt(hankel)
    transform = lc @ v / root[None, :]
    inverse = (u / root[None, :]).T @ lo.T
    return inverse @ a @ transform, inverse @ b, c @ transform


def fit_kernel(frequencies, kernel, *, orders=ORDERS, tolerance: float = DEFAULT_TOLERANCE, row: int = 0,
               col: int = 0) -> KernelFit:
    """A stable, strictly proper state-space model of one kernel K(jw) (``kernel`` (F,) complex) sampled at
    ``frequencies`` (F,) [rad/s] (see the module's docstring for the method and the choice of order)."""
    w = np.asarray(frequencies, dtype=np.float64)
    data = np.asarray(kernel, dtype=np.complex128)
    if w.ndim != 1 or data.shape != w.shape or len(w) < 2 * max(orders):
        raise ValueError(f"fit_kernel: need (F,) frequencies and kernel values with F >= {2 * max(orders)}, got "
                         f"{w.shape} and {data.shape}")
    if not (np.all(np.isfinite(w)) and np.all(w > 0) and np.all(np.isfinite(data))):
        raise ValueError("fit_kernel: frequencies must be finite and > 0 and the kernel finite")
    omega_scale = math.sqrt(w.min() * w.max())  # the fit runs in s / omega_scale, near 1 over the band
    magnitude = np.max(np.abs(data))
    if magnitude == 0.0:
        raise ValueError("fit_kernel: the kernel is zero at every frequency")
    s, scaled = 1j * w / omega_scale, data / magnitude
    candidates = {}
    for order in orders:
        q = _stable_denominator(_denominator(s, scaled, order))
        p = _numerator(s, scaled, q)
        a, b, c = _companion(p, q)
        # back to rad/s and the data's units: K(s) = magnitude * Kc(s / omega_scale)
        a, b, c = balanced(omega_scale * a, omega_scale * b, magnitude * c)
        candidates[order] = (a, b, c, _relative_error(kernel_response(a, b, c, w), data))
    errors = {order: candidate[3] for order, candidate in candidates.items()}
    # A pole far slower or faster than the data's frequencies is constrained by none of them: an artefact of the
    # least squares (a near-cancelled pole at 0.04 rad/s fitted 0.3-9 rad/s would remember heave for minutes).
    admissible = [order for order in orders
                  if np.all((np.abs(np.linalg.eigvals(candidates[order][0])) >= SLOWEST_POLE * w.min())
                            & (np.abs(np.linalg.eigvals(candidates[order][0])) <= FASTEST_POLE * w.max()))]
    admissible = admissible or list(orders)
    best = min(errors[order] for order in admissible)
    chosen = next((order for order in admissible if errors[order] <= tolerance), None)
    if chosen is None:
        chosen = next(order for order in admissible if errors[order] <= 1.05 * best)
    a, b, c, error = candidates[chosen]
    return KernelFit(row=row, col=col, a=a, b=b, c=c, error=error, errors_by_order=errors)


def significant_terms(kernels: np.ndarray, length: float, *, diagonal_threshold: float = DIAGONAL_THRESHOLD,
                      coupling_threshold: float = COUPLING_THRESHOLD) -> list[tuple[int, int]]:
    """The (row, col) pairs with row <= col worth a state-space block, from ``kernels`` (F, 6, 6) and a length [m]
    of the hull (the cube root of its displaced volume: rotational kernels are compared with translational ones
    times its square): see ``DIAGONAL_THRESHOLD`` and ``COUPLING_THRESHOLD``."""
    peak = np.max(np.abs(kernels), axis=0)
    translational = max(float(np.max(np.diag(peak)[:3])), 1e-300)
    scale = np.array([1.0, 1.0, 1.0, length**2, length**2, length**2]) * translational
    diagonal = [i for i in range(6) if peak[i, i] >= diagonal_threshold * scale[i]]
    pairs = [(i, i) for i in diagonal]
    for i in diagonal:
        for j in diagonal:
            if i < j and peak[i, j] >= coupling_threshold * math.sqrt(peak[i, i] * peak[j, j]):
                pairs.append((i, j))
    return pairs


def fit_radiation(frequencies, added_mass, damping, added_mass_infinite, *, length: float, band=None,
                  orders=ORDERS, tolerance: float = DEFAULT_TOLERANCE,
                  coupling_threshold: float = COUPLING_THRESHOLD) -> RadiationFit:
    """Fit every significant radiation kernel of a database's A(w), B(w) and A_inf (see
    :func:`retardation_kernels`, :func:`significant_terms` for ``length`` [m], :func:`fit_kernel`) over the
    frequencies in ``band`` ((low, high) [rad/s]; default all). A coupling's two directions share one fit of
    (K_rc + K_cr) / 2, K being symmetric. Orders above half the number of fitted frequencies are not tried."""
    w = np.asarray(frequencies, dtype=np.float64)
    kernels = retardation_kernels(w, added_mass, damping, added_mass_infinite)
    low, high = (w.min(), w.max()) if band is None else band
    chosen = (w >= low) & (w <= high)
    pairs = significant_terms(kernels[chosen], length, coupling_threshold=coupling_threshold)
    usable = tuple(order for order in orders if 2 * order <= int(chosen.sum()))
    if not usable:
        raise ValueError(f"fit_radiation: {int(chosen.sum())} frequencies in the band {band} are too few for an "
                         f"order of {min(orders)} (at least {2 * min(orders)})")
    fits = []
    for row, col in pairs:
        data = 0.5 * (kernels[chosen, row, col] + kernels[chosen, col, row])
        fit = fit_kernel(w[chosen], data, orders=usable, tolerance=tolerance, row=row, col=col)
        fits.append(fit)
        if row != col:
            fits.append(dataclasses.replace(fit, row=col, col=row))
    return RadiationFit(fits=tuple(fits), band=(float(w[chosen].min()), float(w[chosen].max())))
