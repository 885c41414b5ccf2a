"""README.md's examples work as written.

Every ```python block runs in a fresh Python process, in an empty folder, on the CPU (Warp is shown no GPU),
and everything it writes lands under ``out/`` (the project's convention). A block that cannot run (a
cluster command, say) is marked on the line before its fence with ``<!-- not run: <why> -->``; the counts
of run and marked blocks are pinned, so a block that vanishes or loses its language is noticed.

Of the ```bash blocks, what is cheap to check is checked: every ``ocean-warp <job>`` they name exists, and
every ``--option`` given to a job appears in that job's ``--help``.
"""

from __future__ import annotations

import ast
import dataclasses
import importlib.util
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

from tests.repo_paths import REPO

README = REPO / "README.md"

PYTHON_BLOCKS_RUN = 10
"""How many ```python blocks the README has that run (not marked ``not run``)."""
PYTHON_BLOCKS_NOT_RUN = 0
"""How many are marked ``<!-- not run: ... -->``."""

HANG_GUARD_S = 600
"""Only against a hang: every block runs in seconds to tens of seconds on two CPU cores."""

OPTIONAL_MODULES = {
    "pxr": "usd-core",
    "stable_baselines3": 'the sb3 extra (pip install -e ".[sb3]")',
    "imageio_ffmpeg": 'the video extra (pip install -e ".[video]")',
    "onnxruntime": 'the onnx extra (pip install -e ".[onnx]")',
    "mcap_ros2": 'the mcap extra (pip install -e ".[mcap]")',
}
"""Modules a block may need that a plain install can lack: the block is skipped without them."""
NEEDS_BEHIND_IMPORTS = {"ocean_warp.usd": "pxr"}
"""Imports of ours that need an optional module."""

NOT_RUN = re.compile(r"^<!--\s*not run:\s*(?P<why>.+?)\s*-->\s*$")
FENCE = re.compile(r"^```(?P<language>\S*)\s*$")


@dataclasses.dataclass(frozen=True)
class Block:
    language: str
    code: str
    line: int
    """Line of README.md that opens the fence (1-based)."""
    not_run: str | None
    """Why it is not run, from the marker on the line before the fence; None: it runs."""


def readme_blocks(text: str) -> list[Block]:
    """The fenced code blocks of a Markdown text, in order."""
    lines = text.splitlines()
    blocks, start, language = [], None, ""
    for number, line in enumerate(lines, start=1):
        fence = FENCE.match(line)
        if not fence:
            continue
        if start is None:
            start, language = number, fence["language"]
            continue
        marker = NOT_RUN.match(lines[start - 2]) if start >= 2 else None
        blocks.append(Block(language, "\n".join(lines[start:number - 1]) + "\n", start,
                            marker["why"] if marker else None))
        start = None
    assert start is None, f"README.md: the code fence opened on line {start} is never closed"
    return blocks


BLOCKS = readme_blocks(README.read_text(encoding="utf-8"))
PYTHON = [b for b in BLOCKS if b.language == "python" and b.not_run is None]
BASH = [b for b in BLOCKS if b.language == "bash"]


def test_the_readme_has_the_python_blocks_it_had():
    assert len(PYTHON) == PYTHON_BLOCKS_RUN
    assert sum(b.language == "python" and b.not_run is not None for b in BLOCKS) == PYTHON_BLOCKS_NOT_RUN


def test_block_parsing_on_a_known_text():
    text = "a\n```python\nx = 1\n```\n<!-- not run: a cluster -->\n```bash\nls\n\nls -l\n```\n```\nplain\n```\n"
    assert readme_blocks(text) == [Block("python", "x = 1\n", 2, None), Block("bash", "ls\n\nls -l\n", 6, "a cluster"),
                                   Block("", "plain\n", 11, None)]


def _imported_modules(code: str) -> set[str]:
    modules = set()
    for node in ast.walk(ast.parse(code)):
        if isinstance(node, ast.Import):
            modules.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            modules.add(node.module)
    return modules


def _missing_optional_module(code: str) -> str | None:
    needed = set()
    for module in _imported_modules(code):
        needed.add(module.split(".")[0])
        needed.update(need for ours, need in NEEDS_BEHIND_IMPORTS.items()
                      if module == ours or module.startswith(ours + "."))
    for module in sorted(needed & OPTIONAL_MODULES.keys()):
        if importlib.util.find_spec(module) is None:
            return f"{module} is missing: {OPTIONAL_MODULES[module]}"
    return None


def _cpu_environment() -> dict[str, str]:
    environment = dict(os.environ)
    environment["CUDA_VISIBLE_DEVICES"] = ""  # the blocks pick "cpu" where Warp sees no GPU: as on CI
    return environment


@pytest.mark.parametrize("block", PYTHON, ids=[f"line{b.line}" for b in PYTHON])
def test_python_block_runs_as_written(block, tmp_path):
    missing = _missing_optional_module(block.code)
    if missing:
        pytest.skip(f"README.md line {block.line}: {missing}")
    script, workdir = tmp_path / "block.py", tmp_path / "work"
    script.write_text(block.code, encoding="utf-8")
    workdir.mkdir()
    result = subprocess.run([sys.executable, str(script)], cwd=workdir, env=_cpu_environment(), capture_output=True,
                            text=True, timeout=HANG_GUARD_S)
    assert result.returncode == 0, (f"README.md's python block at line {block.line} failed:\n{result.stdout[-3000:]}"
                                    f"\n{result.stderr[-6000:]}")
    assert {p.name for p in workdir.iterdir()} <= {"out"}, "a README example wrote outside out/"


@dataclasses.dataclass(frozen=True)
class Command:
    job: str
    """The ocean-warp job ("" for ``ocean-warp`` itself)."""
    options: tuple[str, ...]
    line: int


def _segments(code: str):
    """(line, shell words) of each simple command of a bash text: continuations joined, comments dropped,
    split at ``&&``, ``||``, ``;``, ``|`` and ``&``."""
    for number, text in _logical_lines(code):
        words = shlex.split(text, comments=True)
        segment = []
        for word in words + [";"]:
            if word in ("&&", "||", ";", "|", "&"):
                if segment:
                    yield number, segment
                segment = []
            else:
                segment.append(word)


def _logical_lines(code: str):
    """(first line, text) of each line of a bash text, backslash continuations joined."""
    pending, first = "", None
    for number, text in enumerate(code.splitlines(), start=1):
        first = number if first is None else first
        if text.endswith("\\"):
            pending += text[:-1] + " "
            continue
        yield first, pending + text
        pending, first = "", None


TORCHRUN_MODULE = "ocean_warp.envs.training.train"
"""The module torchrun starts once per rank (``ocean-warp train`` as a module)."""


def ocean_warp_commands(code: str, block_line: int = 0) -> list[Command]:
    """The ``ocean-warp`` (and ``python -m ocean_warp.envs.training.train``) commands of a bash text, with the
    options each gives its job."""
    commands = []
    for number, words in _segments(code):
        if words[0] == "ocean-warp":
            rest = words[1:]
            job = "" if not rest or rest[0].startswith("-") else rest.pop(0)
        elif "-m" in words and TORCHRUN_MODULE in words[words.index("-m") + 1:words.index("-m") + 2]:
            job, rest = "train", words[words.index("-m") + 2:]
        else:
            continue
        options = tuple(word.split("=")[0] for word in rest if word.startswith("--"))
        commands.append(Command(job, options, block_line + number))
    return commands


def test_command_parsing_on_a_known_text():
    text = ("python3 -m venv .venv && . .venv/bin/activate && ocean-warp demo\n"
            "ocean-warp train --task X --set a=b   # --not-an-option\n"
            "torchrun --nnodes=2 \\\n    -m ocean_warp.envs.training.train --device=cuda --minutes 10\n"
            "roscore &\nocean-warp --version\n")
    assert ocean_warp_commands(text, 10) == [Command("demo", (), 11), Command("train", ("--task", "--set"), 12),
                                             Command("train", ("--device", "--minutes"), 13),
                                             Command("", ("--version",), 16)]


COMMANDS = [command for block in BASH for command in ocean_warp_commands(block.code, block.line)]


def _ocean_warp() -> list[str]:
    """The installed ``ocean-warp`` command of this Python (its module where no script was installed)."""
    script = Path(sys.executable).with_name("ocean-warp")
    return [str(script)] if script.is_file() else [sys.executable, "-m", "ocean_warp.cli"]


def _help_options(job: str) -> set[str] | None:
    """The options ``ocean-warp <job> --help`` names; None where the job does not exist."""
    result = subprocess.run([*_ocean_warp(), *([job] if job else []), "--help"],
                            env=_cpu_environment(), capture_output=True, text=True, timeout=HANG_GUARD_S)
    if result.returncode != 0:
        return None
    return set(re.findall(r"(?<![\w-])--[a-z0-9][a-z0-9-]*", result.stdout))


def test_the_bash_blocks_name_jobs_and_options_that_exist():
    assert len(COMMANDS) >= 20, "the README's bash blocks lost their ocean-warp commands (or the parser broke)"
    jobs = sorted({command.job for command in COMMANDS})
    helps = {job: _help_options(job) for job in jobs}
    wrong = []
    for command in COMMANDS:
        known = helps[command.job]
        if known is None:
            wrong.append(f"line {command.line}: no job `ocean-warp {command.job}`")
            continue
        for option in command.options:
            if option not in known:
                wrong.append(f"line {command.line}: `ocean-warp {command.job}` has no {option}")
    assert not wrong, "README.md's bash blocks:\n" + "\n".join(wrong)
