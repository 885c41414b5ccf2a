"""Copying precomputed ocean fields into an ocean's own, for oceans that share one evaluation.

A set of slots holds the fields of several update times, each a (FIELD_COUNT * n, n) block of field
pairs as ``Ocean`` keeps them. An ocean that reads from slots takes, at each update, the block that a
device-side cursor points at, then moves the cursor on: the slot chosen at replay time, not at capture.
"""

import warp as wp

__all__ = ["copy_slot_fields", "advance_cursor"]


@wp.kernel
def copy_slot_fields(slots: wp.array3d(dtype=wp.vec2f), cursor: wp.array(dtype=wp.int32),
                     rows: wp.array2d(dtype=wp.vec2f)):
    """rows = slots[cursor[0]]: one ocean's fields, index [field * n + iy, ix]; one thread a row (a CPU
    launch pays per thread, and its users are CPU processes)."""
    i = wp.tid()
    slot = cursor[0]
    for j in range(rows.shape[1]):
        rows[i, j] = slots[slot, i, j]


@wp.kernel
def advance_cursor(cursor: wp.array(dtype=wp.int32)):
    """cursor[0] += 1: the next update reads the next slot."""
    cursor[0] = cursor[0] + 1
