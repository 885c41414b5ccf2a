"""Components: what lives inside an environment's decision besides the task (an obstacle course, a sensor, a
recorder), with the hook points the environment calls, in this order, for every component it holds:

- at construction, its ``force_models`` are added to the simulator (``Simulator.add_model``: contact...);
- at every episode start (``reset`` and the same-step reset of the environments that ended), ``draw`` after the
  task drew the new starts and before the vessel's masked reset;
- after the physics (and again after the episode starts), ``sense``: before the task reads the boats;
- wherever the task writes an observation, ``append_observation`` after it;
- on a seeded restart (``reset(seed)``), ``restart_streams``.

Every hook is launches only (it runs inside the decision's replayed graph). A component is built from explicit
parts (the scene, the simulator's ``add_model``, its configs), never from a half-built environment.
"""

from __future__ import annotations

import warp as wp

__all__ = ["EnvComponent"]


class EnvComponent:
    """A part of a decision (see the module's docstring); every hook does nothing unless overridden."""

    force_models: tuple = ()
    """The force models this component adds to the simulator (``Simulator.add_model``), in order."""

    def draw(self, seed: wp.array, first_env: int, mask: wp.array, course) -> None:
        """New episodes for the environments whose ``mask`` (N,) int32 is set, from the env's ``seed`` (1,) and
        ``first_env``; ``course`` is the task's per-environment struct (its new starts already drawn)."""

    def sense(self) -> None:
        """Read the boats' current poses (a scan, the gap to obstacles) before the task does."""

    def append_observation(self, policy: wp.array, critic: wp.array) -> None:
        """Write this component's values into the policy's and the critic's (N, *) observations."""

    def restart_streams(self) -> None:
        """Random streams back to their first draw (a seeded restart of the environment)."""
