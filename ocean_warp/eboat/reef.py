"""The E-Boat's reef levels on the host: what sail a level sets, for tests, docs and drawings.

A reef level k sails the full sail scaled by a linear factor s_k about its tack, the foot of its luff at the
mast (``EBoatConfig.reef_areas``; the rig's kernel, ``kernels.sailing_rig``, does the same on the device):
area s^2 A, the centre of effort's height above the foot s times the full sail's, its arm aft of the mast s
times the full sail's. Level 0 is the full sail (s = 1).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .eboat import EBoat

__all__ = ["ReefedSail", "reefed_sail", "require_reef_levels"]


@dataclasses.dataclass(frozen=True)
class ReefedSail:
    """The sail of one reef level, as the rig sails it (body frame: x to the bow, y to port, z up) [m]."""

    level: int
    """0: the full sail; k: ``EBoatConfig.reef_areas[k - 1]``."""
    scale: float
    """Linear factor s on the full sail's dimensions about its tack."""
    area: float
    """[m^2]: s^2 times the full sail's."""
    arm: float
    """Distance of the centre of effort aft of the boom's pivot, along the boom [m]."""
    foot_height: float
    """Height of the sail's foot (its tack), the same at every level [m]."""
    center_height: float
    """Height of the centre of effort [m]: foot + s (full centre - foot)."""
    center: np.ndarray
    """(3,) the centre of effort with the boom at ``boom_angle`` [m] (the pivot plus ``arm`` along the boom)."""


def reefed_sail(eboat: EBoat, level: int, boom_angle: float = 0.0) -> ReefedSail:
    """The sail ``eboat`` sets at reef ``level`` (0 ... ``eboat.config.reef_levels`` - 1), its centre of effort
    with the boom at ``boom_angle`` [rad, positive to port]."""
    levels = eboat.config.reef_levels
    if isinstance(level, bool) or not isinstance(level, (int, np.integer)) or not 0 <= level < levels:
        raise ValueError(f"reefed_sail: reef_level must be an integer in [0, {levels - 1}], got {level!r}")
    if not math.isfinite(boom_angle):
        raise ValueError(f"reefed_sail: boom_angle must be finite [rad], got {boom_angle!r}")
    scale = eboat.config.reef_scales[int(level)]
    figures, geometry = eboat.rig_figures, eboat.geometry
    foot, full_height = eboat.sail_foot_height, eboat.sail_center_height
    arm = scale * figures.sail_arm
    height = foot + scale * (full_height - foot)
    pivot = geometry.boom_pivot
    center = np.array([pivot[0] - arm * math.cos(boom_angle), pivot[1] + arm * math.sin(boom_angle), height])
    return ReefedSail(level=int(level), scale=scale, area=scale * scale * figures.sail_area, arm=arm,
                      foot_height=foot, center_height=height, center=center)


def require_reef_levels(owner: str, field: str, value, count: int, levels: int) -> np.ndarray:
    """(count,) int32 reef levels from one level or ``count`` of them, each a whole number in [0, levels);
    else ``ValueError`` naming ``owner.field``."""
    if hasattr(value, "detach"):
        value = value.detach().cpu().numpy()
    try:
        array = np.broadcast_to(np.asarray(value), (count,))
    except (TypeError, ValueError):
        raise ValueError(f"{owner}.{field} must be one reef level or {count} of them, got shape "
                         f"{np.shape(value)}") from None
    if array.dtype == bool or not (np.issubdtype(array.dtype, np.integer) or np.issubdtype(array.dtype, np.floating)):
        raise ValueError(f"{owner}.{field} must hold whole reef levels in [0, {levels - 1}], got {value!r}")
    numbers = array.astype(np.float64)
    if not np.all(np.isfinite(numbers)) or np.any(numbers != np.round(numbers)) or np.any(numbers < 0) \
            or np.any(numbers >= levels):
        raise ValueError(f"{owner}.{field} must hold whole reef levels in [0, {levels - 1}] (the boat's "
                         f"{levels} levels), got {value!r}")
    return numbers.astype(np.int32)
