"""Replayable random seeds for the tests' ``rng`` fixture (a pytest plugin; tests/conftest.py loads it).

One base seed per session: ``pytest --rng-seed N``, else the environment variable ``OCEAN_WARP_TEST_SEED``,
else a fresh one. Each test's seed is derived from the base and the test's node id, so the same base gives
every test the same numbers whichever tests run, in whatever order. The base is printed in pytest's header,
and a failing test that drew from ``rng`` prints the line that replays it:
``replay: pytest --rng-seed N 'tests/...::test_x[cpu]'``.
"""

from __future__ import annotations

import hashlib
import os

import numpy as np
import pytest

ENVIRONMENT_VARIABLE = "OCEAN_WARP_TEST_SEED"
_BASE = pytest.StashKey[int]()
_SOURCE = pytest.StashKey[str]()


def _seed(text: str, where: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = -1
    if not 0 <= value < 2**64:
        raise pytest.UsageError(f"{where} must be an integer from 0 to 2**64 - 1, got {text!r}")
    return value


def pytest_addoption(parser):
    parser.addoption("--rng-seed", action="store", default=None, metavar="N",
                     help=f"base seed of the tests' rng fixture (default: ${ENVIRONMENT_VARIABLE}, else fresh); "
                          "each test's seed derives from it and the test's node id.")


def pytest_configure(config):
    option, variable = config.getoption("--rng-seed"), os.environ.get(ENVIRONMENT_VARIABLE, "").strip()
    if option is not None:
        config.stash[_BASE], config.stash[_SOURCE] = _seed(option, "--rng-seed"), "--rng-seed"
    elif variable:
        config.stash[_BASE], config.stash[_SOURCE] = _seed(variable, ENVIRONMENT_VARIABLE), ENVIRONMENT_VARIABLE
    else:
        config.stash[_BASE] = int(np.random.SeedSequence().generate_state(1, np.uint64)[0])
        config.stash[_SOURCE] = "fresh"


def pytest_report_header(config):
    base = config.stash[_BASE]
    return f"rng base seed: {base} ({config.stash[_SOURCE]}); replay every test's draws: pytest --rng-seed {base}"


def derived_seed(base: int, nodeid: str) -> np.random.SeedSequence:
    """The seed of the test ``nodeid`` in a session of base seed ``base``."""
    node = int.from_bytes(hashlib.sha256(nodeid.encode()).digest()[:8], "little")
    return np.random.SeedSequence([base, node])



@pytest.fixture
def rng(request):
    """A numpy Generator seeded from the session's base seed and this test's node id."""
    return np.random.default_rng(derived_seed(request.config.stash[_BASE], request.node.nodeid))


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if report.failed and "rng" in getattr(item, "fixturenames", ()):
        report.sections.append(("rng seed", f"replay: pytest --rng-seed {item.config.stash[_BASE]} '{item.nodeid}'"))
