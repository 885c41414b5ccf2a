"""The E-Boat's shipped hydrodynamic database (ocean_warp/eboat/eboat_hydrodynamics.json): it is the default
physics hull's, its state-space fits reproduce its own kernels, its BEM data keep the symmetries of the hull,
and the RAOs it gives a free-floating hull have the long-wave limits of linear wave theory (the hull follows the
surface: heave and sway amplitudes one per metre of wave, pitch and roll the wave's slope k)."""

from __future__ import annotations

import numpy as np
import pytest

from ocean_warp.eboat import EBoat
from ocean_warp.hull_form import displaced_volume
from ocean_warp.seakeeping import eboat_hydro_database, hull_fingerprint
from ocean_warp.seakeeping.radiation_fit import FASTEST_POLE, SLOWEST_POLE
from ocean_warp.seakeeping.response import (
    hydrostatic_stiffness,
    response_amplitude_operators,
    rigid_body_mass_matrix,
)

RHO, G = 1025.0, 9.81
SYMMETRIC, ANTISYMMETRIC = (0, 2, 4), (1, 3, 5)


@pytest.fixture(scope="module")
def eboat():
    return EBoat()


@pytest.fixture(scope="module")
def database(eboat):
    return eboat_hydro_database(eboat.hull)


def _band(db) -> np.ndarray:
    low, high = db.provenance["fit_band_rad_s"]
    return (db.frequencies >= low - 1e-9) & (db.frequencies <= high + 1e-9)


def test_it_is_the_default_hulls_at_its_rest_pose_in_sea_water(eboat, database):
    assert database.hull_fingerprint == hull_fingerprint(eboat.hull)
    assert database.water_density == RHO and database.gravity == G
    # upright at rest the hull displaces what it carries (the boat less what keel, bulb and rudder displace)
    displaced = RHO * displaced_volume(eboat.hull, -database.rest_height)
    assert displaced == pytest.approx(eboat.hull_load(RHO), rel=1e-4)
    assert database.rest_height == pytest.approx(eboat.rest_height(), abs=1e-4)  # the simulator's own rest


def test_its_fits_reproduce_its_own_kernels(database):
    """Every fitted term within 2.5 % (relative RMS) of B(w) + jw (A(w) - A_inf) over the fitted frequencies,
    stable, with poles inside the range the data constrain; every term left out is small."""
    band = _band(database)
    kernels = database.kernels()[band]
    fitted = database.radiation_force_response(database.frequencies[band])
    low, high = database.frequencies[band][[0, -1]]
    terms = {(t.row, t.col): t for t in database.radiation}
    assert {(i, i) for i in range(6)} <= set(terms)
    for (row, col), term in terms.items():
        data = 0.5 * (kernels[:, row, col] + kernels[:, col, row])
        error = np.sqrt(np.sum(np.abs(fitted[:, row, col] - data) ** 2) / np.sum(np.abs(data) ** 2))
        assert error < 0.025 and error == pytest.approx(term.fit_error, rel=1e-3, abs=1e-4), (row, col)
        poles = np.linalg.eigvals(term.a)
        assert np.all(poles.real < 0)
        assert np.all((np.abs(poles) >= SLOWEST_POLE * low) & (np.abs(poles) <= FASTEST_POLE * high)), (row, col)
    peak = np.max(np.abs(kernels), axis=0)
    for row in range(6):
        for col in range(6):
            if (row, col) not in terms:
                assert peak[row, col] < 0.05 * np.sqrt(peak[row, row] * peak[col, col]), (row, col)


def test_its_data_keep_the_hulls_symmetries(database):
    """Reciprocity within 8 % (5.4 % in added mass and 7.6 % in damping, both sway-roll: the panels'
    discretisation, halved on twice the panels) and the couplings port-starboard symmetry forbids below 0.1 %
    (each entry scaled by sqrt(max A_ii max A_jj) over the fitted frequencies)."""
    band = _band(database)
    for name in ("added_mass", "damping"):
        data = getattr(database, name)[band]
        scale = np.sqrt(np.outer(*(2 * [np.diagonal(data, axis1=1, axis2=2).max(axis=0)])))
        assert np.max(np.abs(data - data.transpose(0, 2, 1)).max(axis=0) / scale) < 0.08, name
        assert np.max((np.abs(data).max(axis=0) / scale)[np.ix_(SYMMETRIC, ANTISYMMETRIC)]) < 1e-3, name
    # head seas push only surge, heave and pitch (beam seas all six)
    head, beam = database.excitation[band, 0, :], database.excitation[band, 1, :]
    assert np.degrees(database.excitation_headings).tolist() == [180.0, 90.0]
    assert np.max(np.abs(head[:, ANTISYMMETRIC]) / np.abs(beam[:, ANTISYMMETRIC]).max(axis=0)) < 1e-3


def test_a_free_floating_hull_follows_long_waves(eboat, database):
    """At w = 0.3 rad/s (wavelength 685 m) the hull in equilibrium (its displaced mass, the centre of mass over
    the centre of buoyancy) heaves 1 m per metre of wave in head seas and pitches with the slope k; in beam seas
    it sways 1 m per metre and rolls with the slope."""
    volume = displaced_volume(eboat.hull, -database.rest_height)
    mass = RHO * volume
    upright = hydrostatic_stiffness(eboat.hull, database.rest_height, mass, (0.0, 0.0, 0.0))
    center_of_buoyancy_x = -upright[3, 5] / (RHO * G * volume)  # C46 = -rho g V x_B with x_G = 0
    center = (center_of_buoyancy_x, 0.0, float(eboat.mass_properties.center_of_mass[2]))
    mass_matrix = rigid_body_mass_matrix(mass, center, eboat.mass_properties.inertia)
    stiffness = hydrostatic_stiffness(eboat.hull, database.rest_height, mass, center)
    assert abs(stiffness[3, 5]) < 1e-6 * stiffness[3, 3]
    k = database.frequencies[0] ** 2 / G
    head = response_amplitude_operators(database, mass_matrix, stiffness, heading_deg=180.0)[0]
    beam = response_amplitude_operators(database, mass_matrix, stiffness, heading_deg=90.0)[0]
    assert abs(head[2]) == pytest.approx(1.0, rel=0.01) and abs(head[4]) == pytest.approx(k, rel=0.02)
    assert abs(beam[1]) == pytest.approx(1.0, rel=0.01) and abs(beam[3]) == pytest.approx(k, rel=0.02)
