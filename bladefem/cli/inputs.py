"""Options shared by the subcommands that read a blade: input file, geometry, rotor speeds, mesh."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..io.case import read_case
from ..io.elastodyn_blade import blade_from_elastodyn, read_elastodyn_blade
from ..io.elastodyn_main import read_elastodyn_main
from ..sections import ROOTS, Blade

YAML_SUFFIXES = (".yaml", ".yml")


def add_blade_options(parser: argparse.ArgumentParser) -> None:
    """INPUT plus the geometry options used for ElastoDyn blade files (and as overrides for case files)."""
    parser.add_argument("input", metavar="INPUT", help="bladefem case file (.yaml) or ElastoDyn blade file")
    geometry = parser.add_argument_group("geometry (ElastoDyn blade files; override case-file values)")
    geometry.add_argument("--tip-radius", type=float, metavar="M", help="rotor tip radius TipRad, m")
    geometry.add_argument("--hub-radius", type=float, metavar="M", help="hub radius HubRad, m")
    geometry.add_argument("--precone-deg", "--precone", dest="precone_deg", type=float, metavar="DEG",
                          help="precone angle, degrees")
    geometry.add_argument("--pitch-deg", "--pitch", dest="pitch_deg", type=float, metavar="DEG",
                          help="blade pitch angle, degrees (positive to feather)")
    geometry.add_argument("--tip-mass", type=float, metavar="KG", help="tip (brake) point mass, kg")
    geometry.add_argument("--elastodyn-main", metavar="FILE",
                          help="ElastoDyn main file to read TipRad, HubRad, PreCone(1), TipMass(1) from")
    geometry.add_argument("--root", choices=ROOTS, help="root condition (default: from the case, else cantilever)")
    parser.add_argument("--elements", type=positive_int, metavar="N",
                        help="target number of elements along the span (default: refined until converged)")


def positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got '{text}'") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got '{text}'")
    return value


def finite_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got '{text}'") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, got '{text}'")
    return value


def rpm_range(text: str) -> np.ndarray:
    """START:STOP:COUNT (rpm) -> evenly spaced rotor speeds."""
    parts = text.split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected START:STOP:COUNT in rpm (e.g. 0:15:16), got '{text}'") from None
    if not (math.isfinite(start) and math.isfinite(stop)) or count < 1 or start < 0 or stop < start:
        raise argparse.ArgumentTypeError(f"need 0 <= START <= STOP and COUNT >= 1, got '{text}'")
    return np.linspace(start, stop, count)


def read_blade(args: argparse.Namespace) -> Blade:
    """The blade described by INPUT and the geometry options."""
    path = Path(args.input)
    if not path.exists():
        raise InputError("file not found", file=str(path))
    if path.suffix.lower() in YAML_SUFFIXES:
        blade = read_case(path)
    else:
        blade = _elastodyn_blade(path, args)
    changes: dict[str, object] = {}
    if args.hub_radius is not None and path.suffix.lower() in YAML_SUFFIXES:
        raise InputError("--hub-radius applies to ElastoDyn blade files; edit hub_radius_m in the case file",
                         file=str(path), field="hub_radius_m")
    if args.precone_deg is not None:
        changes["precone"] = math.radians(args.precone_deg)
    if args.pitch_deg is not None:
        changes["pitch"] = math.radians(args.pitch_deg)
    if args.root is not None:
        changes["root"] = args.root
    return blade.with_(**changes) if changes else blade


def _elastodyn_blade(path: Path, args: argparse.Namespace) -> Blade:
    blade_file = read_elastodyn_blade(path)
    if args.elastodyn_main:
        main = read_elastodyn_main(args.elastodyn_main)
        tip_radius, hub_radius = main.tip_radius, main.hub_radius
        precone, tip_mass = main.precone[0], main.tip_mass[0]
    else:
        if args.tip_radius is None:
            raise InputError("an ElastoDyn blade file needs --tip-radius (m) or --elastodyn-main FILE",
                             file=str(path), field="TipRad")
        tip_radius, hub_radius, precone, tip_mass = args.tip_radius, args.hub_radius or 0.0, 0.0, 0.0
    if args.tip_radius is not None:
        tip_radius = args.tip_radius
    if args.hub_radius is not None:
        hub_radius = args.hub_radius
    if args.tip_mass is not None:
        if args.tip_mass < 0:
            raise InputError(f"must not be negative, got {args.tip_mass}", field="--tip-mass")
        tip_mass = args.tip_mass
    return blade_from_elastodyn(blade_file, tip_radius=tip_radius, hub_radius=hub_radius, precone=precone,
                                tip_mass=tip_mass)
