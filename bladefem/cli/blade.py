"""``bladefem modes`` and ``bladefem campbell``."""

from __future__ import annotations

import argparse
import sys

from ..errors import InputError
from ..io.results import campbell_to_dict, dumps, modal_to_dict
from ..modal import blade_matrices, campbell_sweep, solve_modes
from ..modal.results import ModalResult
from ..report import progress_bar
from ..sections import Blade
from ..sections.tower import as_tower
from .inputs import (
    add_blade_options,
    apply_deck_settings,
    deck_settings,
    finite_float,
    positive_int,
    read_blade,
    read_structure,
    rpm_range,
)
from .tables import campbell_table, modes_table
from .tower import add_tower_options, is_tower_input, tower_modes_command

METHODS = ("fe", "galerkin")


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    modes = subparsers.add_parser("modes", help="natural frequencies and mode shapes at one rotor speed",
                                  description="Natural frequencies (Hz) and mode shapes at one rotor speed.")
    add_blade_options(modes)
    add_tower_options(modes)
    modes.add_argument("--rpm", type=finite_float,
                       help="rotor speed, rpm (default: a BModes deck's rot_rpm x rpm_mult, else 0)")
    modes.add_argument("--n-modes", type=positive_int, metavar="N",
                       help="number of modes (default: a BModes deck's modepr, else 10)")
    modes.add_argument("--method", choices=METHODS, default="fe",
                       help="fe: finite elements (default); galerkin: the analytical assumed-modes model")
    modes.add_argument("--terms", metavar="NW,NV,NPHI", default="5,5,3",
                       help="Galerkin terms for flap, lag and torsion (default 5,5,3)")
    modes.add_argument("--json", action="store_true", help="print JSON instead of a table")
    modes.set_defaults(run=run_modes)

    campbell = subparsers.add_parser("campbell", help="Campbell diagram: modes over a sweep of rotor speeds",
                                     description="Mode families over rotor speed, tracked by MAC.")
    add_blade_options(campbell)
    campbell.add_argument("--rpm", type=rpm_range, required=True, metavar="START:STOP:COUNT",
                          help="rotor speeds, rpm (e.g. 0:15:16)")
    campbell.add_argument("--n-modes", type=positive_int, default=6, metavar="N", help="families (default 6)")
    campbell.add_argument("--operating-rpm", type=finite_float, metavar="RPM",
                          help="operating speed to mark (default: a BModes deck's rot_rpm x rpm_mult)")
    campbell.add_argument("--plot", metavar="FILE.png", help="write the Campbell diagram to this image")
    campbell.add_argument("--json", action="store_true", help="print JSON instead of a table")
    campbell.add_argument("--quiet", action="store_true", help="no progress bar")
    campbell.set_defaults(run=run_campbell)


def _check_rpm(rpm: float) -> None:
    if rpm < 0:
        raise InputError(f"must not be negative, got {rpm}", field="--rpm")


def compute_modes(blade: Blade, args: argparse.Namespace) -> ModalResult:
    if args.method == "galerkin":
        from ..models.galerkin import galerkin_modes, parse_terms
        return galerkin_modes(blade, rpm=args.rpm, n_modes=args.n_modes, terms=parse_terms(args.terms))
    matrices = blade_matrices(blade, args.elements, args.n_modes, args.rpm)
    return solve_modes(matrices, args.rpm, args.n_modes, blade.notes + matrices.notes)


def run_modes(args: argparse.Namespace) -> int:
    apply_deck_settings(args, n_modes=True)
    if is_tower_input(args.input):
        return tower_modes_command(args)
    blade = read_structure(args)
    if not isinstance(blade, Blade):      # a BModes or windIO tower deck
        return tower_modes_command(args, as_tower(blade))
    _check_rpm(args.rpm)
    result = compute_modes(blade, args)
    if args.json:
        print(dumps({"input": args.input, **modal_to_dict(result, args.method)}))
    else:
        print(modes_table(blade, result, args.method))
    return 0


def run_campbell(args: argparse.Namespace) -> int:
    if args.operating_rpm is None:
        args.operating_rpm = deck_settings(args.input)[0] or None
    blade = read_blade(args)
    matrices = blade_matrices(blade, args.elements, args.n_modes, float(args.rpm.max()))
    result = campbell_sweep(matrices, args.rpm, args.n_modes, blade.notes + matrices.notes,
                            progress_bar("Campbell sweep", args.quiet or args.json))
    if args.plot:
        from ..plots.campbell import save_campbell_plot
        save_campbell_plot(result, args.plot, title=blade.name, operating_rpm=args.operating_rpm)
    if args.json:
        print(dumps({"input": args.input, **campbell_to_dict(result)}))
    else:
        print(campbell_table(blade, result))
        if args.plot:
            print(f"Campbell diagram written to {args.plot}", file=sys.stderr)
    return 0
