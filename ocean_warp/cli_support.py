"""What every ``ocean-warp <job>`` shares: its parser (usage ``ocean-warp <job>``, each option's default in
the help), one-line errors with exit status 2, option checks, the ``--device`` option, and counts in words.

A bad option, value or input file is one line on stderr, ``ocean-warp <job>: error: <what is wrong>``, as
argparse writes its own errors, and exit status 2; no usage, no traceback. (A job that fails while it runs
says ``ocean-warp <job>: <what failed>`` and exits with status 1.)
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from typing import NoReturn

from .devices import DEVICE_FORMS, resolve_device

__all__ = ["COMMAND", "HelpFormatter", "RawDescriptionHelpFormatter", "job_parser", "error_text", "fail",
           "report_error", "option_problem", "check_options", "finite_at_least",
           "finite_above", "add_device_argument", "checked_device", "made_folder", "plural"]

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


class RawDescriptionHelpFormatter(HelpFormatter, argparse.RawDescriptionHelpFormatter):
    """:class:`HelpFormatter` that prints the description as written (a module docstring with its layout)."""


def job_parser(job: str, description: str, *, raw_description: bool = False) -> argparse.ArgumentParser:
    """The parser of ``ocean-warp <job>``: usage ``ocean-warp <job> [options]``, defaults in the help;
    ``raw_description`` keeps the description's line breaks (a module docstring)."""
    formatter = RawDescriptionHelpFormatter if raw_description else HelpFormatter
    return argparse.ArgumentParser(prog=f"{COMMAND} {job}", description=description, formatter_class=formatter)


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


def add_device_argument(parser: argparse.ArgumentParser, default: str | None = "cpu") -> None:
    """``--device``: a Warp device; None as ``default`` means Warp's preferred one (a GPU where there is one)."""
    where = "Warp's preferred device: cuda:0 where there is a GPU, else cpu" if default is None else default
    parser.add_argument("--device", default=default, help=f"Warp device: {DEVICE_FORMS} (default: {where})")


def checked_device(parser: argparse.ArgumentParser, device: str | None) -> str:
    """``device`` (``--device``'s value) resolved and checked (:func:`ocean_warp.devices.resolve_device`), or
    :func:`fail` with why it cannot be used."""
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


def plural(count: int, noun: str, plural_form: str | None = None) -> str:
    """``count`` and ``noun`` in words: "1 run", "20 runs" (``plural_form`` where adding "s" is wrong)."""
    return f"{count} {noun if count == 1 else plural_form or noun + 's'}"
