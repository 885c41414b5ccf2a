"""Batched sensors, once per step: the true readings and the noisy ones, per boat and channel.

Channels (columns of the (boats, 16) reading arrays):

    0-2   GNSS position, world ENU [m]
    3-5   GNSS velocity, world [m/s]: over the ground
    6-8   IMU specific force, body frame [m/s^2]: acceleration minus gravity (at rest: +g up)
    9-11  IMU angular rate, body frame [rad/s]
    12    compass heading: yaw of the bow from +x (east) counter-clockwise [rad], [-pi, pi)
    13    apparent wind angle at the masthead: where the wind comes from, from the bow, positive to
          port [rad], [-pi, pi)
    14    apparent wind speed at the masthead [m/s]
          (13 and 14, as a masthead unit turning with the boat, see the wind's part in the deck plane:
          its body-frame x and y)
    15    speed through the water (the log): surge relative to the water at the boat's origin, the waves'
          orbital velocity and the current [m/s]: the surge over the ground (3-5 seen along the bow) less
          the water's, so in a current the log and the GNSS disagree by the current's part along the bow

A channel with period p steps refreshes its noisy reading every p steps (and holds it between);
noise is Gaussian with the channel's standard deviation, plus, for the IMU, a bias drawn per boat at
reset; both are multiplied by the boat's ``noise_scale`` (domain randomisation, 1: as configured).
Angles are wrapped after the noise. A reset reads the reset boats' every channel at once, so no
reading of a previous episode survives it.
"""

from __future__ import annotations

import warp as wp

from .random_streams import IMU_BIAS, stream_state
from .spatial import heading_of, point_velocity, vec6, wrap_angle
from .wind_field import GustModel, wind_at_height

__all__ = ["CHANNELS", "vec16", "GNSS_POSITION", "GNSS_VELOCITY", "SPECIFIC_FORCE", "ANGULAR_RATE", "HEADING",
           "WIND_ANGLE", "WIND_SPEED", "WATER_SPEED", "SensorModel", "read_sensors", "reset_sensors"]

CHANNELS = wp.constant(16)
vec16 = wp.types.vector(length=16, dtype=wp.float32)
GNSS_POSITION = wp.constant(0)
"""First of the GNSS position's three channels (x, y, z)."""
GNSS_VELOCITY = wp.constant(3)
"""First of the GNSS velocity's three channels (x, y, z)."""
SPECIFIC_FORCE = wp.constant(6)
"""First of the IMU specific force's three channels (body x, y, z)."""
ANGULAR_RATE = wp.constant(9)
"""First of the IMU angular rate's three channels (body x, y, z: roll, pitch, yaw rate)."""
IMU_FIRST = SPECIFIC_FORCE
IMU_LAST = wp.constant(11)
HEADING = wp.constant(12)
WIND_ANGLE = wp.constant(13)
WIND_SPEED = wp.constant(14)
WATER_SPEED = wp.constant(15)


@wp.struct
class SensorModel:
    noise_std: wp.array(dtype=float)
    """(16,) per channel, in the channel's unit."""
    period: wp.array(dtype=int)
    """(16,) steps between refreshes of each channel (>= 1)."""
    masthead: wp.vec3
    """Vane and anemometer in the body frame [m]."""
    gravity: float
    """[m/s^2]"""
    step: float
    """Duration of one step [s], for the acceleration."""
    seed: int
    """Seed of the noise and bias streams."""
    first_index: int
    """Number of this batch's first boat in the random streams (see ``GustModel.first_index``)."""


@wp.kernel(enable_backward=False)
def read_sensors(
    mask: wp.array(dtype=wp.int32),
    refresh_all: int,
    stream: int,
    sensors: SensorModel,
    gusts: GustModel,
    counter: wp.array(dtype=int),
    position: wp.array(dtype=wp.vec3),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    water_velocity: wp.array(dtype=wp.vec3),
    wind_velocity: wp.array(dtype=wp.vec3),
    imu_bias: wp.array(dtype=vec6),
    noise_scale: wp.array(dtype=float),
    previous_velocity: wp.array(dtype=wp.vec3),
    truth: wp.array2d(dtype=float),
    measured: wp.array2d(dtype=float),
):
    """Readings of every boat whose ``mask`` is non-zero: the truth, and the noisy channels due at step
    ``counter[0]`` (all of them with ``refresh_all``), with noise from the random stream tagged
    ``stream``, times the boat's ``noise_scale``. The caller advances ``counter`` once per step."""
    boat = wp.tid()
    if mask[boat] == 0:
        return
    rotation = orientation[boat]
    nu = velocity[boat]
    linear = wp.vec3(nu[0], nu[1], nu[2])
    angular = wp.vec3(nu[3], nu[4], nu[5])
    world_velocity = wp.quat_rotate(rotation, linear)
    acceleration = (world_velocity - previous_velocity[boat]) / sensors.step
    previous_velocity[boat] = world_velocity
    specific_force = wp.quat_rotate_inv(rotation, acceleration + wp.vec3(0.0, 0.0, sensors.gravity))
    heading = heading_of(rotation)
    masthead_world = position[boat] + wp.quat_rotate(rotation, sensors.masthead)
    wind = wp.quat_rotate_inv(rotation, wind_at_height(wind_velocity[boat], masthead_world[2], gusts))
    apparent = wind - point_velocity(nu, sensors.masthead)
    through_water = linear[0] - water_velocity[boat][0]

    p = position[boat]
    values = vec16(p[0], p[1], p[2], world_velocity[0], world_velocity[1], world_velocity[2],
                   specific_force[0], specific_force[1], specific_force[2], angular[0], angular[1], angular[2],
                   heading, wp.atan2(-apparent[1], -apparent[0]), wp.sqrt(apparent[0] * apparent[0] + apparent[1] * apparent[1]),
                   through_water)
    bias = imu_bias[boat]
    scale = noise_scale[boat]
    state = stream_state(sensors.seed, stream, counter[0], sensors.first_index + boat)
    for c in range(CHANNELS):
        truth[boat, c] = values[c]
        noise = scale * (sensors.noise_std[c] * wp.randn(state))
        if refresh_all != 0 or counter[0] % sensors.period[c] == 0:
            reading = values[c] + noise
            if c >= IMU_FIRST and c <= IMU_LAST:
                reading += bias[c - IMU_FIRST]
            if c == HEADING or c == WIND_ANGLE:
                reading = wrap_angle(reading)
            measured[boat, c] = reading


@wp.kernel(enable_backward=False)
def reset_sensors(
    mask: wp.array(dtype=wp.int32),
    bias_std: vec6,
    sensors: SensorModel,
    counter: wp.array(dtype=int),
    orientation: wp.array(dtype=wp.quat),
    velocity: wp.array(dtype=vec6),
    new_noise_scale: wp.array(dtype=float),
    imu_bias: wp.array(dtype=vec6),
    previous_velocity: wp.array(dtype=wp.vec3),
    noise_scale: wp.array(dtype=float),
):
    """For the boats whose ``mask`` is non-zero: their noise factor from ``new_noise_scale`` (may be
    ``noise_scale`` itself, to keep it), new IMU biases (times that factor), and their velocity as the
    last one seen (no false jolt)."""
    boat = wp.tid()
    if mask[boat] == 0:
        return
    scale = new_noise_scale[boat]
    noise_scale[boat] = scale
    state = stream_state(sensors.seed, IMU_BIAS, counter[0], sensors.first_index + boat)
    bias = vec6(bias_std[0] * wp.randn(state), bias_std[1] * wp.randn(state), bias_std[2] * wp.randn(state),
                bias_std[3] * wp.randn(state), bias_std[4] * wp.randn(state), bias_std[5] * wp.randn(state))
    imu_bias[boat] = scale * bias
    nu = velocity[boat]
    previous_velocity[boat] = wp.quat_rotate(orientation[boat], wp.vec3(nu[0], nu[1], nu[2]))
