"""The radiation memory of Cummins' equation as a few states per boat, and the wave-diffraction load.

A hull moving in water radiates waves; their force is the convolution of the hull's velocity history with
its retardation kernels, mu(t) = int K(t - s) nu_r(s) ds (Cummins 1962). A hull's hydrodynamic database
(``ocean_warp.seakeeping``) replaces each significant kernel K_ij by a small state-space model,
dx/dt = A x + B nu_r[j], mu_i += C x; here each model advances by its exact zero-order-hold step,
x <- Phi x + Gamma nu_r[j] (Phi = e^{A h}, Gamma = int_0^h e^{A s} ds B, computed once on the host for the
substep h). The velocity that drives them is the hull's relative to the water's orbital motion at the
ocean's middle depth, fitted as a rigid motion over a grid of points under the hull
(``kernels.hull_forces.water_motion_under_hull``: the relative-motion form, in which a hull that moves with
the water radiates nothing), and the acceleration of that motion loads the hull through the infinite-frequency
added mass (the diffraction correction of relative-motion strip theory: waves short against the hull average
out over the grid, as they do in the Froude-Krylov pressure).

Layout: the terms of hull type t are ``first_term[t]`` .. ``first_term[t + 1] - 1``; term e couples DOF
``column[e]`` into DOF ``row[e]`` (0..5: surge, sway, heave, roll, pitch, yaw) through ``order[e]`` states
at ``state_offset[e]`` in the boat's block of ``states_per_boat``, its coefficients at ``coefficient_offset[e]``
in ``coefficients``: Phi (order x order, row-major), then Gamma (order), then C (order).
"""

from __future__ import annotations

import warp as wp

from .spatial import vec6

__all__ = ["RadiationModel", "MAX_TERM_ORDER", "radiation_force", "advance_radiation", "diffraction_wrench",
           "reset_radiation_masked"]

MAX_TERM_ORDER = wp.constant(8)
"""Most states of one kernel's model."""
_term_vector = wp.types.vector(length=8, dtype=wp.float32)


@wp.struct
class RadiationModel:
    """Every hull type's radiation models, discretised for one substep (see the module's docstring)."""

    first_term: wp.array(dtype=int)
    """(types + 1,) index of each type's first term; the last entry is the number of terms."""
    row: wp.array(dtype=int)
    column: wp.array(dtype=int)
    order: wp.array(dtype=int)
    state_offset: wp.array(dtype=int)
    coefficient_offset: wp.array(dtype=int)
    coefficients: wp.array(dtype=float)
    """Phi [-], Gamma [s, in the units of x per unit of nu_r] and C [N or N m per unit of x], per term."""
    added_mass_infinite: wp.array(dtype=wp.types.matrix(shape=(6, 6), dtype=wp.float32))
    """(types,) A_inf [kg, kg m, kg m^2] of the types with a database (zero for the others)."""
    has_database: wp.array(dtype=int)
    """(types,) 1 where the type has a hydrodynamic database (radiation and diffraction on)."""
    states_per_boat: int
    """Length of each boat's block of ``radiation_state``."""


@wp.func
def radiation_force(model: RadiationModel, kind: int, boat: int, state: wp.array(dtype=float)) -> vec6:
    """mu = sum over the type's terms of C x: the radiation memory force [N] and moment [N m], body frame,
    about the origin (it acts against the motion: the equations of motion subtract it)."""
    mu = vec6()
    block = boat * model.states_per_boat
    for term in range(model.first_term[kind], model.first_term[kind + 1]):
        order = model.order[term]
        first = block + model.state_offset[term]
        c = model.coefficient_offset[term] + order * order + order
        total = float(0.0)
        for i in range(order):
            total += model.coefficients[c + i] * state[first + i]
        row = model.row[term]
        mu[row] = mu[row] + total
    return mu


@wp.func
def advance_radiation(model: RadiationModel, kind: int, boat: int, nu_r: vec6, state: wp.array(dtype=float)):
    """x <- Phi x + Gamma nu_r[column] for every term of the boat's type (exact for nu_r held over the substep)."""
    block = boat * model.states_per_boat
    for term in range(model.first_term[kind], model.first_term[kind + 1]):
        order = model.order[term]
        first = block + model.state_offset[term]
        phi = model.coefficient_offset[term]
        gamma = phi + order * order
        drive = nu_r[model.column[term]]
        old = _term_vector()
        for i in range(order):
            old[i] = state[first + i]
        for i in range(order):
            total = model.coefficients[gamma + i] * drive
            for j in range(order):
                total += model.coefficients[phi + i * order + j] * old[j]
            state[first + i] = total


@wp.func
def diffraction_wrench(model: RadiationModel, kind: int, water_acceleration: vec6) -> vec6:
    """A_inf times the acceleration of the water's rigid motion under the hull (body frame [m/s^2, rad/s^2],
    about the origin) as a wrench [N, N m] about the origin."""
    return model.added_mass_infinite[kind] * water_acceleration


@wp.kernel(enable_backward=False)
def reset_radiation_masked(mask: wp.array(dtype=wp.int32), states_per_boat: int, state: wp.array(dtype=float)):
    """Zero the radiation states of every boat whose ``mask`` is non-zero (launch dim (boats, states_per_boat))."""
    boat, index = wp.tid()
    if mask[boat] != 0:
        state[boat * states_per_boat + index] = 0.0
