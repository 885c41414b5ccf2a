"""Host side of the radiation memory: each hull type's state-space models, discretised for one substep, as
the ``RadiationModel`` struct the integrator reads (``ocean_warp.kernels.radiation``)."""

from __future__ import annotations

import numpy as np
import warp as wp

from .kernels.radiation import MAX_TERM_ORDER, RadiationModel

__all__ = ["radiation_states_per_boat", "radiation_terms_per_boat", "radiation_model", "zero_order_hold",
           "check_wave_point_depths"]


def _terms(boat_type) -> tuple:
    database = getattr(boat_type, "seakeeping", None)
    return () if database is None else tuple(database.radiation)


def radiation_states_per_boat(boat_types) -> int:
    """The largest number of radiation states of any of ``boat_types`` (each boat gets a block this long)."""
    return max((sum(len(term.b) for term in _terms(t)) for t in boat_types), default=0)


def radiation_terms_per_boat(boat_types) -> int:
    """The most radiation terms of any of ``boat_types``."""
    return max((len(_terms(t)) for t in boat_types), default=0)


def _matrix_exponential(matrix: np.ndarray) -> np.ndarray:
    """e^M by scaling and squaring with a Taylor series (float64; for the small matrices of a fit)."""
    norm = float(np.abs(matrix).sum(axis=1).max()) if matrix.size else 0.0
    squarings = max(0, int(np.ceil(np.log2(norm / 0.25))) if norm > 0.25 else 0)
    scaled = matrix / 2.0**squarings
    result = np.eye(len(matrix))
    power = np.eye(len(matrix))
    for k in range(1, 18):
        power = power @ scaled / k
        result = result + power
    for _ in range(squarings):
        result = result @ result
    return result


def zero_order_hold(a: np.ndarray, b: np.ndarray, step: float) -> tuple[np.ndarray, np.ndarray]:
    """(Phi, Gamma) of dx/dt = A x + B u over ``step`` [s] with u held: Phi = e^{A h}, Gamma = int_0^h e^{A s} ds B
    (from the exponential of the augmented matrix [[A, B], [0, 0]] h)."""
    order = len(b)
    augmented = np.zeros((order + 1, order + 1))
    augmented[:order, :order] = a
    augmented[:order, order] = b
    exponential = _matrix_exponential(augmented * step)
    return exponential[:order, :order], exponential[:order, order]


def radiation_model(boat_types, substep: float, device) -> RadiationModel:
    """Every type's radiation terms discretised for ``substep`` [s] (types without a database have none)."""
    first_term, rows, columns, orders, state_offsets, coefficient_offsets = [0], [], [], [], [], []
    coefficients: list[float] = []
    added_mass = np.zeros((len(boat_types), 6, 6), dtype=np.float32)
    has_database = np.zeros(len(boat_types), dtype=np.int32)
    for index, boat_type in enumerate(boat_types):
        database = getattr(boat_type, "seakeeping", None)
        if database is not None:
            has_database[index] = 1
            added_mass[index] = database.added_mass_infinite
        state = 0
        for term in _terms(boat_type):
            order = len(term.b)
            if order > MAX_TERM_ORDER:
                raise ValueError(f"radiation term ({term.row}, {term.col}) of {boat_type.name!r} has {order} states; "
                                 f"at most {MAX_TERM_ORDER} are supported")
            phi, gamma = zero_order_hold(np.asarray(term.a, float), np.asarray(term.b, float), substep)
            rows.append(term.row)
            columns.append(term.col)
            orders.append(order)
            state_offsets.append(state)
            coefficient_offsets.append(len(coefficients))
            coefficients += list(phi.ravel()) + list(gamma) + list(np.asarray(term.c, float))
            state += order
        first_term.append(len(rows))
    model = RadiationModel()
    as_int = lambda values: wp.array(np.asarray(values, dtype=np.int32).reshape(-1), dtype=int,  # noqa: E731
                                     device=device)
    model.first_term = as_int(first_term)
    model.row = as_int(rows or [0])
    model.column = as_int(columns or [0])
    model.order = as_int(orders or [0])
    model.state_offset = as_int(state_offsets or [0])
    model.coefficient_offset = as_int(coefficient_offsets or [0])
    model.coefficients = wp.array(np.asarray(coefficients or [0.0], dtype=np.float32), dtype=float, device=device)
    model.added_mass_infinite = wp.array(added_mass, dtype=wp.types.matrix(shape=(6, 6), dtype=wp.float32),
                                         device=device)
    model.has_database = wp.array(has_database, dtype=int, device=device)
    model.states_per_boat = radiation_states_per_boat(boat_types)
    model.max_terms = radiation_terms_per_boat(boat_types)
    return model


def check_wave_point_depths(boat_types, pressure_depths) -> None:
    """``ValueError`` (one line) where a type's diffraction weights were fitted for other ocean pressure depths than
    ``pressure_depths`` (3,) [m, positive down], the ones its wave points will read."""
    depths = tuple(float(v) for v in pressure_depths)
    for boat_type in boat_types:
        fitted = getattr(getattr(boat_type, "seakeeping", None), "diffraction", None)
        if fitted is None:
            continue
        assumed = fitted.pressure_depths or (depths[0], fitted.velocity_depth, fitted.pressure_depth)
        if not np.allclose(assumed, depths, rtol=0.0, atol=1e-6):
            raise ValueError(f"boat type {boat_type.name!r}: its hydrodynamic database's diffraction weights were "
                             f"fitted for ocean pressure depths {list(assumed)} m, the ocean has {list(depths)} m "
                             "(OceanConfig.pressure_depths): recompute the database or use those depths")
