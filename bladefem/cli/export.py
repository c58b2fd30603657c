"""``bladefem export``: mode shapes as VTK files (ParaView), PNG pictures and animated GIFs."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..modal import ModalResult, blade_matrices, solve_modes
from ..sections import Blade
from .inputs import add_blade_options, apply_deck_settings, positive_int, read_blade


def rotor_speeds(text: str) -> np.ndarray:
    """R (one speed, rpm) or START:STOP:COUNT (a sweep) -> rotor speeds, rpm."""
    if ":" in text:
        from .inputs import rpm_range
        return rpm_range(text)
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a rotor speed in rpm or START:STOP:COUNT, got '{text}'") from None
    if not math.isfinite(value) or value < 0:
        raise argparse.ArgumentTypeError(f"expected a non-negative rotor speed in rpm, got '{text}'")
    return np.array([value])


def add_planform_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--aerodyn", metavar="FILE",
                        help="AeroDyn blade file: chord for drawing the blade as a surface (ElastoDyn inputs)")


def read_drawn_blade(args: argparse.Namespace) -> Blade:
    """The blade of INPUT, with the chord of ``--aerodyn FILE`` when given."""
    blade = read_blade(args)
    if args.aerodyn:
        from ..io.aerodyn import read_aerodyn_blade, with_planform
        blade = with_planform(blade, read_aerodyn_blade(args.aerodyn))
    return blade


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    export = subparsers.add_parser(
        "export", help="write mode shapes for inspection: VTK (ParaView), PNG pictures, animated GIFs",
        description="Mode shapes at one rotor speed, or mode families over a sweep, as VTK files (a .pvd collection "
                    "indexed by rotor speed plus a JSON sidecar with frequencies and kinds), PNG pictures of the "
                    "deformed blade and animated GIFs. With none of --vtk/--png/--gif, writes VTK.")
    add_blade_options(export)
    add_planform_option(export)
    export.add_argument("--rpm", type=rotor_speeds, metavar="R|START:STOP:COUNT",
                        help="rotor speed, rpm (default: a BModes deck's rot_rpm x rpm_mult, else 0), or a sweep "
                             "(VTK collection and Campbell diagram)")
    export.add_argument("-o", "--output", required=True, metavar="DIR", help="output directory")
    export.add_argument("--n-modes", type=positive_int, default=6, metavar="N", help="modes (default 6)")
    export.add_argument("--vtk", action="store_true", help="VTU files, a .pvd collection and a JSON sidecar")
    export.add_argument("--png", action="store_true",
                        help="one picture per mode and a strip of all (one speed), or the Campbell diagram (sweep)")
    export.add_argument("--gif", action="store_true", help="an animated GIF per mode (one speed only)")
    export.add_argument("--stem", default="modes", help="file-name stem of the VTK files (default 'modes')")
    export.add_argument("--quiet", action="store_true", help="no progress bar")
    export.set_defaults(run=run_export)


def require_pyvista(option: str) -> None:
    try:
        import pyvista  # noqa: F401
    except ImportError:
        raise InputError("mode pictures need pyvista: pip install 'bladefem[render]'", field=option) from None


def run_export(args: argparse.Namespace) -> int:
    from ..report import progress_bar, sweep

    apply_deck_settings(args)
    args.rpm = np.atleast_1d(np.asarray(args.rpm, dtype=float))
    if args.gif and len(args.rpm) > 1:
        raise InputError("animated GIFs are drawn at one rotor speed; give --rpm R", field="--gif")
    vtk = args.vtk or not (args.png or args.gif)
    if (args.png and len(args.rpm) == 1) or args.gif:
        require_pyvista("--gif" if args.gif else "--png")
    blade = read_drawn_blade(args)
    matrices = blade_matrices(blade, args.elements, args.n_modes, float(max(args.rpm)))
    out = Path(args.output)
    written: list[Path] = []
    if len(args.rpm) > 1:
        result = sweep(matrices, args.rpm, args.n_modes, blade.notes + matrices.notes,
                       progress_bar("Campbell sweep", args.quiet))
        if args.png:
            from ..plots.campbell import save_campbell_plot
            written.append(out / "campbell.png")
            save_campbell_plot(result, written[-1], title=blade.name)
    else:
        result = solve_modes(matrices, float(args.rpm[0]), args.n_modes, blade.notes + matrices.notes)
        written += pictures(blade, result, out, args)
    if vtk:
        from ..io.vtk import write_vtk
        export = write_vtk(blade, result, out, args.stem, args.n_modes, progress_bar("VTK files", args.quiet))
        written += [export.collection, export.sidecar]
    for path in written:
        print(path)
    if not args.quiet:
        print(f"{len(written)} files written to {out}", file=sys.stderr)
    return 0


def pictures(blade: Blade, result: ModalResult, out: Path, args: argparse.Namespace) -> list[Path]:
    """PNG pictures (each mode and the strip) and GIFs of a single-speed result, as asked."""
    from ..plots.modes3d import save_mode_gif, save_mode_png, save_mode_strip
    from ..report import progress_bar

    written = []
    numbers = range(1, len(result.modes) + 1)
    for number in progress_bar("Pictures", args.quiet)(list(numbers)):
        if args.png:
            written.append(out / f"mode{number:02d}.png")
            save_mode_png(blade, result, number, written[-1])
        if args.gif:
            written.append(out / f"mode{number:02d}.gif")
            save_mode_gif(blade, result, number, written[-1])
    if args.png:
        written.append(out / "modes.png")
        save_mode_strip(blade, result, written[-1], len(result.modes))
    return written
