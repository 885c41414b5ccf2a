"""The radiation memory and the diffraction load in the step, against independent numpy solutions."""

import math
import types

import numpy as np
import pytest

import ocean_warp as ow
from ocean_warp.radiation import zero_order_hold
from tests.hull_setups import calm_ocean

RHO, G = 1025.0, 9.81


def heave_database(rng):
    """A stand-in database: a heave kernel K(s) = k s / (s^2 + 2 z w s + w^2) (zero at s = 0, as radiation
    kernels are) and a diagonal A_inf, with coefficients drawn at random."""
    omega, ratio, gain = rng.uniform(3.0, 6.0), rng.uniform(0.3, 0.8), rng.uniform(2500.0, 4000.0)
    a = np.array([[0.0, 1.0], [-omega * omega, -2.0 * ratio * omega]])
    term = types.SimpleNamespace(row=2, col=2, a=a, b=np.array([0.0, 1.0]), c=np.array([0.0, gain]))
    added = np.diag([rng.uniform(5.0, 20.0), rng.uniform(20.0, 60.0), rng.uniform(150.0, 400.0),
                     rng.uniform(1.0, 5.0), rng.uniform(10.0, 40.0), rng.uniform(10.0, 40.0)])
    return types.SimpleNamespace(added_mass_infinite=added, radiation=(term,))


def test_zero_order_hold_matches_the_integral(rng):
    """Phi = e^{A h} and Gamma = int e^{A s} ds B, against a fine numpy quadrature of the same ODE."""
    a = rng.normal(size=(3, 3)) - 3.0 * np.eye(3)
    b = rng.normal(size=3)
    step = 0.05
    phi, gamma = zero_order_hold(a, b, step)
    x, fine = rng.normal(size=3), 20000
    h = step / fine
    y = x.copy()
    for _ in range(fine):  # RK4 with u = 1
        k1 = a @ y + b
        k2 = a @ (y + 0.5 * h * k1) + b
        k3 = a @ (y + 0.5 * h * k2) + b
        k4 = a @ (y + h * k3) + b
        y = y + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    np.testing.assert_allclose(phi @ x + gamma, y, rtol=1e-9, atol=1e-12)


def test_heave_decay_follows_the_single_degree_of_freedom_solution(device, rng):
    """Wall-sided boxes dropped in still water heave as (m + A_inf) z'' + C x_r + rho g A_wp z = 0 with the
    radiation states dx_r/dt = A x_r + B z': the simulator against the exact solution of that linear system, for
    two hull types of one fleet, each with its own database (their terms and states kept apart)."""
    length, beam, height = 2.0, 1.0, 0.6
    drafts = (0.2, float(rng.uniform(0.15, 0.25)))
    databases = (heave_database(rng), heave_database(rng))
    hull = ow.Hull.box(length, beam, height)
    boats = [ow.BoatType(hull=hull, mass=RHO * length * beam * d, seakeeping=db) for d, db in zip(drafts, databases)]
    fleet = ow.Fleet(boats, types=[1, 0, 1], device=device)
    rests = [0.5 * height - d for d in drafts]  # the origin at the box's centre, its bottom at -draft
    drops = rng.uniform(0.02, 0.04, size=3)
    kinds = fleet.model.hull_type.numpy()
    fleet.reset(position=[[5.0 * i, 0.0, rests[k] + drop] for i, (k, drop) in enumerate(zip(kinds, drops))])
    config = ow.SimulatorConfig(dt=0.01, substeps=4, hydrodynamics=ow.HydrodynamicsConfig().without_drag())
    simulator = ow.Simulator(calm_ocean(device), fleet, config)
    steps = 300
    heave = []
    for _ in range(steps):
        simulator.step()
        heave.append(fleet.numpy()["position"][:, 2] - np.array([rests[k] for k in kinds]))
    heave = np.array(heave)

    for boat, (kind, drop) in enumerate(zip(kinds, drops)):
        database = databases[kind]
        term = database.radiation[0]
        total = boats[kind].mass + database.added_mass_infinite[2, 2]
        stiffness = RHO * G * length * beam
        system = np.zeros((4, 4))
        system[0, 1] = 1.0
        system[1, 0] = -stiffness / total
        system[1, 2:] = -term.c / total
        system[2:, 1] = term.b
        system[2:, 2:] = term.a
        state = np.array([drop, 0.0, 0.0, 0.0])
        step_map, _ = zero_order_hold(system, np.zeros(4), config.dt)
        expected = []
        for _ in range(steps):
            state = step_map @ state
            expected.append(state[0])
        expected = np.array(expected)
        assert np.max(np.abs(heave[:, boat] - expected)) < 0.03 * drop
        # The radiation damps it: over the last 1.2 s (a heave period or more) less than 0.8 of the drop is left,
        # where without the memory the box would still swing at its full drop (no other damping here).
        assert np.max(np.abs(heave[-120:, boat])) < 0.8 * drop
