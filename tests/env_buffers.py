"""Comparing two environments' buffers, as several tests do."""

from __future__ import annotations

import dataclasses

import torch

from ocean_warp.envs import EnvBuffers


def assert_same_buffers(actual, expected, when: str) -> None:
    """Every field of two :class:`EnvBuffers` equal bit for bit (NaN equal to NaN: a score the task does not keep);
    ``when`` names the moment in the message."""
    for field in dataclasses.fields(EnvBuffers):
        torch.testing.assert_close(getattr(actual, field.name), getattr(expected, field.name), rtol=0, atol=0,
                                   equal_nan=True, msg=f"{field.name} {when}")


def bit_equal(a: torch.Tensor, b: torch.Tensor) -> bool:
    """Equal shapes and values, NaN equal to NaN (a score a task does not keep is NaN in both)."""
    return a.shape == b.shape and a.dtype == b.dtype and bool(torch.equal(a, b) or (
        a.is_floating_point() and torch.equal(torch.isnan(a), torch.isnan(b))
        and torch.equal(torch.nan_to_num(a, nan=0.0), torch.nan_to_num(b, nan=0.0))))


def sail_in_lockstep(single, other, generator: torch.Generator, steps: int, reset_step: int, reset_seed: int) -> int:
    """Step two batched envs of the same task and seed with the same random actions in [-1, 1) for ``steps``
    decisions, both re-seeded (``reset(seed=reset_seed)``) before decision ``reset_step``, asserting every buffer
    bit for bit after each; returns the episodes ``single`` ended (same-step resets crossed)."""
    resets = 0
    for step in range(steps):
        if step == reset_step:
            single.reset(seed=reset_seed)
            other.reset(seed=reset_seed)
        actions = 2.0 * torch.rand(single.num_envs, single.num_actions, generator=generator) - 1.0
        single.step(actions)
        other.step(actions)
        resets += int(single.buffers.done.sum())
        for field in dataclasses.fields(EnvBuffers):
            assert bit_equal(getattr(single.buffers, field.name), getattr(other.buffers, field.name)), \
                (step, field.name)
    return resets
