"""What every ``ocean-warp <job>`` shares: its parser (usage ``ocean-warp <job>``, each option's default in
the help), one-line errors with exit status 2, option checks, the ``--device`` option, and counts in words.

A bad option, value or input file is one line on stderr, ``ocean-warp <job>: error: <what is wrong>``, as
argparse writes its own errors, and exit status 2; no usage, no traceback. (A job that fails while it runs
says ``ocean-warp <job>: <what failed>`` and exits with status 1.)
"""

from __future__ import annotations

import argparse
import ast
import importlib.util
import math
import os
import re
import sys
import tempfile
from typing import NoReturn

from .devices import DEVICE_FORMS, resolve_device

__all__ = ["COMMAND", "HelpFormatter", "RawDescriptionHelpFormatter", "JobArgumentParser", "job_parser",
           "error_text", "fail",
           "report_error", "option_problem", "check_options", "finite_at_least",
           "finite_above", "add_device_argument", "checked_device", "made_folder", "checked_output_folder",
           "checked_output_file", "plain_text", "module_docstring", "plural"]

COMMAND = "ocean-warp"
"""The command's name, as its usage lines say it."""


class HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """argparse's help with each option's default, "(default: X)", left out where it says nothing: a default
    of None, an empty list (a repeatable option's) or a flag's (store_true), or a help text that already names
    the default."""

    def _get_help_string(self, action):
        text = action.help or ""
        default = action.default
        says_nothing = default is None or default is argparse.SUPPRESS or (isinstance(default, (list, tuple))
                                                                           and not default)
        if says_nothing or action.nargs == 0 or "default" in text:
            return text
        return super()._get_help_string(action)

    def _fill_text(self, text, width, indent):
        if text.startswith(EXAMPLES_HEADING):  # the examples epilog: one command a line, as written
            return "".join(indent + line for line in text.splitlines(keepends=True))
        return super()._fill_text(text, width, indent)


EXAMPLES_HEADING = "examples:\n"
"""How a job's help epilog of example commands begins."""


class RawDescriptionHelpFormatter(HelpFormatter, argparse.RawDescriptionHelpFormatter):
    """:class:`HelpFormatter` that prints the description and epilog as written (their line breaks kept)."""


def job_parser(job: str, description: str, *, long_help_from: str | None = None,
               examples: tuple[str, ...] = ()) -> argparse.ArgumentParser:
    """The parser of ``ocean-warp <job>``: usage ``ocean-warp <job> [options]``, ``description`` (a few
    sentences) above the options, defaults in the help, ``examples`` (command lines) below them.
    ``long_help_from``: the module whose docstring ``--help-long`` prints as plain text (read from its source,
    not imported: Warp and torch stay unloaded)."""
    epilog = EXAMPLES_HEADING + "".join(f"  {line}\n" for line in examples) if examples else None
    parser = JobArgumentParser(prog=f"{COMMAND} {job}", description=description, epilog=epilog,
                               formatter_class=HelpFormatter)
    if long_help_from is not None:
        parser.add_argument("--help-long", action=_LongHelp, module=long_help_from,
                            help="show the long description (what the job does and writes, in detail) and exit")
    return parser


class JobArgumentParser(argparse.ArgumentParser):
    """argparse's parser whose errors (an unknown option, a value of the wrong type) are one line,
    ``<prog>: error: <message>``, and exit status 2, without the usage lines."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, error_text(self.prog, message) + "\n")


class _LongHelp(argparse.Action):
    """``--help-long``: print a module's docstring as plain text and exit 0."""

    def __init__(self, option_strings, dest, module: str, help=None):
        super().__init__(option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, nargs=0, help=help)
        self.module = module

    def __call__(self, parser, namespace, values, option_string=None):
        print(plain_text(module_docstring(self.module)).rstrip())  # on stdout, as --help
        parser.exit(0)


def module_docstring(name: str) -> str:
    """The docstring of the module ``name``, read from its source file without importing it."""
    spec = importlib.util.find_spec(name)
    with open(spec.origin, encoding="utf-8") as source:
        return ast.get_docstring(ast.parse(source.read()), clean=True) or ""


_ROLE = re.compile(r":[a-z]+:`~?([^`<]*?)(?:\s*<[^>]*>)?`")
"""An RST role, :class:`Name` or :func:`~a.b`: its text kept."""
_LITERAL = re.compile(r"``([^`]+)``")
"""An RST literal, ``code``: its text kept."""


def plain_text(text: str) -> str:
    """``text`` (a docstring in RST) as plain text: roles and literals become their bare text."""
    return _LITERAL.sub(r"\1", _ROLE.sub(r"\1", text))


def error_text(prog: str, message: str) -> str:
    """A job's error line: ``<prog>: error: <message>`` (``prog`` "ocean-warp <job>")."""
    return f"{prog}: error: {message}"


def fail(parser: argparse.ArgumentParser, message: str) -> NoReturn:
    """Exit with status 2 and the error line on stderr (no usage, no traceback)."""
    parser.exit(2, error_text(parser.prog, message) + "\n")


def report_error(prog: str, message: str) -> int:
    """Write the error line to stderr and return 2, for a job whose ``main`` returns its exit status."""
    print(error_text(prog, message), file=sys.stderr)
    return 2


def option_problem(checks) -> str | None:
    """The first of ``checks`` that fails, in words: "<option> must be <must>, got <value>"; None when none does.

    Args:
        checks: (option, value, valid, must) tuples, e.g. ("--runs", 0, False, "a whole number >= 1").
    """
    for option, value, valid, must in checks:
        if not valid:
            return f"{option} must be {must}, got {value}"
    return None


def check_options(parser: argparse.ArgumentParser, checks) -> None:
    """:func:`fail` with the first of ``checks`` that fails (:func:`option_problem`), if one does."""
    problem = option_problem(checks)
    if problem is not None:
        fail(parser, problem)


def finite_at_least(value, low: float) -> bool:
    """Whether ``value`` is a finite number >= ``low`` (NaN and inf are not)."""
    return value is not None and math.isfinite(value) and value >= low


def finite_above(value, low: float) -> bool:
    """Whether ``value`` is a finite number > ``low`` (NaN and inf are not)."""
    return value is not None and math.isfinite(value) and value > low


def add_device_argument(parser: argparse.ArgumentParser) -> None:
    """``--device``: a Warp device, by default "auto" (:func:`checked_device` resolves it)."""
    parser.add_argument("--device", default="auto", help=f"Warp device: {DEVICE_FORMS} (default: auto)")


def checked_device(parser: argparse.ArgumentParser, device: str | None) -> str:
    """``device`` (``--device``'s value) resolved and checked, "auto" (or None) as Warp's preferred device
    (:func:`ocean_warp.devices.resolve_device`: the one place every job resolves it), or :func:`fail` with
    why it cannot be used."""
    try:
        return resolve_device(device, name="--device")
    except ValueError as error:
        fail(parser, str(error))


def made_folder(parser: argparse.ArgumentParser, folder: str, option: str = "--out") -> str:
    """``folder`` (``option``'s value) made if it is not there yet, or :func:`fail` with why it cannot be."""
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as error:
        fail(parser, f"{option} {folder}: {error.strerror or error}")
    return folder


def _writable_problem(folder: str) -> str | None:
    """Why nothing can be written into ``folder``, or under it once its missing parts are made; None when
    something can. Checked by making and removing a temporary file in the deepest folder that exists (nothing
    is made where the check fails, and nothing is left behind)."""
    existing = os.path.abspath(folder)
    while not os.path.exists(existing):
        existing = os.path.dirname(existing)
    if not os.path.isdir(existing):
        return f"{existing} is a file, not a folder"
    try:
        with tempfile.NamedTemporaryFile(dir=existing, prefix=".ocean-warp-check-"):
            pass
    except OSError as error:
        return f"cannot write in {existing} ({error.strerror or error})"
    return None


def checked_output_folder(parser: argparse.ArgumentParser, folder: str, option: str = "--out") -> str:
    """``folder`` (``option``'s value), a folder a job writes into, checked before the work starts: an
    existing file there, a file in its path or a folder that cannot be written in is :func:`fail` with one
    line naming ``option`` and ``folder``. Nothing is made."""
    problem = ("is a file, not a folder" if os.path.exists(folder) and not os.path.isdir(folder)
               else _writable_problem(folder))
    if problem is not None:
        fail(parser, f"{option} {folder}: {problem}")
    return folder


def checked_output_file(parser: argparse.ArgumentParser, path: str, option: str = "--out",
                        suffixes: tuple[str, ...] = ()) -> str:
    """``path`` (``option``'s value), a file a job writes, checked before the work starts: a folder there, a
    suffix not among ``suffixes`` (any where empty), a file in its folder's path or a folder that cannot be
    written in is :func:`fail` with one line naming ``option`` and ``path``. Nothing is made."""
    if os.path.isdir(path):
        fail(parser, f"{option} {path}: is a folder, not a file"
                     + (f"; give a name ending in {' or '.join(suffixes)}" if suffixes else ""))
    if suffixes and not path.lower().endswith(tuple(suffix.lower() for suffix in suffixes)):
        fail(parser, f"{option} {path}: must end in {' or '.join(suffixes)}")
    problem = _writable_problem(os.path.dirname(os.path.abspath(path)))
    if problem is not None:
        fail(parser, f"{option} {path}: {problem}")
    return path


def plural(count: int, noun: str, plural_form: str | None = None) -> str:
    """``count`` and ``noun`` in words: "1 run", "20 runs" (``plural_form`` where adding "s" is wrong)."""
    return f"{count} {noun if count == 1 else plural_form or noun + 's'}"
