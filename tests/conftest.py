"""Test devices and replayable random numbers.

Every test that takes ``device`` runs on "cpu" and, where Warp sees a GPU, on "cuda:0" too.
``pytest --device cpu`` (or ``cuda``) restricts the run to one of them.
The ``rng`` fixture draws from a per-session base seed (``--rng-seed N`` or ``$OCEAN_WARP_TEST_SEED`` to replay
one; tests/rng_seed.py).
"""

import logging

import pytest
import torch
import warp as wp

from tests import rng_seed
from tests.rng_seed import pytest_configure, pytest_report_header, pytest_runtest_makereport, rng  # noqa: F401

wp.config.log_level = logging.WARNING  # no module-load chatter in test logs
wp.init()


def pytest_addoption(parser):
    rng_seed.pytest_addoption(parser)
    parser.addoption(
        "--device",
        action="store",
        default="all",
        choices=("all", "cpu", "cuda"),
        help="Warp device(s) to test on: cpu, cuda, or all available (default).",
    )


def _devices(choice: str) -> list[str]:
    has_cuda = wp.get_cuda_device_count() > 0
    if choice == "cpu":
        return ["cpu"]
    if choice == "cuda":
        return ["cuda:0"] if has_cuda else []
    return ["cpu"] + (["cuda:0"] if has_cuda else [])


def pytest_generate_tests(metafunc):
    if "device" in metafunc.fixturenames:
        devices = _devices(metafunc.config.getoption("--device"))
        if not devices:
            pytest.skip("no CUDA device for --device cuda")
        metafunc.parametrize("device", devices)


@pytest.fixture
def one_torch_thread():
    """Tiny networks train fastest on one thread, and two threads contend with Warp on a 2-core CI box;
    one thread also makes CPU training bit-reproducible."""
    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    yield
    torch.set_num_threads(threads)
