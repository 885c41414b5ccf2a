"""A mainsail alone: lift and drag coefficients by angle of attack, from the ORC's published figures.

The ORC VPP (ORC VPP Documentation, "Aerodynamic model"; the coefficients go back to Hazen 1980 and
were revised by the ORC) tabulates a main's lift C_L and parasitic drag C_Dp against the apparent wind
angle, the sail trimmed for speed, and adds a quadratic drag:

    C_D = C_Dp + (k_p + 1 / (pi AR_e)) C_L^2,     AR_e = h_eff^2 / A,   h_eff = 1.1 (P + BAD),

k_p = 0.0138 the main's viscous quadratic term and h_eff the effective span of a main alone (its luff P
and the boom's height above deck BAD; the 1.1 counts the deck's reflection). Our kernel reads the sail's
coefficients by angle of attack between the boom and the flow, so the ORC figures are read this way:

- Sheeted in (up to 28 deg): at the ORC's smallest apparent wind angles the main is sheeted on the
  centreline, so the angle of attack is the apparent wind angle: C_L and C_Dp through the ORC's points
  at 0, 7, 9, 12 and 28 deg (monotone cubic). Those were measured with a jib, whose upwash lets the
  main draw at 7 deg; a main alone flogs until the wind meets its luff from the windward side. So the
  points are spread linearly from [0, 28] over [``luff_deg``, 28] deg, with C_L 0 and the ORC's 0.034
  flogging drag below ``luff_deg``. Easing the sheet lowers the angle of attack: the sail luffs towards
  C_L 0: that is how the boat depowers.
- Separated (45 deg and beyond): a stalled sail pushes normal to its chord, C_N = 1.34 (the ORC's C_D
  square to the wind, 180 deg apparent), so C_L = C_N cos(alpha) and C_D = C_N sin(alpha). The ORC's
  points at 120 and 150 deg apparent (C_L 0.93, C_D 0.97; 0.39, 1.32) are this with C_N 1.34 and 1.37.
  Past 135 deg (wind from the leech) the normal force fades as sqrt(2) sin(alpha).
- Between 28 and 45 deg the attached sail (C_L held at its 28-deg value) blends into the separated
  one (smoothstep).

Heel needs no factor here: the kernel resolves the flow in the sail's own section plane, so a heeled
rig sees the horizontal wind's component normal to its mast (``kernels.foils``), as the ORC's
cos(heel) factors do.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .validation import require_in_range, require_positive

__all__ = ["ORC_MAIN", "Mainsail"]

ORC_MAIN = {
    "apparent_wind_deg": (0.0, 7.0, 9.0, 12.0, 28.0, 60.0, 90.0, 120.0, 150.0, 180.0),
    "lift": (0.0, 0.94828, 1.13793, 1.25, 1.42681, 1.38319, 1.26724, 0.93103, 0.38793, -0.11207),
    "parasitic_drag": (0.03448, 0.01724, 0.01466, 0.01466, 0.02586, 0.11302, 0.3825, 0.96888, 1.31578, 1.34483),
    "quadratic_drag": 0.01379,
}
"""The ORC's main coefficients ("high" lift set, as python-vpp 1.0.0 ships them in dat/main.dat): C_L and
C_Dp at the apparent wind angles [deg], and k_p."""

_SHEETED_IN = 5
"""The ORC points read as angles of attack with the main on the centreline (0 to 28 deg)."""
EFFECTIVE_SPAN_FACTOR = 1.1
"""h_eff / (P + BAD) of a main alone (ORC)."""


def _smoothstep(x: np.ndarray) -> np.ndarray:
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


def _monotone_cubic(x_known: np.ndarray, y_known: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Fritsch-Carlson monotone cubic Hermite interpolation of (x_known, y_known) at ``x`` (inside)."""
    h = np.diff(x_known)
    delta = np.diff(y_known) / h
    slope = np.zeros_like(y_known)
    for i in range(1, len(x_known) - 1):
        if delta[i - 1] * delta[i] > 0.0:
            w1, w2 = 2.0 * h[i] + h[i - 1], h[i] + 2.0 * h[i - 1]
            slope[i] = (w1 + w2) / (w1 / delta[i - 1] + w2 / delta[i])
    slope[0], slope[-1] = delta[0], delta[-1]
    i = np.clip(np.searchsorted(x_known, x, side="right") - 1, 0, len(h) - 1)
    t = (x - x_known[i]) / h[i]
    h00, h10, h01, h11 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t, -2 * t**3 + 3 * t**2, t**3 - t**2
    return h00 * y_known[i] + h10 * h[i] * slope[i] + h01 * y_known[i + 1] + h11 * h[i] * slope[i + 1]


@dataclasses.dataclass(frozen=True)
class Mainsail:
    """A main alone, by its area and the span that sets its induced drag (see the module docstring)."""

    area: float
    """A [m^2]."""
    luff: float
    """P, the luff's length [m]."""
    boom_above_deck: float
    """BAD [m]."""
    normal_force: float = 1.34
    """C_N of the separated sail (dimensionless, 0.5 to 2)."""
    separated_deg: float = 45.0
    """Angle of attack [deg] from which the sail is wholly separated (between 28 and 90)."""
    luff_deg: float = 8.0
    """Angle of attack [deg] below which a main alone flogs (0 to 20; 0: the ORC's points as they are, a main
    behind a jib). 8 deg: the seed's sail table, the E-Boat's Gazebo model, holds C_L under 0.15 up to 7 deg."""

    def __post_init__(self):
        owner = "Mainsail"
        require_positive(owner, "area", self.area, unit=" [m^2]")
        require_positive(owner, "luff", self.luff, unit=" [m]")
        require_in_range(owner, "boom_above_deck", self.boom_above_deck, 0.0, 10.0, unit=" [m]")
        require_in_range(owner, "normal_force", self.normal_force, 0.5, 2.0)
        require_in_range(owner, "separated_deg", self.separated_deg, 29.0, 90.0, unit=" [deg]")
        require_in_range(owner, "luff_deg", self.luff_deg, 0.0, 20.0, unit=" [deg]")

    @property
    def effective_aspect_ratio(self) -> float:
        """AR_e = (1.1 (P + BAD))^2 / A."""
        return (EFFECTIVE_SPAN_FACTOR * (self.luff + self.boom_above_deck)) ** 2 / self.area

    @property
    def quadratic_drag(self) -> float:
        """k_p + 1 / (pi AR_e): C_D per C_L^2."""
        return ORC_MAIN["quadratic_drag"] + 1.0 / (math.pi * self.effective_aspect_ratio)

    def coefficients(self, alpha) -> tuple[np.ndarray, np.ndarray]:
        """(C_L, C_D) at angles of attack ``alpha`` [rad] in [-pi, pi]: C_L odd, C_D even."""
        signed = np.degrees(np.asarray(alpha, dtype=np.float64))
        if np.any(~np.isfinite(signed)) or np.any(np.abs(signed) > 180.0 + 1e-9):
            raise ValueError(f"Mainsail.coefficients: alpha must be finite, in [-pi, pi] rad, got {alpha!r}")
        degrees = np.abs(signed)
        known = np.array(ORC_MAIN["apparent_wind_deg"][:_SHEETED_IN])
        spread = (degrees - self.luff_deg) * known[-1] / (known[-1] - self.luff_deg)
        held = np.clip(spread, 0.0, known[-1])
        lift = _monotone_cubic(known, np.array(ORC_MAIN["lift"][:_SHEETED_IN]), held)
        parasitic = _monotone_cubic(known, np.array(ORC_MAIN["parasitic_drag"][:_SHEETED_IN]), held)
        attached_drag = parasitic + self.quadratic_drag * lift**2
        b = np.radians(degrees)
        normal = self.normal_force * np.minimum(1.0, math.sqrt(2.0) * np.sin(b))
        separated_lift, separated_drag = normal * np.cos(b), normal * np.sin(b)
        w = _smoothstep((degrees - known[-1]) / (self.separated_deg - known[-1]))
        lift = np.sign(signed) * ((1.0 - w) * lift + w * separated_lift)
        return lift, (1.0 - w) * attached_drag + w * np.maximum(separated_drag, parasitic)

    def tables(self) -> tuple[np.ndarray, np.ndarray]:
        """C_L and C_D at 0, 1, ..., 180 deg, (181,) each (the foil kernel's layout)."""
        return self.coefficients(np.radians(np.arange(181.0)))
