"""Tests of ``ocean_warp.eboat``."""
