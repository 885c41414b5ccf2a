"""Linear seakeeping helpers (ocean_warp.seakeeping.response): the rigid-body mass matrix about the body origin,
the hydrostatic stiffness of a hull against a box's closed forms, and the natural period."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ocean_warp.hull import Hull
from ocean_warp.seakeeping import hull_fingerprint, natural_period
from ocean_warp.seakeeping.database import HydroDatabase
from ocean_warp.seakeeping.response import hydrostatic_stiffness, rigid_body_mass_matrix

RHO, G = 1025.0, 9.81


def test_mass_matrix_gives_the_kinetic_energy(rng):
    """1/2 nu^T M nu is the kinetic energy of a body whose centre of mass moves with v + omega x r_g and spins
    with omega against I_g, for random velocities and mass properties."""
    for _ in range(5):
        mass = rng.uniform(1.0, 200.0)
        r_g = rng.normal(size=3)
        root = rng.normal(size=(3, 3))
        inertia = root @ root.T + np.eye(3)
        nu = rng.normal(size=6)
        v, omega = nu[:3], nu[3:]
        expected = 0.5 * mass * np.sum((v + np.cross(omega, r_g)) ** 2) + 0.5 * omega @ inertia @ omega
        matrix = rigid_body_mass_matrix(mass, r_g, inertia)
        assert 0.5 * nu @ matrix @ nu == pytest.approx(expected, rel=1e-12)
        np.testing.assert_allclose(matrix, matrix.T, atol=1e-12)


def test_box_hydrostatic_stiffness_matches_the_closed_forms():
    """A box L x B x H centred at (xc, 0, 0), floating at draft T with its body origin h above the water and
    its centre of mass at (xc, 0, zg): C33 = rho g L B, C35 = -rho g L B xc, C55 = rho g (B L^3/12 + L B xc^2 +
    V z_B) - m g z_G, C44 = rho g (L B^3/12 + V z_B) - m g z_G, z_B = -h - T/2."""
    length, beam, height, xc = 2.0, 0.8, 0.6, 0.3
    box = Hull.box(length, beam, height, subdivisions=1)
    box = Hull(box.vertices + np.array([xc, 0.0, 0.0]), box.triangles)
    draft = 0.2
    rest_height = height / 2 - draft  # the bottom at -height/2
    volume = length * beam * draft
    mass, z_g = RHO * volume, 0.05
    c = hydrostatic_stiffness(box, rest_height, mass, (xc, 0.0, z_g), water_density=RHO, gravity=G)
    z_b = -rest_height - draft / 2
    assert c[2, 2] == pytest.approx(RHO * G * length * beam, rel=1e-12)
    assert c[2, 4] == pytest.approx(-RHO * G * length * beam * xc, rel=1e-12) and c[4, 2] == c[2, 4]
    assert c[3, 3] == pytest.approx(RHO * G * (length * beam**3 / 12 + volume * z_b) - mass * G * z_g, rel=1e-12)
    assert c[4, 4] == pytest.approx(RHO * G * (beam * length**3 / 12 + length * beam * xc**2 + volume * z_b)
                                    - mass * G * z_g, rel=1e-12)
    # in equilibrium (x_G = x_B): no yaw terms; symmetric about y = 0: no heave-roll or roll-pitch terms
    np.testing.assert_allclose(c[:, 5], 0.0, atol=1e-9)
    assert abs(c[2, 3]) < 1e-9 and abs(c[3, 4]) < 1e-9
    np.testing.assert_allclose(c[:2], 0.0, atol=0.0)


def test_hydrostatic_stiffness_of_a_hull_out_of_the_water_is_refused():
    box = Hull.box(2.0, 1.0, 0.6)
    with pytest.raises(ValueError, match="out of the water at rest height 0.5"):
        hydrostatic_stiffness(box, 0.5, 100.0, (0.0, 0.0, 0.0))


def _flat_database(hull: Hull, added: float) -> HydroDatabase:
    w = np.geomspace(0.1, 50.0, 30)
    matrix = np.eye(6) * added
    return HydroDatabase(hull_name=hull.name, hull_fingerprint=hull_fingerprint(hull), water_density=RHO, gravity=G,
                         rest_height=0.0, frequencies=w, added_mass=np.broadcast_to(matrix, (len(w), 6, 6)),
                         damping=np.zeros((len(w), 6, 6)), added_mass_infinite=matrix, radiation=())


def test_natural_period_of_a_constant_added_mass_is_the_textbook_one():
    db = _flat_database(Hull.box(1.0, 1.0, 1.0), 300.0)
    assert natural_period(db, 158.0, 14_800.0, 2) == pytest.approx(2 * math.pi * math.sqrt(458.0 / 14_800.0),
                                                                   rel=1e-9)
    assert math.isnan(natural_period(db, 158.0, -1.0, 3))
