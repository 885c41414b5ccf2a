"""A sailing boat's rig and drive, one thread per boat per substep: actuators, boom, sail, keel,
rudder, windage and propeller, summed into the boat's model wrench (body frame, about the origin).

Conventions (body frame FLU): the boom angle is positive with the boom to port; the rudder angle is
positive with its trailing edge to port, which turns a boat going ahead to port (yaw rate > 0). The
boom swings free within +-(sheet limit), driven by the sail's moment about the mast against the
joint's damping, and stops dead at the limit. The rudder and the sheet limit move towards their
commands at fixed rates within their ranges.
"""

from __future__ import annotations

import warp as wp

from .foils import FoilTables, angle_of_attack, foil_coefficients
from .hull_forces import vec6
from .wind import GustModel, wind_at_height

__all__ = ["RigParameters", "sailing_rig", "reset_rig", "set_sheet"]

DEGREES = wp.constant(57.29577951308232)


@wp.struct
class RigParameters:
    """Geometry, actuators and the densities of a sailing rig (one boat type)."""

    mast_step: wp.vec3
    """Foot of the (vertical) mast in the body frame [m]."""
    sail_arm: float
    """Distance of the sail's centre of effort aft of the mast along the boom [m]."""
    sail_height: float
    """Height of the sail's centre of effort in the body frame [m]."""
    sail_area: float
    keel_center: wp.vec3
    keel_area: float
    rudder_center: wp.vec3
    rudder_area: float
    propeller_position: wp.vec3
    thrust_per_level: float
    """[N] per propeller level ahead."""
    reverse_factor: float
    max_level: int
    rudder_limit: float
    """[rad]"""
    rudder_rate: float
    """[rad/s]"""
    sheet_limit_max: float
    """[rad]"""
    sheet_rate: float
    """[rad/s]"""
    boom_inertia: float
    """Boom and sail about the mast [kg m^2]."""
    boom_damping: float
    """[N m s/rad]"""
    air_density: float
    water_density: float
    windage_area: float
    """Drag area (C_D A) of the mast, rigging and topsides in the apparent wind [m^2]."""
    windage_center: wp.vec3
    """Where the windage acts, body frame [m]."""
    sail_lift_limit_deg: float
    """C_L is read at min(|alpha|, this) (180: the table as it is; the original V-C used 100)."""
    foil_lift_limit_deg: float
    """The same for keel and rudder (the original V-C used 90)."""
    original_tuning: int
    """1: the original V-C's other tuning (rudder force x 0.3, keel minus 0.6 of the sail's side force,
    sail force x 0.1 outside 5-160 degrees of attack)."""


@wp.func
def _tabulated_force(
    flow: wp.vec3, chord: wp.vec3, span: wp.vec3, area: float, density: float,
    lift: wp.array(dtype=float), drag: wp.array(dtype=float), lift_limit_deg: float,
) -> wp.vec4:
    """(force [N], angle of attack [rad]) of a foil; C_L read no further than ``lift_limit_deg``."""
    section = flow - wp.dot(flow, span) * span
    speed = wp.length(section)
    if speed < 1.0e-6:
        return wp.vec4()
    direction = section / speed
    alpha = angle_of_attack(direction, chord, span)
    limited = wp.where(alpha < 0.0, -1.0, 1.0) * wp.min(wp.abs(alpha), lift_limit_deg / DEGREES)
    c_lift = foil_coefficients(lift, drag, limited)[0]
    c_drag = foil_coefficients(lift, drag, alpha)[1]
    force = (0.5 * density * area * speed * speed) * (c_lift * wp.cross(span, direction) + c_drag * direction)
    return wp.vec4(force[0], force[1], force[2], alpha)


@wp.func
def _approach(value: float, target: float, max_step: float) -> float:
    return value + wp.clamp(target - value, -max_step, max_step)


@wp.func
def _add(wrench: vec6, force: wp.vec3, at: wp.vec3) -> vec6:
    moment = wp.cross(at, force)
    return wrench + vec6(force[0], force[1], force[2], moment[0], moment[1], moment[2])


@wp.kernel(enable_backward=False)
def sailing_rig(
    rig: RigParameters,
    tables: FoilTables,
    gusts: GustModel,
    dt: float,
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    water_velocity: wp.array(dtype=wp.vec3),
    wind_velocity: wp.array(dtype=wp.vec3),
    rudder_command: wp.array(dtype=float),
    sheet_command: wp.array(dtype=float),
    propeller_command: wp.array(dtype=int),
    rudder_angle: wp.array(dtype=float),
    sheet_limit: wp.array(dtype=float),
    boom_angle: wp.array(dtype=float),
    boom_rate: wp.array(dtype=float),
    model_wrench: wp.array(dtype=vec6),
):
    """One substep of ``dt`` [s]: actuators and boom move, and the sail, keel, rudder and propeller
    wrenches are added to ``model_wrench``. Commands: rudder and sheet angles [rad], propeller level."""
    boat = wp.tid()
    rotation = orientation[boat]
    nu = velocity[boat]
    linear = wp.vec3(nu[0], nu[1], nu[2])
    angular = wp.vec3(nu[3], nu[4], nu[5])
    up = wp.vec3(0.0, 0.0, 1.0)
    down = wp.vec3(0.0, 0.0, -1.0)

    # Actuators.
    rudder = _approach(rudder_angle[boat], wp.clamp(rudder_command[boat], -rig.rudder_limit, rig.rudder_limit),
                       rig.rudder_rate * dt)
    limit = _approach(sheet_limit[boat], wp.clamp(sheet_command[boat], 0.0, rig.sheet_limit_max), rig.sheet_rate * dt)
    rudder_angle[boat] = rudder
    sheet_limit[boat] = limit

    # Sail: apparent wind at the centre of effort, which swings with the boom.
    boom = boom_angle[boat]
    boom_direction = wp.vec3(-wp.cos(boom), wp.sin(boom), 0.0)
    sail_center = wp.vec3(rig.mast_step[0], rig.mast_step[1], rig.sail_height) + rig.sail_arm * boom_direction
    sail_world = position[boat] + wp.quat_rotate(rotation, sail_center)
    wind = wp.quat_rotate_inv(rotation, wind_at_height(wind_velocity[boat], sail_world[2], gusts))
    sail_flow = wind - (linear + wp.cross(angular, sail_center))
    sail = _tabulated_force(sail_flow, boom_direction, up, rig.sail_area, rig.air_density, tables.sail_lift,
                            tables.sail_drag, rig.sail_lift_limit_deg)
    sail_force = wp.vec3(sail[0], sail[1], sail[2])
    if rig.original_tuning != 0:
        attack = wp.abs(sail[3]) * DEGREES
        if attack < 5.0 or attack > 160.0:
            sail_force = 0.1 * sail_force

    # Boom: free within the sheet limit, driven by the sail's moment about the mast. A positive boom
    # angle turns the boom clockwise seen from above (towards port, aft of the mast): about -z.
    about_mast = -wp.dot(wp.cross(rig.sail_arm * boom_direction, sail_force), up)
    rate = (boom_rate[boat] * rig.boom_inertia + dt * about_mast) / (rig.boom_inertia + dt * rig.boom_damping)
    new_boom = boom + dt * rate
    if new_boom > limit:
        new_boom = limit
        rate = wp.min(rate, 0.0)
    elif new_boom < -limit:
        new_boom = -limit
        rate = wp.max(rate, 0.0)
    boom_angle[boat] = new_boom
    boom_rate[boat] = rate

    # Keel and rudder in the water (its orbital velocity at the boat, body frame).
    water = water_velocity[boat]
    keel_flow = water - (linear + wp.cross(angular, rig.keel_center))
    keel = _tabulated_force(keel_flow, wp.vec3(-1.0, 0.0, 0.0), down, rig.keel_area, rig.water_density,
                            tables.foil_lift, tables.foil_drag, rig.foil_lift_limit_deg)
    keel_force = wp.vec3(keel[0], keel[1], keel[2])
    rudder_chord = wp.vec3(-wp.cos(rudder), wp.sin(rudder), 0.0)
    rudder_flow = water - (linear + wp.cross(angular, rig.rudder_center))
    rudder_drag = _tabulated_force(rudder_flow, rudder_chord, down, rig.rudder_area, rig.water_density,
                                   tables.foil_lift, tables.foil_drag, rig.foil_lift_limit_deg)
    rudder_force = wp.vec3(rudder_drag[0], rudder_drag[1], rudder_drag[2])
    if rig.original_tuning != 0:
        rudder_force = 0.3 * rudder_force
        keel_force = keel_force - wp.vec3(0.0, 0.6 * sail_force[1], 0.0)

    # Windage: the parasitic air drag of everything that is not sail.
    windage_world = position[boat] + wp.quat_rotate(rotation, rig.windage_center)
    windage_wind = wp.quat_rotate_inv(rotation, wind_at_height(wind_velocity[boat], windage_world[2], gusts))
    windage_flow = windage_wind - (linear + wp.cross(angular, rig.windage_center))
    windage_force = (0.5 * rig.air_density * rig.windage_area * wp.length(windage_flow)) * windage_flow

    # Propeller: integer levels, weaker astern, along the body x axis.
    level = wp.clamp(propeller_command[boat], -rig.max_level, rig.max_level)
    thrust = rig.thrust_per_level * float(level)
    if level < 0:
        thrust = thrust * rig.reverse_factor

    total = model_wrench[boat]
    total = _add(total, sail_force, sail_center)
    total = _add(total, keel_force, rig.keel_center)
    total = _add(total, rudder_force, rig.rudder_center)
    total = _add(total, windage_force, rig.windage_center)
    total = _add(total, wp.vec3(thrust, 0.0, 0.0), rig.propeller_position)
    model_wrench[boat] = total


@wp.kernel(enable_backward=False)
def reset_rig(
    boats: wp.array(dtype=int),
    rudder_command: wp.array(dtype=float),
    sheet_command: wp.array(dtype=float),
    propeller_command: wp.array(dtype=int),
    rudder_angle: wp.array(dtype=float),
    sheet_limit: wp.array(dtype=float),
    boom_angle: wp.array(dtype=float),
    boom_rate: wp.array(dtype=float),
):
    """Centre the rudder and boom, sheet in, stop the propeller, and clear the commands."""
    i = wp.tid()
    boat = boats[i]
    rudder_command[boat] = 0.0
    sheet_command[boat] = 0.0
    propeller_command[boat] = 0
    rudder_angle[boat] = 0.0
    sheet_limit[boat] = 0.0
    boom_angle[boat] = 0.0
    boom_rate[boat] = 0.0


@wp.kernel(enable_backward=False)
def set_sheet(boats: wp.array(dtype=int), angles: wp.array(dtype=float), sheet_command: wp.array(dtype=float),
              sheet_limit: wp.array(dtype=float)):
    """Sheet command and actual boom limit of ``boats[i]`` set to ``angles[i]`` [rad]."""
    i = wp.tid()
    sheet_command[boats[i]] = angles[i]
    sheet_limit[boats[i]] = angles[i]
