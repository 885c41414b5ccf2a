"""One ocean evaluated for all the workers of a :class:`~ocean_warp.envs.parallel.sharded.ShardedSailingEnv`.

Every worker's ocean would evaluate the same fields at the same times: the sea does not depend on the
boats. With the four-point hull that evaluation (20 updates of a 64² grid a decision in the seed task)
is most of a small shard's work, and every worker paid it. Instead the parent evaluates each decision's
fields once, into shared memory, while the workers step the decision before; each worker's ocean copies
the block it needs at each update (``Ocean.read_fields_from``).

Double buffered: 2 U slots, U the ocean updates of one decision; a decision of parity p reads slots
[p U, (p + 1) U) while the parent fills the other half for the next decision. The parent's clock makes
the same float64 additions as a worker's simulator (the substep dt, every substep), so the fields are
bit for bit those a worker would have evaluated itself.
"""

from __future__ import annotations

import torch
import warp as wp

from ocean_warp.kernels.ocean_spectrum import FIELD_COUNT
from ocean_warp.ocean import Ocean
from ocean_warp.replay import ReplayedLaunches
from ocean_warp.simulator import launch_clock_advance, ocean_updates_of_step

from ..tasks.task_configs import TaskConfig

__all__ = ["SharedOcean", "ocean_updates_per_decision"]


def ocean_updates_per_decision(task: TaskConfig) -> int:
    """How many times one decision of ``task`` updates the ocean."""
    sim = task.simulator
    return task.steps_per_decision * sum(ocean_updates_of_step(sim.substeps, sim.ocean_every_substep))


class SharedOcean:
    """The parent's ocean and the shared slots it fills, one decision ahead of the workers.

    The caller keeps the order: :meth:`restart` before the first decision (and after anything that
    changes the sea or rewinds the clock), then for every decision tell the workers its
    :attr:`parity`, :meth:`fill_next` while they step, and :meth:`advance` when they are done.
    """

    def __init__(self, task: TaskConfig):
        sim = task.simulator
        self.ocean = Ocean(sim.ocean, device="cpu")
        """The parent's ocean: its amplitudes (sea state) and clock are the workers'."""
        self.updates_per_decision = ocean_updates_per_decision(task)
        n = sim.ocean.resolution
        self.slots = torch.zeros((2 * self.updates_per_decision, FIELD_COUNT * n, n, 2),
                                 dtype=torch.float32).share_memory_()
        """(2 U, FIELD_COUNT * n, n, 2) float32 in shared memory: the fields of two decisions' updates."""
        self.parity = 0
        """Which half of the slots holds the fields of the next decision the workers step."""
        self._next_start = 0.0
        self._following_start = 0.0
        self._slot_view = wp.from_torch(self.slots, dtype=wp.vec2f)
        self._steps, self._substeps = task.steps_per_decision, sim.substeps
        self._every_substep = sim.ocean_every_substep
        self._substep_dt = sim.simulator_config().substep_dt
        self._fill = [ReplayedLaunches(lambda p=parity: self._launch_fill(p), "cpu") for parity in (0, 1)]

    def _launch_fill(self, parity: int) -> None:
        """The updates of one decision into half ``parity`` of the slots, on the simulator's own schedule
        and clock (``ocean_warp.simulator``'s ``ocean_updates_of_step`` and ``launch_clock_advance``)."""
        slot = parity * self.updates_per_decision
        for _ in range(self._steps):
            for update_ocean in ocean_updates_of_step(self._substeps, self._every_substep):
                if update_ocean:
                    self.ocean.update(out=self._slot_view[slot])
                    slot += 1
                launch_clock_advance(self.ocean.time, self._substep_dt, "cpu")

    def restart(self, start_time: float | None = None) -> None:
        """Evaluate the next decision's fields again, from ``start_time`` [s] (None: from the start time
        it had), after a change of sea state or a rewind of the workers' clocks."""
        if start_time is not None:
            self._next_start = float(start_time)
        self.ocean.time.fill_(self._next_start)
        self._fill[self.parity]()

    def fill_next(self) -> None:
        """Evaluate the fields of the decision after the next one into the other half of the slots (call
        while the workers step the next one, which reads only its own half)."""
        self._following_start = float(self.ocean.time.numpy()[0])
        self._fill[1 - self.parity]()

    def advance(self) -> None:
        """The workers finished the decision: the half filled by :meth:`fill_next` is the next one."""
        self.parity = 1 - self.parity
        self._next_start = self._following_start
