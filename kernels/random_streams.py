"""Seeded random streams for kernels that draw fresh numbers every step, per item (boat, environment).

Warp's ``rand_init(seed, offset)`` hashes both arguments into a 32-bit state. A stream hashes its
seed, its own tag and the step counter into the seed and takes the item's index as the offset. So
streams with one user seed do not share numbers, and no product of step and item count can overflow
the 32-bit offset and make a stream repeat.
"""

from __future__ import annotations

import warp as wp

__all__ = ["WIND_GUSTS", "SENSOR_NOISE", "SENSOR_RESET_NOISE", "IMU_BIAS", "LIDAR_NOISE", "EPISODE_START",
           "RANDOMISATION", "CURRENT_DRAW", "REEF_DRAW", "LAYOUT", "VRX_START", "VRX_CONDITIONS", "PATH_OBSTACLES",
           "STREAM_TAGS", "stream_state", "advance_counter"]

# The tags of every stream, core and environments alike, here in one place so that no two share one: two
# streams with one tag and one seed draw the same numbers wherever their counters and indices meet.
WIND_GUSTS = wp.constant(0x2F6B_1D35)
"""The wind's gusts (``wind_field``)."""
SENSOR_NOISE = wp.constant(0x5BD1_E995)
"""The sensors' noise of every step (``sensor_readings``)."""
SENSOR_RESET_NOISE = wp.constant(0x1B87_3593)
"""The sensors' noise drawn at a reset."""
IMU_BIAS = wp.constant(0x68E3_1DA4)
"""The IMU's biases."""
LIDAR_NOISE = wp.constant(0x7A2C_64D1)
"""The lidar's range noise and dropouts (``lidar``; until issue 35 it shared EPISODE_START's tag)."""
EPISODE_START = wp.constant(0x3C6E_F372)
"""Each sailing task's episode start (``envs/tasks/task_kernels``)."""
RANDOMISATION = wp.constant(0x510E_527F)
"""Each sailing episode's domain randomisation (foil and sensor-noise factors)."""
CURRENT_DRAW = wp.constant(0x5BE0_CD19)
"""Each sailing episode's current (speed and direction)."""
REEF_DRAW = wp.constant(0x6C4B_2E97)
"""Each sailing episode's random reef level (``ReefRule.random_level``; until issue 35 it shared LAYOUT's tag)."""
LAYOUT = wp.constant(0x1F83_D9AB)
"""Each episode's obstacle layout (``envs/tasks/obstacle_kernels``)."""
VRX_START = wp.constant(0x4A7F_3C21)
"""Each VRX episode's start and goals (``envs/vrx/vrx_kernels``)."""
VRX_CONDITIONS = wp.constant(0x2D19_86E5)
"""Each VRX episode's wind, current and sensor noise."""
PATH_OBSTACLES = wp.constant(0x5C0E_91B7)
"""Each follow-the-path episode's obstacle buoys (``envs/vrx/path_course_kernels``)."""

STREAM_TAGS = {name: int(globals()[name]) for name in (
    "WIND_GUSTS", "SENSOR_NOISE", "SENSOR_RESET_NOISE", "IMU_BIAS", "LIDAR_NOISE", "EPISODE_START", "RANDOMISATION",
    "CURRENT_DRAW", "REEF_DRAW", "LAYOUT", "VRX_START", "VRX_CONDITIONS", "PATH_OBSTACLES")}
"""Every tag above by name (``tests/ocean_warp/test_random_stream_tags.py``: distinct, and the only ones)."""


@wp.func
def stream_state(seed: int, stream: int, counter: int, index: int) -> wp.uint32:
    """Random state for item ``index`` at step ``counter`` of the stream tagged ``stream``."""
    step_seed = wp.rand_init(seed ^ stream, counter)
    return wp.rand_init(int(step_seed), index)


@wp.kernel(enable_backward=False)
def advance_counter(counter: wp.array(dtype=int)):
    """counter[0] += 1, on the device (so a captured graph advances it)."""
    counter[0] = counter[0] + 1
