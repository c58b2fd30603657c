"""``bladefem report``: a Markdown and HTML report with the model summary, frequencies, pictures and Campbell."""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from ..errors import InputError
from .export import add_planform_option, read_drawn_blade
from .inputs import add_blade_options, apply_deck_settings, finite_float, positive_int, rpm_range


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    report = subparsers.add_parser(
        "report", help="an inspection report (Markdown and HTML with images)",
        description="Model summary (mass, first and second mass moments, provenance), frequency table, mode "
                    "pictures, Campbell diagram with crossings, and ElastoDyn mode-shape coefficients.")
    add_blade_options(report)
    add_planform_option(report)
    report.add_argument("-o", "--output", required=True, metavar="DIR", help="output directory")
    report.add_argument("--rpm", type=finite_float, metavar="RPM",
                        help="operating rotor speed, rpm (frequency table, pictures, coefficients; default: a BModes "
                             "deck's rot_rpm x rpm_mult, else 0)")
    report.add_argument("--sweep", type=rpm_range, metavar="START:STOP:COUNT",
                        help="Campbell sweep, rpm (default 0 to 1.25 x RPM, or 0 to 15 rpm, 16 speeds)")
    report.add_argument("--n-modes", type=positive_int, default=6, metavar="N", help="modes (default 6)")
    report.add_argument("--no-pictures", action="store_true", help="leave out the 3-D mode pictures")
    report.add_argument("--quiet", action="store_true", help="no progress bar")
    report.set_defaults(run=run_report)


def default_sweep(rpm: float) -> np.ndarray:
    top = math.ceil(1.25 * rpm) if rpm > 0 else 15.0
    return np.linspace(0.0, top, 16)


def run_report(args: argparse.Namespace) -> int:
    from ..report import write_report

    apply_deck_settings(args)
    if args.rpm < 0:
        raise InputError(f"must not be negative, got {args.rpm}", field="--rpm")
    blade = read_drawn_blade(args)
    speeds = args.sweep if args.sweep is not None else default_sweep(args.rpm)
    if len(speeds) < 2:
        raise InputError("a Campbell sweep needs at least two rotor speeds", field="--sweep")
    written = write_report(blade, args.output, args.rpm, speeds, args.n_modes, args.elements,
                           pictures=not args.no_pictures, quiet=args.quiet)
    print(written.markdown)
    print(written.html)
    if not args.quiet:
        print(f"report written to {args.output}", file=sys.stderr)
    return 0
