"""The BEM run (ocean_warp.seakeeping.bem, capytaine) against analytic results, and ``ocean-warp bem``.

A floating hemisphere: its heave added mass at infinite frequency is half its displaced water's mass (the
double body: a sphere in unbounded fluid has half its volume's mass); in long waves its heave force is the
hydrostatic rho g A_wp; and its heave damping and wave force obey the deep-water Haskind/energy relation
B33 = w^3 |X3|^2 / (2 rho g^3) for an axisymmetric body. A coarse E-Boat hull (symmetric port and starboard):
reciprocity (A_ij = A_ji), the couplings its symmetry forbids vanish, head seas push only its symmetric DOFs, and
the database it gives loads, is stable and is fitted. Coarse meshes, a few seconds each.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest
import trimesh

from ocean_warp import cli
from ocean_warp.hull import Hull
from ocean_warp.seakeeping import HydroDatabase, compute_database, rest_height_for_mass
from ocean_warp.seakeeping.bem import check_rest_height

pytest.importorskip("capytaine", reason="the bem extra: pip install -e '.[bem]'")

RHO, G = 1025.0, 9.81
RADIUS = 0.5
SYMMETRIC, ANTISYMMETRIC = (0, 2, 4), (1, 3, 5)
"""Surge, heave, pitch against sway, roll, yaw: a hull symmetric about its centre plane never couples them."""


@pytest.fixture(scope="module")
def hemisphere():
    """A sphere of radius 0.5 m (656 panels below water) floating half immersed, its centre at the origin."""
    hull = Hull.sphere(RADIUS, subdivisions=3, name="sphere")
    result = compute_database(hull, rest_height=0.0, frequencies=[0.3, 2.0, 3.0, 4.0], headings_deg=(180.0,),
                              progress=False)
    return hull, result.database


def test_hemisphere_heave_added_mass_at_infinite_frequency_is_half_the_displaced_mass(hemisphere):
    _, db = hemisphere
    half_displaced = 0.5 * RHO * (2.0 / 3.0) * np.pi * RADIUS**3
    # 2.6 % above on this mesh (the panels' discretisation); converges from above as it is refined
    assert db.added_mass_infinite[2, 2] == pytest.approx(half_displaced, rel=0.04)


def test_hemisphere_heave_force_in_long_waves_is_hydrostatic(hemisphere):
    """At w = 0.3 rad/s (wavelength 685 m, k R = 0.005) the heave force per metre of wave is rho g A_wp, A_wp the
    mesh's waterplane (trimesh's section of it), in phase with the wave at the origin."""
    hull, db = hemisphere
    section = hull.to_trimesh().section(plane_origin=[0.0, 0.0, 0.0], plane_normal=[0.0, 0.0, 1.0])
    (outline,) = section.discrete  # the waterline, in order
    x, y = outline[:, 0], outline[:, 1]
    waterplane = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))  # shoelace
    assert waterplane == pytest.approx(np.pi * RADIUS**2, rel=0.02)
    force = db.excitation[0, 0, 2]
    assert abs(force) == pytest.approx(RHO * G * waterplane, rel=0.015)
    assert abs(np.angle(force)) < 0.02


def test_hemisphere_damping_and_wave_force_obey_the_haskind_relation(hemisphere):
    _, db = hemisphere
    for k, omega in enumerate(db.frequencies):
        if omega < 1.0:
            continue  # B33 ~ w^3 is tiny there; relative errors of the panels grow
        haskind = omega**3 * abs(db.excitation[k, 0, 2]) ** 2 / (2 * RHO * G**3)
        assert db.damping[k, 2, 2] == pytest.approx(haskind, rel=0.05), omega


@pytest.fixture(scope="module")
def coarse_eboat():
    """The procedural E-Boat canoe body meshed coarsely (about 300 triangles), at the boat's mass."""
    from ocean_warp.eboat.hull_shape import HullShape, eboat_hull

    hull = eboat_hull(HullShape().with_triangle_budget(300))
    result = compute_database(hull, mass=158.27, frequencies=np.geomspace(0.5, 8.0, 12), progress=False)
    return hull, result


def _scaled(matrix: np.ndarray, diagonal: np.ndarray) -> np.ndarray:
    """matrix_ij / sqrt(d_i d_j): entries of mixed units made comparable."""
    root = np.sqrt(np.abs(diagonal))
    return matrix / np.outer(root, root)


def test_coarse_hull_reciprocity_and_symmetry(coarse_eboat):
    _, result = coarse_eboat
    db = result.database
    for k in np.flatnonzero(db.frequencies <= result.resolved_frequency):  # waves the panels resolve
        for name in ("added_mass", "damping"):
            matrix = getattr(db, name)[k]
            # damping vanishes in long waves: scaled by its largest diagonal over frequency
            diagonal = np.diagonal(db.damping, axis1=1, axis2=2).max(axis=0) if name == "damping" else np.diag(matrix)
            scaled = _scaled(matrix, diagonal)
            # reciprocity holds to the panels' discretisation: 5 % at worst on these 180 panels (roll-yaw damping
            # at 4.8 rad/s), about as much on the E-Boat's 1 052 (test_eboat_hydro_database.py); it halves when
            # the panels are halved
            assert np.max(np.abs(scaled - scaled.T)) < 0.07, (name, db.frequencies[k])
            forbidden = scaled[np.ix_(SYMMETRIC, ANTISYMMETRIC)]
            assert np.max(np.abs(forbidden)) < 0.01, (name, db.frequencies[k])
    infinite = _scaled(db.added_mass_infinite, np.diag(db.added_mass_infinite))
    assert np.max(np.abs(infinite[np.ix_(SYMMETRIC, ANTISYMMETRIC)])) < 0.01
    # the couplings its shape allows are there: heave-pitch (not symmetric fore and aft), sway-roll
    assert abs(infinite[2, 4]) > 0.1 and abs(infinite[1, 3]) > 0.3
    # head seas push only surge, heave and pitch; beam seas push all
    head, beam = db.excitation[:, 0, :], db.excitation[:, 1, :]
    assert np.all(np.abs(head[:, ANTISYMMETRIC]) < 1e-2 * np.abs(beam[:, ANTISYMMETRIC]))


def test_coarse_hull_database_loads_and_its_fits_reproduce_its_kernels(coarse_eboat, tmp_path):
    hull, result = coarse_eboat
    db = result.database
    path = tmp_path / "coarse.json"
    db.save(path)
    loaded = HydroDatabase.load(path, hull=hull)
    assert {(t.row, t.col) for t in loaded.radiation} >= {(i, i) for i in range(6)} | {(1, 3), (3, 1), (2, 4)}
    for term in loaded.radiation:
        assert np.max(np.linalg.eigvals(term.a).real) < 0
        assert term.fit_error < 0.03
    low, high = result.fit.band
    band = (db.frequencies >= low) & (db.frequencies <= high)
    fitted = loaded.radiation_force_response(db.frequencies[band])
    kernels = db.kernels()[band]
    for term in loaded.radiation:
        data = 0.5 * (kernels[:, term.row, term.col] + kernels[:, term.col, term.row])
        error = np.sqrt(np.sum(np.abs(fitted[:, term.row, term.col] - data) ** 2) / np.sum(np.abs(data) ** 2))
        assert error < 0.03, (term.row, term.col)
    assert result.wall_time < 60.0


def test_rest_height_of_a_box_is_where_it_displaces_its_mass():
    box = Hull.box(2.0, 1.0, 0.6, subdivisions=1)
    mass = 300.0
    assert rest_height_for_mass(box, mass) == pytest.approx(0.3 - mass / (RHO * 2.0), abs=1e-6)
    with pytest.raises(ValueError, match=r"^hull 'box' sinks at 2000 kg: its whole volume floats at most 1230 kg"):
        rest_height_for_mass(box, 2000.0)
    with pytest.raises(ValueError, match=r"^hull 'box' floats out of the water at 0.1 kg"):
        rest_height_for_mass(box, 0.1)
    with pytest.raises(ValueError, match=r"its deck \(z = 0.3 m\) would be under water"):
        check_rest_height(box, -0.35)
    with pytest.raises(ValueError, match=r"its lowest point \(z = -0.3 m\) would be 0.05 m above the water"):
        check_rest_height(box, 0.35)


# --- ocean-warp bem -----------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def mesh_files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("meshes")
    box = trimesh.creation.box(extents=[2.0, 1.0, 0.6])
    box = box.subdivide().subdivide()
    box.export(folder / "box.stl")
    lidless = trimesh.Trimesh(box.vertices, box.faces[box.triangles_center[:, 2] < 0.299], process=False)
    lidless.export(folder / "open_box.stl")
    return folder


def _refused(argv, capsys) -> str:
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["bem", *argv])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("ocean-warp bem: error: "), err
    return err[0]


def test_an_open_mesh_is_one_line_and_nothing_is_written(mesh_files, tmp_path, capsys):
    out = tmp_path / "out" / "open.json"
    path = mesh_files / "open_box.stl"
    line = _refused(["--hull", str(path), "--mass", "300", "--out", str(out)], capsys)
    assert f"--hull {path} is not closed: 16 open edges" in line
    assert not (tmp_path / "out").exists()


def test_missing_capytaine_is_one_line(mesh_files, tmp_path, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "capytaine", None)  # import capytaine now raises ImportError
    out = tmp_path / "box.json"
    line = _refused(["--hull", str(mesh_files / "box.stl"), "--mass", "300", "--out", str(out)], capsys)
    assert line == "ocean-warp bem: error: capytaine is not installed: pip install -e '.[bem]'"
    assert not out.exists()


@pytest.mark.parametrize("argv, message", [
    (["--mass", "5000"], "hull 'box' sinks at 5000 kg: its whole volume floats at most 1230 kg"),
    (["--rest-height", "0.4"], "hull 'box' floats out of the water at rest height 0.4 m"),
    (["--mass", "-3"], "--mass must be a number > 0 [kg], got -3.0"),
    (["--mass", "300", "--frequencies", "2", "1", "10"], "--frequencies must be LOW > 0, HIGH > LOW [rad/s] and a "
                                                         "whole COUNT from 4 to 400, got 2 1 10"),
    ([], "--hull needs --mass KG or --rest-height M"),
    (["--mass", "300", "--out", "box.txt"], "--out box.txt: must end in .json"),
])
def test_bad_inputs_are_one_line(mesh_files, tmp_path, monkeypatch, capsys, argv, message):
    monkeypatch.chdir(tmp_path)
    line = _refused(["--hull", str(mesh_files / "box.stl"), *argv], capsys)
    assert message in line, line
    assert list(tmp_path.iterdir()) == []


def test_the_command_writes_a_database_the_hull_loads(mesh_files, tmp_path, capsys):
    out = tmp_path / "bem" / "box.json"
    cli.main(["bem", "--hull", str(mesh_files / "box.stl"), "--mass", "300", "--frequencies", "0.5", "8", "10",
              "--headings", "180", "--out", str(out)])
    text = capsys.readouterr().out
    assert f"wrote {out}" in text and "heave natural period" in text and "heave " in text
    db = HydroDatabase.load(out, hull=Hull.from_file(mesh_files / "box.stl"))
    assert len(db.frequencies) == 10 and db.excitation.shape == (10, 1, 6)
    assert db.rest_height == pytest.approx(0.3 - 300.0 / (RHO * 2.0), abs=1e-6)
