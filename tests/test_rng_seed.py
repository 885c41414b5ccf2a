"""The ``rng`` fixture's seeds replay: a tiny test file run in a pytest subprocess with tests/rng_seed.py as its
only plugin draws the same numbers for the same base seed (option or environment variable, any selection of
tests) and different ones for fresh seeds; the header and a failing test print how to replay."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TINY = '''
def test_first(rng):
    print("DRAW first", rng.integers(2**62, size=3).tolist())

def test_second(rng):
    print("DRAW second", rng.integers(2**62, size=3).tolist())

def test_fails(rng):
    print("DRAW fails", rng.integers(2**62, size=3).tolist())
    assert False
'''


def _run(folder: Path, *args: str, seed_variable: str | None = None) -> tuple[int, str, dict[str, list[int]]]:
    env = {key: value for key, value in os.environ.items() if key != "OCEAN_WARP_TEST_SEED"}
    env["PYTHONPATH"] = str(ROOT)
    if seed_variable is not None:
        env["OCEAN_WARP_TEST_SEED"] = seed_variable
    done = subprocess.run([sys.executable, "-m", "pytest", "-p", "tests.rng_seed", "-p", "no:cacheprovider", "-s",
                           "--rootdir", str(folder), "-c", str(folder / "pytest.ini"), *args], cwd=folder, env=env,
                          capture_output=True, text=True, timeout=300)
    draws = {name: eval(numbers) for name, numbers in re.findall(r"DRAW (\w+) (\[[\d, ]+\])", done.stdout)}
    return done.returncode, done.stdout + done.stderr, draws


def _folder(tmp_path: Path) -> Path:
    (tmp_path / "pytest.ini").write_text("[pytest]\n")
    (tmp_path / "test_tiny.py").write_text(TINY)
    return tmp_path


def test_a_base_seed_replays_every_draw_and_fresh_seeds_differ(tmp_path):
    folder = _folder(tmp_path)
    code, output, by_option = _run(folder, "--rng-seed", "123", "test_tiny.py")
    assert code == 1 and sorted(by_option) == ["fails", "first", "second"]
    assert "rng base seed: 123 (--rng-seed)" in output
    assert "replay: pytest --rng-seed 123 'test_tiny.py::test_fails'" in output
    assert "--rng-seed 123 'test_tiny.py::test_first'" not in output  # only failures say it
    assert len({tuple(numbers) for numbers in by_option.values()}) == 3  # each test its own numbers

    assert _run(folder, "--rng-seed", "123", "test_tiny.py")[2] == by_option
    assert _run(folder, "test_tiny.py", seed_variable="123")[2] == by_option
    # the replay line of one failing test, run alone, draws what it drew in the whole file
    assert _run(folder, "--rng-seed", "123", "test_tiny.py::test_fails")[2] == {"fails": by_option["fails"]}

    code, output, fresh = _run(folder, "test_tiny.py")
    base = re.search(r"rng base seed: (\d+) \(fresh\)", output).group(1)
    assert fresh != by_option and fresh != _run(folder, "test_tiny.py")[2]
    assert _run(folder, "--rng-seed", base, "test_tiny.py")[2] == fresh


def test_a_bad_seed_is_one_usage_error(tmp_path):
    folder = _folder(tmp_path)
    code, output, draws = _run(folder, "test_tiny.py", seed_variable="twelve")
    assert code == 4 and not draws
    assert "OCEAN_WARP_TEST_SEED must be an integer from 0 to 2**64 - 1, got 'twelve'" in output
    code, output, _ = _run(folder, "--rng-seed", "-1", "test_tiny.py")
    assert code == 4 and "--rng-seed must be an integer from 0 to 2**64 - 1, got '-1'" in output
