"""A fin (keel, rudder) as a lifting surface: lift and drag coefficients from its planform.

Below stall, lifting-line theory for a finite wing as Helmbold's low-aspect-ratio form gives it (the
lift slope of Anderson, "Fundamentals of Aerodynamics", eq. 5.82, and Hoerner, "Fluid-Dynamic Lift",
ch. 3):

    a = 2 pi AR_e / (2 + sqrt(AR_e^2 + 4))   [per rad],     C_L = a alpha,
    C_D = C_D0 + C_L^2 / (pi e AR_e),

with AR_e the effective aspect ratio: the geometric span^2 / area times ``end_plate_factor`` (2 for a
fin whose root meets the hull, which mirrors it like a wall: Hoerner; 1 for a free fin) and e the span
efficiency (Oswald). The profile drag is the section's: C_D0 = 2 C_F (1 + 2 t/c + 60 (t/c)^4) with C_F
the ITTC-1957 line at the mean chord's Reynolds number (Hoerner, "Fluid-Dynamic Drag", ch. 6).

Stall: the attached lift is held to ``max_lift`` and, beyond the angle where a alpha reaches it, blended
(smoothstep over ``stall_width``) into a flat plate's normal-force coefficient C_N sin(alpha), i.e.
C_L = C_N sin(alpha) cos(alpha), C_D = C_D0 + C_N sin^2(alpha) (Hoerner: C_N of about 1.2 at 90 deg for
fins of this aspect ratio). Past 90 deg the fin meets the flow trailing edge first: C_L(180 - b) =
-C_L(b), C_D(180 - b) = C_D(b), as the seed's tables assume too.

:meth:`LiftingSurface.tables` tabulates C_L and C_D from 0 to 180 deg in 1 deg steps, the layout the
foil kernel reads (``kernels.foils``).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .resistance import ittc_1957
from .validation import require_in_range, require_positive

__all__ = ["LiftingSurface"]


def _smoothstep(x: np.ndarray) -> np.ndarray:
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


@dataclasses.dataclass(frozen=True)
class LiftingSurface:
    """A trapezoidal fin: span and chords [m], and the figures of its lift and drag."""

    span: float
    """From root to tip [m]."""
    root_chord: float
    """[m]"""
    tip_chord: float
    """[m]"""
    thickness_ratio: float = 0.12
    """t/c of the section (dimensionless, 0 to 0.3)."""
    end_plate_factor: float = 2.0
    """Effective over geometric aspect ratio: 2 for a fin on a hull (a reflection plane), 1 free (1 to 2)."""
    span_efficiency: float = 0.9
    """e of the induced drag (dimensionless, 0.5 to 1): 1 for an elliptic load, about 0.9 for a tapered fin."""
    max_lift: float = 1.0
    """Largest attached C_L (dimensionless, 0.3 to 2): a NACA 00xx section at Re of a few 10^5 reaches
    about 1.1 (Abbott and von Doenhoff), a little less on a finite fin."""
    stall_width: float = math.radians(8.0)
    """Angle over which attached flow gives way to the flat plate [rad] (0.01 to 0.6)."""
    flat_plate_normal: float = 1.2
    """C_N of the stalled fin at 90 deg (dimensionless, 0.5 to 2; Hoerner)."""
    design_speed: float = 1.5
    """Flow speed [m/s] for the section's Reynolds number (profile drag)."""
    kinematic_viscosity: float = 1.19e-6
    """nu [m^2/s], sea water at 15 C."""

    def __post_init__(self):
        owner = "LiftingSurface"
        for name in ("span", "root_chord", "tip_chord", "design_speed", "kinematic_viscosity"):
            require_positive(owner, name, getattr(self, name))
        require_in_range(owner, "thickness_ratio", self.thickness_ratio, 0.0, 0.3)
        require_in_range(owner, "end_plate_factor", self.end_plate_factor, 1.0, 2.0)
        require_in_range(owner, "span_efficiency", self.span_efficiency, 0.5, 1.0)
        require_in_range(owner, "max_lift", self.max_lift, 0.3, 2.0)
        require_in_range(owner, "stall_width", self.stall_width, 0.01, 0.6, unit=" [rad]")
        require_in_range(owner, "flat_plate_normal", self.flat_plate_normal, 0.5, 2.0)

    @property
    def area(self) -> float:
        """Planform area [m^2]."""
        return 0.5 * self.span * (self.root_chord + self.tip_chord)

    @property
    def aspect_ratio(self) -> float:
        """Geometric span^2 / area."""
        return self.span ** 2 / self.area

    @property
    def effective_aspect_ratio(self) -> float:
        return self.end_plate_factor * self.aspect_ratio

    @property
    def lift_slope(self) -> float:
        """dC_L/dalpha [per rad]."""
        ar = self.effective_aspect_ratio
        return 2.0 * math.pi * ar / (2.0 + math.sqrt(ar * ar + 4.0))

    @property
    def stall_angle(self) -> float:
        """Angle of attack [rad] at which the attached lift reaches ``max_lift``."""
        return self.max_lift / self.lift_slope

    @property
    def profile_drag(self) -> float:
        """C_D0 of the section at the design speed."""
        mean_chord = self.area / self.span
        friction = float(ittc_1957(self.design_speed * mean_chord / self.kinematic_viscosity))
        t = self.thickness_ratio
        return 2.0 * friction * (1.0 + 2.0 * t + 60.0 * t ** 4)

    def coefficients(self, alpha) -> tuple[np.ndarray, np.ndarray]:
        """(C_L, C_D) at angles of attack ``alpha`` [rad] (any sign: C_L odd, C_D even)."""
        alpha = np.asarray(alpha, dtype=np.float64)
        sign = np.sign(alpha)
        angle = np.abs(np.mod(alpha + math.pi, 2.0 * math.pi) - math.pi)  # |alpha| wrapped to [0, pi]
        reversed_flow = angle > 0.5 * math.pi
        b = np.where(reversed_flow, math.pi - angle, angle)
        attached_lift = np.minimum(self.lift_slope * b, self.max_lift)
        attached_drag = self.profile_drag + attached_lift ** 2 / (math.pi * self.span_efficiency
                                                                  * self.effective_aspect_ratio)
        normal = self.flat_plate_normal * np.sin(b)
        plate_lift = normal * np.cos(b)
        plate_drag = self.profile_drag + normal * np.sin(b)
        w = _smoothstep((b - self.stall_angle) / self.stall_width)
        lift = (1.0 - w) * attached_lift + w * plate_lift
        drag = (1.0 - w) * attached_drag + w * plate_drag
        return sign * np.where(reversed_flow, -lift, lift), drag

    def tables(self) -> tuple[np.ndarray, np.ndarray]:
        """(181,) C_L and (181,) C_D at 0, 1, ..., 180 deg."""
        return self.coefficients(np.radians(np.arange(181.0)))
