"""The random streams' tags: no two streams share one (two streams with one tag and one seed draw the same
numbers where their counters and indices meet: the lidar's noise and the sailing tasks' starts did, and so did
the reef draw and the obstacle layouts), and no module keeps a tag of its own outside ``kernels/random_streams``.
"""

import ast
import pathlib

from ocean_warp.kernels import random_streams

ROOT = pathlib.Path(__file__).resolve().parents[2]
SOURCES = ("kernels", "ocean_warp", "envs")


def test_every_tag_is_distinct_and_fits_31_bits():
    tags = random_streams.STREAM_TAGS
    assert len(tags) >= 13
    assert len(set(tags.values())) == len(tags), f"two streams share a tag: {tags}"
    assert all(0 < value < 2**31 for value in tags.values())


def _hex_constants(tree: ast.AST) -> list[tuple[str, int]]:
    """Module-level ``NAME = wp.constant(0x...)`` assignments: (name, value)."""
    found = []
    for node in tree.body:
        if not (isinstance(node, ast.Assign) and isinstance(node.value, ast.Call) and node.value.args):
            continue
        call, argument = node.value, node.value.args[0]
        if getattr(call.func, "attr", None) == "constant" and isinstance(argument, ast.Constant) \
                and isinstance(argument.value, int) and argument.value > 0xFFFF:
            found.extend((target.id, argument.value) for target in node.targets if isinstance(target, ast.Name))
    return found


def test_no_module_keeps_a_stream_tag_of_its_own():
    """A large hexadecimal Warp constant outside ``random_streams`` that a module passes to ``stream_state`` is a
    tag kept apart from the others; the walk finds the registry's own."""
    own = {}
    elsewhere = []
    for folder in SOURCES:
        for path in sorted((ROOT / folder).rglob("*.py")):
            source = path.read_text(encoding="utf-8")
            for name, value in _hex_constants(ast.parse(source)):
                if path.name == "random_streams.py":
                    own[name] = value
                elif "stream_state" in source:
                    elsewhere.append((str(path.relative_to(ROOT)), name))
    assert own == random_streams.STREAM_TAGS
    assert not elsewhere, f"stream tags outside kernels/random_streams.py: {elsewhere}"


def test_the_walk_finds_a_planted_tag():
    planted = "import warp as wp\nTAG = wp.constant(0x1234_5678)\nSMALL = wp.constant(3)\n"
    assert _hex_constants(ast.parse(planted)) == [("TAG", 0x12345678)]
