"""The layers' one direction, kernels <- ocean_warp <- envs, read from the source with ``ast``: no module of the
core (ocean_warp/, not its envs and kernels packages, which live in envs/ and kernels/) imports
``ocean_warp.envs``, and no module of kernels/ imports any of ``ocean_warp`` but ``ocean_warp.kernels``.
Every import statement counts, those inside functions included; relative imports are resolved to absolute
names from the file's place in the package."""

from __future__ import annotations

import ast
from pathlib import Path

from tests.repo_paths import REPO

LAYERS = {"ocean_warp": REPO / "ocean_warp", "ocean_warp.kernels": REPO / "kernels"}
"""Each checked package and its folder on disk."""


def module_name(package: str, root: Path, path: Path) -> str:
    """The absolute module name of ``path``, a file under ``root``, the folder of ``package``."""
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join([package, *parts])


def imported_names(tree: ast.AST, module: str, is_package: bool) -> list[tuple[int, str]]:
    """(line, absolute name) of everything ``tree`` (the source of ``module``) imports: each ``import a.b``
    gives a.b; ``from a import b`` gives a.b (b may be a module), relative ones resolved against ``module``'s
    package."""
    package = module.split(".") if is_package else module.split(".")[:-1]
    names = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                if node.level - 1 > len(package):
                    raise ValueError(f"{module}: line {node.lineno} imports beyond the top package")
                base = package[:len(package) - (node.level - 1)]
                source = ".".join(base + ([node.module] if node.module else []))
            else:
                source = node.module
            names += [(node.lineno, f"{source}.{alias.name}") for alias in node.names]
    return names


def within(name: str, package: str) -> bool:
    return name == package or name.startswith(package + ".")


def layer_violations(source: str, module: str, is_package: bool, forbidden, allowed=()) -> list[tuple[int, str]]:
    """(line, name) of each import in ``source`` (the text of ``module``) of a name within a ``forbidden``
    package and not within an ``allowed`` one."""
    return [(line, name) for line, name in imported_names(ast.parse(source), module, is_package)
            if any(within(name, bad) for bad in forbidden) and not any(within(name, good) for good in allowed)]


def core_rule(source: str, module: str, is_package: bool = False) -> list[tuple[int, str]]:
    """The core's rule: nothing of ``ocean_warp.envs``."""
    return layer_violations(source, module, is_package, ["ocean_warp.envs"])


def kernels_rule(source: str, module: str, is_package: bool = False) -> list[tuple[int, str]]:
    """The kernels' rule: of ocean_warp, only ``ocean_warp.kernels``."""
    return layer_violations(source, module, is_package, ["ocean_warp"], ["ocean_warp.kernels"])


def _files(package: str) -> list[tuple[Path, str]]:
    root = LAYERS[package]
    return [(path, module_name(package, root, path)) for path in sorted(root.rglob("*.py"))]


def _report(package: str, rule) -> list[str]:
    found = []
    for path, module in _files(package):
        for line, name in rule(path.read_text(encoding="utf-8"), module, path.name == "__init__.py"):
            found.append(f"{path.relative_to(REPO)}:{line}: imports {name}")
    return found


def test_the_core_never_imports_the_environments():
    files = _files("ocean_warp")
    assert len(files) > 50, "the walk found too few of the core's files"
    assert not any(module.startswith("ocean_warp.envs") for _, module in files)
    wrong = _report("ocean_warp", core_rule)
    assert not wrong, "the core imports the environment layer:\n" + "\n".join(wrong)


def test_the_kernels_import_only_kernels():
    assert len(_files("ocean_warp.kernels")) > 10, "the walk found too few kernel files"
    wrong = _report("ocean_warp.kernels", kernels_rule)
    assert not wrong, "kernels/ imports the layers above it:\n" + "\n".join(wrong)


PLANTED = '''
import numpy
from . import fleet
from .ocean import Ocean


def later():
    from ..envs.sailing_env import SailingEnv
    from .. import envs
    import ocean_warp.envs.tasks
    from ocean_warp import envs as layer
    return SailingEnv, envs, layer
'''


def test_the_checker_finds_planted_imports_of_the_environments():
    """Inside a function, relative at two levels, a package imported by name from its parent: each is found
    at its line; the core's own imports are not."""
    found = core_rule(PLANTED, "ocean_warp.perception.planted")
    assert found == [(8, "ocean_warp.envs.sailing_env.SailingEnv"), (9, "ocean_warp.envs"),
                     (10, "ocean_warp.envs.tasks"), (11, "ocean_warp.envs")]
    assert core_rule("from . import envs\n", "ocean_warp", is_package=True) == [(1, "ocean_warp.envs")]
    assert core_rule("from .envs import x\n", "ocean_warp.fleet") == [(1, "ocean_warp.envs.x")]
    assert core_rule("from .environment import x\n", "ocean_warp.fleet") == []  # a prefix of the name is not it


def test_the_checker_finds_planted_imports_above_the_kernels():
    source = "from . import ray_cast\nfrom ..fleet import Fleet\nimport ocean_warp.kernels.fft\nimport ocean_warp\n"
    assert kernels_rule(source, "ocean_warp.kernels.planted") == [(2, "ocean_warp.fleet.Fleet"), (4, "ocean_warp")]


# --- the vessel seam: what draws, senses, records and publishes boats takes a vessel ----------------------

VESSEL_BLIND = ("ocean_warp.perception", "ocean_warp.usd", "ocean_warp.ros", "ocean_warp.contact")
"""The core's modules that take a vessel (``ocean_warp.vessel``) and must not import a particular one."""


def vessel_rule(source: str, module: str, is_package: bool = False) -> list[tuple[int, str]]:
    """The seam's rule for a vessel-blind module: nothing of ``ocean_warp.eboat`` or ``ocean_warp.wamv``."""
    return layer_violations(source, module, is_package, ["ocean_warp.eboat", "ocean_warp.wamv"])


def test_the_vessel_blind_modules_import_no_vessel():
    files = [(path, module) for path, module in _files("ocean_warp")
             if any(within(module, package) for package in VESSEL_BLIND)]
    assert len(files) > 25, "the walk found too few of the vessel-blind modules"
    wrong = []
    for path, module in files:
        for line, name in vessel_rule(path.read_text(encoding="utf-8"), module, path.name == "__init__.py"):
            wrong.append(f"{path.relative_to(REPO)}:{line}: imports {name}")
    assert not wrong, "modules that take a vessel import a particular one:\n" + "\n".join(wrong)


def test_the_checker_finds_planted_imports_of_a_vessel():
    source = ("from ..meshes import MeshData\nfrom ..vessel import VesselPart\n"
              "def f():\n    from ..eboat.parts import eboat_parts\n    import ocean_warp.wamv\n"
              "from ocean_warp import eboat\nfrom ..eboatish import x\n")
    assert sorted(vessel_rule(source, "ocean_warp.perception.planted")) == [
        (4, "ocean_warp.eboat.parts.eboat_parts"), (5, "ocean_warp.wamv"), (6, "ocean_warp.eboat")]
