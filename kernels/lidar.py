"""A lidar on every boat: beams cast through the ray-cast scene from the boat's mount point, with range noise
and dropouts, and the reductions a policy or a viewer reads from a scan.

Frames: the body frame (x to the bow, y to port, z up, origin at the waterline); the sensor frame is the
body frame turned by the mount's rotation and moved to the mount point. A beam of azimuth az (from the
sensor's x toward its y, counter-clockwise seen from above) and elevation el (up positive) [rad] points
along (cos el cos az, cos el sin az, sin el) in the sensor frame.

A scan is one thread per (boat, beam): the beam is cast with ``ray_cast.cast_ray`` through the objects,
the boats and, with water returns on, the sea of the boat's environment (the sea's height map crossed cell
by cell, see ``ray_cast``), ignoring the boat itself, over [min_range, max_range]. Its range [m] is the
distance to the first hit plus Gaussian noise (clamped to [min_range, max_range]); a beam that hits
nothing, that drops out, that belongs to a boat outside the scene or to a boat whose pose is not finite,
reports ``max_range`` and ``HIT_NONE`` (so no NaN leaves the kernel).
"""

from __future__ import annotations

import warp as wp

from .random_streams import LIDAR_NOISE, stream_state
from .ray_cast import HIT_NONE, SceneView, cast_ray

__all__ = ["LIDAR_NOISE", "LidarModel", "beam_direction", "scan_lidar", "sector_minimum", "hit_points"]


@wp.struct
class LidarModel:
    """One lidar model, the same on every boat (built by ``ocean_warp.perception.lidar.Lidar``)."""

    azimuth: wp.array(dtype=float)
    """(C * B,) each beam's azimuth in the sensor frame [rad], beam j = channel * B + b."""
    elevation: wp.array(dtype=float)
    """(C * B,) each beam's elevation in the sensor frame [rad], up positive."""
    mount_position: wp.vec3
    """The sensor's origin in the body frame [m]."""
    mount_rotation: wp.quat
    """Sensor frame -> body frame."""
    min_range: float
    """[m]: nothing nearer is seen."""
    max_range: float
    """[m]: nothing farther is seen; the range a beam without a hit reports."""
    range_noise_std: float
    """Standard deviation of the Gaussian noise added to the range of a hit [m]."""
    dropout: float
    """Probability that a beam returns nothing, in [0, 1)."""
    water_returns: int
    """1: the sea returns beams; 0: beams pass through it."""
    seed: int
    """Seed of the noise and dropout stream."""
    first_index: int
    """Random-stream number of this batch's first boat (a shard of a larger batch draws as the batch would)."""


@wp.func
def beam_direction(azimuth: float, elevation: float) -> wp.vec3:
    """Unit direction of a beam in the sensor frame from its azimuth and elevation [rad]."""
    horizontal = wp.cos(elevation)
    return wp.vec3(horizontal * wp.cos(azimuth), horizontal * wp.sin(azimuth), wp.sin(elevation))


@wp.func
def _noisy_range(model: LidarModel, distance: float, counter: int, stream_index: int) -> float:
    """``distance`` [m] with Gaussian noise, clamped to [min_range, max_range]; -1 when the beam drops out.
    Both draws come from the beam's own state (its index and the scan's counter), in a fixed order; an
    exact sensor (no noise, no dropouts) draws nothing."""
    if model.range_noise_std == 0.0 and model.dropout == 0.0:
        return distance
    state = stream_state(model.seed, LIDAR_NOISE, counter, stream_index)
    lost = wp.randf(state) < model.dropout
    noisy = distance + model.range_noise_std * wp.randn(state)
    if lost:
        return -1.0
    return wp.clamp(noisy, model.min_range, model.max_range)


@wp.kernel(enable_backward=False)
def scan_lidar(scene: SceneView, model: LidarModel, boat_env: wp.array(dtype=int),
               counter: wp.array(dtype=int), ranges: wp.array2d(dtype=float), kinds: wp.array2d(dtype=int),
               sensor_position: wp.array(dtype=wp.vec3), sensor_orientation: wp.array(dtype=wp.quat)):
    """One thread per (boat, beam), boats at the scene's poses (``scene.boat_position``, ``boat_orientation``):
    ``ranges`` [m] and ``kinds`` (``ray_cast.HIT_*``) of every beam, and, from beam 0, the sensor's world pose
    at this scan (position [m], sensor -> world; as non-finite as the boat's pose where that is not finite,
    its beams then report nothing). ``scene``: a view whose ``water_visible`` is ``model.water_returns``;
    ``boat_env`` (N,): each boat's
    environment (-1: not in the scene); ``counter`` (1,): the scan's number in the random stream (advanced
    by the caller)."""
    boat, beam = wp.tid()
    position = scene.boat_position[boat]
    rotation = scene.boat_orientation[boat]
    origin = position + wp.quat_rotate(rotation, model.mount_position)
    sensor = rotation * model.mount_rotation
    if beam == 0:
        sensor_position[boat] = origin
        sensor_orientation[boat] = sensor
    ranges[boat, beam] = model.max_range
    kinds[boat, beam] = HIT_NONE
    env = boat_env[boat]
    if env < 0 or not wp.isfinite(position) or not wp.isfinite(rotation):
        return
    direction = wp.normalize(wp.quat_rotate(sensor, beam_direction(model.azimuth[beam], model.elevation[beam])))
    hit = cast_ray(scene, env, origin, direction, model.min_range, model.max_range, boat)
    distance = hit.t
    kind = hit.kind
    if kind == HIT_NONE or not wp.isfinite(distance):
        return
    stream_index = (model.first_index + boat) * ranges.shape[1] + beam
    measured = _noisy_range(model, distance, counter[0], stream_index)
    if measured < 0.0:
        return
    ranges[boat, beam] = measured
    kinds[boat, beam] = kind


@wp.kernel(enable_backward=False)
def sector_minimum(ranges: wp.array2d(dtype=float), beams_per_channel: int, max_range: float,
                   nearest: wp.array2d(dtype=float)):
    """One thread per (boat, sector): the least range [m] over the sector's beams of every channel, over
    ``max_range``, clamped to [0, 1]. The K sectors split each channel's ``beams_per_channel`` beams into K
    equal runs of consecutive beams (K divides it); beam j belongs to channel j // beams_per_channel."""
    boat, sector = wp.tid()
    width = beams_per_channel // nearest.shape[1]
    channels = ranges.shape[1] // beams_per_channel
    least = max_range
    for channel in range(channels):
        first = channel * beams_per_channel + sector * width
        for beam in range(first, first + width):
            least = wp.min(least, ranges[boat, beam])
    nearest[boat, sector] = wp.clamp(least / max_range, 0.0, 1.0)


@wp.kernel(enable_backward=False)
def hit_points(model: LidarModel, ranges: wp.array2d(dtype=float), kinds: wp.array2d(dtype=int),
               sensor_position: wp.array(dtype=wp.vec3), sensor_orientation: wp.array(dtype=wp.quat),
               points: wp.array2d(dtype=wp.vec3)):
    """One thread per (boat, beam): the world point [m] each beam's measured range puts its hit at, from the
    sensor's pose at that scan; NaN for a beam that hit nothing."""
    boat, beam = wp.tid()
    if kinds[boat, beam] == HIT_NONE:
        nan = wp.nan
        points[boat, beam] = wp.vec3(nan, nan, nan)
        return
    direction = wp.normalize(wp.quat_rotate(sensor_orientation[boat],
                                            beam_direction(model.azimuth[beam], model.elevation[beam])))
    points[boat, beam] = sensor_position[boat] + ranges[boat, beam] * direction
