"""``bladefem modes`` and ``bladefem campbell``, for blades and towers."""

from __future__ import annotations

import argparse
import math
import sys

from ..errors import InputError, SolveError
from . import options
from .damping import (
    add_aero_options,
    add_coriolis_option,
    coriolis_campbell,
    quadratic_modes,
    reject_for_towers,
    wants_quadratic,
)
from .inputs import (
    add_blade_options,
    add_gravity_options,
    apply_deck_settings,
    deck_settings,
    is_blade,
    positive_int,
    read_structure,
    rpm_band,
)

METHODS = ("fe", "galerkin")


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    modes = subparsers.add_parser(
        "modes", help="natural frequencies and mode shapes of a blade or tower",
        description="Natural frequencies (Hz) and mode shapes of a blade at one rotor speed, or of a tower.")
    add_blade_options(modes)
    modes.add_argument("--rpm", type=options.rpm,
                       help="rotor speed, rpm (blades; default: a BModes deck's rot_rpm x rpm_mult, else 0)")
    modes.add_argument("--n-modes", type=options.n_modes, metavar="N",
                       help="number of modes (default: a BModes deck's modepr, else 10)")
    modes.add_argument("--method", choices=METHODS, default="fe",
                       help="fe: finite elements (default); galerkin: the analytical assumed-modes model (blades)")
    modes.add_argument("--terms", metavar="NW,NV,NPHI",
                       help="Galerkin terms for flap, lag and torsion (default: grown until the frequencies settle "
                            "to the finite elements' tolerance; 5,5,3 is the truncation of the model's paper)")
    modes.add_argument("--elastodyn-coefficients", action="store_true",
                       help="towers: also fit ElastoDyn tower mode-shape coefficients (TwFAM1Sh .. TwSSM2Sh)")
    modes.add_argument("--operating-point", action="store_true",
                       help="blades: the modes about the blade's deflection under its centrifugal load at --rpm (a "
                            "prebent blade bends back toward the rotor plane; BeamDyn linearizes so), the static "
                            "moments' stiffness included (default: about the undeflected blade)")
    add_gravity_options(modes)
    add_coriolis_option(modes)
    add_aero_options(modes)
    modes.add_argument("--json", action="store_true", help="print JSON instead of a table")
    modes.set_defaults(run=run_modes)

    campbell = subparsers.add_parser(
        "campbell", help="Campbell diagram (blade) or soft-stiff chart (tower) over rotor speed",
        description="Blade: mode families over rotor speed, tracked by MAC, with the nP lines. Tower: the tower's "
                    "frequencies against the rotor's 1P and blade-passing bands over the operating range, and the "
                    "soft-soft / soft-stiff / stiff-stiff classification.")
    add_blade_options(campbell)
    campbell.add_argument("--rpm", type=options.rpm_sweep, required=True, metavar="START:STOP:COUNT",
                          help="rotor speeds, rpm (e.g. 0:15:16)")
    campbell.add_argument("--n-modes", type=options.n_modes, default=6, metavar="N", help="families (default 6)")
    campbell.add_argument("--operating-rpm", type=rpm_band, metavar="RPM|LOW:HIGH",
                          help="operating speed to mark, or operating range (towers: the range of the 1P and "
                               "blade-passing bands; default a BModes deck's rot_rpm x rpm_mult, else the swept "
                               "range)")
    campbell.add_argument("--blades", type=positive_int, default=3, metavar="N",
                          help="towers: number of blades, the blade-passing harmonic (default 3)")
    campbell.add_argument("--margin-percent", type=options.non_negative, metavar="PCT",
                          help="towers: separation asked from each band, percent of its edge frequency (default 10; "
                               "a design check's soft_stiff margin_percent means the same)")
    campbell.add_argument("--plot", metavar="FILE.png", help="write the diagram to this image (PNG, PDF, SVG)")
    campbell.add_argument("--vtk", metavar="DIR",
                          help="write the mode shapes as VTK for ParaView into this folder: each family at every "
                               "speed (a .pvd collection, time = rotor speed in rpm; towers: the tower's modes) and a "
                               "JSON sidecar")
    add_gravity_options(campbell)
    add_coriolis_option(campbell)
    campbell.add_argument("--json", action="store_true", help="print JSON instead of a table")
    campbell.add_argument("--quiet", action="store_true", help="no progress bar")
    campbell.set_defaults(run=run_campbell)


def _check_rpm(rpm: float) -> None:
    if rpm < 0:
        raise InputError(f"must not be negative, got {rpm}", field="--rpm")


def refuse_buckled(blade, frequencies_hz, rpm: float) -> None:
    """A blade whose weight makes a frequency negative (K0 + Omega^2 K2 not positive definite) buckles under it:
    its modes are no result (exit 1)."""
    import numpy as np

    if blade.gravity is not None and blade.root == "cantilever" and np.min(frequencies_hz) < 0:
        raise SolveError(f"the blade buckles under its own weight at {math.degrees(blade.gravity.azimuth):g} deg "
                         f"azimuth and {rpm:g} rpm (a frequency of {np.min(frequencies_hz):.4g} Hz): no modes about "
                         "an unstable equilibrium")


def compute_modes(blade, args: argparse.Namespace):
    """The blade's modes by the method asked (Galerkin: converged terms unless --terms is given)."""
    if wants_quadratic(args):
        return quadratic_modes(blade, args)
    if args.method == "galerkin":
        if args.terms is None:
            from ..models.galerkin_converged import converged_galerkin_modes
            return converged_galerkin_modes(blade, rpm=args.rpm, n_modes=args.n_modes)
        from ..models.galerkin import galerkin_modes, parse_terms
        return galerkin_modes(blade, rpm=args.rpm, n_modes=args.n_modes, terms=parse_terms(args.terms))
    from ..modal import blade_matrices, solve_modes
    matrices = blade_matrices(blade, args.elements, args.n_modes, args.rpm)
    return solve_modes(matrices, args.rpm, args.n_modes, blade.notes + matrices.notes)


def run_modes(args: argparse.Namespace) -> int:
    apply_deck_settings(args, n_modes=True)
    _check_rpm(args.rpm)
    model = read_structure(args)
    if not is_blade(model):
        if args.operating_point:
            raise InputError("--operating-point applies to blades", field="--operating-point")
        reject_for_towers(args)
        from .tower import tower_modes_command
        return tower_modes_command(args, model)
    if model.gravity is not None and args.method == "galerkin":
        raise InputError("--gravity is a finite-element model (the Galerkin model has no weight)", field="--gravity")
    if args.terms is not None and args.method != "galerkin":
        raise InputError("--terms sets the Galerkin model's terms; add --method galerkin", field="--terms")
    if args.operating_point:
        if args.method == "galerkin":
            raise InputError("--operating-point is a finite-element model (the Galerkin model is a straight beam)",
                             field="--operating-point")
        from ..modal.operating_point import deflected_blade
        model = deflected_blade(model, args.rpm)[0]
    result = compute_modes(model, args)
    refuse_buckled(model, result.frequencies_hz, args.rpm)
    if args.json:
        from ..outputs.results import dumps, modal_to_dict
        print(dumps({"input": args.input, "structure": "blade", **modal_to_dict(result, args.method)}))
    else:
        from .tables import modes_table
        print(modes_table(model, result, args.method))
    return 0


def run_campbell(args: argparse.Namespace) -> int:
    deck_rpm = deck_settings(args.input)[0]
    if args.operating_rpm is None and deck_rpm:
        args.operating_rpm = (deck_rpm, deck_rpm)
    options.check_sweep(args.rpm, args.n_modes, args.elements)
    options.check_output(args.plot, "--plot")
    if args.vtk:
        options.check_folder(args.vtk, "--vtk")
    model = read_structure(args)
    if not is_blade(model):
        reject_for_towers(args)
        return tower_campbell_command(args, model)
    import numpy as np

    from ..modal import blade_matrices, campbell_sweep
    from ..report import progress_bar

    rpm = np.asarray(args.rpm)
    progress = progress_bar("Campbell sweep", args.quiet or args.json)
    if args.coriolis:
        result = coriolis_campbell(model, args, progress)
    else:
        matrices = blade_matrices(model, args.elements, args.n_modes, float(rpm.max()))
        result = campbell_sweep(matrices, rpm, args.n_modes, model.notes + matrices.notes, progress)
    for speed, modes_at in zip(result.rpm, result.results):
        refuse_buckled(model, modes_at.frequencies_hz, float(speed))
    operating = args.operating_rpm
    if operating is not None and operating[0] == operating[1]:
        operating = operating[0]
    if args.plot:
        from ..plots.campbell import save_campbell_plot
        save_campbell_plot(result, args.plot, title=model.name, operating_rpm=operating)
    write_vtk_folder(model, result, args)
    if args.json:
        from ..outputs.results import campbell_to_dict, dumps
        print(dumps({"input": args.input, "structure": "blade", **campbell_to_dict(result)}))
    else:
        from .tables import campbell_table
        print(campbell_table(model, result))
        if args.plot:
            print(f"Campbell diagram written to {args.plot}", file=sys.stderr)
    return 0


def tower_campbell_command(args: argparse.Namespace, tower) -> int:
    """``bladefem campbell TOWER``: the soft-stiff chart as a table (or JSON) and optionally a figure."""
    from ..models.tower_campbell import tower_campbell

    margin = {} if args.margin_percent is None else {"margin": args.margin_percent / 100.0}
    chart = tower_campbell(tower, args.rpm, args.n_modes, args.elements, args.operating_rpm, args.blades, **margin)
    if args.plot:
        from ..plots.tower_campbell import save_tower_campbell_plot
        save_tower_campbell_plot(chart, args.plot)
    write_vtk_folder(tower, chart.modes, args)
    if args.json:
        from ..outputs.results import dumps, tower_campbell_to_dict
        print(dumps({"input": args.input, "structure": "tower", **tower_campbell_to_dict(chart)}))
    else:
        from .tables import tower_campbell_table
        print(tower_campbell_table(tower, chart))
        if args.plot:
            print(f"tower chart written to {args.plot}", file=sys.stderr)
    return 0


def write_vtk_folder(structure, result, args: argparse.Namespace) -> None:
    """``--vtk DIR``: the modes of ``result`` (a blade's sweep, or the modes of a tower's chart) as VTK files in
    DIR (``campbell.pvd``, its VTU files and sidecar), the folder named on stderr."""
    if not args.vtk:
        return
    from ..outputs.vtk import write_vtk
    export = write_vtk(structure, result, args.vtk, "campbell")
    files = f"{len(export.meshes)} VTU file" + ("s" if len(export.meshes) != 1 else "")
    print(f"mode shapes for ParaView: {export.collection} ({files}, sidecar {export.sidecar.name})", file=sys.stderr)
