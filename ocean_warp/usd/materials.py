"""Materials of the stage: UsdPreviewSurface shaders (UsdShade), which viewers and importers that ignore
``displayColor`` (Blender's, for one) read, bound to every visible part.

Each material lives under :data:`~ocean_warp.usd.paths.LOOKS` and carries its colour both as the preview
surface's ``diffuseColor`` and, on the gprims it is bound to, as their ``displayColor``, so the stage
looks the same with or without material support. The ocean's material takes its colour from the mesh's
per-vertex ``displayColor`` through a ``UsdPrimvarReader_float3`` when the mesh has one.
"""

from __future__ import annotations

import dataclasses

from pxr import Gf, Sdf, UsdShade

from .paths import LOOKS

__all__ = ["Look", "LOOKS_BY_NAME", "HULL_PALETTE", "define_look", "define_vertex_color_look", "bind_look",
           "hull_look_name"]


@dataclasses.dataclass(frozen=True)
class Look:
    """A UsdPreviewSurface: ``color`` (r, g, b in 0-1, linear), ``roughness`` and ``metallic`` in 0-1."""

    color: tuple[float, float, float]
    roughness: float = 0.5
    metallic: float = 0.0


LOOKS_BY_NAME = {
    "Hull": Look((0.92, 0.92, 0.90), roughness=0.35),
    "Foil": Look((0.18, 0.20, 0.24), roughness=0.4),
    "Spar": Look((0.70, 0.70, 0.72), roughness=0.3, metallic=0.8),
    "Sail": Look((0.98, 0.96, 0.86), roughness=0.8),
    "Buoy": Look((1.0, 0.45, 0.05), roughness=0.4),
    "Route": Look((1.0, 0.85, 0.1), roughness=0.6),
    "Wind": Look((0.85, 0.1, 0.1), roughness=0.5),
    "Sea": Look((0.05, 0.35, 0.55), roughness=0.1),
}
"""The stage's materials by name (the prim name under LOOKS)."""

HULL_PALETTE = (
    (0.92, 0.92, 0.90), (0.80, 0.12, 0.12), (0.10, 0.22, 0.55), (0.95, 0.75, 0.10),
    (0.12, 0.55, 0.25), (0.95, 0.45, 0.10), (0.10, 0.60, 0.65), (0.45, 0.20, 0.60),
)
"""Hull colours of the boats in the one-prim-per-boat layout, boat i taking entry i mod 8 (the first is the
prototype's white hull)."""


def hull_look_name(index: int) -> str:
    """Name of the material of hull colour ``index`` of :data:`HULL_PALETTE` (0: the prototype's "Hull")."""
    return "Hull" if index % len(HULL_PALETTE) == 0 else f"Hull_{index % len(HULL_PALETTE)}"


def _surface(stage, path: str, look: Look) -> tuple[UsdShade.Material, UsdShade.Shader]:
    material = UsdShade.Material.Define(stage, path)
    shader = UsdShade.Shader.Define(stage, f"{path}/PreviewSurface")
    shader.CreateIdAttr("UsdPreviewSurface")
    shader.CreateInput("diffuseColor", Sdf.ValueTypeNames.Color3f).Set(Gf.Vec3f(*map(float, look.color)))
    shader.CreateInput("roughness", Sdf.ValueTypeNames.Float).Set(float(look.roughness))
    shader.CreateInput("metallic", Sdf.ValueTypeNames.Float).Set(float(look.metallic))
    material.CreateSurfaceOutput().ConnectToSource(shader.ConnectableAPI(), "surface")
    return material, shader


def define_look(stage, name: str, look: Look | None = None) -> UsdShade.Material:
    """The material ``LOOKS/name``, a UsdPreviewSurface of ``look`` (default: ``LOOKS_BY_NAME[name]``),
    defined once per stage (later calls return the one defined)."""
    path = f"{LOOKS}/{name}"
    existing = UsdShade.Material.Get(stage, path)
    if existing:
        return existing
    return _surface(stage, path, look if look is not None else LOOKS_BY_NAME[name])[0]


def define_vertex_color_look(stage, name: str = "Ocean", fallback: Look | None = None) -> UsdShade.Material:
    """The material ``LOOKS/name`` whose diffuse colour is the gprim's ``displayColor`` primvar, read by a
    ``UsdPrimvarReader_float3`` (``fallback``'s colour where a gprim has none; default: the sea's)."""
    path = f"{LOOKS}/{name}"
    existing = UsdShade.Material.Get(stage, path)
    if existing:
        return existing
    fallback = fallback if fallback is not None else LOOKS_BY_NAME["Sea"]
    material, surface = _surface(stage, path, fallback)
    reader = UsdShade.Shader.Define(stage, f"{path}/DisplayColor")
    reader.CreateIdAttr("UsdPrimvarReader_float3")
    reader.CreateInput("varname", Sdf.ValueTypeNames.String).Set("displayColor")
    reader.CreateInput("fallback", Sdf.ValueTypeNames.Float3).Set(Gf.Vec3f(*map(float, fallback.color)))
    reader.CreateOutput("result", Sdf.ValueTypeNames.Float3)
    surface.GetInput("diffuseColor").ConnectToSource(reader.ConnectableAPI(), "result")
    return material


def bind_look(prim, material: UsdShade.Material) -> None:
    """Bind ``material`` to ``prim`` (applying MaterialBindingAPI, as USD's validators ask)."""
    UsdShade.MaterialBindingAPI.Apply(prim).Bind(material)
