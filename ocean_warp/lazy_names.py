"""A package's public names imported on first use (PEP 562's module ``__getattr__``), so that importing one
light module of the package (the command line's parsers) does not load the heavy ones (Warp, torch)."""

from __future__ import annotations

import importlib

__all__ = ["lazy_attributes"]


def lazy_attributes(package: str, public: dict[str, str]):
    """``__getattr__`` and ``__dir__`` for the package named ``package``.

    Args:
        package: the package's ``__name__``.
        public: each public name and the module that holds it, relative to ``package`` ("recorder" for
            ``package.recorder``; a leading dot climbs as in a relative import: "..eboat.parts").

    ``package.<name>`` is then the public name, imported from its module on first use and kept in the
    package's namespace, or else the submodule ``package.<name>``; ``AttributeError`` where neither exists.
    """
    namespace = importlib.import_module(package).__dict__

    def __getattr__(name: str):
        if name in public:
            module = public[name]
            value = getattr(importlib.import_module(module if module.startswith(".") else f".{module}", package),
                            name)
            namespace[name] = value
            return value
        try:
            return importlib.import_module(f"{package}.{name}")
        except ModuleNotFoundError as error:
            if error.name != f"{package}.{name}":
                raise
            raise AttributeError(f"module {package!r} has no attribute {name!r}") from None

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(public))

    return __getattr__, __dir__
