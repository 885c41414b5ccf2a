"""Policy checkpoints: writing them atomically, reading them safely, and a policy to act with.

A checkpoint is a dict saved with ``torch.save`` and read back with ``torch.load(weights_only=True)``
(tensors, numbers, strings, lists and dicts only: a file from elsewhere cannot run code). Keys:

    format          "ocean_warp.policy/1"
    task            the task id the policy is for ("EBoatMission-v0", ...)
    observation     the observation set it reads ("seed" or "plus")
    num_obs         policy observation size
    num_actions     3
    actor_config    {"hidden_dims": [...], "activation": ..., "obs_normalization": bool,
                     "distribution_cfg": {...}}: how to rebuild rsl-rl's actor
    actor_state_dict
    critic_state_dict, optimizer_state_dict, critic_config, iteration, torch_rng_state, curriculum,
    train_config: present in training checkpoints (``--resume``), absent from exported policies.
"""

from __future__ import annotations

import os
import pickle
import re
import zipfile
from collections.abc import Mapping
from typing import Any

import torch
from tensordict import TensorDict

from ocean_warp.atomic_files import atomic_output

__all__ = ["CHECKPOINT_FORMAT", "CheckpointError", "Policy", "save_checkpoint", "read_checkpoint", "load_policy",
           "export_policy", "is_torchscript_archive", "other_task_note"]

CHECKPOINT_FORMAT = "ocean_warp.policy/1"
_ZIP_MAGIC = b"PK\x03\x04"
"""How a file written by ``torch.save`` begins (a zip archive)."""
_POLICY_KEYS = ("task", "observation", "num_obs", "num_actions", "actor_config", "actor_state_dict")


class CheckpointError(ValueError):
    """A checkpoint file that cannot be used: missing, truncated, not ours, or for another setting."""


def save_checkpoint(path: str | os.PathLike, checkpoint: Mapping[str, Any]) -> None:
    """Write ``checkpoint`` to ``path`` atomically (a temporary file beside it, then one rename)."""
    with atomic_output(path, suffix=".pt") as temporary:
        torch.save(dict(checkpoint, format=CHECKPOINT_FORMAT), temporary)


def read_checkpoint(path: str | os.PathLike, *, map_location: str | torch.device = "cpu") -> dict[str, Any]:
    """The checkpoint dict in ``path``, checked to be an ocean_warp policy checkpoint.

    Raises:
        CheckpointError: the file is missing, is not a readable torch file (truncated, corrupt, or holding
            objects other than tensors and plain data), or is not an ocean_warp policy checkpoint.
    """
    path = os.fspath(path)
    if os.path.isdir(path):
        raise CheckpointError(f"checkpoint {path!r} is a folder, not an ocean_warp policy checkpoint file")
    if not os.path.isfile(path):
        raise CheckpointError(f"checkpoint {path!r}: no such file")
    with open(path, "rb") as stream:
        start = stream.read(len(_ZIP_MAGIC))
    if start != _ZIP_MAGIC:
        raise CheckpointError(f"checkpoint {path!r} is not an ocean_warp policy checkpoint: not a file written by "
                              "torch.save (text, another format, or damaged at its start)")
    if is_torchscript_archive(path):
        raise CheckpointError(f"checkpoint {path!r} is a TorchScript export (for libtorch, made by ocean-warp "
                              "export-policy), not a policy checkpoint: pass the checkpoint ocean-warp train writes "
                              "(policy.pt or model_<it>.pt in its run folder)")
    try:
        data = torch.load(path, map_location=map_location, weights_only=True)
    except pickle.UnpicklingError as error:
        # torch's message advises ways to load what it refused (weights_only=False, allow-listing), which would
        # run or build whatever the file names: never repeated here, only the name of what it refused.
        refused = re.search(r"Unsupported global: GLOBAL ([\w.]+)", str(error))
        what = refused.group(1) if refused else "objects"
        raise CheckpointError(f"checkpoint {path!r} is not an ocean_warp policy checkpoint: it holds {what}, not "
                              "only tensors and plain data, and such files are never loaded") from None
    except Exception:  # noqa: BLE001 - torch's restricted unpickler raises anything (IndexError, KeyError, ...)
        raise CheckpointError(f"checkpoint {path!r} is not an ocean_warp policy checkpoint: it could not be read as "
                              "a torch file (truncated or corrupt)") from None
    if not isinstance(data, dict):
        raise CheckpointError(f"checkpoint {path!r} holds a {type(data).__name__}, not an ocean_warp policy "
                              "checkpoint (a dict)")
    found = data.get("format")
    if found != CHECKPOINT_FORMAT:
        what = "no 'format' key" if found is None else f"format {found!r}"
        raise CheckpointError(f"checkpoint {path!r} is not an ocean_warp policy checkpoint ({what}; expected "
                              f"{CHECKPOINT_FORMAT!r}); rsl-rl's own model_*.pt files are not read here")
    missing = [key for key in _POLICY_KEYS if key not in data]
    if missing:
        raise CheckpointError(f"checkpoint {path!r} lacks {', '.join(missing)}")
    return data


def is_torchscript_archive(path: str | os.PathLike) -> bool:
    """Whether ``path`` is a TorchScript archive (a zip holding code/ and constants.pkl), which torch.load
    would refuse with a warning and a misleading error."""
    try:
        with zipfile.ZipFile(path) as archive:
            return any(name.endswith("/constants.pkl") for name in archive.namelist())
    except (OSError, zipfile.BadZipFile):
        return False


def other_task_note(policy: "Policy", task: str) -> str | None:
    """None where ``policy`` was trained on ``task`` (a task id, with or without "ocean_warp/"); else what
    to tell a user who sails it there (its observation may fit, but it learnt another task)."""
    trained = policy.task.removeprefix("ocean_warp/")
    if trained == task.removeprefix("ocean_warp/"):
        return None
    task = task.removeprefix("ocean_warp/")
    return (f"the policy was trained on {trained}, not on {task}; its results here show how it transfers, not "
            f"what training on {task} gives")


class Policy(torch.nn.Module):
    """A trained actor that maps observations (N, P) to actions (N, 3), deterministically (the mean of
    rsl-rl's Gaussian, not clipped: the environment clips actions to [-1, 1]).

    Attributes:
        task: the task id it was trained for.
        observation: the observation set it reads ("seed" or "plus").
        num_obs: P.
    """

    def __init__(self, actor: torch.nn.Module, *, task: str, observation: str, num_obs: int):
        super().__init__()
        self.actor = actor
        self.task = task
        self.observation = observation
        self.num_obs = int(num_obs)

    @torch.no_grad()
    def forward(self, observations: torch.Tensor) -> torch.Tensor:
        if observations.ndim != 2 or observations.shape[1] != self.num_obs:
            raise ValueError(f"Policy for {self.task}: observations must have shape (N, {self.num_obs}), got "
                             f"{tuple(observations.shape)}")
        return self.actor(TensorDict({"policy": observations}, batch_size=[observations.shape[0]]))


def build_actor(num_obs: int, num_actions: int, actor_config: Mapping[str, Any], device="cpu") -> torch.nn.Module:
    """rsl-rl's MLPModel for a policy observation of ``num_obs`` values, as the trainer builds it."""
    from rsl_rl.models import MLPModel

    dummy = TensorDict({"policy": torch.zeros(1, num_obs)}, batch_size=[1])
    config = {key: value for key, value in actor_config.items() if key != "class_name"}
    return MLPModel(dummy, {"actor": ["policy"]}, "actor", num_actions, **config).to(device)


def load_policy(path: str | os.PathLike, *, device: str | torch.device = "cpu", task: str | None = None) -> Policy:
    """The policy in a checkpoint (a training checkpoint or an exported one), on ``device``, in eval mode.

    Args:
        path: the checkpoint file.
        device: torch device to run it on.
        task: if given, the task id the policy must be for.

    Raises:
        CheckpointError: unreadable or foreign file, a policy for another task, or weights that do not fit
            the network the checkpoint describes.
    """
    data = read_checkpoint(path)
    if task is not None and data["task"].removeprefix("ocean_warp/") != task.removeprefix("ocean_warp/"):
        raise CheckpointError(f"checkpoint {os.fspath(path)!r} holds a policy for {data['task']}, not {task}")
    try:
        actor = build_actor(int(data["num_obs"]), int(data["num_actions"]), data["actor_config"])
        actor.load_state_dict(data["actor_state_dict"])
    except (RuntimeError, TypeError, ValueError, KeyError) as error:
        first_line = str(error).strip().splitlines()[0]
        raise CheckpointError(f"checkpoint {os.fspath(path)!r}: its weights do not fit the network it describes "
                              f"({data['actor_config']}): {first_line}") from None
    policy = Policy(actor, task=data["task"], observation=data["observation"], num_obs=int(data["num_obs"]))
    return policy.to(device).eval()


def export_policy(checkpoint: Mapping[str, Any], path: str | os.PathLike) -> None:
    """Write only what acting needs (the actor and what describes it: kilobytes) to ``path``."""
    save_checkpoint(path, {key: checkpoint[key] for key in _POLICY_KEYS})
