"""``bladefem export``: mode shapes of a blade or tower as VTK files (ParaView), PNG pictures and animated GIFs.

Every file written is printed on stdout, one path a line; stderr ends with the count and the folder.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..errors import InputError
from . import options
from .inputs import add_blade_options, apply_deck_settings, is_blade, read_structure


def rotor_speeds(text: str) -> tuple[float, ...]:
    """R (one speed, rpm) or START:STOP:COUNT (a sweep) -> rotor speeds, rpm."""
    if ":" in text:
        return options.rpm_sweep(text)
    try:
        float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a rotor speed in rpm or START:STOP:COUNT, got '{text}'") from None
    return (options.rpm(text),)


def add_planform_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--aerodyn", metavar="FILE",
                        help="AeroDyn blade file: chord for drawing the blade as a surface (ElastoDyn inputs)")


def read_drawn_structure(args: argparse.Namespace) -> object:
    """The blade (with the chord of ``--aerodyn FILE`` when given) or tower of INPUT."""
    model = read_structure(args)
    if args.aerodyn:
        if not is_blade(model):
            raise InputError("--aerodyn draws a blade's planform; INPUT describes a tower", field="--aerodyn")
        from ..builders.aerodyn import read_aerodyn_blade, with_planform
        model = with_planform(model, read_aerodyn_blade(args.aerodyn))
    return model


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    export = subparsers.add_parser(
        "export", help="write mode shapes for inspection: VTK (ParaView), PNG pictures, animated GIFs",
        description="Mode shapes of a blade at one rotor speed, or mode families over a sweep, or of a tower, as "
                    "VTK files (a .pvd collection indexed by rotor speed plus a JSON sidecar with frequencies and "
                    "kinds), PNG pictures of the deformed structure (with its tip or top mass) and animated GIFs. "
                    "With none of --vtk/--png/--gif, writes VTK. Every file written is listed on stdout.")
    add_blade_options(export)
    add_planform_option(export)
    export.add_argument("--rpm", type=rotor_speeds, metavar="R|START:STOP:COUNT",
                        help="rotor speed, rpm (default: a BModes deck's rot_rpm x rpm_mult, else 0), or a sweep "
                             "(VTK collection and Campbell diagram); blades only")
    export.add_argument("-o", "--output", required=True, metavar="DIR", help="output directory")
    export.add_argument("--n-modes", type=options.n_modes, default=6, metavar="N", help="modes (default 6)")
    export.add_argument("--vtk", action="store_true", help="VTU files, a .pvd collection and a JSON sidecar")
    export.add_argument("--png", action="store_true",
                        help="one picture per mode and a strip of all (one speed), or the Campbell diagram (sweep)")
    export.add_argument("--gif", action="store_true", help="an animated GIF per mode (one speed only)")
    export.add_argument("--stem", default="modes", help="file-name stem of the VTK files (default 'modes')")
    export.add_argument("--quiet", action="store_true", help="no progress bar, no summary line")
    export.set_defaults(run=run_export)


def require_pyvista(option: str) -> None:
    try:
        import pyvista  # noqa: F401
    except ImportError:
        raise InputError("mode pictures need pyvista: pip install 'bladefem[render]'", field=option) from None


def run_export(args: argparse.Namespace) -> int:
    apply_deck_settings(args)
    args.rpm = tuple(args.rpm) if isinstance(args.rpm, tuple) else (float(args.rpm),)
    sweep = len(args.rpm) > 1
    if args.gif and sweep:
        raise InputError("animated GIFs are drawn at one rotor speed; give --rpm R", field="--gif")
    vtk = args.vtk or not (args.png or args.gif)
    if (args.png and not sweep) or args.gif:
        require_pyvista("--gif" if args.gif else "--png")
    options.check_sweep(args.rpm, args.n_modes, args.elements)
    options.check_folder(args.output)
    model = read_drawn_structure(args)
    out = Path(args.output)
    if is_blade(model):
        result, written = blade_result(model, out, args)
    else:
        if sweep or args.rpm[0] != 0:
            raise InputError("a tower does not rotate: export its modes without --rpm", field="--rpm")
        from ..models.tower import tower_modes
        result, written = tower_modes(model, args.n_modes, args.elements), []
        written += pictures(model, result, out, args)
    if vtk:
        from ..outputs.vtk import write_vtk
        from ..report import progress_bar
        export = write_vtk(model, result, out, args.stem, args.n_modes, progress_bar("VTK files", args.quiet))
        written += [*export.meshes, export.collection, export.sidecar]
    for path in written:
        print(path)
    if not args.quiet:
        print(f"{len(written)} files written to {out}", file=sys.stderr)
    return 0


def blade_result(blade, out: Path, args: argparse.Namespace):
    """The blade's modes (one speed) or Campbell sweep, and the pictures written for it."""
    import numpy as np

    from ..modal import blade_matrices, solve_modes
    from ..report import progress_bar, sweep

    matrices = blade_matrices(blade, args.elements, args.n_modes, float(max(args.rpm)))
    written: list[Path] = []
    if len(args.rpm) > 1:
        result = sweep(matrices, np.asarray(args.rpm), args.n_modes, blade.notes + matrices.notes,
                       progress_bar("Campbell sweep", args.quiet))
        if args.png:
            from ..plots.campbell import save_campbell_plot
            written.append(out / "campbell.png")
            save_campbell_plot(result, written[-1], title=blade.name)
        return result, written
    result = solve_modes(matrices, float(args.rpm[0]), args.n_modes, blade.notes + matrices.notes)
    return result, pictures(blade, result, out, args)


def pictures(structure, result, out: Path, args: argparse.Namespace) -> list[Path]:
    """PNG pictures (each mode and the strip) and GIFs of a single-speed result, as asked."""
    if not (args.png or args.gif):
        return []
    from ..plots.modes3d import save_mode_gif, save_mode_png, save_mode_strip
    from ..report import progress_bar

    written = []
    numbers = range(1, len(result.modes) + 1)
    for number in progress_bar("Pictures", args.quiet)(list(numbers)):
        if args.png:
            written.append(out / f"mode{number:02d}.png")
            save_mode_png(structure, result, number, written[-1])
        if args.gif:
            written.append(out / f"mode{number:02d}.gif")
            save_mode_gif(structure, result, number, written[-1])
    if args.png:
        written.append(out / "modes.png")
        save_mode_strip(structure, result, written[-1], len(result.modes))
    return written
