"""Configs to Warp structs: the one helper that copies a config's values into the struct a kernel reads.

A config (a dataclass a person writes, SI units) and the ``@wp.struct`` its kernels read mostly share
field names; :func:`struct_from` copies those by name and takes the rest (derived values: reciprocals,
flags as ints, fields of a nested config) from keyword arguments, so a struct field that nothing sets is an
error instead of a silent zero.
"""

from __future__ import annotations

from typing import Any

__all__ = ["struct_fields", "struct_from"]


def struct_fields(struct_type: Any) -> list[str]:
    """The field names of the Warp struct ``struct_type`` (a ``@wp.struct`` class), in declaration order."""
    return list(struct_type.vars)


def struct_from(struct_type: Any, *sources: Any, **values: Any) -> Any:
    """A new ``struct_type`` instance with every field set: from ``values`` where it names the field, else
    from the first of ``sources`` (configs) that has an attribute of the field's name.

    Raises:
        ValueError: a field that neither gives (named, with the struct), or a keyword that is not a field.
    """
    names = struct_fields(struct_type)
    unknown = sorted(set(values) - set(names))
    if unknown:
        raise ValueError(f"{struct_type.key}: no field {', '.join(unknown)}; its fields: {', '.join(names)}")
    instance = struct_type()
    missing = []
    for name in names:
        if name in values:
            setattr(instance, name, values[name])
            continue
        source = next((s for s in sources if hasattr(s, name)), None)
        if source is None:
            missing.append(name)
        else:
            setattr(instance, name, getattr(source, name))
    if missing:
        raise ValueError(f"{struct_type.key}: nothing gives {', '.join(missing)}")
    return instance
