"""Tests of ``ocean_warp.envs.interfaces``."""
