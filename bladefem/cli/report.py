"""``bladefem report``: a Markdown and HTML report of a blade or tower with the model summary, frequencies,
pictures, the Campbell diagram (blade) or rotor-speed chart (tower), and where it came from."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

from ..errors import InputError
from .export import add_planform_option, read_drawn_structure
from . import options
from .inputs import add_blade_options, is_blade, positive_int, rpm_band


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    report = subparsers.add_parser(
        "report", help="an inspection report (Markdown and HTML with images)",
        description="Provenance (bladefem version, date, input files with their SHA-256), model summary (mass, "
                    "first and second mass moments), frequency table, mode pictures, Campbell diagram with "
                    "crossings (blade) or the tower's frequencies against the rotor's 1P and blade-passing bands "
                    "(tower), and ElastoDyn mode-shape coefficients.")
    add_blade_options(report)
    add_planform_option(report)
    report.add_argument("-o", "--output", required=True, metavar="DIR", help="output directory")
    report.add_argument("--rpm", type=options.rpm, default=0.0, metavar="RPM",
                        help="blades: operating rotor speed, rpm (frequency table, pictures, coefficients; "
                             "default 0)")
    report.add_argument("--sweep", type=options.rpm_sweep, metavar="START:STOP:COUNT",
                        help="Campbell sweep, rpm (default 0 to 1.25 x RPM, or 0 to 15 rpm, 16 speeds)")
    report.add_argument("--operating-rpm", type=rpm_band, metavar="LOW:HIGH",
                        help="towers: the rotor's operating range for the 1P and blade-passing bands, rpm "
                             "(default the sweep)")
    report.add_argument("--blades", type=positive_int, default=3, metavar="N",
                        help="towers: number of blades (default 3)")
    report.add_argument("--n-modes", type=options.n_modes, default=6, metavar="N", help="modes (default 6)")
    report.add_argument("--no-pictures", action="store_true", help="leave out the 3-D mode pictures")
    report.add_argument("--quiet", action="store_true", help="no progress bar")
    report.set_defaults(run=run_report)


def default_sweep(rpm: float) -> tuple[float, ...]:
    top = math.ceil(1.25 * rpm) if rpm > 0 else 15.0
    return tuple(top * k / 15 for k in range(16))


def input_files(args: argparse.Namespace, source: str) -> list[str]:
    """INPUT, the other files named on the command line and the section data's file, each once."""
    named = [args.input, args.elastodyn_main, args.aerodyn, source]
    found: list[str] = []
    for name in named:
        if name and Path(name).is_file() and all(Path(name).resolve() != Path(f).resolve() for f in found):
            found.append(str(name))
    return found


def run_report(args: argparse.Namespace) -> int:
    from ..report import write_report

    if args.rpm < 0:
        raise InputError(f"must not be negative, got {args.rpm}", field="--rpm")
    speeds = args.sweep if args.sweep is not None else default_sweep(args.rpm)
    options.check_sweep(speeds, args.n_modes, args.elements, "--sweep")
    options.check_folder(args.output)
    model = read_drawn_structure(args)
    if not is_blade(model) and args.rpm != 0:
        raise InputError("a tower does not rotate: give the rotor's range with --operating-rpm LOW:HIGH",
                         field="--rpm")
    if len(speeds) < 2:
        raise InputError("a Campbell sweep needs at least two rotor speeds", field="--sweep")
    written = write_report(model, args.output, args.rpm, speeds, args.n_modes, args.elements,
                           pictures=not args.no_pictures, quiet=args.quiet,
                           inputs=input_files(args, model.sections.source), operating_rpm=args.operating_rpm,
                           blades=args.blades)
    for path in (written.markdown, written.html, *written.images):
        print(path)
    if not args.quiet:
        print(f"report written to {args.output}", file=sys.stderr)
    return 0
