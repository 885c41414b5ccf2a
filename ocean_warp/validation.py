"""Checks shared by the configs and the reset calls: each raises ``ValueError`` naming the field, the value
and what is allowed, so bad input fails on the host and not as NaN inside a kernel."""

from __future__ import annotations

import math
from numbers import Integral, Real

import numpy as np

__all__ = [
    "require_finite",
    "require_positive",
    "require_non_negative",
    "require_in_range",
    "require_int_in_range",
    "require_choice",
    "require_indices",
    "require_per_item",
    "require_rows",
]


def _describe(owner: str, field: str) -> str:
    return f"{owner}.{field}"


def require_finite(owner: str, field: str, value) -> float:
    """Return ``value`` as a float if it is a finite real number, else raise ``ValueError``."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise ValueError(f"{_describe(owner, field)} must be a real number, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{_describe(owner, field)} must be finite, got {value!r}")
    return value


def require_positive(owner: str, field: str, value, *, allow_inf: bool = False, unit: str = "") -> float:
    """Return ``value`` as a float if it is > 0 (and finite unless ``allow_inf``), else raise."""
    if isinstance(value, bool) or not isinstance(value, Real) or math.isnan(float(value)):
        raise ValueError(f"{_describe(owner, field)} must be a number > 0{unit}, got {value!r}")
    value = float(value)
    if math.isinf(value) and not (allow_inf and value > 0):
        allowed = "a number > 0 or inf" if allow_inf else "a finite number > 0"
        raise ValueError(f"{_describe(owner, field)} must be {allowed}{unit}, got {value!r}")
    if value <= 0.0:
        raise ValueError(f"{_describe(owner, field)} must be > 0{unit}, got {value!r}")
    return value


def require_non_negative(owner: str, field: str, value, *, unit: str = "") -> float:
    """Return ``value`` as a float if it is finite and >= 0, else raise ``ValueError``."""
    value = require_finite(owner, field, value)
    if value < 0.0:
        raise ValueError(f"{_describe(owner, field)} must be >= 0{unit}, got {value!r}")
    return value


def require_in_range(owner: str, field: str, value, low: float, high: float, *, unit: str = "") -> float:
    """Return ``value`` as a float if ``low <= value <= high``, else raise ``ValueError``."""
    value = require_finite(owner, field, value)
    if not low <= value <= high:
        raise ValueError(f"{_describe(owner, field)} must be in [{low}, {high}]{unit}, got {value!r}")
    return value


def require_range_pair(owner: str, field: str, pair, low: float, high: float) -> tuple[float, float]:
    """Return ``pair`` as a (low, high) tuple of floats, each in [``low``, ``high``] and in order, else raise
    ``ValueError`` naming ``owner.field``."""
    if not (isinstance(pair, (tuple, list)) and len(pair) == 2):
        raise ValueError(f"{_describe(owner, field)} must be a (low, high) pair, got {pair!r}")
    a = require_in_range(owner, field, pair[0], low, high)
    b = require_in_range(owner, field, pair[1], low, high)
    if a > b:
        raise ValueError(f"{_describe(owner, field)} must have low <= high, got {pair!r}")
    return (a, b)


def require_int_in_range(owner: str, field: str, value, low: int, high: int) -> int:
    """Return ``value`` as an int if it is an integer with ``low <= value <= high``, else raise."""
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise ValueError(f"{_describe(owner, field)} must be an integer in [{low}, {high}], got {value!r}")
    value = int(value)
    if not low <= value <= high:
        raise ValueError(f"{_describe(owner, field)} must be an integer in [{low}, {high}], got {value!r}")
    return value


def require_choice(owner: str, field: str, value, enum_type):
    """Return the member of ``enum_type`` (a str-valued Enum) named by ``value``, else raise."""
    try:
        return enum_type(value)
    except ValueError:
        allowed = ", ".join(repr(member.value) for member in enum_type)
        raise ValueError(f"{_describe(owner, field)} must be one of {allowed}, got {value!r}") from None


def require_indices(owner: str, field: str, indices, count: int) -> np.ndarray:
    """(K,) int32 indices into ``count`` items from None (all), a sequence, a numpy array or a torch tensor;
    raise ``ValueError`` on non-integers or indices outside [0, count)."""
    if indices is None:
        return np.arange(count, dtype=np.int32)
    if hasattr(indices, "detach"):  # a torch tensor
        indices = indices.detach().cpu().numpy()
    array = np.asarray(indices).reshape(-1)
    if array.size and not np.issubdtype(array.dtype, np.integer):
        raise ValueError(f"{_describe(owner, field)} must be integer indices, got dtype {array.dtype}")
    if array.size and (array.min() < 0 or array.max() >= count):
        raise ValueError(f"{_describe(owner, field)}: indices must lie in [0, {count - 1}], got "
                         f"[{array.min()}, {array.max()}]")
    return array.astype(np.int32)


def require_per_item(owner: str, field: str, value, count: int) -> np.ndarray:
    """(count,) float64 from one finite number or ``count`` of them (numpy, list or torch); else raise."""
    if hasattr(value, "detach"):
        value = value.detach().cpu().numpy()
    try:
        array = np.broadcast_to(np.asarray(value, dtype=np.float64), (count,))
    except (TypeError, ValueError):
        raise ValueError(f"{_describe(owner, field)} must be one number or {count} of them, got "
                         f"shape {np.shape(value)}") from None
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{_describe(owner, field)} holds NaN or infinite values")
    return array


def require_rows(owner: str, field: str, value, k: int, width: int) -> np.ndarray:
    """(k, width) float64 from ``k`` rows or one row of ``width`` finite numbers (numpy, list or torch)
    that broadcasts; else raise ``ValueError``."""
    if hasattr(value, "detach"):
        value = value.detach().cpu().numpy()
    array = np.asarray(value, dtype=np.float64)
    if array.shape == (width,):
        array = np.tile(array, (k, 1))
    if array.shape != (k, width):
        raise ValueError(f"{_describe(owner, field)} must have shape ({k}, {width}) or ({width},), got {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{_describe(owner, field)} holds NaN or infinite values")
    return array
