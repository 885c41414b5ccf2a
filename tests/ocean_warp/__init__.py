"""Tests of ``ocean_warp``."""
