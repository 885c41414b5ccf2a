"""Policies shipped with ocean_warp: exported checkpoints (``ocean_warp.envs.training.policy_io``) beside this file."""

from __future__ import annotations

import pathlib

from ...task_specs import TASK_SPECS

__all__ = ["SHIPPED_POLICIES", "shipped_policy_path"]

SHIPPED_POLICIES = {spec.id: spec.policy_file for spec in TASK_SPECS if spec.policy_file is not None}
"""Task id -> file name of its shipped policy, in this package's folder (``task_specs.TASK_SPECS``)."""


def shipped_policy_path(task_id: str) -> pathlib.Path:
    """The path of the policy shipped for ``task_id`` (a key of ``SHIPPED_POLICIES``, optionally prefixed
    "ocean_warp/").

    Raises:
        ValueError: no policy is shipped for that task.
        FileNotFoundError: the policy is known but its file is not there (not trained and exported yet).
    """
    name = str(task_id).removeprefix("ocean_warp/")
    if name not in SHIPPED_POLICIES:
        raise ValueError(f"no policy is shipped for task {task_id!r}; shipped: {', '.join(SHIPPED_POLICIES)}")
    path = pathlib.Path(__file__).resolve().parent / SHIPPED_POLICIES[name]
    if not path.is_file():
        raise FileNotFoundError(f"the shipped policy for {name} is not there yet: {path} (train and export one, "
                                "or pass a checkpoint with --policy)")
    return path
