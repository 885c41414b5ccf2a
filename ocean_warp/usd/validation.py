"""Check a written stage with USD's own validators (``pxr.UsdValidation``, every registered one)."""

from __future__ import annotations

import os

from pxr import Usd, UsdValidation

__all__ = ["validate_stage"]


def _site(site) -> str:
    if site.IsPrim():
        return str(site.GetPrim().GetPath())
    if site.IsProperty():
        return str(site.GetProperty().GetPath())
    layer = site.GetLayer()
    return layer.identifier if layer else "stage"


def validate_stage(path, *, warnings: bool = False) -> list[str]:
    """Run every validator USD has registered on the stage at ``path`` and return one line per error
    ("validator: message (at site, ...)"); an empty list means the stage passed. ``warnings``: report the
    validators' warnings too. Raises ``ValueError`` when the file cannot be opened as a stage."""
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise ValueError(f"validate_stage: no file at {path!r}")
    stage = Usd.Stage.Open(path)
    if stage is None:
        raise ValueError(f"validate_stage: USD cannot open {path!r} as a stage")
    context = UsdValidation.ValidationContext(UsdValidation.ValidationRegistry().GetOrLoadAllValidators())
    reported = {UsdValidation.ValidationErrorType.Error}
    if warnings:
        reported.add(UsdValidation.ValidationErrorType.Warn)
    lines = []
    # The errors' sites point into the stage: keep it alive (it is, in this frame) while reading them.
    for error in context.Validate(stage):
        if error.GetType() not in reported:
            continue
        sites = ", ".join(_site(site) for site in error.GetSites())
        lines.append(f"{error.GetName() or error.GetValidator().GetMetadata().name}: {error.GetMessage()}"
                     + (f" (at {sites})" if sites else ""))
    del stage
    return lines
