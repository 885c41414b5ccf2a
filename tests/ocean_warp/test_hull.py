"""Hull meshes: loading, repairs, clear errors and mass properties against closed forms."""

import math

import numpy as np
import pytest
import trimesh

import ocean_warp as ow
from ocean_warp import HullRepairWarning


def test_box_properties_are_closed_forms(rng):
    length, beam, height = rng.uniform(0.5, 10.0, size=3)
    hull = ow.Hull.box(length, beam, height, subdivisions=int(rng.integers(0, 3)))
    assert hull.volume == pytest.approx(length * beam * height, rel=1e-12)
    assert hull.surface_area == pytest.approx(2 * (length * beam + length * height + beam * height), rel=1e-12)
    np.testing.assert_allclose(hull.center_of_volume, 0.0, atol=1e-12 * length)
    assert hull.length == pytest.approx(length)
    mass = rng.uniform(10, 1000)
    expected = mass / 12 * np.diag([beam**2 + height**2, length**2 + height**2, length**2 + beam**2])
    np.testing.assert_allclose(hull.solid_inertia(mass), expected, rtol=1e-10, atol=1e-12 * mass)


def test_ellipsoid_converges_to_its_volume(rng):
    a, b, c = rng.uniform(0.2, 3.0, size=3)
    exact = 4 / 3 * math.pi * a * b * c
    errors = [abs(ow.Hull.ellipsoid(a, b, c, subdivisions=k).volume - exact) / exact for k in (1, 2, 3, 4)]
    assert all(later < earlier / 3 for earlier, later in zip(errors, errors[1:]))
    assert errors[-1] < 3e-3


@pytest.mark.parametrize("suffix", ["obj", "stl", "ply", "glb"])
def test_from_file_round_trip(tmp_path, rng, suffix):
    length, beam, height = rng.uniform(0.5, 5.0, size=3)
    box = trimesh.creation.box(extents=[length, beam, height])
    path = tmp_path / f"hull.{suffix}"
    box.export(path)
    hull = ow.Hull.from_file(path)
    assert hull.volume == pytest.approx(length * beam * height, rel=1e-5)
    assert hull.name == "hull"


def test_millimetre_model_is_refused_with_a_hint(tmp_path):
    path = tmp_path / "model.stl"
    trimesh.creation.box(extents=[2500.0, 1000.0, 600.0]).export(path)
    with pytest.raises(ValueError, match=r"millimetres\? pass scale=0.001"):
        ow.Hull.from_file(path)
    assert ow.Hull.from_file(path, scale=0.001).volume == pytest.approx(2.5 * 1.0 * 0.6, rel=1e-6)


def test_nan_vertex_is_refused():
    box = trimesh.creation.box(extents=[2.0, 1.0, 0.5])
    vertices = np.array(box.vertices)
    vertices[3, 1] = np.nan
    with pytest.raises(ValueError, match="1 vertices are NaN or infinite"):
        ow.Hull(vertices, box.faces)


def _obj_text(vertices, faces) -> str:
    """An OBJ file's text: a ``v`` line per vertex (numpy's repr, so NaN is written "nan"), an ``f`` line per
    triangle (1-based)."""
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    return "\n".join(lines + [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces.tolist()]) + "\n"


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_a_mesh_file_with_a_non_finite_vertex_is_refused(tmp_path, rng, bad):
    """trimesh would drop the vertex and its faces (the box would load with a corner cut off)."""
    box = trimesh.creation.box(extents=rng.uniform(0.5, 3.0, size=3))
    vertices = np.array(box.vertices)
    corner = int(rng.integers(len(vertices)))
    vertices[corner, int(rng.integers(3))] = bad
    path = tmp_path / "hull.obj"
    path.write_text(_obj_text(vertices, np.asarray(box.faces)))
    with pytest.raises(ValueError, match=rf"^Hull.from_file: {path}: 1 of its 8 vertices are NaN or infinite"):
        ow.Hull.from_file(path)
    vertices[corner] = box.vertices[corner]  # the same file with the corner back loads whole
    path.write_text(_obj_text(vertices, np.asarray(box.faces)))
    assert ow.Hull.from_file(path).volume == pytest.approx(np.prod(box.extents), rel=1e-6)


def test_a_folder_is_not_a_mesh_file(tmp_path):
    folder = tmp_path / "hull.obj"
    folder.mkdir()
    with pytest.raises(ValueError, match=rf"^Hull.from_file: {folder} is a folder, not a mesh file"):
        ow.Hull.from_file(folder)
    with pytest.raises(FileNotFoundError, match="^Hull.from_file: no such file"):
        ow.Hull.from_file(tmp_path / "missing.obj")


@pytest.mark.parametrize("suffix", ["obj", "stl", "ply", "glb"])
def test_random_bytes_are_not_a_mesh(tmp_path, rng, suffix):
    path = tmp_path / f"noise.{suffix}"
    path.write_bytes(rng.bytes(512))
    # Depending on the bytes, trimesh's parser raises (most draws) or reads them as a text file with no valid
    # line (some OBJ and STL draws): either is one line naming the file and its format
    with pytest.raises(ValueError, match=rf"^Hull.from_file: {path} (is not a mesh of a readable format "
                                         r"\(OBJ, STL, PLY, OFF, GLB, GLTF\)|holds no triangles: an empty mesh, or "
                                         rf"not a valid {suffix.upper()} file)") as raised:
        ow.Hull.from_file(path)
    assert "charset_normalizer" not in str(raised.value) and "\n" not in str(raised.value)
    other = tmp_path / "noise.bin"
    other.write_bytes(rng.bytes(512))
    with pytest.raises(ValueError, match="its name must end in one of .obj, .stl, .ply, .off, .glb, .gltf"):
        ow.Hull.from_file(other)


def test_inward_normals_are_turned_out_with_a_warning(rng):
    box = trimesh.creation.box(extents=rng.uniform(0.5, 3.0, size=3))
    with pytest.warns(HullRepairWarning, match="turned inward-facing normals outward"):
        hull = ow.Hull(box.vertices, box.faces[:, ::-1])
    assert hull.volume == pytest.approx(box.volume)


def test_inconsistent_winding_is_fixed_with_a_warning():
    sphere = trimesh.creation.icosphere(subdivisions=2)
    faces = np.array(sphere.faces)
    faces[::7] = faces[::7, ::-1]
    with pytest.warns(HullRepairWarning, match="made the triangle winding consistent"):
        hull = ow.Hull(sphere.vertices, faces)
    assert hull.volume == pytest.approx(sphere.volume, rel=1e-9)


def test_degenerate_triangles_are_removed_with_a_warning():
    box = trimesh.creation.box(extents=[2.0, 1.0, 0.5])
    faces = np.vstack([box.faces, [[0, 1, 1], [2, 2, 2]]])
    with pytest.warns(HullRepairWarning, match="removed 2 degenerate triangles"):
        hull = ow.Hull(box.vertices, faces)
    assert hull.triangle_count == 12


def test_open_mesh_is_refused():
    box = trimesh.creation.box(extents=[2.0, 1.0, 0.5])
    normals = box.face_normals
    keep = ~((np.abs(normals[:, 0]) > 0.5) & (normals[:, 0] > 0) | (normals[:, 1] > 0.5))  # drop two whole sides
    with pytest.raises(ValueError, match="not watertight"):
        ow.Hull(box.vertices, box.faces[keep])


@pytest.mark.parametrize("kwargs,message", [
    (dict(length=-1.0, beam=1.0, height=1.0), "length must be a finite number > 0"),
    (dict(length=1.0, beam=math.nan, height=1.0), "beam must be a finite number > 0"),
    (dict(length=1.0, beam=1.0, height=1.0, subdivisions=9), "subdivisions must be an integer in"),
])
def test_bad_sizes_are_refused(kwargs, message):
    with pytest.raises(ValueError, match=message):
        ow.Hull.box(**kwargs)


def test_boat_type_checks_its_numbers():
    hull = ow.Hull.box(2.0, 1.0, 0.5)
    with pytest.raises(ValueError, match="mass must be a finite number > 0"):
        ow.BoatType(hull=hull, mass=0.0)
    with pytest.raises(ValueError, match="triangle inequality"):
        ow.BoatType(hull=hull, mass=10.0, inertia=np.diag([1.0, 1.0, 5.0]))
    with pytest.raises(ValueError, match="added_mass must be symmetric"):
        ow.BoatType(hull=hull, mass=10.0, added_mass=np.triu(np.ones((6, 6))))
    with pytest.raises(ValueError, match="linear_damping must be 6 finite values >= 0"):
        ow.BoatType(hull=hull, mass=10.0, linear_damping=[1, 2, 3])


def test_mass_matrix_is_the_momentum_of_the_mass(rng):
    hull = ow.Hull.box(2.0, 1.0, 0.5)
    mass = rng.uniform(10, 100)
    offset = rng.uniform(-0.3, 0.3, size=3)
    # The inertia about the origin, summed over point masses of a cloud with that centre and inertia.
    points = rng.normal(size=(4000, 3))
    points -= points.mean(axis=0)
    cloud_inertia = sum(np.dot(p, p) * np.eye(3) - np.outer(p, p) for p in points) * mass / len(points)
    cloud = ow.BoatType(hull=hull, mass=mass, center_of_mass=offset, inertia=cloud_inertia)
    shifted = points + offset
    about_origin = sum(np.dot(p, p) * np.eye(3) - np.outer(p, p) for p in shifted) * mass / len(points)
    np.testing.assert_allclose(cloud.inertia_about_origin, about_origin, rtol=1e-9)
    # M_RB nu is the cloud's momentum and its angular momentum about the origin, summed point by point.
    nu = rng.uniform(-2.0, 2.0, size=6)
    point_velocities = nu[:3] + np.cross(nu[3:], shifted)
    momentum = point_velocities.sum(axis=0) * mass / len(points)
    angular_momentum = np.cross(shifted, point_velocities).sum(axis=0) * mass / len(points)
    np.testing.assert_allclose(cloud.rigid_body_mass_matrix @ nu, np.concatenate([momentum, angular_momentum]),
                               rtol=1e-9, atol=1e-9 * mass)
