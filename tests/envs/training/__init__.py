"""Tests of ``ocean_warp.envs.training``."""
