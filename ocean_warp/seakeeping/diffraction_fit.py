"""Fitting a hull's diffraction weights to a BEM's wave excitation.

Held still in a regular wave, a hull in the simulator feels the Froude-Krylov pressure over its panels
(:mod:`ocean_warp.seakeeping.panel_pressure`) and the diffraction load of the relative-motion form: the effective
water velocity V = W s of its wave points (:mod:`ocean_warp.seakeeping.wave_points`) loads it through A_inf dV/dt
and the radiation memory driven by -V, in the frequency domain Z(w) V with Z = i w A_inf + K(i w), K the fitted
kernels. The weights W (6 x 33 x 4, constant over frequency) are the regularised least squares that make FK_panels
+ Z W s match the BEM's excitation (its Froude-Krylov plus diffraction forces) over the frequencies the panels
resolve and the headings all round, each residual relative to the excitation it corrects (at least 5 % of that
degree of freedom's largest over the headings at that frequency: where the ends of the hull cancel each other's
loads, or symmetry leaves none), so that short waves count as much as long ones. A uniform flow gives V its
velocity exactly, and a uniform pressure head nothing (a current neither turns nor lifts the hull; long waves see
the rigid-motion limit).

The rigid-motion fit of the velocities (:func:`ocean_warp.seakeeping.wave_points.rigid_motion_weights`, the
long-wave approximation) is one W among those this searches: on the E-Boat it leaves the excitation off by up to
4x in head seas shorter than 1.25 s, where the hull spans more than a wavelength.
"""

from __future__ import annotations

import numpy as np

from .diffraction_weights import DiffractionWeights
from .wave_points import WAVE_POINT_COUNT, WAVE_POINT_INPUTS, regular_wave_inputs

__all__ = ["FIT_HEADINGS_DEG", "fit_diffraction_weights", "simulated_excitation"]

FIT_HEADINGS_DEG = tuple(float(h) for h in np.arange(0.0, 360.0, 15.0))
"""Wave headings [deg] the weights are fitted over: every 15 deg."""
FLOOR_FRACTION = 0.05
"""A residual is relative to its excitation, or to this fraction of the DOF's largest over the headings at that
frequency, whichever is larger (1 % of the largest over all frequencies weighs beam-sea roll less: 15 % off at
1-1.25 s, against 7 %)."""
REGULARISATION = 1e-3
"""Ridge weight, relative to the mean diagonal of the column-scaled normal equations (chosen on headings between
the fitted ones: 1e-4 fits them as well and generalises worse)."""


def simulated_excitation(weights: DiffractionWeights, frequencies, impedance, froude_krylov, headings,
                         gravity: float) -> np.ndarray:
    """(F, H, 6) complex: FK_panels + Z(w) W s(w, heading) for ``impedance`` (F, 6, 6) and ``froude_krylov``
    (F, H, 6) (per metre of wave amplitude, phase against the elevation at the body origin)."""
    out = np.array(froude_krylov, dtype=np.complex128)
    for f, omega in enumerate(frequencies):
        for h, heading in enumerate(headings):
            s = regular_wave_inputs(weights.points, omega, heading, weights.velocity_depth, weights.pressure_depth,
                                    gravity)
            out[f, h] += impedance[f] @ weights.effective_velocity(s)
    return out


def _uniform_flow_constraints() -> tuple[np.ndarray, np.ndarray]:
    """(C, d) with C x = d: sum over points of W[i, :, c] is 1 for c = i < 3 (a uniform flow is V's velocity),
    0 otherwise."""
    unknowns = 6 * WAVE_POINT_COUNT * WAVE_POINT_INPUTS
    rows, values = [], []
    for i in range(6):
        for c in range(WAVE_POINT_INPUTS):
            row = np.zeros((6, WAVE_POINT_COUNT, WAVE_POINT_INPUTS))
            row[i, :, c] = 1.0
            rows.append(row.reshape(unknowns))
            values.append(1.0 if (i == c and i < 3) else 0.0)
    return np.array(rows), np.array(values)


def fit_diffraction_weights(points, frequencies, impedance, excitation, froude_krylov, headings, *,
                            pressure_depths, gravity: float) -> DiffractionWeights:
    """The weights (module docstring) for wave points at ``points`` (33, 2) [m] from the BEM's ``excitation``
    (F, H, 6) and the panels' ``froude_krylov`` (F, H, 6) (complex, per metre of wave amplitude) at
    ``frequencies`` (F,) [rad/s] and ``headings`` (H,) [rad], with ``impedance`` (F, 6, 6) = i w A_inf + K(i w);
    the points read velocities at the middle of ``pressure_depths`` (3,) [m, positive down] and pressure heads at
    the deepest."""
    frequencies = np.asarray(frequencies, dtype=np.float64)
    headings = np.asarray(headings, dtype=np.float64)
    excitation = np.asarray(excitation, dtype=np.complex128)
    depths = tuple(float(v) for v in pressure_depths)
    velocity_depth, pressure_depth = depths[1], depths[2]
    target = excitation - np.asarray(froude_krylov, dtype=np.complex128)
    floor = FLOOR_FRACTION * np.abs(excitation).max(axis=1, keepdims=True)
    floor = np.where(floor > 0, floor, 1.0)
    scale = 1.0 / np.maximum(np.abs(excitation), floor)  # (F, H, 6)
    blocks, rhs = [], []
    for f, omega in enumerate(frequencies):
        for h, heading in enumerate(headings):
            s = regular_wave_inputs(points, omega, heading, velocity_depth, pressure_depth, gravity).reshape(-1)
            # row i: sum_j Z[i, j] sum_q W[j, q] s[q]
            blocks.append(np.kron(impedance[f], s[None, :]) * scale[f, h][:, None])
            rhs.append(target[f, h] * scale[f, h])
    matrix, values = np.concatenate(blocks), np.concatenate(rhs)
    matrix, values = np.vstack([matrix.real, matrix.imag]), np.concatenate([values.real, values.imag])
    columns = np.linalg.norm(matrix, axis=0)
    columns = np.where(columns > 0, columns, 1.0)
    scaled = matrix / columns
    normal = scaled.T @ scaled
    normal += REGULARISATION * np.trace(normal) / len(normal) * np.eye(len(normal))
    constraints, constraint_values = _uniform_flow_constraints()
    constraints = constraints / columns
    size, extra = len(normal), len(constraints)
    kkt = np.zeros((size + extra, size + extra))
    kkt[:size, :size], kkt[:size, size:], kkt[size:, :size] = normal, constraints.T, constraints
    solution = np.linalg.solve(kkt, np.concatenate([scaled.T @ values, constraint_values]))[:size] / columns
    weights = solution.reshape(6, WAVE_POINT_COUNT, WAVE_POINT_INPUTS)
    fitted = DiffractionWeights(points=points, weights=weights, velocity_depth=velocity_depth,
                                pressure_depth=pressure_depth, pressure_depths=depths)
    simulated = simulated_excitation(fitted, frequencies, impedance, froude_krylov, headings, gravity)
    relative = np.abs(simulated - excitation) * scale
    error = float(np.sqrt(np.mean(relative[..., 2:5] ** 2)))
    return DiffractionWeights(points=points, weights=weights, velocity_depth=velocity_depth,
                              pressure_depth=pressure_depth, pressure_depths=depths, fit_error=error)
