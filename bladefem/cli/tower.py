"""Tower inputs for ``bladefem modes``: YAML tower cases (``kind: tower``) and ElastoDyn tower or main files.

``bladefem modes`` calls :func:`is_tower_input` on INPUT and, when true, :func:`tower_modes_command`. The options
of :func:`add_tower_options` are added to the ``modes`` parser; the blade options ``--n-modes``, ``--elements``,
``--json``, ``--elastodyn-main`` and ``--tip-mass`` are shared.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..io.detect import detect_format
from ..io.elastodyn_main import read_elastodyn_main
from ..io.elastodyn_tower import read_elastodyn_tower, tower_from_elastodyn
from ..io.results import dumps, modal_to_dict
from ..io.tower_case import is_tower_case, read_tower_case
from ..io.tower_elastodyn import elastodyn_tower
from ..modal.results import ModalResult
from ..models.tower import tower_modes
from ..sections.tower import TopMass, Tower

YAML_SUFFIXES = (".yaml", ".yml")
#: the modes the ElastoDyn fit needs: two fore-aft and two side-side
FIT_MODES = 8


def is_tower_input(path: str | Path) -> bool:
    """True if INPUT describes a tower: a YAML case with ``kind: tower`` or an ElastoDyn tower file."""
    try:
        found = detect_format(path)
    except InputError:               # missing or unrecognised: the reader chosen instead says so
        return False
    return found == "elastodyn-tower" or (found == "case" and is_tower_case(path))


def add_tower_options(parser: argparse.ArgumentParser) -> None:
    """Tower options of ``bladefem modes`` (besides the shared ones)."""
    group = parser.add_argument_group("towers (YAML kind: tower, ElastoDyn tower files)")
    group.add_argument("--tower-height", type=float, metavar="M",
                       help="flexible tower length for an ElastoDyn tower file without --elastodyn-main, m")
    group.add_argument("--no-gravity", action="store_true", help="leave out gravity (axial load, pendulum effect)")
    group.add_argument("--point-top-mass", action="store_true",
                       help="with --elastodyn-main: the rotor-nacelle mass as a point mass, as ElastoDyn uses it "
                            "(default: a rigid body with offset and inertia)")
    group.add_argument("--rotor-azimuth-deg", type=float, default=0.0, metavar="DEG",
                       help="azimuth of blade 1 for the rigid rotor-nacelle body, degrees (default 0)")
    group.add_argument("--elastodyn-coefficients", action="store_true",
                       help="also fit ElastoDyn tower mode-shape coefficients (TwFAM1Sh .. TwSSM2Sh)")


def read_tower(args: argparse.Namespace) -> Tower:
    """The tower described by INPUT and the options."""
    path = Path(args.input)
    if not path.exists():
        raise InputError("file not found", file=str(path))
    if path.suffix.lower() in YAML_SUFFIXES:
        tower = read_tower_case(path)
    elif getattr(args, "elastodyn_main", None):
        main = read_elastodyn_main(args.elastodyn_main)
        if Path(main.tower_file).resolve() == path.resolve():
            tower = elastodyn_tower(args.elastodyn_main, point_mass=getattr(args, "point_top_mass", False),
                                    azimuth=math.radians(getattr(args, "rotor_azimuth_deg", 0.0)))
        else:     # another tower file: its own sections, the main file's height and a point top mass
            tower = _bare_tower(path, args, main)
    else:
        tower = _bare_tower(path, args, None)
    return tower.with_(gravity=0.0) if getattr(args, "no_gravity", False) else tower


def _bare_tower(path: Path, args: argparse.Namespace, main: Any) -> Tower:
    """An ElastoDyn tower file with its height from --tower-height (or the main file) and a point top mass."""
    height = getattr(args, "tower_height", None)
    if height is None and main is not None:
        height = main.tower_height - main.tower_base_height
    if height is None:
        raise InputError("an ElastoDyn tower file needs --elastodyn-main FILE or --tower-height M", file=str(path),
                         field="TowerHt")
    top = getattr(args, "tip_mass", None) or 0.0
    if top < 0:
        raise InputError(f"must not be negative, got {top}", field="--tip-mass")
    plain = tower_from_elastodyn(read_elastodyn_tower(path), height=height)
    return Tower(sections=plain.sections, top_mass=TopMass(top) if top > 0 else None, name=plain.name,
                 notes=plain.notes + (f"tower-top point mass {top:g} kg (--tip-mass)",))


def elastodyn_coefficients(tower: Tower, n_modes: int, elements: int | None, nodes: int = 20) -> dict[str, Any]:
    """ElastoDyn coefficients of the first two fore-aft and side-side modes (the io engineer's fit, which removes
    rigid base motion and evaluates ElastoDyn's own frequency of each polynomial with its gravity term)."""
    from ..models.tower_fit import tower_coefficients
    fitted = tower_coefficients(tower, nodes=nodes, n_modes=max(n_modes, FIT_MODES), elements=elements)
    return {name: {"coefficients": [float(c) for c in fit.fit.coefficients], "rms_error": fit.fit.rms_error,
                   "fe_frequency_hz": fit.fe_frequency_hz, "elastodyn_frequency_hz": fit.elastodyn_frequency_hz,
                   "warnings": list(fit.warnings)}
            for name, fit in fitted.fits.items()}


def tower_table(tower: Tower, result: ModalResult) -> str:
    """Plain-text table of tower modes with kinetic-energy shares."""
    top = tower.top_mass.mass if tower.top_mass is not None else 0.0
    lines = [f"# {tower.name}: height {tower.height:.4g} m, top mass {top:.6g} kg, gravity {tower.gravity:g} m/s^2"]
    lines += [f"# note: {note}" for note in result.notes]
    lines.append(f"# {result.n_dofs} DOFs; shares: fa fore-aft, ss side-side, tor torsion, ax axial, ptfm platform")
    lines.append(f"{'mode':>4}  {'frequency_hz':>12}  {'kind':<10} {'fa':>5} {'ss':>5} {'tor':>5} {'ax':>5} "
                 f"{'ptfm':>5}  {'residual':>9}")
    for i, mode in enumerate(result.modes, 1):
        e = mode.energy_fractions
        platform = sum(e[k] for k in ("surge", "sway", "heave", "roll", "pitch", "yaw"))
        lines.append(f"{i:>4}  {mode.frequency_hz:>12.5f}  {mode.kind:<10} {e['fore-aft']:>5.2f} "
                     f"{e['side-side']:>5.2f} {e['torsion']:>5.2f} {e['axial']:>5.2f} {platform:>5.2f}  "
                     f"{mode.residual:>9.1e}")
    return "\n".join(lines)


def tower_modes_command(args: argparse.Namespace, tower: Tower | None = None) -> int:
    """``bladefem modes TOWER_INPUT``: print the tower's modes as a table or JSON; returns the exit code. ``tower``:
    an already-read tower (BModes and windIO decks), else INPUT is read here."""
    if tower is None:
        tower = read_tower(args)
    elif getattr(args, "no_gravity", False):
        tower = tower.with_(gravity=0.0)
    n_modes, elements = getattr(args, "n_modes", 10), getattr(args, "elements", None)
    shown = tower_modes(tower, n_modes, elements)
    coefficients = None
    if getattr(args, "elastodyn_coefficients", False):
        coefficients = elastodyn_coefficients(tower, n_modes, elements)
    if getattr(args, "json", False):
        data = {"input": args.input, "structure": "tower", **modal_to_dict(shown, "fe")}
        if coefficients is not None:
            data["elastodyn_coefficients"] = coefficients
        print(dumps(data))
        return 0
    print(tower_table(tower, shown))
    if coefficients is not None:
        for name, fit_data in coefficients.items():
            values = "  ".join(f"{c:.6g}" for c in fit_data["coefficients"])
            print(f"# ElastoDyn {name} (x^2 .. x^6): {values}   rms {fit_data['rms_error']:.2e}, "
                  f"ElastoDyn frequency {fit_data['elastodyn_frequency_hz']:.5f} Hz")
    return 0


def tower_parser() -> argparse.ArgumentParser:
    """A standalone parser with the ``modes`` options a tower uses (for tests and scripts)."""
    parser = argparse.ArgumentParser(prog="bladefem modes")
    parser.add_argument("input")
    parser.add_argument("--n-modes", type=int, default=10)
    parser.add_argument("--elements", type=int)
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--elastodyn-main")
    parser.add_argument("--tip-mass", type=float)
    add_tower_options(parser)
    return parser
