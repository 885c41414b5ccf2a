"""The decision loop of ``ocean-warp ros`` (:mod:`ocean_warp.envs.ros.node`): commands in (rospy's threads write a
:class:`~ocean_warp.ros.commands.CommandInbox`), pacing at a rate factor (with /clock ticks between decisions)
or lockstep with the commands, one decision, the state out (and into the MCAP log), episode ends (published and
logged), the reset service (the clock goes on), a clean stop on SIGINT and SIGTERM."""

from __future__ import annotations

import argparse
import functools
import math
import signal
import threading
import time

from ocean_warp.cli_support import plural

from .commands import COMMAND_TOPICS, WIND_TOPIC, CommandInbox
from .topics import BOAT_TOPICS, EPISODE_TOPIC, NODE_TOPICS, boat_namespace, episode_end_reason

__all__ = ["PROG", "RESET_SERVICE", "RESET_WAIT_S", "Throttle", "Pacer", "NodeLoop"]

PROG = "ocean-warp ros"
RESET_SERVICE = "~reset"
"""The reset service (std_srvs/Trigger), private to the node: /ocean_warp/reset."""
RESET_WAIT_S = 10.0
"""How long the reset service waits for the decision loop [s, wall clock]."""


class Throttle:
    """At most one warning line a second per key; the lines held back are counted into the next."""

    def __init__(self, warn, interval: float = 1.0):
        self.warn, self.interval = warn, interval
        self._last: dict = {}
        self._held: dict = {}
        self._lock = threading.Lock()

    def __call__(self, key, text: str) -> None:
        now = time.monotonic()
        with self._lock:
            if now - self._last.get(key, -math.inf) < self.interval:
                self._held[key] = self._held.get(key, 0) + 1
                return
            held = self._held.pop(key, 0)
            self._last[key] = now
        self.warn(text + (f" ({held} more like it ignored before)" if held else ""))


class Pacer:
    """Keeps decisions ``period`` [s, wall clock] apart (0: no waiting); after falling a whole period behind it
    starts again from now (no catching up). Between decisions it can run actions at fractions of the period
    (the /clock ticks)."""

    def __init__(self, period: float):
        self.period = period
        self._next = None
        self.behind = 0

    def restart(self) -> None:
        self._next = None

    def wait(self, stop: threading.Event, between=()) -> None:
        """Until the next decision is due; ``between``: (fraction of the period, action) pairs in order, each
        action run when that fraction of the period before the decision's time has passed (all at once without
        pacing, on the first decision, after a restart or when behind). Returns early once ``stop`` is set."""
        if self.period <= 0.0:
            for _, action in between:
                action()
            return
        now = time.monotonic()
        if self._next is None or now - self._next > self.period:
            if self._next is not None:
                self.behind += 1
            self._next = now
        start = self._next - self.period
        for fraction, action in between:
            delay = start + fraction * self.period - time.monotonic()
            if delay > 0.0 and stop.wait(delay):
                return
            action()
        delay = self._next - time.monotonic()
        if delay > 0.0:
            stop.wait(delay)
        self._next += self.period


class NodeLoop:
    """The decision loop of the node and its subscribers' and service's callbacks."""

    def __init__(self, sim, bus, args: argparse.Namespace, recorder):
        self.sim, self.bus, self.recorder = sim, bus, recorder
        self.duration = args.duration
        self.clock_hz = args.clock_hz
        self.lockstep = args.lockstep
        self.lockstep_timeout = math.inf if args.lockstep_timeout == 0 else args.lockstep_timeout
        rate = 0.0 if args.as_fast_as_possible else args.rate_factor
        self.rate_text = "as fast as possible" if rate == 0 else f"{rate:g} x real time"
        self.pacer = Pacer(0.0 if rate == 0 else sim.env.decision_period / rate)
        self.inbox = CommandInbox(sim.boats)
        self.stop = threading.Event()
        self.stop_reason = "rospy shut down"
        self._resets: list[dict] = []
        """Reset requests waiting for the loop: {"done": Event, "ok": bool}."""
        self._reset_lock = threading.Lock()
        self.warn = Throttle(bus.warn)
        self.decisions = self.episodes = self.reached = 0
        self._latched = ()
        self._said_behind = False

    # --- callbacks (rospy's threads) ------------------------------------------------------------------
    def _on_command(self, boat: int, topic: str, message) -> None:
        reason = self.inbox.put(boat, topic, message.data)
        if reason is not None:
            self.warn((boat, topic), f"{PROG}: {self._topic(boat, topic)}: {reason}")

    def _on_wind(self, boat: int, message) -> None:
        header = getattr(message, "_connection_header", None) or {}
        if header.get("callerid") == self.bus.caller_id:
            return  # the node's own report of the wind
        reason = self.inbox.put_wind(boat, message.x, message.y, message.z)
        if reason is not None:
            self.warn((boat, WIND_TOPIC), f"{PROG}: {self._topic(boat, WIND_TOPIC)}: {reason}")

    def _on_reset(self, request) -> tuple[bool, str]:
        """The reset service's answer, (success, message): the bus makes its Trigger response of it."""
        ticket = {"done": threading.Event(), "ok": False}
        with self._reset_lock:
            self._resets.append(ticket)
        if not ticket["done"].wait(RESET_WAIT_S) or not ticket["ok"]:
            return False, f"the simulator did not reset (stopped, or busy for {RESET_WAIT_S:g} s)"
        return True, (f"every boat restarted from seed {self.sim.seed}; the clock goes on at "
                      f"t = {self.sim.time_s():.1f} s")

    def _topic(self, boat: int, topic: str) -> str:
        return f"{boat_namespace(boat, self.sim.boats)}/{topic}"

    def _on_signal(self, number, frame) -> None:
        self.stop_reason = signal.Signals(number).name
        self.stop.set()

    # --- the loop -----------------------------------------------------------------------------------------
    def run(self) -> str:
        """Sail until the duration is reached or the node is stopped; returns a summary line."""
        previous = {s: signal.signal(s, self._on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
        try:
            self._connect()
            self._publish(with_static=True)
            self.bus.info(self._start_text())
            while not self._stopping():
                if self._reset_pending():
                    self._reset()
                    continue
                if self.lockstep and not self._wait_for_commands():
                    continue
                self.pacer.wait(self.stop, self._clock_ticks())
                if self.pacer.behind == 1 and not self._said_behind:
                    self._said_behind = True
                    self.bus.warn(f"{PROG}: cannot keep up with {self.rate_text}: sailing as fast as it can")
                if self._stopping():
                    break
                self._decide()
                if self.duration is not None and self.sim.time_s() >= self.duration - 1e-9:
                    self.stop_reason = f"the duration {self.duration:g} s was reached"
                    break
        finally:
            for number, handler in previous.items():
                signal.signal(number, handler)
            self._release_resets()
        return (f"stopped at t = {self.sim.time_s():.1f} s ({self.stop_reason}): "
                f"{plural(self.decisions, 'decision')}, {plural(self.sim.boats, 'boat')}, "
                f"{plural(self.episodes, 'episode')} ended, {self.reached} reached the last waypoint"
                + (f"; fell behind {self.rate_text} {plural(self.pacer.behind, 'time')}" if self.pacer.behind else ""))

    def _connect(self) -> None:
        bus, boats = self.bus, self.sim.boats
        for boat in range(boats):
            ns = boat_namespace(boat, boats)
            for topic in COMMAND_TOPICS:
                type_name = BOAT_TOPICS[topic]
                bus.subscribe(f"{ns}/{topic}", type_name, functools.partial(self._on_command, boat, topic))
            bus.subscribe(f"{ns}/{WIND_TOPIC}", BOAT_TOPICS[WIND_TOPIC], functools.partial(self._on_wind, boat))
            for topic, type_name in NODE_TOPICS.items():  # known to the master before the first episode ends
                bus.publisher(f"{ns}/{topic}", type_name)
        if self.lockstep:
            self._latched = {f"{boat_namespace(b, boats)}/mission_control/observations" for b in range(boats)}
        bus.service(RESET_SERVICE, self._on_reset)

    def _start_text(self) -> str:
        sim = self.sim
        names = ", ".join(boat_namespace(b, sim.boats) for b in range(min(sim.boats, 3))) + \
            (", ..." if sim.boats > 3 else "")
        return (f"{PROG}: {sim.task_id}, {plural(sim.boats, 'boat')} ({names}), seed {sim.seed}, device "
                f"{sim.env.device}: a decision every {sim.env.decision_period:g} s of simulated time, "
                f"{self.rate_text}{', lockstep with the commands' if self.lockstep else ''}; "
                f"commands on <boat>/control_interface/{{sail,rudder,propulsion}}; reset: "
                f"{self.bus.resolve_name(RESET_SERVICE)} (std_srvs/Trigger)")

    def _stopping(self) -> bool:
        if self.bus.shut_down() and not self.stop.is_set():
            self.stop_reason = "rospy shut down"
            self.stop.set()
        return self.stop.is_set()

    def _reset_pending(self) -> bool:
        with self._reset_lock:
            return bool(self._resets)

    def _wait_for_commands(self) -> bool:
        """Lockstep: wait for every boat's commands; False where the loop must look again first (stopped, a
        reset asked for)."""
        complete = self.inbox.wait_for_commands(self.lockstep_timeout,
                                                wake=lambda: self.stop.is_set() or self._reset_pending())
        if self._stopping() or self._reset_pending():
            return False
        if not complete:
            gaps = self.inbox.missing()
            missing = ", ".join(self._topic(b, t) for b, t in gaps[:3]) + \
                (f" and {len(gaps) - 3} more" if len(gaps) > 3 else "")
            self.warn("lockstep", f"{PROG}: lockstep: no command on {missing} within {self.lockstep_timeout:g} s; "
                                  "stepping with the commands held")
        self.pacer.restart()
        return True

    def _decide(self) -> None:
        sim = self.sim
        ends = sim.step(self.inbox.take(), self.inbox.take_wind())
        self.decisions += 1
        self._publish(with_static=False)
        if ends:
            self.bus.publish(ends)
            if self.recorder is not None:
                self.recorder.write(ends)
            for message in ends:
                boat = self._boat_of(message.topic)
                success, waypoints, decisions, total, flags = message.fields["data"][:5]
                self.episodes += 1
                self.reached += int(success == 1.0)
                held = self.inbox.held_wind(boat)
                if held is not None:
                    sim.set_wind(boat, *held)
                self.bus.info(f"{PROG}: {self._topic(boat, EPISODE_TOPIC)}: episode ended at t = "
                              f"{sim.time_s():.1f} s: {episode_end_reason(message)}, {int(waypoints)} waypoint(s), "
                              f"{int(decisions)} decisions, return {total:.3f}, status flags {int(flags)}")

    def _boat_of(self, topic: str) -> int:
        boats = self.sim.boats
        return 0 if boats == 1 else int(topic.split("/")[1].rsplit("_", 1)[1])

    def _publish(self, *, with_static: bool) -> None:
        self.bus.publish(self.sim.messages(with_static=with_static), latched=self._latched)
        if self.recorder is not None:
            self.recorder.record(self.sim.env, lidar=self.sim.lidar_hook, camera=self.sim.camera_hook,
                                 time_offset_ns=self.sim.time_offset_ns)

    def _clock_ticks(self) -> list:
        """(fraction of the decision period, publish it) for each /clock tick before the next decision."""
        period_ns = float(self.sim.env.decision_period) * 1e9
        now = self.sim.clock_ns()
        return [((tick.time_ns - now) / period_ns, functools.partial(self._tick, tick))
                for tick in self.sim.clock_ticks(self.clock_hz)]

    def _tick(self, message) -> None:
        self.bus.publish([message])
        if self.recorder is not None:
            self.recorder.write([message])

    def _reset(self) -> None:
        with self._reset_lock:
            waiting, self._resets = self._resets, []
        for _, tick in self._clock_ticks():  # the clock runs on through the reset's decision
            tick()
        self.sim.reset()
        self.inbox.clear()
        self.pacer.restart()
        self._publish(with_static=False)
        self.bus.info(f"{PROG}: reset: every boat restarted from seed {self.sim.seed}; the clock goes on at "
                      f"t = {self.sim.time_s():.1f} s")
        for ticket in waiting:
            ticket["ok"] = True
            ticket["done"].set()

    def _release_resets(self) -> None:
        """Answer reset requests still waiting when the loop ends (they fail: nothing was reset)."""
        with self._reset_lock:
            waiting, self._resets = self._resets, []
        for ticket in waiting:
            ticket["done"].set()
