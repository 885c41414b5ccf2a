"""A new USD stage that appears at its path only when complete.

The stage is written to a temporary file beside its target (same folder, a name that still ends in the
target's extension, since USD picks the file format from it) and renamed onto the target with
``os.replace`` after its last save, so an interrupted run never leaves a broken stage at the target and
an existing file there stays intact until then. :meth:`StageFile.abort`, or the garbage collection of an
unfinished StageFile, deletes the temporary file, and ``abort`` also removes the folders the StageFile
made for it (when still empty), so a failed run leaves nothing behind.

Crate files (``.usdc``) are saved every ``save_every`` frames: after a save, the samples written so far
live in the file, not in memory, so memory stays bounded however long the recording. Each such save
appends to the file what changed, so a crate file saved more than once is written afresh (compacted) at
the end: a long recording is then several times smaller. Text files (``.usda``) are held in memory and
written once at the end; use them for small stages.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
import weakref

from pxr import Kind, Sdf, Usd, UsdGeom

from ..validation import require_positive

__all__ = ["StageFile", "stage_format", "check_stage_path"]

EXTENSIONS = (".usdc", ".usda", ".usd")


def stage_format(owner: str, path, ascii: bool | None) -> str:
    """"usdc" or "usda" for a stage at ``path``: by its extension (``.usdc``, ``.usda``; ``.usd`` is crate
    unless ``ascii``). Raises ``ValueError`` for another extension or an ``ascii`` that contradicts it."""
    extension = os.path.splitext(os.fspath(path))[1].lower()
    if extension not in EXTENSIONS:
        raise ValueError(f"{owner}: path must end in .usdc, .usda or .usd, got {os.fspath(path)!r}")
    if ascii is not None and not isinstance(ascii, bool):
        raise ValueError(f"{owner}: ascii must be True, False or None, got {ascii!r}")
    if extension == ".usd":
        return "usda" if ascii else "usdc"
    wanted = extension[1:]
    if ascii is not None and ascii != (wanted == "usda"):
        raise ValueError(f"{owner}: ascii={ascii} contradicts the extension of {os.fspath(path)!r}; "
                         f"use .usda for text, .usdc for crate, or .usd with either")
    return wanted


def check_stage_path(owner: str, path, ascii: bool | None = None) -> str:
    """The format of a stage at ``path`` (see :func:`stage_format`), after checking, without creating anything,
    that its folder exists or can be made: the nearest existing ancestor must be a writable folder. Raises
    ``ValueError`` (one line, naming the path) otherwise."""
    wanted = stage_format(owner, path, ascii)
    folder = os.path.dirname(os.path.abspath(os.fspath(path)))
    ancestor = folder
    while not os.path.exists(ancestor):
        parent = os.path.dirname(ancestor)
        if parent == ancestor:
            break
        ancestor = parent
    if not os.path.isdir(ancestor):
        raise ValueError(f"{owner}: cannot make the folder {folder!r}: {ancestor!r} is not a folder")
    if not os.access(ancestor, os.W_OK | os.X_OK):
        raise ValueError(f"{owner}: cannot write in the folder {ancestor!r}")
    return wanted


def _missing_folders(folder: str) -> list[str]:
    """The folders that ``os.makedirs(folder)`` would create, deepest first."""
    missing = []
    while not os.path.exists(folder):
        missing.append(folder)
        parent = os.path.dirname(folder)
        if parent == folder:
            break
        folder = parent
    return missing


def _remove_quietly(path: str) -> None:
    with contextlib.suppress(FileNotFoundError):
        os.remove(path)


class StageFile:
    """A stage being written to a temporary file until :meth:`commit` renames it onto ``path``.

    The stage has the project's conventions set: z up, 1 metre per unit, ``time_codes_per_second`` both as
    its timeCodesPerSecond and its framesPerSecond (so time code = time [s] x time_codes_per_second, and a
    viewer playing the stage's frame rate shows it in real time) and ``/World``, a ``group`` model, as its
    default prim.
    """

    def __init__(self, path, *, time_codes_per_second: float, ascii: bool | None = None, save_every: int = 100,
                 owner: str = "StageFile"):
        self.path = os.path.abspath(os.fspath(path))
        self.format = stage_format(owner, path, ascii)
        rate = require_positive(owner, "time_codes_per_second", time_codes_per_second, unit=" [1/s]")
        directory = os.path.dirname(self.path)
        self._made_folders = _missing_folders(directory)
        os.makedirs(directory, exist_ok=True)
        extension = os.path.splitext(self.path)[1]
        handle, self.temporary = tempfile.mkstemp(dir=directory, prefix=f".{os.path.basename(self.path)}.",
                                                  suffix=extension)
        os.close(handle)
        self._finalizer = weakref.finalize(self, _remove_quietly, self.temporary)
        try:
            layer = Sdf.Layer.CreateNew(self.temporary, args={"format": self.format})
            if layer is None:
                raise OSError(f"{owner}: USD could not create a layer at {self.temporary!r}")
            self.layer = layer
            self.stage = Usd.Stage.Open(layer)
            UsdGeom.SetStageUpAxis(self.stage, UsdGeom.Tokens.z)
            UsdGeom.SetStageMetersPerUnit(self.stage, UsdGeom.LinearUnits.meters)
            self.stage.SetTimeCodesPerSecond(rate)
            self.stage.SetFramesPerSecond(rate)
            world = UsdGeom.Xform.Define(self.stage, "/World").GetPrim()
            Usd.ModelAPI(world).SetKind(Kind.Tokens.group)
            self.stage.SetDefaultPrim(world)
        except BaseException:
            self.abort()
            raise
        self.time_codes_per_second = rate
        self.save_every = int(save_every)
        self._unsaved_frames = 0
        self._saved = False
        self.closed = False

    def frame_written(self) -> None:
        """Count one frame; a crate file is saved every ``save_every`` of them (memory stays bounded)."""
        self._unsaved_frames += 1
        if self.format == "usdc" and self._unsaved_frames >= self.save_every:
            self.layer.Save()
            self._saved = True
            self._unsaved_frames = 0

    def commit(self) -> str:
        """Save, release the stage and rename the file onto :attr:`path` (readable as any new file of the
        user's); returns the path. The stage must not be used afterwards."""
        if self.closed:
            raise ValueError(f"StageFile: {self.path!r} is already closed")
        compact = None
        try:
            if not self.layer.Save():
                raise OSError(f"StageFile: USD could not save {self.temporary!r}")
            final = self.temporary
            if self._saved:
                # Saved before: the file holds the superseded data of every earlier save too. Write it afresh.
                extension = os.path.splitext(self.path)[1]
                handle, compact = tempfile.mkstemp(dir=os.path.dirname(self.path),
                                                   prefix=f".{os.path.basename(self.path)}.", suffix=extension)
                os.close(handle)
                if not self.layer.Export(compact):
                    raise OSError(f"StageFile: USD could not write {compact!r}")
                final = compact
            self._release()
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(final, 0o666 & ~umask)
            os.replace(final, self.path)
            if compact is not None:
                _remove_quietly(self.temporary)
        except BaseException:
            if compact is not None:
                _remove_quietly(compact)
            self.abort()
            raise
        self._finalizer.detach()
        self._made_folders = []
        return self.path

    def abort(self) -> None:
        """Drop the stage and delete the temporary file and the folders made for it that are empty; the
        target path is left as it was."""
        self._release()
        _remove_quietly(self.temporary)
        self._finalizer.detach()
        for folder in self._made_folders:  # deepest first
            try:
                os.rmdir(folder)
            except OSError:  # not empty (something else was put there), or gone already
                break
        self._made_folders = []

    def _release(self) -> None:
        self.closed = True
        self.stage = None
        self.layer = None
