"""Lift and drag of foils (sail, keel, rudder) from tabulated coefficients, in 3D.

A foil is a span direction s, a chord direction c (leading edge to trailing edge, perpendicular to
s), an area A and a centre of effort. The flow it sees is the fluid's velocity minus the velocity of
that point; only its part in the section plane (perpendicular to s) counts, so when the boat heels
and the mast leans, the sail sees less of a horizontal wind, with no separate heel formula. With d
the unit section flow and alpha the angle from c to d about s:

    F = 1/2 rho A |V_section|^2 (C_L(alpha) s x d + C_D(alpha) d)

The tables hold C_L and C_D from 0 to 180 degrees in 1-degree steps; C_L is odd and C_D even in alpha.
"""

from __future__ import annotations

import warp as wp

from .spatial import DEGREES

__all__ = ["FoilTables", "interpolate_table", "angle_of_attack", "foil_force"]

TABLE_STEP_DEG = wp.constant(1.0)
TABLE_LAST = wp.constant(180)
# Below this section speed [m/s] the flow direction is undefined and the foil carries no force.
MIN_FOIL_SPEED = wp.constant(1.0e-6)


@wp.struct
class FoilTables:
    """Coefficient tables, 181 entries each, index = angle of attack in degrees."""

    sail_lift: wp.array(dtype=float)
    sail_drag: wp.array(dtype=float)
    keel_lift: wp.array(dtype=float)
    keel_drag: wp.array(dtype=float)
    rudder_lift: wp.array(dtype=float)
    rudder_drag: wp.array(dtype=float)


@wp.func
def interpolate_table(table: wp.array(dtype=float), angle_deg: float) -> float:
    """Linear interpolation of a 0-180 degree table at ``angle_deg`` in [0, 180]."""
    position = wp.clamp(angle_deg / TABLE_STEP_DEG, 0.0, float(TABLE_LAST))
    lower = wp.min(int(wp.floor(position)), TABLE_LAST - 1)
    fraction = position - float(lower)
    return table[lower] + fraction * (table[lower + 1] - table[lower])


@wp.func
def angle_of_attack(flow_direction: wp.vec3, chord: wp.vec3, span: wp.vec3) -> float:
    """Signed angle [rad] from the chord to the (unit, in-plane) flow direction, about the span."""
    return wp.atan2(wp.dot(wp.cross(chord, flow_direction), span), wp.dot(chord, flow_direction))


@wp.func
def foil_force(
    flow: wp.vec3, chord: wp.vec3, span: wp.vec3, area: float, density: float,
    lift: wp.array(dtype=float), drag: wp.array(dtype=float), lift_limit: float,
) -> wp.vec4:
    """(force [N], angle of attack [rad]) of a foil of ``area`` [m^2] in a fluid of ``density``
    [kg/m^3] moving at ``flow`` [m/s] relative to its centre of effort. Vectors in any one frame;
    ``chord`` and ``span`` unit and perpendicular. C_L is read at no larger |alpha| than
    ``lift_limit`` [rad] (pi: the table as it is)."""
    section = flow - wp.dot(flow, span) * span
    speed = wp.length(section)
    if speed < MIN_FOIL_SPEED:
        return wp.vec4()
    direction = section / speed
    alpha = angle_of_attack(direction, chord, span)
    magnitude = wp.abs(alpha) * DEGREES
    sign = wp.where(alpha < 0.0, -1.0, 1.0)
    c_lift = sign * interpolate_table(lift, wp.min(magnitude, lift_limit * DEGREES))
    c_drag = interpolate_table(drag, magnitude)
    force = (0.5 * density * area * speed * speed) * (c_lift * wp.cross(span, direction) + c_drag * direction)
    return wp.vec4(force[0], force[1], force[2], alpha)
