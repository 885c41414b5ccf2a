"""A new USD stage that appears at its path only when complete.

The stage is written to a temporary file beside its target (same folder, a name that still ends in the
target's extension, since USD picks the file format from it) and renamed onto the target with
``os.replace`` after its last save, so an interrupted run never leaves a broken stage at the target and
an existing file there stays intact until then. :meth:`StageFile.abort`, or the garbage collection of an
unfinished StageFile, deletes the temporary file.

Crate files (``.usdc``) are saved every ``save_every`` frames: after a save, the samples written so far
live in the file, not in memory, so memory stays bounded however long the recording. Text files
(``.usda``) are held in memory and written once at the end; use them for small stages.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
import weakref

from pxr import Sdf, Usd, UsdGeom

from ..validation import require_positive

__all__ = ["StageFile", "stage_format"]

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


def _remove_quietly(path: str) -> None:
    with contextlib.suppress(FileNotFoundError):
        os.remove(path)


class StageFile:
    """A stage being written to a temporary file until :meth:`commit` renames it onto ``path``.

    The stage has the project's conventions set: z up, 1 metre per unit, ``fps`` time codes per second
    (so time code = time [s] x fps) and ``/World`` as its default prim.
    """

    def __init__(self, path, *, fps: float, ascii: bool | None = None, save_every: int = 100, owner: str = "StageFile"):
        self.path = os.path.abspath(os.fspath(path))
        self.format = stage_format(owner, path, ascii)
        fps = require_positive(owner, "fps", fps, unit=" [frames/s]")
        directory = os.path.dirname(self.path)
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
            self.stage.SetTimeCodesPerSecond(fps)
            self.stage.SetFramesPerSecond(fps)
            self.stage.SetDefaultPrim(UsdGeom.Xform.Define(self.stage, "/World").GetPrim())
        except BaseException:
            self.abort()
            raise
        self.fps = fps
        self.save_every = int(save_every)
        self._unsaved_frames = 0
        self.closed = False

    def frame_written(self) -> None:
        """Count one frame; a crate file is saved every ``save_every`` of them (memory stays bounded)."""
        self._unsaved_frames += 1
        if self.format == "usdc" and self._unsaved_frames >= self.save_every:
            self.layer.Save()
            self._unsaved_frames = 0

    def commit(self) -> str:
        """Save, release the stage and rename the file onto :attr:`path` (readable as any new file of the
        user's); returns the path. The stage must not be used afterwards."""
        if self.closed:
            raise ValueError(f"StageFile: {self.path!r} is already closed")
        try:
            if not self.layer.Save():
                raise OSError(f"StageFile: USD could not save {self.temporary!r}")
            self._release()
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(self.temporary, 0o666 & ~umask)
            os.replace(self.temporary, self.path)
        except BaseException:
            self.abort()
            raise
        self._finalizer.detach()
        return self.path

    def abort(self) -> None:
        """Drop the stage and delete the temporary file; the target path is left as it was."""
        self._release()
        _remove_quietly(self.temporary)
        self._finalizer.detach()

    def _release(self) -> None:
        self.closed = True
        self.stage = None
        self.layer = None
