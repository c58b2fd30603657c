"""``bladefem elastodyn``: ElastoDyn mode-shape coefficients from the finite-element modes, with their quality, the
frequencies ElastoDyn would derive from them, a verdict on the coefficients already in an ElastoDyn file
(``--check``), and an in-place update of an ElastoDyn blade or tower file (``--write``) that refuses a fit worse
than the file's unless ``--force``.

"Worse" and "off" are judged by the frequency ElastoDyn derives from a polynomial (its own generalized mass and
stiffness) against the finite-element frequency of the same mode: the quantity a polynomial must get right for
ElastoDyn to vibrate at the right frequency.
"""

from __future__ import annotations

import argparse
import difflib
import math
import sys
from pathlib import Path
from typing import Any

from ..errors import InputError
from . import options
from .inputs import add_sections_option

DEFAULT_BLADE_NODES = 17
DEFAULT_TOWER_NODES = 20
#: :data:`bladefem.modal.elastodyn_fit.MIN_TIP_RATIO`, repeated so that parsing imports no numpy (a test checks)
MIN_TIP_RATIO = 0.3
#: --check's default: largest accepted |ElastoDyn frequency / FE frequency - 1|, percent
CHECK_TOLERANCE_PERCENT = 1.0
#: a fresh fit counts as worse than the file's when its frequency error exceeds the file's by more than this
#: (relative): 0.01 %, the resolution of the diff_% column that the report prints
WORSE_SLACK = 1e-4


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "elastodyn", help="ElastoDyn mode-shape coefficients (fit, quality, in-place update)",
        description="Fit ElastoDyn's polynomial mode shapes (flap 1, flap 2, edge 1 of a blade at a rotor speed; "
                    "fore-aft and side-side 1 and 2 of a tower) to the finite-element modes, report the fit quality "
                    "and the frequencies ElastoDyn would derive from the polynomials, and optionally update an "
                    "ElastoDyn blade or tower file in place.")
    parser.add_argument("input", metavar="INPUT",
                        help="ElastoDyn main, blade or tower file, BModes .bmi, windIO or bladefem case .yaml")
    parser.add_argument("--rpm", type=float, metavar="R",
                        help="rotor speed for blade modes, rpm (default: RotSpeed of an ElastoDyn main file, or the "
                             "BModes deck's rotor speed)")
    action = parser.add_mutually_exclusive_group()
    action.add_argument("--write", metavar="FILE.dat",
                        help="update the coefficient lines of this ElastoDyn blade or tower file in place")
    action.add_argument("--check", action="store_true",
                        help="verdict on the coefficients in INPUT's ElastoDyn blade or tower file: exit 1 when a "
                             "mode's ElastoDyn frequency is off from the FE frequency by more than --tolerance")
    parser.add_argument("--tolerance", type=float, default=CHECK_TOLERANCE_PERCENT, metavar="PERCENT",
                        help="with --check: accepted frequency difference, percent "
                             f"(default {CHECK_TOLERANCE_PERCENT:g})")
    parser.add_argument("--dry-run", action="store_true", help="with --write: show a unified diff, write nothing")
    parser.add_argument("--backup", action="store_true", help="with --write: keep the old file as FILE.dat.bak")
    parser.add_argument("--force", action="store_true",
                        help="with --write: write the fresh fit even where it is worse than the file's coefficients")
    parser.add_argument("--part", choices=("blade", "tower"),
                        help="blade or tower (default: from --write or INPUT; blade for files with both)")
    parser.add_argument("--nodes", type=int, metavar="N",
                        help="ElastoDyn analysis nodes for its own integrals (default: BldNodes/TwrNodes of the main "
                             f"file, else {DEFAULT_BLADE_NODES} for a blade and {DEFAULT_TOWER_NODES} for a tower)")
    parser.add_argument("--n-modes", type=int, default=12, metavar="N", help="FE modes computed (default 12)")
    parser.add_argument("--elements", type=int, metavar="N", help="FE elements (default: refined until converged)")
    parser.add_argument("--min-tip-ratio", type=options.non_negative, default=MIN_TIP_RATIO, metavar="X",
                        help=f"warn when |tip displacement| / max |displacement| < X (default {MIN_TIP_RATIO})")
    geometry = parser.add_argument_group("geometry for ElastoDyn blade or tower files given alone")
    geometry.add_argument("--elastodyn-main", metavar="FILE", help="ElastoDyn main file to take the geometry from")
    geometry.add_argument("--tip-radius", type=options.positive, metavar="M", help="TipRad, m")
    geometry.add_argument("--hub-radius", type=options.non_negative, metavar="M", help="HubRad, m")
    geometry.add_argument("--tower-height", type=options.positive, metavar="M", help="flexible tower length, m")
    geometry.add_argument("--top-mass", type=options.non_negative, metavar="KG", help="tower-top point mass, kg")
    geometry.add_argument("--htc", metavar="FILE",
                          help="HAWC2 .htc file whose blade body (c2_def) gives a HAWC2 st INPUT its twist")
    add_sections_option(geometry)
    parser.add_argument("--elastodyn-compatible", nargs="?", const="twisted", choices=("twisted", "untwisted"),
                        help="blades: compute the FE modes on what ElastoDyn can hold (mass on the axis, principal "
                             "flap and edge stiffnesses about the tension centre turned by the twist plus the "
                             "principal angle, no offsets, no torsion); 'untwisted' also drops the twist (OpenFAST's "
                             "guidance for mode-shape fits); a curved reference axis is straightened (ElastoDyn's "
                             "blade is straight). Default: the FE modes of the blade as given")
    parser.set_defaults(run=run)


def _check(args: argparse.Namespace) -> None:
    for name in ("rpm", "tip_radius", "hub_radius", "tower_height", "top_mass", "min_tip_ratio", "tolerance"):
        value = getattr(args, name)
        if value is not None and not (math.isfinite(value) and value >= 0):
            raise InputError(f"must be a non-negative number, got {value}", field="--" + name.replace("_", "-"))
    for name in ("nodes", "n_modes", "elements"):
        value = getattr(args, name)
        if value is not None and value < 1:
            raise InputError(f"must be a positive integer, got {value}", field="--" + name.replace("_", "-"))
    if args.dry_run and not args.write:
        raise InputError("--dry-run needs --write FILE.dat", field="--dry-run")
    if args.force and not args.write:
        raise InputError("--force needs --write FILE.dat", field="--force")
    options.check_limits(args)
    if args.backup and not args.write:
        raise InputError("--backup needs --write FILE.dat", field="--backup")
    if args.write and not args.dry_run:
        from ..files import check_writable
        check_writable(args.write, field="--write", replaces_input=True)   # an in-place update of its coefficients


def _part(args: argparse.Namespace) -> str | None:
    """'blade' or 'tower' from --part or the --write target; None to let INPUT decide."""
    from ..builders.detect import detect_format

    if args.part:
        return args.part
    if args.write:
        target = detect_format(args.write)
        if target not in ("elastodyn-blade", "elastodyn-tower"):
            raise InputError("--write needs an existing ElastoDyn blade or tower file", file=args.write,
                             field="--write")
        return "tower" if target == "elastodyn-tower" else "blade"
    return None


def _main_file(args: argparse.Namespace, kind: str) -> str | None:
    return args.input if kind == "elastodyn-main" else args.elastodyn_main


def _shipped(args: argparse.Namespace, kind: str, part: str) -> tuple[dict | None, str | None]:
    """Coefficients already in the file to be written, or in the ElastoDyn file given as INPUT."""
    from ..builders.elastodyn_blade import read_elastodyn_blade
    from ..formats.elastodyn_main import read_elastodyn_main
    from ..builders.elastodyn_tower import read_elastodyn_tower

    source = args.write
    if source is None:
        main = _main_file(args, kind)
        if kind == f"elastodyn-{part}":
            source = args.input
        elif main:
            parsed = read_elastodyn_main(main)
            source = str(parsed.tower_file if part == "tower" else parsed.blade_files[0])
    if source is None:
        return None, None
    data = read_elastodyn_tower(source) if part == "tower" else read_elastodyn_blade(source)
    return data.modes, source


def run(args: argparse.Namespace) -> int:
    from ..builders.detect import BEAM_FORMATS, Geometry, detect_format, read_model
    from ..formats.elastodyn_main import read_elastodyn_main
    from ..sections import Blade

    _check(args)
    kind = detect_format(args.input)
    wanted = _part(args)
    geometry = Geometry(tip_radius=args.tip_radius, hub_radius=args.hub_radius, elastodyn_main=args.elastodyn_main,
                        tower_height=args.tower_height, top_mass=args.top_mass, htc=args.htc,
                        sections=args.sections,
                        axis="straight" if args.elastodyn_compatible and kind in BEAM_FORMATS + ("windio",)
                        else args.axis)
    model = read_model(args.input, wanted, geometry)
    part = "blade" if isinstance(model, Blade) else "tower"
    if args.elastodyn_compatible:
        model = _elastodyn_compatible(model, args.elastodyn_compatible == "twisted", args.input)
    if wanted is not None and part != wanted:
        raise InputError(f"INPUT describes a {part}, not a {wanted}", file=args.input, field="--part")
    main_path = _main_file(args, kind)
    main = read_elastodyn_main(main_path) if main_path else None
    shipped, shipped_from = _shipped(args, kind, part)
    if args.check and shipped is None:
        raise InputError("--check compares the coefficients of an ElastoDyn file: give an ElastoDyn main, blade or "
                         "tower file as INPUT, or --elastodyn-main FILE", file=args.input, field="--check")
    try:
        result = _coefficients(args, kind, model, main, shipped)
    except LookupError as error:
        raise InputError(f"{error}", file=args.input, field="--n-modes") from None
    print(report(model.name, result, shipped_from))
    if args.check:
        return check_verdict(result, shipped_from, args.tolerance)
    if args.write:
        worse = worse_modes(result)
        if worse and args.dry_run:
            print(f"# warning: the fresh fit is worse than the file's coefficients ({'; '.join(worse)}); --write "
                  "refuses it without --force")
        elif worse and not args.force:
            raise InputError(f"the fresh fit is worse than the file's coefficients ({'; '.join(worse)}); nothing "
                             "written (--force writes it anyway)", file=args.write, field="--write")
        _update(args.write, result, args.dry_run, args.backup)
    return 0


def _elastodyn_compatible(model: Any, twisted: bool, path: str) -> Any:
    """The blade with :func:`bladefem.sections.principal.elastodyn_sections`, named in its notes."""
    from ..sections import Blade
    from ..sections.principal import elastodyn_sections

    if not isinstance(model, Blade):
        raise InputError("--elastodyn-compatible applies to blades", file=path, field="--elastodyn-compatible")
    note = ("--elastodyn-compatible: FE modes of ElastoDyn's section model (mass on the pitch axis, principal flap "
            "and edge stiffnesses about the tension centre, " + ("turned by the twist plus the principal angle"
                                                                  if twisted else "untwisted")
            + "; no offsets, no torsion; the reference axis straightened onto the pitch axis)")
    return model.with_(sections=elastodyn_sections(model.sections, twisted), notes=model.notes + (note,))


def frequency_error(fit: Any) -> float:
    """|ElastoDyn frequency / FE frequency - 1| of one mode's polynomial."""
    return abs(fit.elastodyn_frequency_hz / fit.fe_frequency_hz - 1)


def worse_modes(result: Any) -> list[str]:
    """The modes whose fresh polynomial gives a larger ElastoDyn frequency error than the file's, described."""
    if not result.shipped:
        return []
    found = []
    for name, fresh in result.fits.items():
        old = result.shipped.get(name)
        if old is not None and frequency_error(fresh) > frequency_error(old) + WORSE_SLACK:
            found.append(f"{name}: ElastoDyn frequency {_signed(fresh)} from FE against {_signed(old)}")
    return found


def _signed(fit: Any) -> str:
    return f"{100 * (fit.elastodyn_frequency_hz / fit.fe_frequency_hz - 1):+.2f} %"


def check_verdict(result: Any, source: str | None, tolerance_percent: float) -> int:
    """Print one verdict line per mode of the file and a summary; 0 when every mode is within the tolerance, 1
    otherwise."""
    lines = [f"# check of {source} (tolerance {tolerance_percent:g} % on the ElastoDyn frequency):"]
    failed = []
    for name, fit in (result.shipped or {}).items():
        ok = 100 * frequency_error(fit) <= tolerance_percent
        failed += [] if ok else [name]
        lines.append(f"#   {name:<6} {'ok' if ok else 'OFF':<4} ElastoDyn {fit.elastodyn_frequency_hz:.5f} Hz, "
                     f"FE {fit.fe_frequency_hz:.5f} Hz ({_signed(fit)})")
    lines.append(f"# verdict: {'FAIL: ' + ', '.join(failed) + ' off' if failed else 'PASS'}")
    print("\n".join(lines))
    return 1 if failed else 0


def _coefficients(args: argparse.Namespace, kind: str, model, main, shipped):
    from ..sections import Blade

    if not isinstance(model, Blade):
        from ..models.tower_fit import tower_coefficients
        nodes = args.nodes or (main.tower_nodes if main else DEFAULT_TOWER_NODES)
        return tower_coefficients(model, nodes=nodes, n_modes=args.n_modes, elements=args.elements,
                                  shipped=shipped, min_tip_ratio=args.min_tip_ratio)
    from ..modal.elastodyn_fit import blade_coefficients
    rpm = _rpm(args, kind, main)
    nodes = args.nodes or (main.blade_nodes if main else DEFAULT_BLADE_NODES)
    return blade_coefficients(model, rpm, nodes=nodes, n_modes=args.n_modes, elements=args.elements,
                              shipped=shipped, min_tip_ratio=args.min_tip_ratio)


def _rpm(args: argparse.Namespace, kind: str, main) -> float:
    if args.rpm is not None:
        return args.rpm
    if main is not None:
        return main.rotor_speed_rpm
    if kind == "bmodes":
        from ..formats.bmodes import read_bmodes
        return read_bmodes(args.input).rotor_speed_rpm
    raise InputError("give the rotor speed with --rpm R (rpm)", file=args.input, field="--rpm")


def report(name: str, result: Any, shipped_from: str | None = None) -> str:
    """The quality table, the warnings and the coefficient blocks as ElastoDyn lines."""
    from ..formats._modeshape_blocks import block_lines, decimal_texts
    from ..builders.elastodyn_blade import BLADE_BLOCKS
    from ..builders.elastodyn_tower import TOWER_BLOCKS

    speed = "tower (non-rotating)" if result.tower else f"rotor speed {result.rpm:g} rpm"
    lines = [f"# {name}: FE modes, {speed}; ElastoDyn frequencies from its own integrals over {result.nodes} nodes"]
    lines += [f"# note: {note}" for note in result.notes]
    lines += _table("fresh fit", result.fits) + _coupled(getattr(result, "coupled_hz", None))
    if result.shipped:
        lines += _table(f"coefficients in {shipped_from}", result.shipped)
        lines += _coupled(getattr(result, "shipped_coupled_hz", None))
    lines += [f"# warning: {warning}" for warning in result.warnings]
    blocks = TOWER_BLOCKS if result.tower else BLADE_BLOCKS
    lines.append("")
    for mode, fit in result.fits.items():
        texts = decimal_texts(fit.fit.coefficients)
        lines += [line.rstrip("\n") for line in block_lines(blocks[mode], fit.fit.coefficients, fit.label, texts)]
    return "\n".join(lines)


def _coupled(frequencies: dict[str, float] | None) -> list[str]:
    """The line of the three blade modes together in ElastoDyn's equations (what its linearization finds)."""
    if not frequencies:
        return []
    listed = ", ".join(f"{name} {hz:.5f}" for name, hz in sorted(frequencies.items(), key=lambda item: item[1]))
    return [f"# ElastoDyn's three modes together (its linearization, coupled through the mass): {listed} Hz"]


def _table(title: str, fits: dict) -> list[str]:
    lines = [f"# {title}:",
             f"# {'mode':<6} {'FE_Hz':>10} {'ElastoDyn_Hz':>13} {'diff_%':>7} {'rms_err':>9} {'tip_slope_err':>13} "
             f"{'cond':>8} {'tip_ratio':>9} {'sum-1':>9}"]
    for mode, f in fits.items():
        diff = 100 * (f.elastodyn_frequency_hz / f.fe_frequency_hz - 1)
        cond = f"{f.fit.condition_number:8.2e}" if math.isfinite(f.fit.condition_number) else f"{'-':>8}"
        lines.append(f"  {mode:<6} {f.fe_frequency_hz:>10.5f} {f.elastodyn_frequency_hz:>13.5f} {diff:>7.2f} "
                     f"{f.fit.rms_error:>9.2e} {f.fit.tip_slope_error:>13.2e} {cond} {f.tip_ratio:>9.3f} "
                     f"{f.fit.coefficients.sum() - 1:>9.1e}")
    return lines


def _update(path: str, result: Any, dry_run: bool, backup: bool = False) -> None:
    from ..files import write_atomic
    from ..formats._fast_format import text_encoding
    from ..builders.elastodyn_blade import blade_with_mode_shapes
    from ..builders.elastodyn_tower import tower_with_mode_shapes

    updater = tower_with_mode_shapes if result.tower else blade_with_mode_shapes
    old, new = updater(path, result.coefficients)
    if dry_run:
        diff = difflib.unified_diff(old.splitlines(keepends=True), new.splitlines(keepends=True),
                                    fromfile=path, tofile=f"{path} (updated)")
        sys.stdout.write("\n" + "".join(diff))
        return
    write_atomic(Path(path), new, encoding=text_encoding(path), backup=backup, replaces_input=True)
    changed = sum(a != b for a, b in zip(old.splitlines(), new.splitlines()))
    print(f"\n# updated {path}: {changed} coefficient lines changed, every other byte kept")
