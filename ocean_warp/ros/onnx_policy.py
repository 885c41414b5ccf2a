"""Run a policy exported by ``ocean-warp export-policy --format onnx`` with numpy and onnxruntime alone.

This is the policy half of the boat's controller: the same file drives the simulator's ROS node and the
real boat. The exported graph holds the whole actor, observation normalisation included, so
:meth:`OnnxPolicy.act` takes the raw observation the task defines (``OnnxPolicy.observation_layout`` says
what each value is) and returns the policy's deterministic actions: the mean of its Gaussian, *not*
clipped. The simulator clips each action to [-1, 1] before it turns them into commands; a controller on
the boat must do the same (``OnnxPolicy.action_meaning`` says what each action commands, with units).

Imports: this module reads only the standard library, numpy and onnxruntime, and no other module of
ocean_warp, so that torch and Warp never load for it. ``import ocean_warp.ros.onnx_policy`` runs
``ocean_warp/__init__.py`` first, which imports Warp (not torch); where Warp is unwanted (a boat's computer
without it), load this file on its own, e.g. copied beside the node as ``onnx_policy.py``, or::

    spec = importlib.util.spec_from_file_location("onnx_policy", "/path/to/ocean_warp/ros/onnx_policy.py")
    onnx_policy = importlib.util.module_from_spec(spec); spec.loader.exec_module(onnx_policy)

Needs the onnx extra: ``pip install 'ocean-warp[onnx]'`` (or just ``pip install onnxruntime numpy``).
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence

import numpy as np

__all__ = ["EXPORT_FORMAT", "INPUT_NAME", "OUTPUT_NAME", "INSTALL_HINT", "OnnxPolicy", "decode_metadata"]

EXPORT_FORMAT = "ocean_warp.exported_policy/1"
"""Value of the "format" metadata entry of every exported policy (ONNX and TorchScript)."""
INPUT_NAME = "observation"
"""The exported graph's input: float32 (batch, num_obs), the raw observation."""
OUTPUT_NAME = "action"
"""The exported graph's output: float32 (batch, num_actions), the deterministic actions, not clipped."""
INSTALL_HINT = "pip install 'ocean-warp[onnx]'"
"""How to get onnx and onnxruntime."""
LIST_KEYS = ("actions", "observation_layout")
"""Metadata entries that hold a JSON list of strings (every other entry is a plain string)."""


def decode_metadata(entries: Mapping[str, str]) -> dict[str, object]:
    """An exported policy's metadata (string to string, as stored) with its lists decoded and its counts as
    ints: "num_obs" and "num_actions" -> int, "actions" and "observation_layout" -> tuple of str.

    Raises:
        ValueError: not an exported ocean_warp policy's metadata (no or another "format"), or an entry that
            does not decode.
    """
    found = entries.get("format")
    if found != EXPORT_FORMAT:
        what = "no 'format' entry" if found is None else f"format {found!r}"
        raise ValueError(f"not an exported ocean_warp policy ({what} in its metadata; expected {EXPORT_FORMAT!r})")
    metadata: dict[str, object] = dict(entries)
    try:
        for key in ("num_obs", "num_actions"):
            metadata[key] = int(entries[key])
        for key in LIST_KEYS:
            if key in entries:
                metadata[key] = tuple(str(item) for item in json.loads(entries[key]))
    except (KeyError, ValueError, TypeError) as error:
        raise ValueError(f"exported policy metadata that does not decode: {type(error).__name__}: {error}") from None
    return metadata


class OnnxPolicy:
    """An exported policy, run by onnxruntime: :meth:`act` maps observations to actions.

    Attributes:
        path: the ONNX file.
        metadata: every metadata entry (:func:`decode_metadata`): "task", "observation", "num_obs",
            "num_actions", "actions", "observation_layout", "checkpoint_format", "observation_normalisation",
            and "source" / "source_sha256" (the checkpoint it came from) where the export knew them.
    """

    def __init__(self, path: str | os.PathLike, *, threads: int = 1, providers: Sequence[str] | None = None):
        """Load an exported policy.

        Args:
            path: the ``.onnx`` file ``ocean-warp export-policy`` wrote.
            threads: onnxruntime's intra-op threads; 1 suits these small networks (lowest latency, no
                contention with the rest of the node).
            providers: onnxruntime execution providers, in order of preference (default: the CPU's).

        Raises:
            ImportError: onnxruntime is not installed (the message says how to install it).
            FileNotFoundError: no such file.
            ValueError: not an ONNX file, or not an exported ocean_warp policy (its metadata or its input and
                output do not fit).
        """
        ort = _onnxruntime()
        self.path = os.fspath(path)
        if not os.path.isfile(self.path):
            raise FileNotFoundError(f"exported policy {self.path!r}: no such file")
        options = ort.SessionOptions()
        options.intra_op_num_threads = int(threads)
        options.inter_op_num_threads = 1
        options.log_severity_level = 3  # errors only: the node's log is not the place for graph-optimiser notes
        try:
            self._session = ort.InferenceSession(self.path, sess_options=options,
                                                 providers=list(providers or ["CPUExecutionProvider"]))
        except Exception as error:  # noqa: BLE001 - onnxruntime raises its own Fail / InvalidProtobuf types
            first_line = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
            raise ValueError(f"exported policy {self.path!r} is not an ONNX model onnxruntime can run: "
                             f"{first_line}") from None
        try:
            self.metadata = decode_metadata(self._session.get_modelmeta().custom_metadata_map)
            self._check_signature()
        except ValueError as error:
            raise ValueError(f"exported policy {self.path!r}: {error}") from None

    @property
    def task(self) -> str:
        """The task id the policy was trained for ("EBoatMission-v0", ...)."""
        return str(self.metadata["task"])

    @property
    def observation(self) -> str:
        """The observation set it reads ("seed" or "plus"; a task may append values, e.g. lidar sectors)."""
        return str(self.metadata["observation"])

    @property
    def num_obs(self) -> int:
        """Values in one observation."""
        return int(self.metadata["num_obs"])

    @property
    def num_actions(self) -> int:
        """Values in one action (3: propeller, sheet, rudder)."""
        return int(self.metadata["num_actions"])

    @property
    def observation_layout(self) -> tuple[str, ...]:
        """What each observation value is, with its scaling and units (empty where the export did not say)."""
        return tuple(self.metadata.get("observation_layout", ()))

    @property
    def action_meaning(self) -> tuple[str, ...]:
        """What each action commands once clipped to [-1, 1], with units (empty where the export did not say)."""
        return tuple(self.metadata.get("actions", ()))

    def act(self, observation) -> np.ndarray:
        """The policy's actions: the Gaussian's mean, not clipped (clip to [-1, 1] before use, as the simulator
        does).

        Args:
            observation: one observation, shape (num_obs,), or a batch, shape (B, num_obs) with B >= 1; any
                real dtype (converted to float32), every value finite.

        Returns:
            float32 actions, shape (num_actions,) for one observation, (B, num_actions) for a batch.

        Raises:
            ValueError: a shape other than those, or a value that is NaN or infinite.
        """
        batch, single = self._as_batch(observation)
        (actions,) = self._session.run([OUTPUT_NAME], {INPUT_NAME: batch})
        return actions[0] if single else actions

    def describe(self) -> str:
        """One line for a log: the file, the task, the observation set and the sizes."""
        return (f"policy {self.path}: {self.task}, observation {self.observation!r} ({self.num_obs} values) -> "
                f"{self.num_actions} actions")

    def __repr__(self) -> str:
        return (f"OnnxPolicy({self.path!r}, task={self.task!r}, observation={self.observation!r}, "
                f"num_obs={self.num_obs})")

    def _as_batch(self, observation) -> tuple[np.ndarray, bool]:
        """``observation`` as a contiguous float32 (B, num_obs) array, and whether it was a single one."""
        try:
            values = np.asarray(observation, dtype=np.float32)
        except (TypeError, ValueError) as error:
            raise ValueError(f"{self.task} policy: observation must be numbers, {error}") from None
        single = values.ndim == 1
        if not (values.ndim in (1, 2) and values.shape[-1] == self.num_obs and values.size > 0):
            raise ValueError(f"{self.task} policy: observation must have shape ({self.num_obs},) or "
                             f"(B, {self.num_obs}) with B >= 1, got {values.shape}")
        batch = np.ascontiguousarray(values.reshape(-1, self.num_obs))
        bad = ~np.isfinite(batch)
        if bad.any():
            rows, columns = np.nonzero(bad)
            where = f"value {columns[0]}" if single else f"row {rows[0]}, value {columns[0]}"
            raise ValueError(f"{self.task} policy: observation holds {int(bad.sum())} NaN or infinite value(s), "
                             f"first at {where}")
        return batch, single

    def _check_signature(self) -> None:
        """Raise ValueError where the graph's input and output are not what an exported policy has."""
        inputs, outputs = self._session.get_inputs(), self._session.get_outputs()
        if [item.name for item in inputs] != [INPUT_NAME] or OUTPUT_NAME not in [item.name for item in outputs]:
            raise ValueError(f"its graph must take {INPUT_NAME!r} and give {OUTPUT_NAME!r}, it takes "
                             f"{[item.name for item in inputs]} and gives {[item.name for item in outputs]}")
        width = inputs[0].shape[-1] if inputs[0].shape else None
        if width != self.num_obs:
            raise ValueError(f"its metadata says {self.num_obs} observation values, its graph takes {width}")


def _onnxruntime():
    """The onnxruntime module, or ImportError saying how to install it."""
    try:
        import onnxruntime
    except ImportError:
        raise ImportError(f"running an exported ONNX policy needs onnxruntime: {INSTALL_HINT}") from None
    return onnxruntime
