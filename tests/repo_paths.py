"""Where the tests find the repository's files."""

from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
"""The repository's root folder (the one holding pyproject.toml)."""
BENCHMARK_DATA = REPO / "benchmarks" / "data"
"""Tables the benchmarks measured or computed (independent references, e.g. the VPP's)."""
