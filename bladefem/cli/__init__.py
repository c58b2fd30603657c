"""The ``bladefem`` command line: ``modes``, ``campbell`` and the other subcommands.

User mistakes (bad files, bad option values) print one line naming file, line and field and exit with code 2.
Start-up stays fast: only the module of the subcommand being run is imported (``bladefem --help`` imports none),
and each module imports its numerical libraries inside the function that runs it.
"""

from __future__ import annotations

import argparse
import atexit
import importlib
import os
import sys
import threading
import warnings
from collections.abc import Sequence
from types import ModuleType
from typing import NoReturn

from ..errors import InputError, SolveError
from ..files import note_input, recording_inputs

__all__ = ["COMMANDS", "Parser", "build_parser", "entry", "main"]

#: LLVM optimization level of the kernels numba compiles in a ``bladefem`` process (``NUMBA_OPT``, unless the user
#: set it): a cold first ``turbine --simulate 20`` compiles in 13.8-14.5 s wall at 1 against 15.7-15.9 s at numba's
#: default 3, the warm runs as fast (100 s simulated: 3.7-3.8 s against 3.8 s; ROSCO 5.0-5.2 s against 5.1 s) and the
#: tables the same to the bit (no fast-math: LLVM may not reorder floating-point operations at either level)
NUMBA_OPTIMIZATION = "1"

#: argparse names of the input files given on the command line (outputs may not name them)
INPUT_ARGUMENTS = ("input", "main", "spec", "elastodyn_main", "plan", "nrel5mw", "schedule", "aero", "aerodyn")

#: subcommand -> (module in bladefem.cli that adds it, one-line help shown by ``bladefem --help``)
COMMANDS: dict[str, tuple[str, str]] = {
    "modes": ("blade", "natural frequencies and mode shapes of a blade or tower"),
    "campbell": ("blade", "Campbell diagram (blade) or soft-stiff chart (tower) over rotor speed"),
    "verify": ("verify", "self-check: FE, Galerkin and closed-form references (exit 1 on a broken bound)"),
    "elastodyn": ("elastodyn", "ElastoDyn mode-shape coefficients (fit, quality, check, in-place update)"),
    "export": ("export", "write mode shapes for inspection: VTK (ParaView), PNG pictures, animated GIFs"),
    "report": ("report", "an inspection report (Markdown and HTML with images)"),
    "flutter": ("flutter", "blade flutter: damping of each mode over rotor or wind speed (unsteady aerodynamics)"),
    "turbine": ("turbine", "16-DOF Kane turbine model (ElastoDyn structure) fed by bladefem modes"),
    "standstill": ("standstill", "stall-induced vibration of a parked blade: mode damping against wind direction"),
    "check": ("check", "design checks for CI: frequency windows, resonance margins, soft-stiff band, baselines"),
    "batch": ("batch", "run a plan of cases (grid, Monte Carlo, files) on Dask; results in Parquet"),
    "batch-summary": ("batch", "statistics and sensitivities of batch results"),
    "batch-loads": ("loads", "damage-equivalent and extreme loads of a DLC 1.2 batch"),
}


class Parser(argparse.ArgumentParser):
    """argparse with one-line errors and exit code 2."""

    def error(self, message: str) -> NoReturn:
        print(f"{self.prog}: error: {message}", file=sys.stderr)
        raise SystemExit(2)


def command_module(command: str) -> ModuleType:
    """The ``bladefem.cli`` module that adds and runs ``command``."""
    return importlib.import_module(f".{COMMANDS[command][0]}", __name__)


def build_parser(command: str | None = None) -> Parser:
    """The parser with every subcommand complete (``command`` None), or with only ``command`` complete and the
    others as names with their help (what :func:`main` uses, so that only one module is imported)."""
    parser = Parser(prog="bladefem", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"bladefem {_version()}")
    subparsers = parser.add_subparsers(dest="command", required=True, parser_class=Parser, metavar="COMMAND")
    wanted = list(COMMANDS) if command is None else [command] if command in COMMANDS else []
    for name in wanted:
        if name not in subparsers.choices:       # a module may add several commands
            command_module(name).add_parser(subparsers)
    for name, (_, help_text) in COMMANDS.items():
        if name not in subparsers.choices:
            subparsers.add_parser(name, help=help_text, add_help=False)
    return parser


def _version() -> str:
    from .. import __version__
    return __version__


def subcommand(argv: Sequence[str]) -> str:
    """The subcommand named in ``argv`` ('' if none): its first argument that is not an option."""
    return next((word for word in argv if not word.startswith("-")), "")


def one_line_warning(message: Warning | str, category: type[Warning], filename: str, lineno: int,
                     file: object = None, line: str | None = None) -> None:
    """A warning as one line on stderr, ``bladefem: warning: ...`` (not Python's file and source line)."""
    print(f"bladefem: warning: {message}", file=sys.stderr)


def follow_openfast_deck(args: argparse.Namespace) -> None:
    """An OpenFAST deck (.fst) given as the INPUT of a blade or tower command stands for its ElastoDyn main file
    (``EDFile``), said on stderr; ``turbine`` reads the whole deck itself."""
    from pathlib import Path

    path = getattr(args, "input", None)
    if not isinstance(path, str) or not Path(path).is_file():
        return
    if Path(path).suffix.lower() != ".fst":
        with open(path, encoding="utf-8", errors="replace") as stream:
            words = {word for _, line in zip(range(200), stream) for word in line.split()[:3]}
        if not {"CompElast", "EDFile"} <= words:
            return
    from ..formats._labels import Labels
    labels = Labels.read(path)
    main_file = labels.existing_file("EDFile")
    print(f"# OpenFAST deck {path}: its ElastoDyn main file {main_file} (EDFile, line {labels.line('EDFile')})",
          file=sys.stderr)
    args.input = str(main_file)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``bladefem`` console script; returns the exit code."""
    argv = list(sys.argv[1:] if argv is None else argv)
    command = subcommand(argv)
    try:
        args = build_parser(command).parse_args(argv)
    except SystemExit as exit:         # --help, --version, or a usage error already printed on one line
        return int(exit.code or 0)
    try:
        with warnings.catch_warnings(), recording_inputs():
            warnings.showwarning = one_line_warning
            for name in INPUT_ARGUMENTS:
                if isinstance(getattr(args, name, None), str):
                    note_input(getattr(args, name))
            follow_openfast_deck(args)
            return int(args.run(args) or 0)
    except InputError as error:
        print(f"bladefem: error: {error}", file=sys.stderr)
        return 2
    except SolveError as error:        # the input read, but the answer would not be a result
        source = getattr(args, "input", None) or getattr(args, "main", None)
        print(f"bladefem: error: {source + ': ' if source else ''}{error}", file=sys.stderr)
        return 1
    except BrokenPipeError:
        return 0
    except KeyboardInterrupt:
        print("bladefem: interrupted (Ctrl-C)", file=sys.stderr)
        return 130
    except SystemError as error:       # Ctrl-C that landed inside a compiled (numba) call
        if not isinstance(error.__cause__ or error.__context__, KeyboardInterrupt):
            raise
        print("bladefem: interrupted (Ctrl-C)", file=sys.stderr)
        return 130
    except OSError as error:           # e.g. an output folder that cannot be created
        where = f"{error.filename}: " if error.filename else ""
        print(f"bladefem: error: {where}{error.strerror or error}", file=sys.stderr)
        return 2


def entry() -> NoReturn:
    """The ``bladefem`` console script and ``python -m bladefem``: numba's optimization level set
    (:data:`NUMBA_OPTIMIZATION`, before numba is imported), :func:`main`, then the process ends without
    tearing the interpreter down where that loses nothing (one thread left; the exit handlers run, the standard
    streams flushed, every output already written and closed by the command). Freeing numba's compiled code and
    the modules' objects took 1.1 s of a cold ``turbine --simulate`` and 0.3 s of a warm one (``bench/bench_startup.py
    --exit``); with other threads still running the interpreter ends as usual (it waits for them)."""
    os.environ.setdefault("NUMBA_OPT", NUMBA_OPTIMIZATION)
    code = main()
    run_exit_handlers = getattr(atexit, "_run_exitfuncs", None)
    if threading.active_count() > 1 or run_exit_handlers is None:
        raise SystemExit(code)
    run_exit_handlers()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):                  # a closed pipe (``| head``): nothing more can be shown
            pass
    os._exit(code)
