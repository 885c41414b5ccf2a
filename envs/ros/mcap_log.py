"""Logs ROS tools read: a rosbag2 MCAP file (profile "ros2", ROS 2 ``.msg`` schemas of encoding "ros2msg", CDR
messages) of the E-Boats' topics (:mod:`ocean_warp.ros.topics`), which ``ros2 bag``, Foxglove and PlotJuggler
open. Needs the ``mcap`` extra (``pip install 'ocean-warp[mcap]'``: ``mcap``, ``mcap-ros2-support``).

Example::

    with McapRecorder("out/run.mcap") as log:
        log.record(env)                     # after the reset: t = 0 (and its command tap is attached)
        for _ in range(100):
            env.step(policy(env.buffers.policy_obs))
            log.record(env)                 # once per decision

Every message's log time, publish time and header stamp is the simulated time (the simulator's clock, from 0:
tools show dates in January 1970). What a record holds: ``/clock`` (whenever the simulated time passed the last
one written), ``/tf`` and each boat's state topics at the current time; each boat's commands
(``control_interface/*``) at the start of the decision just sailed (from a
:class:`~ocean_warp.envs.ros.command_tap.CommandTap` the recorder attaches to the env on first sight: the first
record of an env logs no commands); the lidar's scan (the env's own lidar, or one passed) and the camera's
images (a camera passed, after a decision in which it rendered); ``/tf_static`` once per namespace prefix and
sensor. ``ros2 bag play`` republishes ``/tf_static`` with default QoS (the channels carry no QoS metadata):
give it ``--qos-profile-overrides-path`` with transient-local durability for ``/tf_static`` if late subscribers
need it.

The file appears whole or not at all: it is written beside its path under a temporary name and renamed by
:meth:`McapRecorder.close` (:meth:`McapRecorder.abort`, or an exception inside a ``with`` block, removes it).
"""

from __future__ import annotations

import importlib
import os

from ocean_warp.ros.geodesy import GUANABARA_BAY, GeodeticDatum
from ocean_warp.ros.message_definitions import schema_text
from ocean_warp.ros.topics import (CLOCK, Message, boat_namespace, camera_messages, clock_message, command_messages,
                                   env_lidar, lidar_messages, snapshot, state_messages, static_messages)

from .command_tap import CommandTap

__all__ = ["McapRecorder", "check_record_path", "MCAP_INSTALL_HINT"]

MCAP_INSTALL_HINT = "pip install 'ocean-warp[mcap]'"
_DECISION_TOLERANCE_NS = 1_000
"""How close [ns] a command tap's time plus a decision period must come to the clock to count as the decision
just sailed (the clock sums float64 substeps)."""


def _require_libraries() -> None:
    """``ImportError`` in one line naming the extra, unless ``mcap`` and ``mcap_ros2`` import."""
    try:
        for name in ("mcap.writer", "mcap_ros2.writer"):
            importlib.import_module(name)
    except ImportError as error:
        raise ImportError(f"writing MCAP logs needs the mcap and mcap-ros2-support libraries ({error}); "
                          f"install them with: {MCAP_INSTALL_HINT}") from None


def check_record_path(path) -> str:
    """``path`` as a string if an MCAP log can be written there: it ends in ``.mcap`` (else ``ValueError``) and
    the libraries are installed (else a one-line ``ImportError`` naming ``pip install 'ocean-warp[mcap]'``).
    Creates nothing (for command lines, before a long run)."""
    if not isinstance(path, (str, os.PathLike)):
        raise ValueError(f"the MCAP log's path must be a file name ending in .mcap, got {path!r}")
    path = os.fspath(path)
    if not path.lower().endswith(".mcap") or os.path.basename(path).lower() == ".mcap":
        raise ValueError(f"the MCAP log's path must end in .mcap (a rosbag2 MCAP file), got {path!r}")
    _require_libraries()
    return path


class McapRecorder:
    """A rosbag2 MCAP log of one or more :class:`~ocean_warp.envs.SailingEnv` runs (see the module's docstring).

    Args:
        path: the file to write, ending in ``.mcap``; its folder is made if missing.
        datum: where the world frame's origin lies on Earth, for ``gps/fix`` (default Guanabara Bay).
    """

    def __init__(self, path, *, datum: GeodeticDatum = GUANABARA_BAY):
        self.path = check_record_path(path)
        if not isinstance(datum, GeodeticDatum):
            raise ValueError(f"McapRecorder: datum must be a GeodeticDatum, got {datum!r}")
        self.datum = datum
        from mcap_ros2.writer import Writer

        from ocean_warp.atomic_files import atomic_output

        self._atomic = atomic_output(self.path, suffix=".mcap")
        temporary = self._atomic.__enter__()
        try:
            self._file = open(temporary, "wb")
            self._writer = Writer(self._file)
        except BaseException as error:
            self._discard(error)
            raise
        self._writer.add_metadata("ocean_warp", {
            "datum_latitude_deg": repr(datum.latitude_deg), "datum_longitude_deg": repr(datum.longitude_deg),
            "datum_altitude_m": repr(datum.altitude_m), "time": "simulated time from the run's start",
            "frames": "map/odom ENU, base_link FLU (REP 103, 105)"})
        self._open = True
        self._schemas: dict = {}
        self._sequence: dict[str, int] = {}
        self._taps: dict[int, tuple[object, object]] = {}
        """id(env) -> (env, its CommandTap)."""
        self._static: set = set()
        """(prefix, part) whose /tf_static transforms were written: part "odom", "lidar" or "camera"."""
        self._last_commands: dict[str, int] = {}
        """prefix -> time [ns] of the last commands written."""
        self._clock_ns = -1
        self.messages_written = 0
        """Messages written so far."""

    # --- recording -------------------------------------------------------------------------------------
    def record(self, env, *, prefix: str = "", lidar=None, camera=None, time_offset_ns: int = 0) -> None:
        """Log ``env``'s boats now (once after the reset, then once after each decision), under ``prefix`` (""
        or an absolute ROS name: ``/autopilot`` puts boat i under ``/autopilot/eboat_i``). ``lidar``: a
        :class:`~ocean_warp.perception.Lidar` or :class:`~ocean_warp.envs.sensors.LidarHook` to log instead of the
        env's own (its task's lidar, logged by default); ``camera``: a :class:`~ocean_warp.envs.sensors.CameraHook`
        (logged after each decision in which it rendered) or a :class:`~ocean_warp.perception.Camera` (after
        each decision). ``time_offset_ns`` [ns] is added to the simulator's clock (a node that resets its env
        passes what keeps the log's time running on)."""
        if not self._open:
            raise ValueError(f"McapRecorder.record: the log {self.path!r} is closed")
        if not hasattr(env, "simulator") or not hasattr(env, "target_world"):
            raise ValueError(f"McapRecorder.record: env must be a SailingEnv (the log reads its simulator's state), "
                             f"got {type(env).__name__}")
        boat_namespace(0, env.num_envs, prefix)  # checks the prefix
        tap = self._tap(env)
        state = snapshot(env, time_offset_ns)
        t = state.time_ns
        messages: list[Message] = [clock_message(t)]  # written where the time passed the last /clock (write)
        lidar, scan_time = self._lidar(env, lidar)
        camera, camera_due = _camera(camera)
        static = static_messages(env.num_envs, t, prefix=prefix,
                                 odom=(prefix, "odom") not in self._static,
                                 lidar_config=None if lidar is None or (prefix, "lidar") in self._static
                                 else lidar.config,
                                 camera=None if camera is None or (prefix, "camera") in self._static else camera)
        if static.fields["transforms"]:
            messages.append(static)
            self._static |= {(prefix, "odom")} | ({(prefix, "lidar")} if lidar is not None else set()) \
                | ({(prefix, "camera")} if camera is not None else set())
        messages += state_messages(state, prefix=prefix, datum=self.datum)
        decided = False
        started, rudder, sheet, propeller = tap.read()
        if started == started:  # not NaN: a decision was seen
            start_ns = int(round(started * 1e9)) + int(time_offset_ns)
            period_ns = int(round(env.decision_period * 1e9))
            decided = abs(start_ns + period_ns - t) <= _DECISION_TOLERANCE_NS
            if decided and self._last_commands.get(prefix) != start_ns:
                messages += command_messages(start_ns, rudder, sheet, propeller, prefix=prefix)
                self._last_commands[prefix] = start_ns
        if lidar is not None:
            messages += lidar_messages(lidar, t, scan_time=scan_time, prefix=prefix)
        if camera is not None and decided and camera_due:
            messages += camera_messages(camera, env.num_envs, t, prefix=prefix)
        self.write(messages)

    def write(self, messages) -> None:
        """Log ``messages`` (:class:`~ocean_warp.ros.topics.Message`: a node's episode ends, its /clock between
        decisions) as they are; a /clock not past the last one written is left out (the log's clock never
        runs back)."""
        if not self._open:
            raise ValueError(f"McapRecorder.write: the log {self.path!r} is closed")
        for message in messages:
            if message.topic == CLOCK:
                if message.time_ns <= self._clock_ns:
                    continue
                self._clock_ns = message.time_ns
            self._write(message)

    def _tap(self, env):
        """``env``'s command tap, attached on first sight."""
        known = self._taps.get(id(env))
        if known is not None and known[0] is env:
            return known[1]
        tap = CommandTap(env)
        env.attach(tap)
        self._taps[id(env)] = (env, tap)
        self._writer.add_metadata("ocean_warp.env", {
            "task": type(env.task).__name__, "boats": str(env.num_envs), "seed": str(env.seed),
            "decision_period_s": repr(float(env.decision_period))})
        return tap

    @staticmethod
    def _lidar(env, lidar):
        """The lidar to log and its time between scans [s]: the one given (a LidarHook's scan every ``period``
        physics steps, a bare Lidar at its config's rate), else the env's own (one scan a decision), or None."""
        if lidar is None:
            own = env_lidar(env)
            return (own, float(env.decision_period)) if own is not None else (None, 0.0)
        hook_lidar = getattr(lidar, "lidar", None)
        if hook_lidar is not None:
            return hook_lidar, float(lidar.period * env.task.simulator.dt)
        if not hasattr(lidar, "range_array"):
            raise ValueError(f"McapRecorder.record: lidar must be a Lidar or a LidarHook, got {lidar!r}")
        return lidar, 1.0 / float(lidar.config.rate)

    def _write(self, message: Message) -> None:
        schema = self._schemas.get(message.type)
        if schema is None:
            schema = self._schemas[message.type] = self._writer.register_msgdef(message.type,
                                                                                 schema_text(message.type))
        sequence = self._sequence.get(message.topic, 0)
        self._sequence[message.topic] = sequence + 1
        self._writer.write_message(message.topic, schema, message.fields, log_time=message.time_ns,
                                   publish_time=message.time_ns, sequence=sequence)
        self.messages_written += 1

    def add_metadata(self, name: str, data: dict) -> None:
        """A metadata record ``name`` holding ``data`` (string keys and values; others are written as ``str``)."""
        if not self._open:
            raise ValueError(f"McapRecorder.add_metadata: the log {self.path!r} is closed")
        self._writer.add_metadata(str(name), {str(key): str(value) for key, value in data.items()})

    # --- the file --------------------------------------------------------------------------------------
    def close(self) -> str:
        """Finish the file and move it to its path (once; later calls do nothing); returns the path."""
        if self._open:
            self._open = False
            try:
                self._writer.finish()
                self._file.close()
            except BaseException as error:
                self._discard(error)
                raise
            self._atomic.__exit__(None, None, None)
        return self.path

    def abort(self) -> None:
        """Stop without writing the file (its temporary is removed); idempotent."""
        if self._open:
            self._open = False
            self._discard(RuntimeError("McapRecorder aborted"))

    def _discard(self, error: BaseException) -> None:
        file = getattr(self, "_file", None)
        if file is not None and not file.closed:
            file.close()
        self._atomic.__exit__(type(error), error, error.__traceback__)

    def __enter__(self) -> McapRecorder:
        return self

    def __exit__(self, kind, value, traceback) -> None:
        if kind is None:
            self.close()
        else:
            self.abort()


def _camera(camera):
    """(the Camera to log, whether its images are new): a CameraHook's camera rendered in the last decision when
    it renders every decision or its decision counter just left 0; a bare Camera's always."""
    if camera is None:
        return None, False
    inner = getattr(camera, "camera", None)
    if inner is not None and hasattr(camera, "decisions_between_captures"):
        due = camera.decisions_between_captures == 1 or int(inner.gate.numpy()[0]) == 1
        return inner, due
    if not hasattr(camera, "boats") or not hasattr(camera, "camera_info"):
        raise ValueError(f"McapRecorder.record: camera must be a Camera or a CameraHook, got {camera!r}")
    return camera, True
