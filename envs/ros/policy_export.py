"""Export a policy for the boat's computer: ONNX (numpy and onnxruntime run it, ``ocean_warp.ros.onnx_policy``)
or TorchScript (libtorch, C++ or Python).

    ocean-warp export-policy --task EBoatMission-v0                       # the shipped policy, as ONNX
    ocean-warp export-policy --policy out/train/EBoatMission-v0/<run>/policy.pt --out out/export-policy/boat.onnx
    ocean-warp export-policy --task EBoatAvoid-v0 --format torchscript

The exported graph takes the raw observation, float32 (batch, num_obs) with any batch, named "observation",
and gives the policy's deterministic actions, float32 (batch, 3), named "action": exactly what
``Policy`` returns when it acts (the mean of rsl-rl's Gaussian, not clipped; the simulator clips each
action to [-1, 1]). The observation normalisation, (x - mean) / (std + eps) with the statistics learnt in
training, is inside the graph. The file carries its metadata (ONNX: ``metadata_props``; TorchScript: the
extra file ``ocean_warp_policy.json``): task, observation set, num_obs, num_actions, what each
observation value and each action is (JSON lists), the checkpoint format, and the checkpoint it came from.
Before the file replaces anything at --out (atomically), onnxruntime (without it, onnx's reference evaluator;
for TorchScript, torch.jit.load) runs it on 256 random observations spread as in training and must reproduce
the torch policy's actions to 1e-5: the actions clipped to [-1, 1], as the boat applies them, and the
unclipped means up to 1, relative beyond.
(Trained policies' unclipped means reach tens, and float32 resolves 40 to about 4e-6 only. Far outside the
training spread, where hidden activations are large, float32 sums are good to some 2e-5 only: torch itself
differs that much between a batch of 1 and one of 4000.)
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import functools
import hashlib
import importlib.util
import io
import json
import logging
import os
import sys
import warnings

import numpy as np
import torch

from ocean_warp.atomic_files import atomic_output
from ocean_warp.cli_support import check_options, checked_output_file, fail
from ocean_warp.envs.registration import DEFAULT_TASK
from ocean_warp.envs.tasks.observation_blocks import SET_BLOCKS, lidar_block, reef_block
from ocean_warp.envs.training.policy_io import (CHECKPOINT_FORMAT, CheckpointError, Policy, is_torchscript_archive,
                                               load_policy)
from ocean_warp.ros.onnx_policy import EXPORT_FORMAT, INPUT_NAME, INSTALL_HINT, OUTPUT_NAME, OnnxPolicy, decode_metadata

from .policy_export_options import OUT_FOLDER, parser as _parser

__all__ = ["FORMATS", "OPSET", "TOLERANCE", "TORCHSCRIPT_METADATA", "ExportError", "ActionDifference",
           "ExportSummary", "check_observations", "policy_metadata", "observation_layout", "action_meaning",
           "export_onnx", "export_torchscript", "read_torchscript_metadata", "main"]

FORMATS = {"onnx": ".onnx", "torchscript": ".pt"}
"""Export format -> the suffix its file must have."""
OPSET = 18
"""ONNX opset of the exported graph (onnxruntime >= 1.14 runs it)."""
TOLERANCE = 1e-5
"""Largest difference allowed between the exported file's actions and the torch policy's on the check's
observations [action units, the [-1, 1] scale]: on the clipped actions, and on the unclipped means up to 1
(relative beyond 1): :class:`ActionDifference`."""
CHECK_OBSERVATIONS = 256
"""Random observations the export is checked on."""
TORCHSCRIPT_METADATA = "ocean_warp_policy.json"
"""Name of the extra file inside an exported TorchScript archive that holds its metadata (a JSON object)."""

ACTION_NOTE = "the Gaussian's mean, not clipped: clip each action to [-1, 1] first, as the simulator does"


class ExportError(RuntimeError):
    """An export that does not reproduce the torch policy (nothing is written)."""


@dataclasses.dataclass(frozen=True)
class ActionDifference:
    """How far an exported file's actions are from the torch policy's on the same observations, in action
    units (the [-1, 1] scale the simulator clips to).

    Attributes:
        clipped: the largest |clip(file) - clip(torch)|, each action clipped to [-1, 1] as the simulator (and
            the boat's controller) applies it.
        scaled: the largest |file - torch| / max(1, |torch|) over the unclipped means: absolute up to 1,
            relative beyond (float32 resolves a mean of 40 only to about 4e-6, and a trained policy's
            unclipped means reach tens on ordinary observations).
        absolute: the largest |file - torch| over the unclipped means, for the record.
        observations: how many observations were compared.
    """

    clipped: float
    scaled: float
    absolute: float
    observations: int

    @classmethod
    def between(cls, expected: np.ndarray, actual: np.ndarray) -> "ActionDifference":
        """The difference of ``actual`` (the file's actions) from ``expected`` (the torch policy's), (N, A)."""
        expected, actual = np.asarray(expected, np.float64), np.asarray(actual, np.float64)
        error = np.abs(actual - expected)
        clipped = np.abs(np.clip(actual, -1.0, 1.0) - np.clip(expected, -1.0, 1.0))
        return cls(clipped=float(clipped.max()), scaled=float((error / np.maximum(1.0, np.abs(expected))).max()),
                   absolute=float(error.max()), observations=len(expected))

    def within(self, tolerance: float | None = None) -> bool:
        """Whether both the clipped and the scaled difference are at most ``tolerance`` (default TOLERANCE);
        NaN never is."""
        tolerance = TOLERANCE if tolerance is None else tolerance
        return self.clipped <= tolerance and self.scaled <= tolerance

    def text(self) -> str:
        """E.g. "6.1e-07 (clipped actions), 7.5e-07 (means, relative beyond 1; 2.6e-06 absolute) on 256
        observations"."""
        return (f"{self.clipped:.1e} (clipped actions), {self.scaled:.1e} (means, relative beyond 1; "
                f"{self.absolute:.1e} absolute) on {self.observations} observations")


@dataclasses.dataclass(frozen=True)
class ExportSummary:
    """What an export wrote and how well the file reproduces the torch policy.

    Attributes:
        path: the file written.
        format: "onnx" or "torchscript".
        metadata: the metadata stored in it (string to string).
        difference: the file's actions against the torch policy's on the check's observations; None where
            it was not checked (``check`` off).
        checker: what ran the file for the check: "onnxruntime", "onnx's reference evaluator" (ONNX without
            onnxruntime) or "torch.jit.load"; "" where it was not checked.
    """

    path: str
    format: str
    metadata: dict[str, str]
    difference: ActionDifference | None
    checker: str = ""

    def line(self) -> str:
        """The one-line summary ``ocean-warp export-policy`` prints."""
        meta = self.metadata
        check = "not checked" if self.difference is None else (f"{self.checker} reproduces the torch policy to "
                                                               f"{self.difference.text()}")
        kind = f"ONNX opset {OPSET}" if self.format == "onnx" else "TorchScript"
        return (f"wrote {self.path}: {kind}, the {meta['task']} policy (observation {meta['observation']!r}, "
                f"{meta['num_obs']} values -> {meta['num_actions']} actions, normalisation "
                f"{meta['observation_normalisation']}); {check}")


def observation_layout(task: str, observation: str, num_obs: int) -> list[str]:
    """What each of the ``num_obs`` observation values of a policy for ``task`` is, with scaling and units
    (``"name: scale [unit]"``, from ``ocean_warp.envs.tasks.observation_blocks``): the observation set's
    values, then those the task appends (its reef level, its lidar's sectors), as far as the task's default
    config says; values it cannot name are "value k (...)"."""
    config = _default_task_config(task)
    if getattr(config, "vessel", None) is not None:  # one of VRX's tasks: its block and the vessel's actions
        from ..vrx.observation_blocks import vrx_policy_layout

        layout = [column.text() for column in vrx_policy_layout(config)]
        if len(layout) == num_obs:
            return layout
    block = SET_BLOCKS.get(observation)
    if block is None or num_obs < len(block):
        return [f"value {k} (observation set {observation!r}: not described here)" for k in range(num_obs)]
    return [column.text() for column in block.columns] + _appended_layout(task, len(block), num_obs - len(block))


def _appended_layout(task: str, first: int, count: int) -> list[str]:
    """The ``count`` values a task appends to its observation set, from index ``first``: its reef level (a task
    with a reef rule), then its lidar's sectors, where the task's default config appends ``count`` values; the
    lidar's sectors alone where ``count`` is theirs (a policy trained before the task's reef rule)."""
    if count == 0:
        return []
    config = _default_task_config(task)
    reef, lidar = (reef_block(config), lidar_block(config)) if config is not None else ((), ())
    if count == len(reef) + len(lidar):
        columns = reef.columns + lidar.columns
    elif count == len(lidar):
        columns = lidar.columns
    else:
        return [f"value {first + k} (appended by {task}: not described here)" for k in range(count)]
    return [column.text() for column in columns]


def action_meaning(task: str) -> list[str]:
    """What each action commands, once clipped to [-1, 1]: the E-Boat's three (``task_configs``' module docstring),
    or the vessel's of one of VRX's tasks (``Vessel.actions``)."""
    config = _default_task_config(task)
    if getattr(config, "vessel", None) is not None:
        return [f"a{k} {spec.name}: {spec.meaning}" for k, spec in enumerate(config.vessel.actions)]
    propeller = ("a0 propeller level int(5 a0), truncated toward zero: -5 to +5"
                 + ("" if config is None or config.propeller else f" (ignored: {task} sails without propeller)"))
    return [propeller, "a1 sheet: the largest boom angle either side, (a1 + 1) 45 deg",
            "a2 rudder angle: 60 deg a2, positive turns to port"]


@functools.lru_cache(maxsize=None)
def _default_task_config(task: str):
    """The default config of ``task``, or None where it is not a registered task id."""
    from ocean_warp.envs.registration import make_task_config

    try:
        return make_task_config(task)
    except ValueError:
        return None


def policy_metadata(policy: Policy, source: str | os.PathLike | None = None) -> dict[str, str]:
    """The metadata an exported file carries (string to string; lists as JSON), for ``policy`` read from the
    checkpoint ``source`` (None: not from a file)."""
    normaliser = policy.actor.obs_normalizer
    num_actions = policy(torch.zeros(1, policy.num_obs)).shape[1]
    metadata = {
        "format": EXPORT_FORMAT, "checkpoint_format": CHECKPOINT_FORMAT, "task": policy.task,
        "observation": policy.observation, "num_obs": str(policy.num_obs), "num_actions": str(num_actions),
        "input": f"{INPUT_NAME}: float32 (batch, {policy.num_obs}), the raw observation",
        "output": f"{OUTPUT_NAME}: float32 (batch, {num_actions}), {ACTION_NOTE}",
        "observation_normalisation": (f"inside: (x - mean) / (std + {normaliser.eps:g})" if hasattr(normaliser, "eps")
                                      else "none"),
        "actions": json.dumps(action_meaning(policy.task)),
        "observation_layout": json.dumps(observation_layout(policy.task, policy.observation, policy.num_obs)),
    }
    if source is not None:
        metadata["source"] = os.path.basename(os.fspath(source))
        metadata["source_sha256"] = _sha256(source)
    decode_metadata(metadata)  # what the runner will read back must decode
    return metadata


def _sha256(path: str | os.PathLike) -> str:
    with open(path, "rb") as stream:
        return hashlib.sha256(stream.read()).hexdigest()


def _policy_and_source(policy: Policy | str | os.PathLike,
                       source: str | os.PathLike | None) -> tuple[Policy, str | None]:
    """A loaded policy (on the CPU, in eval mode) and the checkpoint it came from: ``policy`` where it is a
    path, else ``source``."""
    if isinstance(policy, Policy):
        return policy.to("cpu").eval(), source
    return load_policy(policy), os.fspath(policy)


def check_observations(policy: Policy, count: int = CHECK_OBSERVATIONS, seed: int = 0) -> np.ndarray:
    """(count, num_obs) float32 observations spread as the policy saw them in training: its normaliser's
    mean + std z, z standard normal (z itself where the policy has no normaliser). The same for the same
    ``seed``."""
    z = np.random.default_rng(seed).standard_normal((count, policy.num_obs))
    normaliser = policy.actor.obs_normalizer
    if not hasattr(normaliser, "mean"):
        return z.astype(np.float32)
    return (normaliser.mean.cpu().numpy() + normaliser.std.cpu().numpy() * z).astype(np.float32)


def _difference(policy: Policy, run) -> ActionDifference:
    """The file's actions against the torch policy's on :func:`check_observations`; ``run`` maps a float32
    numpy batch to the file's numpy actions."""
    observations = check_observations(policy)
    expected = policy(torch.from_numpy(observations)).numpy()
    return ActionDifference.between(expected, run(observations))


def _checked(summary: ExportSummary) -> ExportSummary:
    """``summary``, or ExportError where the file does not reproduce the policy to TOLERANCE."""
    difference = summary.difference
    if difference is not None and not difference.within():
        raise ExportError(f"the exported {summary.format} policy differs from the torch policy by "
                          f"{difference.text()}, more than {TOLERANCE:g}; nothing written")
    return summary


@contextlib.contextmanager
def _quiet_exporter():
    """Silence the exporters' deprecation notes (torch.jit is deprecated in torch 2.13, yet TorchScript is what
    libtorch loads) and log lines (torchvision not installed, ...); errors pass."""
    logger = logging.getLogger("torch.onnx")
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", (DeprecationWarning, FutureWarning, UserWarning))
            yield
    finally:
        logger.setLevel(level)


def _require_onnx():
    """The onnx module, or ImportError saying how to install it."""
    try:
        import onnx
    except ImportError:
        raise ImportError(f"ONNX export needs the onnx package: {INSTALL_HINT}") from None
    return onnx


def _uses_dynamo_exporter() -> bool:
    """Whether torch.onnx.export's default, torch.export-based exporter can run here (it needs onnxscript);
    otherwise the TorchScript-based one is used (same graph for these networks)."""
    return importlib.util.find_spec("onnxscript") is not None


def _onnx_model(policy: Policy):
    """The policy's actor, observation normaliser and mean as an onnx ModelProto with a dynamic batch."""
    onnx = _require_onnx()
    module = policy.actor.as_onnx(verbose=False).eval()
    example = (torch.zeros(2, policy.num_obs),)
    names = {"input_names": [INPUT_NAME], "output_names": [OUTPUT_NAME], "opset_version": OPSET}
    with _quiet_exporter():
        if _uses_dynamo_exporter():
            program = torch.onnx.export(module, example, dynamo=True, verbose=False, **names,
                                        dynamic_shapes=({0: torch.export.Dim("batch")},))
            return program.model_proto
        buffer = io.BytesIO()
        torch.onnx.export(module, example, buffer, dynamo=False, **names,
                          dynamic_axes={INPUT_NAME: {0: "batch"}, OUTPUT_NAME: {0: "batch"}})
    return onnx.load_from_string(buffer.getvalue())


def export_onnx(policy: Policy | str | os.PathLike, out: str | os.PathLike, *, source: str | os.PathLike | None = None,
                check: bool = True) -> ExportSummary:
    """Write ``policy`` (a Policy or a checkpoint file) to ``out`` as ONNX, atomically.

    Args:
        policy: the policy, or the path of its checkpoint (``ocean_warp.policy/1``).
        out: the ``.onnx`` file to write (its folder is made).
        source: the checkpoint a Policy given as ``policy`` was read from, named in the metadata (a path given
            as ``policy`` is its own source).
        check: run the file with onnxruntime (without it: onnx's reference evaluator, numpy's
            implementation of every operator, independent of torch) before it replaces ``out``, and refuse it
            unless it reproduces the torch policy's actions to TOLERANCE.

    Raises:
        ImportError: the onnx package is missing (the message says how to install it).
        CheckpointError: ``policy`` is a file that is not a usable policy checkpoint.
        ExportError: the file does not reproduce the policy (nothing is written).
    """
    onnx = _require_onnx()
    policy, source = _policy_and_source(policy, source)
    metadata = policy_metadata(policy, source)
    model = _onnx_model(policy)
    onnx.helper.set_model_props(model, metadata)
    model.doc_string = f"ocean_warp policy for {policy.task}: raw observation -> actions ({ACTION_NOTE})"
    onnx.checker.check_model(model)
    with atomic_output(out, suffix=".onnx") as temporary:
        onnx.save_model(model, temporary)
        difference, checker = None, ""
        if check:
            checker, run = _onnx_runner(temporary)
            difference = _difference(policy, run)
        summary = _checked(ExportSummary(os.fspath(out), "onnx", metadata, difference, checker))
    return summary


def _onnx_runner(path: str):
    """(name, run) for the check of the ONNX file at ``path``: onnxruntime, what the boat runs, where it
    imports; else onnx's reference evaluator (slow, but these networks are small)."""
    try:
        import onnxruntime  # noqa: F401 - only whether it imports
    except ImportError:
        from onnx.reference import ReferenceEvaluator

        evaluator = ReferenceEvaluator(path)
        return "onnx's reference evaluator", lambda observations: evaluator.run(None, {INPUT_NAME: observations})[0]
    return "onnxruntime", OnnxPolicy(path).act


def export_torchscript(policy: Policy | str | os.PathLike, out: str | os.PathLike, *,
                       source: str | os.PathLike | None = None, check: bool = True) -> ExportSummary:
    """Write ``policy`` (a Policy or a checkpoint file) to ``out`` as a TorchScript archive, atomically; its
    metadata is the extra file TORCHSCRIPT_METADATA (:func:`read_torchscript_metadata`).

    Args:
        policy: the policy, or the path of its checkpoint (``ocean_warp.policy/1``).
        out: the ``.pt`` file to write (its folder is made).
        source: the checkpoint a Policy given as ``policy`` was read from, named in the metadata (a path given
            as ``policy`` is its own source).
        check: load the file back with torch.jit.load before it replaces ``out``, and refuse it unless it
            reproduces the torch policy's actions to TOLERANCE.

    Raises:
        CheckpointError: ``policy`` is a file that is not a usable policy checkpoint.
        ExportError: the file does not reproduce the policy (nothing is written).
    """
    policy, source = _policy_and_source(policy, source)
    metadata = policy_metadata(policy, source)
    exportable = policy.actor.as_jit().eval().requires_grad_(False)  # acting needs no gradients
    with _quiet_exporter(), atomic_output(out, suffix=".pt") as temporary:
        archive = io.BytesIO()  # saved through memory, the archive's folder is "archive", not the temporary's name
        torch.jit.save(torch.jit.script(exportable), archive, _extra_files={TORCHSCRIPT_METADATA: json.dumps(metadata)})
        with open(temporary, "wb") as stream:
            stream.write(archive.getvalue())
        difference = None
        if check:
            loaded = torch.jit.load(temporary, map_location="cpu")
            difference = _difference(policy, lambda batch: loaded(torch.from_numpy(batch)).numpy())
        summary = _checked(ExportSummary(os.fspath(out), "torchscript", metadata, difference, "torch.jit.load"))
    return summary


def read_torchscript_metadata(path: str | os.PathLike) -> dict[str, object]:
    """The metadata of an exported TorchScript policy, decoded as ``ocean_warp.ros.onnx_policy.decode_metadata``
    does (counts as ints, lists as tuples).

    Raises:
        ValueError: not a TorchScript archive, or not an exported ocean_warp policy.
    """
    files = {TORCHSCRIPT_METADATA: ""}
    try:
        with _quiet_exporter():
            torch.jit.load(os.fspath(path), map_location="cpu", _extra_files=files)
        entries = json.loads(files[TORCHSCRIPT_METADATA] or "{}")
    except (RuntimeError, ValueError) as error:
        first_line = (str(error).strip().splitlines() or [type(error).__name__])[0]
        raise ValueError(f"{os.fspath(path)!r} is not an exported TorchScript policy: {first_line}") from None
    return decode_metadata(entries)


EXPORTERS = {"onnx": export_onnx, "torchscript": export_torchscript}


def _export_format(parser: argparse.ArgumentParser, args: argparse.Namespace) -> str:
    """--format, checked against --out's suffix, or the format --out's suffix names."""
    check_options(parser, [("--format", args.format, args.format in (None, *FORMATS), "onnx or torchscript")])
    suffix = None if args.out is None else os.path.splitext(args.out)[1].lower()
    if args.format is None:
        named = [name for name, ending in FORMATS.items() if ending == suffix]
        if args.out is not None and not named:
            fail(parser, f"--out must end in .onnx (ONNX) or .pt (TorchScript), got {args.out!r}")
        return named[0] if named else "onnx"
    if suffix is not None and suffix != FORMATS[args.format]:
        fail(parser, f"--out must end in {FORMATS[args.format]} for --format {args.format}, got {args.out!r}")
    return args.format


def _checkpoint_path(parser: argparse.ArgumentParser, args: argparse.Namespace) -> str:
    """--policy, or the shipped policy of --task (or of DEFAULT_TASK)."""
    if args.policy is not None:
        return args.policy
    from ocean_warp.envs.training.policies import shipped_policy_path

    try:
        return os.fspath(shipped_policy_path(args.task or DEFAULT_TASK))
    except (ValueError, FileNotFoundError) as error:
        fail(parser, f"--task: {error}")


def _out_path(parser: argparse.ArgumentParser, args: argparse.Namespace, checkpoint: str, form: str) -> str:
    """--out, or OUT_FOLDER/<checkpoint name> with the format's suffix, checked before anything runs (the
    folder is made when the file is written)."""
    out = args.out
    if out is None:
        stem = os.path.splitext(os.path.basename(checkpoint))[0]
        out = os.path.join(OUT_FOLDER, stem + (".onnx" if form == "onnx" else ".torchscript.pt"))
    return checked_output_file(parser, out, "--out")


def main(argv=None) -> int:
    """``ocean-warp export-policy [options]``: returns 0 once the file is written and checked; bad options,
    files that are not policies and a missing onnx package exit with status 2, an export that does not
    reproduce the policy with status 1."""
    parser = _parser()
    args = parser.parse_args(argv)
    form = _export_format(parser, args)
    if form == "onnx" and importlib.util.find_spec("onnx") is None:
        fail(parser, f"--format onnx needs the onnx package: {INSTALL_HINT}")
    checkpoint = _checkpoint_path(parser, args)
    out = _out_path(parser, args, checkpoint, form)
    if is_torchscript_archive(checkpoint):
        fail(parser, f"--policy {checkpoint}: a TorchScript archive (an exported policy?), not a policy checkpoint "
                     f"({CHECKPOINT_FORMAT}); export from the checkpoint it came from")
    try:
        policy = load_policy(checkpoint, task=args.task if args.policy is not None else None)
    except CheckpointError as error:
        fail(parser, str(error))
    try:
        summary = EXPORTERS[form](policy, out, source=checkpoint)
    except ExportError as error:
        print(f"{parser.prog}: {error}", file=sys.stderr)
        return 1
    print(summary.line())
    return 0


if __name__ == "__main__":
    sys.exit(main())
