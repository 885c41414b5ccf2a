"""The seed's commands of every boat, held between decisions: what the ROS node's subscribers write and its
decisions read (thread-safe; no ROS library, no Warp).

The seed's command topics (``control_interface/*``, per boat) become the task's actions by the inverse of the
task's mapping (``envs/tasks/task_configs``: a0 propeller level int(5 a0), a1 sheet (a1 + 1) 45 deg, a2 rudder
60 deg a2):

=======================  ===========  ===========================================  ============================
topic                    unit         valid                                        action
=======================  ===========  ===========================================  ============================
control_interface/sail   deg          finite, 0 to 90 (largest boom angle)         a1 = sail / 45 - 1
control_interface/rudder deg          finite, -60 to 60 (positive turns to port)   a2 = rudder / 60
control_interface/       level        -5 to 5                                      a0 = (level + 0.5 sign) / 5,
propulsion                                                                         so int(5 a0) = level
atmosferic_control/wind  m/s (ENU)    finite, horizontal speed 0 to 40             the boat's mean true wind
=======================  ===========  ===========================================  ============================

Each command holds until the next one on its topic. Before the first: sail 45 deg, rudder 0, level 0 (the
actions 0). A command that is not valid (NaN, infinite, out of range) is refused with a one-line reason and
the held one stays. A task without propeller ignores a0 whatever the level.
"""

from __future__ import annotations

import math
import threading

import numpy as np

__all__ = ["SAIL_TOPIC", "RUDDER_TOPIC", "PROPULSION_TOPIC", "WIND_TOPIC", "COMMAND_TOPICS", "SAIL_RANGE_DEG",
           "RUDDER_LIMIT_DEG", "MAX_LEVEL", "MAX_WIND_SPEED", "DEFAULT_SAIL_DEG", "actions_from_commands",
           "CommandInbox"]

SAIL_TOPIC, RUDDER_TOPIC, PROPULSION_TOPIC = ("control_interface/sail", "control_interface/rudder",
                                              "control_interface/propulsion")
WIND_TOPIC = "atmosferic_control/wind"
COMMAND_TOPICS = (SAIL_TOPIC, RUDDER_TOPIC, PROPULSION_TOPIC)
"""The three commands a decision waits for in lockstep, relative to a boat's namespace."""
SAIL_RANGE_DEG = (0.0, 90.0)
"""The sheet command: the largest boom angle either side [deg]."""
RUDDER_LIMIT_DEG = 60.0
"""The rudder command's limit either side [deg]."""
MAX_LEVEL = 5
"""The propeller's levels: -5 ... 5."""
MAX_WIND_SPEED = 40.0
"""The largest mean true wind a wind command may set [m/s]."""
DEFAULT_SAIL_DEG = 45.0
"""The sheet held before the first sail command [deg] (the action a1 = 0)."""


def actions_from_commands(sail_deg, rudder_deg, level) -> np.ndarray:
    """(N, 3) float32 actions of (N,) sheet [deg], rudder [deg] and propeller level commands: a0 = (level +
    0.5 sign(level)) / 5 (clipped to [-1, 1], so the task's int(5 a0) gives the level back exactly),
    a1 = sheet / 45 - 1, a2 = rudder / 60."""
    level = np.asarray(level, dtype=np.float64)
    a0 = np.clip((level + 0.5 * np.sign(level)) / MAX_LEVEL, -1.0, 1.0)
    a1 = np.asarray(sail_deg, dtype=np.float64) / (SAIL_RANGE_DEG[1] / 2.0) - 1.0
    a2 = np.asarray(rudder_deg, dtype=np.float64) / RUDDER_LIMIT_DEG
    return np.clip(np.column_stack([a0, a1, a2]), -1.0, 1.0).astype(np.float32)


def _number(value) -> float | None:
    try:
        number = float(value)
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) else None


class CommandInbox:
    """The commands held for ``boats`` boats (see the module's docstring); every method is thread-safe.

    Subscribers call :meth:`put` and :meth:`put_wind`; the decision loop :meth:`wait_for_commands` (lockstep),
    :meth:`take` and :meth:`take_wind`."""

    def __init__(self, boats: int):
        self.boats = int(boats)
        self._changed = threading.Condition()
        self.clear()

    def clear(self) -> None:
        """Back to the commands before the first (sail 45 deg, rudder 0, level 0), no wind set, none fresh."""
        with self._changed:
            self._sail = np.full(self.boats, DEFAULT_SAIL_DEG)
            self._rudder = np.zeros(self.boats)
            self._level = np.zeros(self.boats, dtype=np.int64)
            self._fresh = np.zeros((self.boats, len(COMMAND_TOPICS)), dtype=bool)
            self._wind: dict[int, tuple[float, float]] = {}
            self._wind_pending: set[int] = set()
            self._changed.notify_all()

    # --- subscribers' side -----------------------------------------------------------------------------
    def put(self, boat: int, topic: str, value) -> str | None:
        """Hold ``value`` as boat ``boat``'s command on ``topic`` (one of :data:`COMMAND_TOPICS`); returns
        None, or why it was refused (one line; the held command stays)."""
        number = _number(value)
        if topic == SAIL_TOPIC:
            low, high = SAIL_RANGE_DEG
            if number is None or not low <= number <= high:
                return f"ignored {value!r} deg: a sail command must be a finite angle from {low:g} to {high:g} deg"
        elif topic == RUDDER_TOPIC:
            if number is None or abs(number) > RUDDER_LIMIT_DEG:
                return (f"ignored {value!r} deg: a rudder command must be a finite angle from "
                        f"{-RUDDER_LIMIT_DEG:g} to {RUDDER_LIMIT_DEG:g} deg")
        elif topic == PROPULSION_TOPIC:
            if number is None or number != int(number) or abs(number) > MAX_LEVEL:
                return f"ignored {value!r}: a propulsion command must be a whole level from {-MAX_LEVEL} to {MAX_LEVEL}"
        else:
            raise ValueError(f"CommandInbox.put: unknown command topic {topic!r}; known: {', '.join(COMMAND_TOPICS)}")
        with self._changed:
            if topic == SAIL_TOPIC:
                self._sail[boat] = number
            elif topic == RUDDER_TOPIC:
                self._rudder[boat] = number
            else:
                self._level[boat] = int(number)
            self._fresh[boat, COMMAND_TOPICS.index(topic)] = True
            self._changed.notify_all()
        return None

    def put_wind(self, boat: int, x, y, z) -> str | None:
        """Set boat ``boat``'s mean true wind from a velocity (x east, y north, z up [m/s]; z is not used):
        its horizontal speed and the direction it blows towards. Returns None, or why it was refused."""
        values = [_number(v) for v in (x, y, z)]
        speed = None if None in values else math.hypot(values[0], values[1])
        if speed is None or speed > MAX_WIND_SPEED:
            return (f"ignored ({x!r}, {y!r}, {z!r}) m/s: a wind command must be a finite velocity with a horizontal "
                    f"speed up to {MAX_WIND_SPEED:g} m/s")
        with self._changed:
            self._wind[boat] = (speed, math.atan2(values[1], values[0]))
            self._wind_pending.add(boat)
            self._changed.notify_all()
        return None

    # --- the decision loop's side ----------------------------------------------------------------------
    def complete(self) -> bool:
        """Whether every boat's three commands arrived since the last :meth:`take`."""
        with self._changed:
            return bool(self._fresh.all())

    def wait_for_commands(self, timeout: float, wake=lambda: False) -> bool:
        """Wait until :meth:`complete`, ``timeout`` [s] passed (``math.inf``: no limit) or ``wake()`` is true
        (checked every 0.1 s); returns :meth:`complete`."""
        deadline = None if math.isinf(timeout) else _now() + timeout
        with self._changed:
            while not self._fresh.all() and not wake():
                left = 0.1 if deadline is None else min(0.1, deadline - _now())
                if left <= 0:
                    break
                self._changed.wait(left)
            return bool(self._fresh.all())

    def missing(self) -> list[tuple[int, str]]:
        """(boat, topic) of the commands that have not arrived since the last :meth:`take`."""
        with self._changed:
            return [(int(b), COMMAND_TOPICS[int(k)]) for b, k in zip(*np.nonzero(~self._fresh))]

    def take(self) -> np.ndarray:
        """(N, 3) float32 actions of the commands held (:func:`actions_from_commands`); none is fresh after."""
        with self._changed:
            self._fresh[:] = False
            return actions_from_commands(self._sail, self._rudder, self._level)

    def take_wind(self) -> dict[int, tuple[float, float]]:
        """The wind commands that arrived since the last call: boat -> (mean speed [m/s], direction it blows
        towards [rad, from east counter-clockwise])."""
        with self._changed:
            pending = {boat: self._wind[boat] for boat in sorted(self._wind_pending)}
            self._wind_pending.clear()
            return pending

    def held_wind(self, boat: int) -> tuple[float, float] | None:
        """Boat ``boat``'s wind as last commanded (speed [m/s], direction [rad]), or None (the task's)."""
        with self._changed:
            return self._wind.get(boat)


def _now() -> float:
    import time

    return time.monotonic()
