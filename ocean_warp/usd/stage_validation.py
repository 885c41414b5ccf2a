"""Check a written stage with USD's own validators (``pxr.UsdValidation``, every registered one) and its
model hierarchy (none of those validators checks ``kind``)."""

from __future__ import annotations

import os

from pxr import Kind, Usd, UsdValidation

__all__ = ["validate_stage", "model_hierarchy_errors"]


def _site(site) -> str:
    if site.IsPrim():
        return str(site.GetPrim().GetPath())
    if site.IsProperty():
        return str(site.GetProperty().GetPath())
    layer = site.GetLayer()
    return layer.identifier if layer else "stage"


def model_hierarchy_errors(stage) -> list[str]:
    """One line per prim whose authored ``kind`` is a model kind (component, group, assembly, ...) that USD
    does not take as a model, because the model hierarchy is broken above it: every ancestor of a model
    must be a group (``group`` or ``assembly``), so a model may not sit below a component or below a prim
    of no kind (USD's rule; ``Usd.Prim.IsModel``)."""
    lines = []
    for prim in stage.Traverse():
        kind = Usd.ModelAPI(prim).GetKind()
        if kind and Kind.Registry.IsA(kind, Kind.Tokens.model) and not prim.IsModel():
            parent = prim.GetParent()
            parent_kind = Usd.ModelAPI(parent).GetKind() if parent else ""
            lines.append(f"ModelHierarchy: {prim.GetPath()} has kind {kind!r} but its parent {parent.GetPath()} "
                         f"(kind {parent_kind!r}) is not a group model, so USD does not take it as a model")
    return lines


def validate_stage(path, *, warnings: bool = False) -> list[str]:
    """Run every validator USD has registered on the stage at ``path``, and :func:`model_hierarchy_errors`,
    and return one line per error ("validator: message (at site, ...)"); an empty list means the stage
    passed. ``warnings``: report the validators' warnings too. Raises ``ValueError`` when the file cannot be
    opened as a stage."""
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
    lines += model_hierarchy_errors(stage)
    del stage
    return lines
