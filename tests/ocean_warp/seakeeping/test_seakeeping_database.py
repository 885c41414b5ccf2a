"""The hydrodynamic database (ocean_warp.seakeeping.database) and the state-space identification of its radiation
kernels (radiation_fit): known rational kernels recovered, fits stable, the file's round trip, and one-line
refusals of files that cannot be trusted. No BEM here: the data are built from kernels known in closed form."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest

from ocean_warp.hull import Hull
from ocean_warp.seakeeping import (
    FORMAT_VERSION,
    HydroDatabase,
    NoHydroDatabaseWarning,
    RadiationTerm,
    database_for,
    fit_kernel,
    fit_radiation,
    hull_fingerprint,
)

FREQUENCIES = np.geomspace(0.3, 30.0, 50)

# A known kernel: K(s) = s (2 + 5 s + s^2) / ((s^2 + s + 4.25)(s^2 + 6 s + 10)), poles -0.5 +- 2j and -3 +- 1j,
# zero at s = 0, relative degree one: what a radiation kernel looks like.
KNOWN_POLES = np.array([-0.5 + 2j, -0.5 - 2j, -3 + 1j, -3 - 1j])


def known_kernel(omega, gain: float = 1.0) -> np.ndarray:
    s = 1j * np.asarray(omega)
    return gain * s * (2 + 5 * s + s**2) / ((s**2 + s + 4.25) * (s**2 + 6 * s + 10))


def coefficients_from_kernel(kernel: np.ndarray, omega, infinite: float) -> tuple[np.ndarray, np.ndarray]:
    """A(w) and B(w) whose K(jw) = B + jw (A - A_inf) is ``kernel``."""
    return infinite + kernel.imag / omega, kernel.real


def synthetic_database(hull: Hull, **overrides) -> HydroDatabase:
    """A database for ``hull`` whose heave, sway and roll kernels are the known one x 1000 N s/m, x 200 N s/m and
    x 10 N m s, and whose sway-roll coupling is the known one x 30 N s, each fitted; no memory in the others."""
    w = FREQUENCIES
    added = np.zeros((len(w), 6, 6))
    damping = np.zeros((len(w), 6, 6))
    infinite = np.diag([10.0, 20.0, 300.0, 5.0, 60.0, 2.0])
    added[:] = infinite  # no memory but in the terms below
    for (row, col), gain in (((2, 2), 1000.0), ((1, 1), 200.0), ((3, 3), 10.0), ((1, 3), 30.0), ((3, 1), 30.0)):
        added[:, row, col], damping[:, row, col] = coefficients_from_kernel(known_kernel(w, gain), w,
                                                                            infinite[row, col])
    fit = fit_radiation(w, added, damping, infinite, length=0.5, tolerance=1e-6)
    terms = tuple(RadiationTerm(row=f.row, col=f.col, a=f.a, b=f.b, c=f.c, fit_error=f.error) for f in fit.fits)
    fields = dict(hull_name=hull.name, hull_fingerprint=hull_fingerprint(hull), water_density=1025.0, gravity=9.81,
                  rest_height=0.1, frequencies=w, added_mass=added, damping=damping, added_mass_infinite=infinite,
                  radiation=terms, excitation_headings=np.radians([180.0, 90.0]),
                  excitation=np.ones((len(w), 2, 6)) * (1.0 + 0.5j))
    fields.update(overrides)
    return HydroDatabase(**fields)


@pytest.fixture(scope="module")
def box() -> Hull:
    return Hull.box(2.0, 1.0, 0.6, name="box")


# --- the fit ----------------------------------------------------------------------------------------------------

def test_a_known_rational_kernel_is_recovered():
    """Data made from a fourth-order kernel: with a tight tolerance the fit picks order 4, its poles are the
    kernel's, and it matches the kernel at frequencies it never saw, beyond the band too."""
    fit = fit_kernel(FREQUENCIES, known_kernel(FREQUENCIES), tolerance=1e-6)
    assert fit.order == 4 and fit.error < 1e-9
    poles = np.linalg.eigvals(fit.a)
    for pole in KNOWN_POLES:
        assert np.min(np.abs(poles - pole)) < 1e-6 * abs(pole)
    elsewhere = np.geomspace(0.01, 300.0, 97)
    response = RadiationTerm(row=2, col=2, a=fit.a, b=fit.b, c=fit.c).response(elsewhere)
    np.testing.assert_allclose(response, known_kernel(elsewhere), rtol=1e-7, atol=1e-12)


def test_a_noisy_kernel_is_fitted_within_the_noise(rng):
    """1 % multiplicative noise on the data: the chosen fit (tolerance 2 %) stays within 2 % of the noise-free
    kernel (RMS over the band), and is stable with the zero at s = 0 (K_fit(j0) = 0)."""
    clean = known_kernel(FREQUENCIES)
    noisy = clean * (1.0 + 0.01 * rng.standard_normal(len(FREQUENCIES)))
    fit = fit_kernel(FREQUENCIES, noisy)
    assert fit.error <= 0.02
    response = RadiationTerm(row=0, col=0, a=fit.a, b=fit.b, c=fit.c).response(FREQUENCIES)
    assert np.sqrt(np.mean(np.abs(response - clean) ** 2) / np.mean(np.abs(clean) ** 2)) < 0.02
    assert np.max(np.linalg.eigvals(fit.a).real) < 0
    assert abs(RadiationTerm(row=0, col=0, a=fit.a, b=fit.b, c=fit.c).response([1e-9])[0]) < 1e-6


def test_unstable_poles_are_reflected():
    """Data of a kernel with a pole pair in the right half-plane (0.3 +- 2j), which no passive hull has: the fit
    is stable, its poles the mirror images (-0.3 +- 2j), and its error says that it does not match the data."""
    s = 1j * FREQUENCIES
    unstable = 3.0 * s / (s**2 - 0.6 * s + 4.09)
    fit = fit_kernel(FREQUENCIES, unstable, orders=(2,))
    poles = np.linalg.eigvals(fit.a)
    assert np.max(poles.real) < 0
    for pole in (-0.3 + 2j, -0.3 - 2j):
        assert np.min(np.abs(poles - pole)) < 1e-6
    response = RadiationTerm(row=0, col=0, a=fit.a, b=fit.b, c=fit.c).response(FREQUENCIES)
    error = np.sqrt(np.sum(np.abs(response - unstable) ** 2) / np.sum(np.abs(unstable) ** 2))
    assert fit.error == pytest.approx(error, rel=1e-9) and error > 0.5


def test_fit_radiation_fits_what_matters_and_both_directions_of_a_coupling(box):
    db = synthetic_database(box)
    assert sorted((t.row, t.col) for t in db.radiation) == [(1, 1), (1, 3), (2, 2), (3, 1), (3, 3)]
    response = db.radiation_force_response(FREQUENCIES)
    np.testing.assert_allclose(response[:, 2, 2], known_kernel(FREQUENCIES, 1000.0), rtol=1e-6)
    np.testing.assert_allclose(response[:, 1, 3], known_kernel(FREQUENCIES, 30.0), rtol=1e-6)
    np.testing.assert_allclose(response[:, 3, 1], response[:, 1, 3], rtol=0, atol=0)
    # and it is what the database's own A(w), B(w) and A_inf say
    np.testing.assert_allclose(response, db.kernels(), rtol=1e-6, atol=1e-9)


def test_stacked_state_space_is_the_sum_of_the_terms(box):
    db = synthetic_database(box)
    a, b, c = db.stacked_state_space()
    assert a.shape[0] == sum(t.order for t in db.radiation)
    omega = np.array([0.5, 2.0, 9.0])
    stacked = np.stack([c @ np.linalg.solve(1j * w * np.eye(len(a)) - a, b) for w in omega])
    np.testing.assert_allclose(stacked, db.radiation_force_response(omega), rtol=1e-10, atol=1e-12)


# --- the file ---------------------------------------------------------------------------------------------------

def test_save_and_load_round_trip(box, tmp_path):
    db = synthetic_database(box)
    path = tmp_path / "box.json"
    db.save(path)
    assert path.stat().st_size < 100_000 and not list(tmp_path.glob(".tmp-*"))
    assert json.loads(path.read_text())["format_version"] == FORMAT_VERSION == 2
    loaded = HydroDatabase.load(path, hull=box)
    assert loaded.hull_name == "box" and loaded.rest_height == db.rest_height
    for name in ("frequencies", "added_mass", "damping", "added_mass_infinite", "excitation"):  # 7 digits kept
        np.testing.assert_allclose(getattr(loaded, name), getattr(db, name), rtol=5e-7, atol=1e-12)
    np.testing.assert_allclose(loaded.excitation_headings, db.excitation_headings, rtol=1e-12)
    omega = np.geomspace(0.1, 50, 20)
    np.testing.assert_array_equal(loaded.radiation_force_response(omega), db.radiation_force_response(omega))
    assert [t.fit_error for t in loaded.radiation] == [t.fit_error for t in db.radiation]


def test_arrays_are_read_only(box):
    db = synthetic_database(box)
    with pytest.raises(ValueError):
        db.added_mass[0, 0, 0] = 1.0
    with pytest.raises(ValueError):
        db.radiation[0].a[0, 0] = 1.0


def _refusal(path, hull=None) -> str:
    with pytest.raises(ValueError) as error:
        HydroDatabase.load(path, hull=hull)
    message = str(error.value)
    assert "\n" not in message and message.startswith(f"hydrodynamic database {path}: "), message
    return message


def _edited(db: HydroDatabase, tmp_path, edit) -> str:
    data = db.to_json()
    edit(data)
    path = tmp_path / "edited.json"
    path.write_text(json.dumps(data))
    return str(path)


def test_a_database_for_another_hull_is_refused(box, tmp_path):
    path = tmp_path / "box.json"
    synthetic_database(box).save(path)
    other = Hull.box(2.0, 1.0, 0.5, name="boat")
    message = _refusal(path, hull=other)
    assert "was computed for hull 'box', not 'boat'" in message
    same_name = Hull.box(2.0, 1.0, 0.5, name="box")
    assert "another mesh of hull 'box'" in _refusal(path, hull=same_name) and "ocean-warp bem" in _refusal(
        path, hull=same_name)


def test_hull_fingerprint_sees_the_mesh_not_round_off():
    vertices, triangles = Hull.box(2.0, 1.0, 0.6).vertices, Hull.box(2.0, 1.0, 0.6).triangles
    base = hull_fingerprint(Hull(vertices, triangles))
    assert len(base) == 64 and base == hull_fingerprint(Hull.box(2.0, 1.0, 0.6, name="renamed"))
    assert hull_fingerprint(Hull(vertices + 1e-8, triangles)) == base
    assert hull_fingerprint(Hull(vertices * 1.0001, triangles)) != base


@pytest.mark.parametrize("edit, expected", [
    (lambda d: d.update(format_version=3), "format version 3 is not 2, the one this ocean_warp reads; it was written "
                                           "by a newer ocean_warp"),
    (lambda d: d.update(format_version="2"), "format version '2' is not 2"),
    (lambda d: d.pop("format"), "not an ocean_warp hydrodynamic database"),
    (lambda d: d.pop("damping"), "missing field 'damping'"),
    (lambda d: d["added_mass"][3][2].__setitem__(2, float("nan")), "added_mass has 1 NaN or infinite values (first "
                                                                   "at frequency 0.3977 rad/s, row 2, col 2)"),
    (lambda d: d.update(damping=d["damping"][:-1]), "damping must have shape (50, 6, 6), got (49, 6, 6)"),
    (lambda d: d["added_mass_infinite"][1].__setitem__(3, 4.0), "added_mass_infinite is not symmetric: [1, 3] = 4"),
    (lambda d: d["added_mass_infinite"][2].__setitem__(2, -1.0), "added_mass_infinite is not positive"),
    (lambda d: (d["added_mass_infinite"][0].__setitem__(2, 100.0), d["added_mass_infinite"][2].__setitem__(0, 100.0)),
     "added_mass_infinite is not positive semi-definite"),
    (lambda d: d["radiation"][0]["a"][0].__setitem__(0, 1e3), "is not stable: an eigenvalue of a has real part"),
    (lambda d: d["radiation"][0]["c"].__setitem__(0, float("nan")), "has NaN or infinite values in a, b or c"),
    (lambda d: d["radiation"][0].update(row=6), "row must be a DOF index 0..5, got 6"),
    (lambda d: d["radiation"].append(d["radiation"][0]), "radiation has two terms for"),
    (lambda d: d.update(frequencies=d["frequencies"][::-1]), "frequencies must be finite, > 0 and increasing"),
    (lambda d: d.update(hull_fingerprint="abc"), "hull_fingerprint must be a sha256"),
    (lambda d: d.update(water_density=0), "water_density must be a finite number > 0"),
    (lambda d: d["excitation"].update(real=[]), "excitation.real must have shape (50, 2, 6), got (0,)"),
])
def test_bad_content_is_one_line_naming_the_file(box, tmp_path, edit, expected):
    path = _edited(synthetic_database(box), tmp_path, edit)
    message = _refusal(path)
    assert expected in message, message


def test_unreadable_files_are_one_line(tmp_path):
    assert "no such file" in _refusal(tmp_path / "missing.json")
    assert "is a folder" in _refusal(tmp_path)
    garbage = tmp_path / "garbage.json"
    garbage.write_text("{not json")
    assert "not JSON" in _refusal(garbage)
    listed = tmp_path / "list.json"
    listed.write_text("[1, 2]")
    assert "not an ocean_warp hydrodynamic database" in _refusal(listed)


def test_an_unstable_term_cannot_be_built():
    with pytest.raises(ValueError, match=r"^RadiationTerm: term \(2, 2\) is not stable"):
        RadiationTerm(row=2, col=2, a=[[0.1]], b=[1.0], c=[1.0])
    with pytest.raises(ValueError, match=r"^RadiationTerm: term \(0, 1\) must have a \(m, m\)"):
        RadiationTerm(row=0, col=1, a=[[-1.0, 0.0]], b=[1.0], c=[1.0])


# --- the fallback -----------------------------------------------------------------------------------------------

def test_database_for_without_a_file_warns_and_falls_back(box):
    with pytest.warns(NoHydroDatabaseWarning, match="hull 'box' has no hydrodynamic database: it keeps its "
                                                    "constant added mass and drag-only damping"):
        assert database_for(box, None) is None


def test_database_for_loads_and_checks(box, tmp_path):
    path = tmp_path / "box.json"
    synthetic_database(box).save(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        db = database_for(box, path)
    assert isinstance(db, HydroDatabase) and db.hull_fingerprint == hull_fingerprint(box)
    with pytest.raises(ValueError, match="was computed for hull 'box', not 'other'"):
        database_for(Hull.box(1.0, 1.0, 1.0, name="other"), path)
    assert math.isclose(db.water_density, 1025.0)
