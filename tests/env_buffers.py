"""Comparing two environments' buffers, as several tests do."""

from __future__ import annotations

import dataclasses

import torch

from ocean_warp.envs import EnvBuffers


def assert_same_buffers(actual, expected, when: str) -> None:
    """Every field of two :class:`EnvBuffers` equal bit for bit, NaN where the other has NaN (``final_score``
    of a task without a score); ``when`` names the moment in the message."""
    for field in dataclasses.fields(EnvBuffers):
        torch.testing.assert_close(getattr(actual, field.name), getattr(expected, field.name), rtol=0, atol=0,
                                   equal_nan=True, msg=f"{field.name} {when}")
