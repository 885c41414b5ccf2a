"""Coefficients of the per-triangle water forces (hydrostatic pressure, drag, friction, slamming)."""

from __future__ import annotations

import dataclasses

from .validation import require_in_range, require_non_negative, require_positive

__all__ = ["HydrodynamicsConfig"]


@dataclasses.dataclass(frozen=True)
class HydrodynamicsConfig:
    """Water and the per-triangle force model, after Kerner ("Water interaction model for boats in
    video games", 2015), applied to each submerged piece of each hull triangle:

    - hydrostatic pressure rho g depth, integrated exactly over the piece (always on);
    - pressure drag on pieces whose outward normal n faces the relative flow (cos t = n.v/|v| > 0):
      F = -(C_PD1 (v/v_r) + C_PD2 (v/v_r)^2) cos(t)^f_P A n;
    - suction on pieces moving away from the water behind them (cos t < 0):
      F = +(C_SD1 (v/v_r) + C_SD2 (v/v_r)^2) |cos t|^f_S A n;
    - viscous skin friction along the surface: F = -1/2 rho C_F A |v_t| v_t, with v_t the tangential
      relative velocity and C_F = 0.075 / (log10 Re - 2)^2 the ITTC-1957 line, Re = U L / nu from the
      boat's speed through the water U and the hull length L (Re held at >= 1e5, where the line is
      defined);
    - optional slamming on triangles entering the water (Kerner's model; off by default).

    With ``cross_flow_only`` the pressure drag and suction see only the flow across the hull (its body-x
    part removed): they then damp sway, heave, roll, pitch and yaw, while a streamlined hull moving
    ahead meets friction (times the form factor 1 + k) and, for a boat type that has one, the residuary
    resistance of ``ocean_warp.resistance``, not a bluff body's ram pressure.

    The water itself (density, gravity, viscosity) is the ocean's (``OceanConfig.water``).

    v is the velocity of the piece's centroid relative to the water's orbital velocity there. The
    default drag coefficients amount to a ram pressure of about 1/2 rho v^2 (drag coefficient 1) at
    the reference speed; tune them per hull.
    """

    reference_speed: float = 1.0
    """v_r [m/s], the speed at which the drag coefficients below are the pressure."""
    pressure_drag_linear: float = 100.0
    """C_PD1 [N/m^2]."""
    pressure_drag_quadratic: float = 500.0
    """C_PD2 [N/m^2]."""
    pressure_drag_falloff: float = 0.5
    """f_P, exponent of cos t in the pressure drag."""
    suction_linear: float = 100.0
    """C_SD1 [N/m^2]."""
    suction_quadratic: float = 500.0
    """C_SD2 [N/m^2]."""
    suction_falloff: float = 0.5
    """f_S, exponent of |cos t| in the suction."""
    skin_friction: bool = True
    """Apply the ITTC-1957 viscous friction."""
    form_factor: float = 0.0
    """k: the friction is (1 + k) times the flat plate's (dimensionless, 0 to 1)."""
    cross_flow_only: bool = False
    """Pressure drag and suction on the cross flow only (see above); False: on the whole relative flow."""
    slamming: bool = False
    """Apply Kerner's slamming force to triangles whose submerged swept volume grows fast."""
    slamming_power: float = 2.0
    """p in clamp(Gamma / Gamma_max, 0, 1)^p."""
    slamming_max_acceleration: float = 100.0
    """Gamma_max [m/s^2], the rate of swept-volume change per area at which slamming stops the piece."""

    def __post_init__(self):
        owner = "HydrodynamicsConfig"
        for name, unit in (("reference_speed", " [m/s]"),
                           ("slamming_max_acceleration", " [m/s^2]")):
            object.__setattr__(self, name, require_positive(owner, name, getattr(self, name), unit=unit))
        for name in ("pressure_drag_linear", "pressure_drag_quadratic", "pressure_drag_falloff", "suction_linear",
                     "suction_quadratic", "suction_falloff", "slamming_power"):
            object.__setattr__(self, name, require_non_negative(owner, name, getattr(self, name)))
        object.__setattr__(self, "form_factor", require_in_range(owner, "form_factor", self.form_factor, 0.0, 1.0))
        for name in ("skin_friction", "slamming", "cross_flow_only"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"{owner}.{name} must be True or False, got {getattr(self, name)!r}")

    def without_drag(self) -> "HydrodynamicsConfig":
        """The same water with only hydrostatic pressure (no drag, suction, friction or slamming)."""
        return dataclasses.replace(self, pressure_drag_linear=0.0, pressure_drag_quadratic=0.0, suction_linear=0.0,
                                   suction_quadratic=0.0, skin_friction=False, slamming=False)
