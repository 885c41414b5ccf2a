"""Tests of ``ocean_warp.envs.tasks``."""
