"""Seeded random streams for kernels that draw fresh numbers every step, per item (boat, environment).

Warp's ``rand_init(seed, offset)`` hashes both arguments into a 32-bit state. A stream hashes its
seed, its own tag and the step counter into the seed and takes the item's index as the offset. So
streams with one user seed do not share numbers, and no product of step and item count can overflow
the 32-bit offset and make a stream repeat.
"""

from __future__ import annotations

import warp as wp

__all__ = ["WIND_GUSTS", "SENSOR_NOISE", "SENSOR_RESET_NOISE", "IMU_BIAS", "stream_state", "advance_counter"]

# Tags of the streams (any distinct 31-bit constants).
WIND_GUSTS = wp.constant(0x2F6B_1D35)
SENSOR_NOISE = wp.constant(0x5BD1_E995)
SENSOR_RESET_NOISE = wp.constant(0x1B87_3593)
IMU_BIAS = wp.constant(0x68E3_1DA4)


@wp.func
def stream_state(seed: int, stream: int, counter: int, index: int) -> wp.uint32:
    """Random state for item ``index`` at step ``counter`` of the stream tagged ``stream``."""
    step_seed = wp.rand_init(seed ^ stream, counter)
    return wp.rand_init(int(step_seed), index)


@wp.kernel(enable_backward=False)
def advance_counter(counter: wp.array(dtype=int)):
    """counter[0] += 1, on the device (so a captured graph advances it)."""
    counter[0] = counter[0] + 1
