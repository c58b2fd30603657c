"""Options shared by the subcommands that read a blade: input file, geometry, rotor speeds, mesh."""

from __future__ import annotations

import argparse
import math

import numpy as np

from ..errors import InputError
from ..io.detect import Geometry, read_model
from ..sections import ROOTS, Blade


def add_blade_options(parser: argparse.ArgumentParser) -> None:
    """INPUT plus the geometry options used for ElastoDyn blade files (and as overrides for case files)."""
    parser.add_argument("input", metavar="INPUT",
                        help="bladefem case or windIO file (.yaml), BModes deck (.bmi), ElastoDyn main or blade file")
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


def deck_settings(path: str) -> tuple[float | None, int | None]:
    """(rotor speed in rpm, number of modes) that INPUT carries: a BModes deck's ``rot_rpm x rpm_mult`` (0 for a
    tower) and ``modepr``; (None, None) for other inputs or when the file cannot be read (the reader then says
    why)."""
    from ..io.detect import detect_format
    try:
        if detect_format(path) != "bmodes":
            return None, None
        from ..io.bmodes import read_bmodes
        deck = read_bmodes(path)
    except InputError:
        return None, None
    return deck.rotor_speed_rpm, deck.modepr


def apply_deck_settings(args: argparse.Namespace, n_modes: bool = False) -> None:
    """Fill ``args.rpm`` (and, with ``n_modes``, ``args.n_modes``) left unset on the command line from the input
    deck's own settings, else 0 rpm and 10 modes."""
    rpm, modes = deck_settings(args.input)
    if getattr(args, "rpm", None) is None:
        args.rpm = rpm if rpm is not None else 0.0
    if n_modes and getattr(args, "n_modes", None) is None:
        args.n_modes = modes if modes is not None else 10


def read_structure(args: argparse.Namespace) -> object:
    """The blade (or, for BModes and windIO tower inputs, the tower) described by INPUT and the geometry options."""
    if args.tip_mass is not None and args.tip_mass < 0:
        raise InputError(f"must not be negative, got {args.tip_mass}", field="--tip-mass")
    geometry = Geometry(tip_radius=args.tip_radius, hub_radius=args.hub_radius, tip_mass=args.tip_mass,
                        elastodyn_main=args.elastodyn_main,
                        precone=None if args.precone_deg is None else math.radians(args.precone_deg),
                        pitch=None if args.pitch_deg is None else math.radians(args.pitch_deg))
    model = read_model(args.input, None, geometry)
    if isinstance(model, Blade) and args.root is not None:
        return model.with_(root=args.root)
    return model


def read_blade(args: argparse.Namespace) -> Blade:
    """The blade described by INPUT (any supported format) and the geometry options."""
    model = read_structure(args)
    if not isinstance(model, Blade):
        raise InputError("this input describes a tower; 'bladefem modes' takes towers", file=str(args.input))
    return model
