"""Tests of ``ocean_warp.kernels``."""
