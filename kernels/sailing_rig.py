"""A sailing boat's rig and drive, one thread per boat per substep: actuators, boom, sail, keel,
rudder, windage and propeller, summed into the boat's model wrench (body frame, about the origin).

Conventions (body frame FLU): the boom angle is positive with the boom to port; the rudder angle is
positive with its trailing edge to port, which turns a boat going ahead to port (yaw rate > 0). The
boom swings free within +-(sheet limit), driven by the sail's moment about the mast against the
joint's damping, and stops dead at the limit; the sail's flow includes the boom's own swing, which
damps it aerodynamically. The rudder and the sheet limit move towards their commands at fixed rates
within their ranges. Each boat sails its rig at a reef level of its own (``RigState.reef_level``, set at a
reset): level k is the full sail scaled by a linear factor s = ``RigParameters.reef_scale[k]`` about its tack
(its foot at the mast), so its area is s^2 ``sail_area``, its centre of effort's height above the foot s
times the full sail's and its arm aft of the mast s times ``sail_arm``, and the sail's share of the boom's
inertia goes as its mass (s^2) times its arm squared (s^2); the coefficient tables stay (a scaled sail has the
same aspect ratio), and level 0 (s = 1) is the full sail exactly. Each boat's ``foil_scale`` multiplies the
lift and drag coefficients of its sail, keel and rudder (domain randomisation; the force is linear in them).
A NaN or infinite command, or wind, flags the boat (BAD_INPUT and NONFINITE) instead of being clamped into a
real value; so does a reef level outside the table (BAD_INPUT).
"""

from __future__ import annotations

import warp as wp

from .foils import FoilTables, foil_force
from .rigid_body import STATUS_BAD_INPUT, STATUS_NONFINITE
from .spatial import DEGREES, point_velocity, vec6, wrench_at
from .water_current import CurrentField, with_current_shift
from .wind_field import GustModel, wind_at_height

__all__ = ["RigParameters", "RigControl", "RigState", "RigSurroundings", "sailing_rig", "reset_rig"]


@wp.struct
class RigParameters:
    """Geometry, actuators and the densities of a sailing rig (one boat type); body frame, SI units."""

    mast_step: wp.vec3
    """Foot of the (vertical) mast [m]; its x and y place the mast (the sail's height is ``sail_height``)."""
    sail_arm: float
    """Distance of the sail's centre of effort aft of the mast along the boom [m]."""
    sail_height: float
    """Height of the sail's centre of effort [m]."""
    sail_area: float
    """Of the full sail [m^2]."""
    sail_foot_height: float
    """Height of the sail's foot (its tack, on the boom), about which a reef scales the sail [m]."""
    reef_scale: wp.array(dtype=float)
    """(levels,) linear factor s of each reef level's sail on the full sail's dimensions (level 0: 1)."""
    sail_inertia: float
    """The sail's share of ``boom_inertia`` [kg m^2] (a reef scales it by s^4)."""
    keel_center: wp.vec3
    """Centre of effort of the keel fin [m]."""
    keel_area: float
    """[m^2]"""
    rudder_center: wp.vec3
    """Centre of effort of the rudder (on its stock) [m]."""
    rudder_area: float
    """[m^2]"""
    propeller_position: wp.vec3
    """Where the thrust acts [m]."""
    thrust_per_level: float
    """[N] per propeller level ahead."""
    reverse_factor: float
    """Thrust astern per level, as a fraction of ``thrust_per_level``."""
    max_level: int
    """Largest propeller level either way."""
    rudder_limit: float
    """[rad]"""
    rudder_rate: float
    """[rad/s]"""
    sheet_limit_max: float
    """[rad]"""
    sheet_rate: float
    """[rad/s]"""
    boom_inertia: float
    """Boom and full sail about the mast [kg m^2]."""
    boom_damping: float
    """[N m s/rad]"""
    air_density: float
    """[kg/m^3]"""
    water_density: float
    """[kg/m^3]"""
    windage_area_ahead: float
    """Drag area (C_D A) of what is not sail, in an apparent wind from ahead or astern [m^2]."""
    windage_area_abeam: float
    """The same in a wind from abeam [m^2]; between, C_D A = ahead cos^2 + abeam sin^2 of the wind's
    horizontal angle off the bow (the ORC's blend)."""
    windage_center: wp.vec3
    """Where the windage acts [m]."""
    sail_lift_limit: float
    """C_L is read at min(|alpha|, this) [rad] (pi: the table as it is; the original V-C used 100 deg)."""
    foil_lift_limit: float
    """The same for keel and rudder [rad] (the original V-C used 90 deg)."""
    original_tuning: int
    """1: the original V-C's other tuning (rudder force x 0.3, keel minus 0.6 of the sail's side force,
    sail force x 0.1 outside 5-160 degrees of attack)."""

@wp.struct
class RigControl:
    """What is commanded of every boat's rig, N rows."""

    rudder: wp.array(dtype=float)
    """Rudder angle to steer to [rad]; positive turns the boat to port (within the rudder limit)."""
    sheet: wp.array(dtype=float)
    """Sheet: largest boom angle either side [rad] (0 to the limit)."""
    propeller: wp.array(dtype=int)
    """Propeller level, -max_level ... +max_level."""


@wp.struct
class RigState:
    """What moves in every boat's rig, and its per-episode foil factors, N rows."""

    rudder_angle: wp.array(dtype=float)
    """Actual rudder angle [rad]."""
    sheet_limit: wp.array(dtype=float)
    """Actual largest boom angle either side [rad] (follows the sheet command)."""
    boom_angle: wp.array(dtype=float)
    """Boom angle, positive with the boom to port [rad]."""
    boom_rate: wp.array(dtype=float)
    """[rad/s]"""
    foil_scale: wp.array(dtype=wp.vec3)
    """Factors on the lift and drag coefficients of the (sail, keel, rudder) (1: as tabulated)."""
    reef_level: wp.array(dtype=int)
    """Reef level of the sail, an index into ``RigParameters.reef_scale`` (0: the full sail)."""


@wp.struct
class RigSurroundings:
    """What the rig reads of its boat and the air and water around it, N rows."""

    position: wp.array(dtype=wp.vec3)
    """Body origin, world frame [m]."""
    orientation: wp.array(dtype=wp.quat)
    """Body (FLU) -> world."""
    velocity: wp.array(dtype=vec6)
    """Fossen's nu: body-frame velocity [m/s] and angular velocity [rad/s]."""
    water_velocity: wp.array(dtype=wp.vec3)
    """The water's velocity at the boat's origin, body frame [m/s]: the waves' orbital velocity and the current."""
    wind_velocity: wp.array(dtype=wp.vec3)
    """The true wind at the reference height, world frame [m/s]."""
    current: CurrentField
    """The current (the Simulator's ``current_field``), for its change with depth down to the keel and rudder."""



@wp.func
def _approach(value: float, target: float, max_step: float) -> float:
    return value + wp.clamp(target - value, -max_step, max_step)


@wp.func
def _force(force_and_angle: wp.vec4) -> wp.vec3:
    return wp.vec3(force_and_angle[0], force_and_angle[1], force_and_angle[2])


@wp.kernel(enable_backward=False)
def sailing_rig(
    rig: RigParameters,
    tables: FoilTables,
    gusts: GustModel,
    dt: float,
    around: RigSurroundings,
    control: RigControl,
    state: RigState,
    model_wrench: wp.array(dtype=vec6),
    status: wp.array(dtype=int),
):
    """One substep of ``dt`` [s]: actuators and boom move, and the sail, keel, rudder and propeller
    wrenches are added to ``model_wrench``. Commands: rudder and sheet angles [rad], propeller level.
    ``foil_scale``: factors on the (sail, keel, rudder) lift and drag coefficients; ``reef_level``: the sail's
    reef (module docstring)."""
    boat = wp.tid()
    if not (wp.isfinite(control.rudder[boat]) and wp.isfinite(control.sheet[boat])
            and wp.isfinite(around.wind_velocity[boat])):
        status[boat] = status[boat] | STATUS_BAD_INPUT | STATUS_NONFINITE
        return
    reef = state.reef_level[boat]
    if reef < 0 or reef >= rig.reef_scale.shape[0]:
        status[boat] = status[boat] | STATUS_BAD_INPUT
        return
    rotation = around.orientation[boat]
    nu = around.velocity[boat]
    scale = state.foil_scale[boat]
    up = wp.vec3(0.0, 0.0, 1.0)
    down = wp.vec3(0.0, 0.0, -1.0)

    # Actuators.
    rudder = _approach(state.rudder_angle[boat], wp.clamp(control.rudder[boat], -rig.rudder_limit, rig.rudder_limit),
                       rig.rudder_rate * dt)
    limit = _approach(state.sheet_limit[boat], wp.clamp(control.sheet[boat], 0.0, rig.sheet_limit_max), rig.sheet_rate * dt)
    state.rudder_angle[boat] = rudder
    state.sheet_limit[boat] = limit

    # The reefed sail: the full one scaled by s about its tack. Written so that s = 1 gives the full sail's
    # figures bit for bit (foot + s (h - foot) would round differently).
    s = rig.reef_scale[reef]
    sail_arm = s * rig.sail_arm
    sail_height = rig.sail_height - (1.0 - s) * (rig.sail_height - rig.sail_foot_height)
    sail_area = (s * s) * rig.sail_area
    boom_inertia = rig.boom_inertia + rig.sail_inertia * (s * s * s * s - 1.0)

    # Sail: apparent wind at the centre of effort, which swings with the boom.
    boom = state.boom_angle[boat]
    swing = state.boom_rate[boat]
    boom_direction = wp.vec3(-wp.cos(boom), wp.sin(boom), 0.0)
    sail_center = wp.vec3(rig.mast_step[0], rig.mast_step[1], sail_height) + sail_arm * boom_direction
    sail_world = around.position[boat] + wp.quat_rotate(rotation, sail_center)
    wind = wp.quat_rotate_inv(rotation, wind_at_height(around.wind_velocity[boat], sail_world[2], gusts))
    swing_velocity = (sail_arm * swing) * wp.vec3(wp.sin(boom), wp.cos(boom), 0.0)
    sail_flow = wind - (point_velocity(nu, sail_center) + swing_velocity)
    sail = foil_force(sail_flow, boom_direction, up, sail_area, rig.air_density, tables.sail_lift,
                      tables.sail_drag, rig.sail_lift_limit)
    sail_force = scale[0] * _force(sail)
    if rig.original_tuning != 0:
        attack = wp.abs(sail[3]) * DEGREES
        if attack < 5.0 or attack > 160.0:
            sail_force = 0.1 * sail_force

    # Boom: free within the sheet limit, driven by the sail's moment about the mast. A positive boom
    # angle turns the boom clockwise seen from above (towards port, aft of the mast): about -z.
    about_mast = -wp.dot(wp.cross(sail_arm * boom_direction, sail_force), up)
    rate = (swing * boom_inertia + dt * about_mast) / (boom_inertia + dt * rig.boom_damping)
    new_boom = boom + dt * rate
    if new_boom > limit:
        new_boom = limit
        rate = wp.min(rate, 0.0)
    elif new_boom < -limit:
        new_boom = -limit
        rate = wp.max(rate, 0.0)
    state.boom_angle[boat] = new_boom
    state.boom_rate[boat] = rate

    # Keel and rudder in the water (its velocity at the boat, body frame, with the current at each foil's depth).
    water = around.water_velocity[boat]
    origin_height = around.position[boat][2]
    keel_water = with_current_shift(water, around.current, boat, rotation, origin_height,
                                    origin_height + wp.quat_rotate(rotation, rig.keel_center)[2])
    rudder_water = with_current_shift(water, around.current, boat, rotation, origin_height,
                                      origin_height + wp.quat_rotate(rotation, rig.rudder_center)[2])
    keel_force = scale[1] * _force(foil_force(keel_water - point_velocity(nu, rig.keel_center),
                                              wp.vec3(-1.0, 0.0, 0.0), down, rig.keel_area, rig.water_density,
                                              tables.keel_lift, tables.keel_drag, rig.foil_lift_limit))
    rudder_chord = wp.vec3(-wp.cos(rudder), wp.sin(rudder), 0.0)
    rudder_force = scale[2] * _force(foil_force(rudder_water - point_velocity(nu, rig.rudder_center), rudder_chord,
                                                down, rig.rudder_area, rig.water_density, tables.rudder_lift,
                                                tables.rudder_drag, rig.foil_lift_limit))
    if rig.original_tuning != 0:
        rudder_force = 0.3 * rudder_force
        keel_force = keel_force - wp.vec3(0.0, 0.6 * sail_force[1], 0.0)

    # Windage: the parasitic air drag of everything that is not sail.
    windage_world = around.position[boat] + wp.quat_rotate(rotation, rig.windage_center)
    windage_wind = wp.quat_rotate_inv(rotation, wind_at_height(around.wind_velocity[boat], windage_world[2], gusts))
    windage_flow = windage_wind - point_velocity(nu, rig.windage_center)
    horizontal_squared = windage_flow[0] * windage_flow[0] + windage_flow[1] * windage_flow[1]
    abeam_share = wp.where(horizontal_squared > 0.0, windage_flow[1] * windage_flow[1] / horizontal_squared, 0.0)
    windage_area = rig.windage_area_ahead + abeam_share * (rig.windage_area_abeam - rig.windage_area_ahead)
    windage_force = (0.5 * rig.air_density * windage_area * wp.length(windage_flow)) * windage_flow

    # Propeller: integer levels, weaker astern, along the body x axis.
    level = wp.clamp(control.propeller[boat], -rig.max_level, rig.max_level)
    thrust = rig.thrust_per_level * float(level)
    if level < 0:
        thrust = thrust * rig.reverse_factor

    model_wrench[boat] = (model_wrench[boat] + wrench_at(sail_force, sail_center)
                          + wrench_at(keel_force, rig.keel_center) + wrench_at(rudder_force, rig.rudder_center)
                          + wrench_at(windage_force, rig.windage_center)
                          + wrench_at(wp.vec3(thrust, 0.0, 0.0), rig.propeller_position))


@wp.kernel(enable_backward=False)
def reset_rig(
    mask: wp.array(dtype=wp.int32),
    sheet: wp.array(dtype=float),
    new_foil_scale: wp.array(dtype=wp.vec3),
    new_reef_level: wp.array(dtype=int),
    sheet_limit_max: float,
    control: RigControl,
    state: RigState,
):
    """For every boat whose ``mask`` is non-zero: centre the rudder and the boom, stop the propeller, set
    the sheet, command and actual boom limit alike, to ``sheet`` [rad] (clamped to [0, max]), the foil
    factors to ``new_foil_scale`` and the reef level to ``new_reef_level`` (either may be the state's own
    array, to keep it)."""
    boat = wp.tid()
    if mask[boat] == 0:
        return
    limit = wp.clamp(sheet[boat], 0.0, sheet_limit_max)
    control.rudder[boat] = 0.0
    control.sheet[boat] = limit
    control.propeller[boat] = 0
    state.rudder_angle[boat] = 0.0
    state.sheet_limit[boat] = limit
    state.boom_angle[boat] = 0.0
    state.boom_rate[boat] = 0.0
    state.foil_scale[boat] = new_foil_scale[boat]
    state.reef_level[boat] = new_reef_level[boat]
