"""The ``bladefem`` command line: ``modes``, ``campbell`` and the other subcommands.

User mistakes (bad files, bad option values) print one line naming file, line and field and exit with code 2.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from typing import NoReturn

from ..errors import InputError
from . import batch, blade, check, elastodyn, export, report, turbine, verify


class Parser(argparse.ArgumentParser):
    """argparse with one-line errors and exit code 2."""

    def error(self, message: str) -> NoReturn:
        print(f"{self.prog}: error: {message}", file=sys.stderr)
        raise SystemExit(2)


def build_parser() -> Parser:
    parser = Parser(prog="bladefem", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"bladefem {_version()}")
    subparsers = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for module in SUBCOMMANDS:
        module.add_parser(subparsers)
    return parser


def _version() -> str:
    from .. import __version__
    return __version__


SUBCOMMANDS = [blade, verify, elastodyn, export, report, turbine, check, batch]


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``bladefem`` console script; returns the exit code."""
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exit:         # --help, --version, or a usage error already printed on one line
        return int(exit.code or 0)
    try:
        return int(args.run(args) or 0)
    except InputError as error:
        print(f"bladefem: error: {error}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        return 0
    except OSError as error:           # e.g. an output folder that cannot be created
        where = f"{error.filename}: " if error.filename else ""
        print(f"bladefem: error: {where}{error.strerror or error}", file=sys.stderr)
        return 2

