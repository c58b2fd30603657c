"""Towers on the command line: reading a tower input, and the tower's ``modes`` table.

Tower inputs: YAML tower cases (``kind: tower``), ElastoDyn tower files (with ``--elastodyn-main`` or
``--tower-height``), ElastoDyn main files and windIO files with ``--part tower``, and BModes tower decks.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from ..errors import InputError

#: the modes the ElastoDyn fit needs: two fore-aft and two side-side
FIT_MODES = 8


def is_tower_input(path: str | Path) -> bool:
    """True if INPUT describes only a tower: a YAML case with ``kind: tower`` or an ElastoDyn tower file."""
    from ..builders.detect import detect_format
    from ..builders.tower_case import is_tower_case

    try:
        found = detect_format(path)
    except InputError:               # missing or unrecognised: the reader chosen instead says so
        return False
    return found == "elastodyn-tower" or (found == "case" and is_tower_case(path))


def read_tower(args: argparse.Namespace) -> Any:
    """The tower described by INPUT and the options (a :class:`bladefem.sections.tower.Tower`)."""
    from ..builders.detect import Geometry, detect_format, read_model
    from ..builders.tower_case import is_tower_case, read_tower_case
    from ..builders.tower_elastodyn import elastodyn_tower
    from ..sections import Blade
    from ..sections.tower import as_tower

    kind = detect_format(args.input)
    main = getattr(args, "elastodyn_main", None)
    if kind == "case" and is_tower_case(args.input):
        return read_tower_case(args.input)
    if kind == "elastodyn-main" or (kind == "elastodyn-tower" and main and _is_tower_of(main, args.input)):
        return elastodyn_tower(main or args.input, point_mass=getattr(args, "point_top_mass", False),
                               azimuth=math.radians(getattr(args, "rotor_azimuth_deg", 0.0)))
    if kind == "elastodyn-tower":
        return _bare_tower(Path(args.input), args, main)
    model = read_model(args.input, "tower", Geometry(top_mass=getattr(args, "tip_mass", None)))
    if isinstance(model, Blade):
        raise InputError("this input describes a blade, not a tower", file=str(args.input), field="--part")
    return as_tower(model)


def _is_tower_of(main_path: str, tower_path: str) -> bool:
    from ..formats.elastodyn_main import read_elastodyn_main
    return Path(read_elastodyn_main(main_path).tower_file).resolve() == Path(tower_path).resolve()


def _bare_tower(path: Path, args: argparse.Namespace, main_path: str | None) -> Any:
    """An ElastoDyn tower file with its height from --tower-height (or the main file) and a point top mass."""
    from ..formats.elastodyn_main import read_elastodyn_main
    from ..builders.elastodyn_tower import read_elastodyn_tower, tower_from_elastodyn
    from ..sections.tower import TopMass, Tower

    height = getattr(args, "tower_height", None)
    if height is None and main_path:
        main = read_elastodyn_main(main_path)
        height = main.tower_height - main.tower_base_height
    if height is None:
        raise InputError("an ElastoDyn tower file needs --elastodyn-main FILE or --tower-height M", file=str(path),
                         field="TowerHt")
    if not (math.isfinite(height) and height > 0):
        raise InputError(f"must be a positive number, got {height}", field="--tower-height")
    top = getattr(args, "tip_mass", None) or 0.0
    plain = tower_from_elastodyn(read_elastodyn_tower(path), height=height)
    return Tower(sections=plain.sections, top_mass=TopMass(top) if top > 0 else None, name=plain.name,
                 notes=plain.notes + (f"tower-top point mass {top:g} kg (--tip-mass)",))


def elastodyn_coefficients(tower: Any, n_modes: int, elements: int | None, nodes: int = 20) -> dict[str, Any]:
    """ElastoDyn coefficients of the first two fore-aft and side-side modes (the fit removes rigid base motion
    and evaluates ElastoDyn's own frequency of each polynomial with its gravity term)."""
    from ..models.tower_fit import tower_coefficients
    fitted = tower_coefficients(tower, nodes=nodes, n_modes=max(n_modes, FIT_MODES), elements=elements)
    return {name: {"coefficients": [float(c) for c in fit.fit.coefficients], "rms_error": fit.fit.rms_error,
                   "fe_frequency_hz": fit.fe_frequency_hz, "elastodyn_frequency_hz": fit.elastodyn_frequency_hz,
                   "warnings": list(fit.warnings)}
            for name, fit in fitted.fits.items()}


def tower_header(tower: Any) -> str:
    top = tower.top_mass.mass if tower.top_mass is not None else 0.0
    return f"# {tower.name}: height {tower.height:.4g} m, top mass {top:.6g} kg, gravity {tower.gravity:g} m/s^2"


def tower_table(tower: Any, result: Any) -> str:
    """Plain-text table of tower modes with kinetic-energy shares."""
    lines = [tower_header(tower)]
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


def tower_modes_command(args: argparse.Namespace, tower: Any) -> int:
    """``bladefem modes TOWER_INPUT``: print the tower's modes as a table or JSON; returns the exit code."""
    from ..outputs.results import dumps, modal_to_dict
    from ..models.tower import tower_modes

    if args.rpm != 0:
        raise InputError("a tower does not rotate: --rpm applies to blades (the tower's rotor-speed chart is "
                         "'bladefem campbell TOWER --rpm START:STOP:COUNT')", field="--rpm")
    if args.method != "fe":
        raise InputError("the Galerkin model is for blades; towers are solved by finite elements", field="--method")
    shown = tower_modes(tower, args.n_modes, args.elements)
    coefficients = None
    if args.elastodyn_coefficients:
        coefficients = elastodyn_coefficients(tower, args.n_modes, args.elements)
    if args.json:
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
