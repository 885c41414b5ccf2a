"""The radiation memory of Cummins' equation as a few states per boat, and the wave-diffraction load.

A hull moving in water radiates waves; their force is the convolution of the hull's velocity history with
its retardation kernels, mu(t) = int K(t - s) nu_r(s) ds (Cummins 1962). A hull's hydrodynamic database
(``ocean_warp.seakeeping``) replaces each significant kernel K_ij by a small state-space model,
dx/dt = A x + B nu_r[j], mu_i += C x; here each model advances by its exact zero-order-hold step,
x <- Phi x + Gamma nu_r[j] (Phi = e^{A h}, Gamma = int_0^h e^{A s} ds B, computed once on the host for the
substep h). The velocity that drives them is the hull's relative to the water's effective velocity V under
it (``kernels.hull_forces.water_motion_under_hull``: the relative-motion form, in which a hull that moves with
the water radiates nothing), and the rate of change of V loads the hull through the infinite-frequency added
mass: the diffraction load. V is a weighted sum of what a grid of points under the hull reads of the ocean
(velocities at its middle depth, pressure heads at its deepest), the weights the database's, fitted so that
this load and the panels' Froude-Krylov pressure give the BEM's wave excitation at every heading
(``ocean_warp.seakeeping.diffraction_fit``); without them, the rigid motion that fits the velocities.

Layout: the terms of hull type t are ``first_term[t]`` .. ``first_term[t + 1] - 1``; term e couples DOF
``column[e]`` into DOF ``row[e]`` (0..5: surge, sway, heave, roll, pitch, yaw) through ``order[e]`` states
from state index ``state_offset[e]`` of the boat's ``states_per_boat``, its coefficients at
``coefficient_offset[e]`` in ``coefficients``: Phi (order x order, row-major), then Gamma (order), then C (order).
The states are stored index-major, state i of boat b at ``i * boats + b``, so that neighbouring threads (boats)
read neighbouring words.
"""

from __future__ import annotations

import warp as wp

from .hull_forces import NO_WAVE_HISTORY
from .seakeeping_frame import heading_tilt, to_heading_frame
from .spatial import vec6

FROZEN = wp.constant(1)
"""``kernels.rigid_body.STATUS_NONFINITE``: a boat frozen at its last finite state."""
__all__ = ["RadiationModel", "MAX_TERM_ORDER", "radiation_force", "advance_radiation_terms", "diffraction_wrench",
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
    """The radiation states of each boat (``radiation_state`` holds states_per_boat x boats)."""
    max_terms: int
    """The most terms of any type (``radiation_output`` holds terms x boats, and the term kernel's second
    launch dimension)."""


@wp.func
def radiation_force(model: RadiationModel, kind: int, boat: int, output: wp.array(dtype=float)) -> vec6:
    """mu: the radiation memory force [N] and moment [N m], heading frame, about the origin (it acts against the
    motion: the equations of motion subtract it), summed from the terms' outputs C x (written by
    :func:`advance_radiation_terms`: the type's term k of boat b at ``output[k N + b]``)."""
    mu = vec6()
    boats = output.shape[0] / model.max_terms
    first = model.first_term[kind]
    for term in range(first, model.first_term[kind + 1]):
        row = model.row[term]
        mu[row] = mu[row] + output[(term - first) * boats + boat]
    return mu


@wp.kernel(enable_backward=False)
def advance_radiation_terms(
    model: RadiationModel,
    hull_type: wp.array(dtype=int),
    velocity: wp.array(dtype=vec6),
    orientation: wp.array(dtype=wp.quat),
    wave_velocity: wp.array(dtype=vec6),
    status: wp.array(dtype=int),
    state: wp.array(dtype=float),
    output: wp.array(dtype=float),
):
    """One substep of every boat's radiation terms (launch dim (boats, most terms of a type)): x <- Phi x +
    Gamma nu_r[column], nu_r the hull's velocity relative to the water's motion under it, in the heading frame
    (``kernels.seakeeping_frame``, as are the outputs) (a boat
    before its first substep, with no water motion yet, counts it at rest), and the term's output C x for the
    next substep's equations of motion (the type's term k of boat b at ``k N + b``). A boat flagged non-finite keeps its states."""
    boat, local = wp.tid()
    kind = hull_type[boat]
    term = model.first_term[kind] + local
    if term >= model.first_term[kind + 1] or (status[boat] & FROZEN) != 0:
        return
    boats = hull_type.shape[0]
    wave = wave_velocity[boat]
    if wave[0] == NO_WAVE_HISTORY:
        wave = vec6()
    rotation = orientation[boat]
    linear = wp.quat_rotate_inv(rotation, wp.vec3(wave[0], wave[1], wave[2]))
    angular = wp.quat_rotate_inv(rotation, wp.vec3(wave[3], wave[4], wave[5]))
    nu = velocity[boat]
    relative = nu - vec6(linear[0], linear[1], linear[2], angular[0], angular[1], angular[2])
    relative = to_heading_frame(heading_tilt(rotation), relative)
    drive = relative[model.column[term]]
    order = model.order[term]
    first = model.state_offset[term] * boats + boat
    phi = model.coefficient_offset[term]
    gamma = phi + order * order
    c = gamma + order
    old = _term_vector()
    for i in range(order):
        old[i] = state[first + i * boats]
    total_output = float(0.0)
    for i in range(order):
        value = model.coefficients[gamma + i] * drive
        for j in range(order):
            value += model.coefficients[phi + i * order + j] * old[j]
        state[first + i * boats] = value
        total_output += model.coefficients[c + i] * value
    output[local * boats + boat] = total_output


@wp.func
def diffraction_wrench(model: RadiationModel, kind: int, water_acceleration: vec6) -> vec6:
    """A_inf times the rate of change of the water's effective velocity under the hull (body frame [m/s^2,
    rad/s^2], about the origin) as a wrench [N, N m] about the origin."""
    return model.added_mass_infinite[kind] * water_acceleration


@wp.kernel(enable_backward=False)
def reset_radiation_masked(mask: wp.array(dtype=wp.int32), state: wp.array(dtype=float),
                           output: wp.array(dtype=float)):
    """Zero the radiation states and outputs of every boat whose ``mask`` is non-zero (launch dim (boats,
    max(states per boat, terms)))."""
    boat, index = wp.tid()
    if mask[boat] == 0:
        return
    boats = mask.shape[0]
    if index * boats + boat < state.shape[0]:
        state[index * boats + boat] = 0.0
    if index * boats + boat < output.shape[0]:
        output[index * boats + boat] = 0.0
