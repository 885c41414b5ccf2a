"""ocean_warp's benchmarks, run from the repository root as modules (``python -m benchmarks.<group>.<name>``):

- ``perf``: performance runs (the ocean, the hull, the E-Boat step, the environments, sharding, USD, GPUs);
- ``references``: implementations written independently of the code under test, that the runs race and
  the tests check against;
- ``studies``: one question each, answered with a table or figure for RESULTS.md.

``data/`` holds the tables they write, ``figures/`` the figures, RESULTS.md what was measured.
"""

from pathlib import Path

BENCHMARKS = Path(__file__).resolve().parent
"""This folder."""
REPO = BENCHMARKS.parent
"""The repository's root."""
DATA = BENCHMARKS / "data"
"""Tables the benchmarks write and read [csv, json]."""
FIGURES = BENCHMARKS / "figures"
"""Figures for RESULTS.md and the README [png]."""
