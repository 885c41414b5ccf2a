"""The diffraction weights of a hydrodynamic database: how the hull pass turns what its wave points read into the
effective water velocity of each degree of freedom (see :mod:`ocean_warp.seakeeping.wave_points`)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .wave_points import WAVE_POINT_COUNT, WAVE_POINT_INPUTS

__all__ = ["DiffractionWeights"]


def _frozen(value) -> np.ndarray:
    array = np.array(value, dtype=np.float64)
    array.flags.writeable = False
    return array


def _rounded(array: np.ndarray) -> list:
    """Nested lists of ``array``'s values to 7 significant digits (the fit is good to a few per cent)."""
    return np.vectorize(lambda v: float(f"{v:.7g}"), otypes=[float])(array).tolist()


@dataclasses.dataclass(frozen=True)
class DiffractionWeights:
    """V_i = sum over points p and inputs c of weights[i, p, c] s[p, c]: s the point's u, v, w [m/s] (body frame)
    at ``velocity_depth`` and its dynamic pressure head [m] at ``pressure_depth``; V about the body origin, body
    frame, [m/s] for surge, sway, heave and [rad/s] for roll, pitch, yaw. Invalid values raise ``ValueError``."""

    points: np.ndarray
    """(33, 2) body-frame x, y [m] of the wave points."""
    weights: np.ndarray
    """(6, 33, 4) [-, 1/s] for the linear DOFs, [1/m, 1/(m s)] for the angular ones (velocity, head inputs)."""
    velocity_depth: float
    """Depth [m, positive down] of the velocities the weights were fitted for (the ocean's middle pressure depth)."""
    pressure_depth: float
    """Depth [m] of the pressure head (the ocean's deepest pressure depth)."""
    pressure_depths: tuple = ()
    """The ocean's three pressure depths [m] the fit assumed (its Froude-Krylov profile), or () where it did not
    depend on them beyond ``velocity_depth`` and ``pressure_depth``."""
    fit_error: float = math.nan
    """RMS over the fitted frequencies and headings of |excitation_sim - excitation_BEM| / max(|excitation_BEM|,
    5 % of its largest over the headings at that frequency), heave, roll and pitch (NaN: not fitted)."""

    def __post_init__(self):
        object.__setattr__(self, "points", _frozen(self.points))
        object.__setattr__(self, "weights", _frozen(self.weights))
        object.__setattr__(self, "pressure_depths", tuple(float(v) for v in self.pressure_depths))
        for name in ("velocity_depth", "pressure_depth", "fit_error"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)):
                raise ValueError(f"diffraction.{name} must be a number, got {value!r}")
            object.__setattr__(self, name, float(value))
        problem = self._problem()
        if problem is not None:
            raise ValueError(f"diffraction: {problem}")

    def _problem(self) -> str | None:
        if self.points.shape != (WAVE_POINT_COUNT, 2):
            return f"points must have shape ({WAVE_POINT_COUNT}, 2), got {self.points.shape}"
        shape = (6, WAVE_POINT_COUNT, WAVE_POINT_INPUTS)
        if self.weights.shape != shape:
            return f"weights must have shape {shape}, got {self.weights.shape}"
        for name in ("points", "weights"):
            bad = ~np.isfinite(getattr(self, name))
            if bad.any():
                first = tuple(int(i) for i in np.argwhere(bad)[0])
                return f"{name} has {int(bad.sum())} NaN or infinite values (first at {first})"
        if not (math.isfinite(self.velocity_depth) and math.isfinite(self.pressure_depth)
                and 0.0 < self.velocity_depth < self.pressure_depth):
            return (f"velocity_depth and pressure_depth must be finite with 0 < velocity_depth < pressure_depth [m], "
                    f"got {self.velocity_depth!r} and {self.pressure_depth!r}")
        depths = self.pressure_depths
        if depths and (len(depths) != 3 or not all(map(math.isfinite, depths))
                       or depths[1:] != (self.velocity_depth, self.pressure_depth)):
            return ("pressure_depths must be three finite depths whose last two are velocity_depth and "
                    f"pressure_depth, got {self.pressure_depths!r}")
        return None

    def effective_velocity(self, inputs) -> np.ndarray:
        """(..., 6) V from ``inputs`` (..., 33, 4) (complex or real)."""
        return np.einsum("ipc,...pc->...i", self.weights, inputs)

    def to_json(self) -> dict:
        return {"points": _rounded(self.points), "weights": _rounded(self.weights),
                "velocity_depth": self.velocity_depth, "pressure_depth": self.pressure_depth,
                "pressure_depths": list(self.pressure_depths),
                "fit_error": None if math.isnan(self.fit_error) else self.fit_error}

    @classmethod
    def from_json(cls, data) -> "DiffractionWeights":
        """From :meth:`to_json`'s dict; ``ValueError`` naming the field otherwise."""
        if not isinstance(data, dict):
            raise ValueError("diffraction must be an object with points, weights, velocity_depth, pressure_depth")
        arrays = {}
        for name in ("points", "weights"):
            if name not in data:
                raise ValueError(f"missing field 'diffraction.{name}'")
            try:
                arrays[name] = np.array(data[name], dtype=np.float64)
            except (TypeError, ValueError):
                raise ValueError(f"diffraction.{name} must be an array of numbers") from None
        for name in ("velocity_depth", "pressure_depth"):
            if name not in data:
                raise ValueError(f"missing field 'diffraction.{name}'")
        depths = data.get("pressure_depths", [])
        if not isinstance(depths, list) or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                   for v in depths):
            raise ValueError(f"diffraction.pressure_depths must be a list of numbers, got {depths!r}")
        error = data.get("fit_error")
        return cls(points=arrays["points"], weights=arrays["weights"], velocity_depth=data["velocity_depth"],
                   pressure_depth=data["pressure_depth"], pressure_depths=tuple(depths),
                   fit_error=math.nan if error is None else error)
