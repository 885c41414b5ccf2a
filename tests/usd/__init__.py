"""Tests of ``ocean_warp.usd``."""
