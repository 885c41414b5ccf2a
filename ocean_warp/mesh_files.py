"""A triangle mesh read from a file (hulls, scene objects): one home for what is refused and how it is said.

trimesh alone would drop a vertex that is NaN, with the faces that use it (a hull then loads with a corner
missing), call a folder "no such file" and, for bytes that are no mesh, report whatever its format sniffing
tripped over (e.g. a missing optional module). Here the file's raw vertices are checked before trimesh
merges and cleans anything.
"""

from __future__ import annotations

import os

import numpy as np

__all__ = ["MESH_FORMATS", "read_mesh_file"]

MESH_FORMATS = ("obj", "stl", "ply", "off", "glb", "gltf")
"""File extensions of the mesh formats read (trimesh's loaders for them)."""

_FORMAT_NAMES = ", ".join(name.upper() for name in MESH_FORMATS)


def read_mesh_file(owner: str, path: str | os.PathLike):
    """The triangle mesh in ``path`` as a processed ``trimesh.Trimesh`` (vertices merged, as trimesh loads
    by default), a scene's geometry merged into one mesh; coordinates as in the file.

    Raises:
        FileNotFoundError: nothing at ``path``.
        ValueError: ``path`` is a folder; its extension is not one of :data:`MESH_FORMATS`; trimesh cannot
            parse it as that format; it holds no triangles; or a vertex is NaN or infinite (the message says
            how many, and the first one's coordinates). Each message starts with ``owner``.
    """
    import trimesh

    path = os.fspath(path)
    if os.path.isdir(path):
        raise ValueError(f"{owner}: {path} is a folder, not a mesh file ({_FORMAT_NAMES})")
    if not os.path.exists(path):
        raise FileNotFoundError(f"{owner}: no such file: {path}")
    extension = os.path.splitext(path)[1].lower().lstrip(".")
    if extension not in MESH_FORMATS:
        raise ValueError(f"{owner}: {path} is not a mesh file of a readable format: its name must end in one of "
                         f"{', '.join('.' + name for name in MESH_FORMATS)}")
    not_readable = f"{owner}: {path} is not a mesh of a readable format ({_FORMAT_NAMES}): not a valid " \
                   f"{extension.upper()} file"
    try:
        # Unprocessed: trimesh's processing removes non-finite vertices without a word.
        mesh = trimesh.load(path, force="mesh", process=False)
    except ImportError:  # its format sniffing for text that is no text needs an optional module
        raise ValueError(not_readable) from None
    except Exception as error:  # noqa: BLE001 - trimesh's parsers raise many kinds
        first_line = (str(error).strip().splitlines() or [type(error).__name__])[0]
        raise ValueError(f"{not_readable} ({first_line})") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        # Noise can parse as a text format with no valid line in it: say that it may not be a mesh at all
        raise ValueError(f"{owner}: {path} holds no triangles: an empty mesh, or not a valid {extension.upper()} "
                         "file")
    bad = ~np.all(np.isfinite(np.asarray(mesh.vertices)), axis=1)
    if bad.any():
        first = ", ".join(f"{value:g}" for value in np.asarray(mesh.vertices)[np.flatnonzero(bad)[0]])
        raise ValueError(f"{owner}: {path}: {int(bad.sum())} of its {len(bad)} vertices are NaN or infinite "
                         f"(the first: {first}); a mesh with such vertices is refused")
    mesh.process()
    return mesh
