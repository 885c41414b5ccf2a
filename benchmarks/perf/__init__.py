"""Performance runs: how fast the ocean, the hull, the E-Boat step, the environments, sharding, USD recording
and multi-GPU training are, against the torch/numpy references where there is one (``timing`` holds the
shared timers). Run from the repository root: ``python -m benchmarks.perf.<name> --help``."""
