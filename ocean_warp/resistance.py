"""Forward resistance of a displacement hull: friction plus residuary (wave-making) resistance.

The per-triangle water model keeps hydrostatics, the Froude-Krylov force and cross-flow drag; what a
streamlined hull meets when it moves ahead lives here, as a naval architect would estimate it:

- friction: the ITTC-1957 line C_F = 0.075 / (log10 Re - 2)^2 with a form factor (1 + k), applied by
  the hull pass per wetted triangle (so the wetted area is the mesh's own, heeled or in waves);
- residuary resistance from the Delft Systematic Yacht Hull Series: the bare-hull regression of
  Keuning and Katgert (2008, "A bare hull resistance prediction method derived from the results of the
  Delft Systematic Yacht Hull Series extended to higher speeds"; the coefficients as tabulated in
  Fossati, "Aero-Hydrodynamics and the Performance of Sailing Yachts", 2009), and the change with heel
  of Keuning and Sonnenberg (1998, "Approximation of the hydrodynamic forces on a sailing yacht based on
  the Delft Systematic Yacht Hull Series"), which scales the increase measured at 20 deg of heel by
  6 phi^1.7 (phi in radians).

The regressions read the hull's form (:class:`~ocean_warp.hull_form.HullForm`, measured on the mesh).
They are tabulated here, once per hull, over the Froude number Fn = U / sqrt(g Lwl) on a uniform grid,
which the hull kernel interpolates per boat (see ``kernels.hull_forces.residuary_wrench``).
"""

from __future__ import annotations

import dataclasses
import numpy as np

from .hull_form import HullForm
from .kernels.hull_forces import RESIDUARY_SAMPLES, RESIDUARY_STEP
from .validation import require_finite, require_positive

__all__ = ["ResiduaryResistance", "ittc_1957", "delft_bare_hull", "delft_heel_increase", "FROUDE_STEP",
           "FROUDE_SAMPLES", "DEFAULT_FORM_FACTOR"]

FROUDE_STEP = float(RESIDUARY_STEP)
"""Spacing of the tabulated Froude numbers, 0.05 (the regressions' own grid)."""
FROUDE_SAMPLES = int(RESIDUARY_SAMPLES)
"""16: Fn = 0, 0.05, ..., 0.75; beyond, the kernel extends the last interval's slope (to Fn 1 at most)."""

DEFAULT_FORM_FACTOR = 0.10
"""k in (1 + k) on the friction of a yacht's canoe body: Larsson and Eliasson ("Principles of Yacht
Design") give 1 + k of about 1.05 to 1.15 for canoe bodies; the middle, for the E-Boat's full sections."""

# Keuning and Katgert (2008), bare hull: Rr / (volume rho g) = a0 + (a1 LCB/Lwl + a2 Cp + a3 V^(2/3)/Aw
# + a4 Bwl/Lwl + a5 LCB/LCF + a6 Bwl/Tc + a7 Cm) V^(1/3)/Lwl, LCB and LCF as fractions of Lwl from the
# forward end of the waterline. One row per coefficient, one column per Froude number.
_DELFT_2008_FROUDE = (0.00, 0.15, 0.20, 0.25, 0.30, 0.35, 0.40, 0.45, 0.50, 0.55, 0.60, 0.65, 0.70, 0.75)
_DELFT_2008 = np.array([
    (0.0, -0.0005, -0.0003, -0.0002, -0.0009, -0.0026, -0.0064, -0.0218, -0.0388, -0.0347, -0.0361, 0.0008, 0.0108, 0.1023),
    (0.0, 0.0023, 0.0059, -0.0156, 0.0016, -0.0567, -0.4034, -0.5261, -0.5986, -0.4764, 0.0037, 0.3728, -0.1238, 0.7726),
    (0.0, -0.0086, -0.0064, 0.0031, 0.0337, 0.0446, -0.1250, -0.2945, -0.3038, -0.2361, -0.2960, -0.3667, -0.2026, 0.5040),
    (0.0, -0.0015, 0.0070, -0.0021, -0.0285, -0.1091, 0.0273, 0.2485, 0.6033, 0.8726, 0.9661, 1.3957, 1.1282, 1.7867),
    (0.0, 0.0061, 0.0014, -0.0070, -0.0367, -0.0707, -0.1341, -0.2428, -0.0430, 0.4219, 0.6123, 1.0343, 1.1836, 2.1934),
    (0.0, 0.0010, 0.0013, 0.0148, 0.0218, 0.0914, 0.3578, 0.6293, 0.8332, 0.8990, 0.7534, 0.3230, 0.4973, -1.5479),
    (0.0, 0.0001, 0.0005, 0.0010, 0.0015, 0.0021, 0.0045, 0.0081, 0.0106, 0.0096, 0.0100, 0.0072, 0.0038, -0.0115),
    (0.0, 0.0052, -0.0020, -0.0043, -0.0172, -0.0078, 0.1115, 0.2086, 0.1336, -0.2272, -0.3352, -0.4632, -0.4477, -0.0977),
])

# Keuning and Sonnenberg (1998), increase at 20 deg of heel: dRr / (volume rho g) = 1e-3 (u0 + u1 Lwl/Bwl
# + u2 Bwl/Tc + u3 (Bwl/Tc)^2 + u4 LCB + u5 LCB^2), LCB in per cent of Lwl forward of midships.
_HEEL_FROUDE = (0.00, 0.25, 0.30, 0.35, 0.40, 0.45, 0.50, 0.55)
_HEEL_1998 = np.array([
    (0.0, -0.0268, 0.6628, 1.6433, -0.8659, -3.2715, -0.1976, 1.5873),
    (0.0, -0.0014, -0.0632, -0.2144, -0.0354, 0.1372, -0.1480, -0.3749),
    (0.0, -0.0057, -0.0699, -0.1640, 0.2226, 0.5547, -0.6593, -0.7105),
    (0.0, 0.0016, 0.0069, 0.0199, 0.0188, 0.0268, 0.1862, 0.2146),
    (0.0, -0.0070, 0.0459, -0.0540, -0.5800, -1.0064, -0.7489, -0.4818),
    (0.0, -0.0017, -0.0004, -0.0268, -0.1133, -0.2026, -0.1648, -0.1174),
])


def ittc_1957(reynolds) -> np.ndarray:
    """The ITTC-1957 model-ship correlation line C_F = 0.075 / (log10 Re - 2)^2 (Re > 100)."""
    reynolds = np.asarray(reynolds, dtype=np.float64)
    if np.any(reynolds <= 100.0):
        raise ValueError(f"ittc_1957: Reynolds numbers must be > 100, got {reynolds!r}")
    return 0.075 / (np.log10(reynolds) - 2.0) ** 2


def delft_bare_hull(form: HullForm) -> tuple[np.ndarray, np.ndarray]:
    """(Froude numbers, Rr / (volume rho g)) of the Keuning-Katgert regression for ``form``."""
    v13 = form.displaced_volume ** (1.0 / 3.0)
    terms = np.array([1.0, form.lcb_fraction, form.prismatic_coefficient, v13 ** 2 / form.waterplane_area,
                      form.waterline_beam / form.waterline_length, form.lcb_fraction / form.lcf_fraction,
                      form.waterline_beam / form.canoe_draft, form.midship_coefficient])
    scale = np.array([1.0] + [v13 / form.waterline_length] * 7)
    return np.array(_DELFT_2008_FROUDE), (terms * scale) @ _DELFT_2008


def delft_heel_increase(form: HullForm) -> tuple[np.ndarray, np.ndarray]:
    """(Froude numbers, increase of Rr / (volume rho g) at 20 deg of heel) of Keuning and Sonnenberg."""
    lcb_percent = (0.5 - form.lcb_fraction) * 100.0
    btr = form.beam_draft_ratio
    terms = np.array([1.0, form.waterline_length / form.waterline_beam, btr, btr * btr, lcb_percent,
                      lcb_percent * lcb_percent])
    return np.array(_HEEL_FROUDE), 1e-3 * (terms @ _HEEL_1998)


LOW_FROUDE_EXPONENT = 4.0
"""Below the regressions' first Froude number the residuary resistance falls as (Fn / Fn_first)^4 (assumed:
wave-making resistance vanishes much faster than linearly at low speed; the regressions are not defined
there, and a straight line to zero left about 1 N of wave resistance at 0.5 m/s where the ORC surfaces
have 0.1 N)."""


def _resample(froude: np.ndarray, values: np.ndarray) -> np.ndarray:
    """``values`` at Fn = 0, FROUDE_STEP, ...: linear inside, the last slope beyond, the low-Froude power
    law below the first non-zero Froude number, never below 0."""
    grid = FROUDE_STEP * np.arange(FROUDE_SAMPLES)
    inside = np.interp(grid, froude, values)
    first = froude[1]
    inside = np.where(grid < first, values[1] * (grid / first) ** LOW_FROUDE_EXPONENT, inside)
    slope = (values[-1] - values[-2]) / (froude[-1] - froude[-2])
    beyond = values[-1] + slope * (grid - froude[-1])
    return np.maximum(np.where(grid > froude[-1], beyond, inside), 0.0)


@dataclasses.dataclass(frozen=True)
class ResiduaryResistance:
    """A hull's residuary resistance, tabulated over the Froude number: R = volume rho g (r(Fn) +
    dr20(Fn) 6 phi^1.7), phi the heel [rad], along minus the speed through the water, at
    ``center`` (body frame [m])."""

    waterline_length: float
    """Lwl [m] of the Froude number Fn = U / sqrt(g Lwl)."""
    displaced_volume: float
    """Canoe body volume at rest [m^3]."""
    upright: tuple
    """r at Fn = 0, 0.05, ..., 0.75 (FROUDE_SAMPLES values, dimensionless, >= 0)."""
    heel_increase: tuple
    """dr20 at the same Froude numbers (dimensionless, >= 0)."""
    center: tuple = (0.0, 0.0, 0.0)
    """Where the force acts [m]: the centre of buoyancy at rest."""

    def __post_init__(self):
        owner = "ResiduaryResistance"
        require_positive(owner, "waterline_length", self.waterline_length, unit=" [m]")
        require_positive(owner, "displaced_volume", self.displaced_volume, unit=" [m^3]")
        for name in ("upright", "heel_increase"):
            values = np.asarray(getattr(self, name), dtype=np.float64)
            if values.shape != (FROUDE_SAMPLES,) or not np.all(np.isfinite(values)) or np.any(values < 0):
                raise ValueError(f"{owner}.{name} must be {FROUDE_SAMPLES} finite values >= 0, got {values!r}")
            object.__setattr__(self, name, tuple(float(v) for v in values))
        center = tuple(require_finite(owner, "center", c) for c in self.center)
        if len(center) != 3:
            raise ValueError(f"{owner}.center must be 3 coordinates [m], got {self.center!r}")
        object.__setattr__(self, "center", center)

    @classmethod
    def delft(cls, form: HullForm) -> "ResiduaryResistance":
        """The Delft regressions for a hull of this ``form``."""
        upright = _resample(*delft_bare_hull(form))
        heel = _resample(*delft_heel_increase(form))
        return cls(waterline_length=form.waterline_length, displaced_volume=form.displaced_volume,
                   upright=tuple(upright), heel_increase=tuple(heel), center=form.center_of_buoyancy)
