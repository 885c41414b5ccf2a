"""Tests of ``ocean_warp.envs.parallel``."""
