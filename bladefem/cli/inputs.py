"""Options shared by the subcommands that read a blade or a tower: input file, geometry, rotor speeds, mesh.

Only the standard library is imported here (argument parsing stays fast); the readers are imported when a
subcommand runs.
"""

from __future__ import annotations

import argparse
import math

from ..errors import InputError
from . import options

#: root conditions of a blade (:data:`bladefem.sections.ROOTS`, repeated so that parsing imports no numpy)
ROOTS: tuple[str, ...] = ("cantilever", "hinged")
PARTS: tuple[str, ...] = ("blade", "tower")


def add_blade_options(parser: argparse.ArgumentParser) -> None:
    """INPUT, ``--part``, the blade geometry options (for ElastoDyn blade files, and overrides), the tower options
    and ``--elements``."""
    parser.add_argument("input", metavar="INPUT",
                        help="bladefem case (blade or tower) or windIO file (.yaml, 1.x or 2.x), BModes deck "
                             "(.bmi), ElastoDyn main, blade or tower file, BeamDyn primary or blade file, HAWC2 st "
                             "(.st) or .htc file")
    parser.add_argument("--part", choices=PARTS,
                        help="blade or tower of an input that holds both (ElastoDyn main, windIO; default blade)")
    geometry = parser.add_argument_group("blade geometry (ElastoDyn blade files; override case-file values)")
    geometry.add_argument("--tip-radius", type=options.positive, metavar="M", help="rotor tip radius TipRad, m")
    geometry.add_argument("--hub-radius", type=options.non_negative, metavar="M", help="hub radius HubRad, m")
    geometry.add_argument("--precone-deg", "--precone", dest="precone_deg", type=options.finite, metavar="DEG",
                          help="precone angle, degrees")
    geometry.add_argument("--pitch-deg", "--pitch", dest="pitch_deg", type=options.finite, metavar="DEG",
                          help="blade pitch angle, degrees (positive to feather)")
    geometry.add_argument("--tip-mass", type=options.non_negative, metavar="KG",
                          help="tip (brake) point mass, kg; for an ElastoDyn tower file, the tower-top point mass")
    geometry.add_argument("--elastodyn-main", metavar="FILE",
                          help="ElastoDyn main file to read TipRad, HubRad, PreCone(1), TipMass(1) (blade) or "
                               "TowerHt and the rotor-nacelle body (tower) from")
    geometry.add_argument("--htc", metavar="FILE",
                          help="HAWC2 .htc file whose blade body (c2_def) gives a HAWC2 st INPUT its twist")
    add_sections_option(geometry)
    geometry.add_argument("--root", choices=ROOTS, help="root condition (default: from the case, else cantilever)")
    add_tower_options(parser)
    parser.add_argument("--elements", type=options.elements, metavar="N",
                        help="target number of elements along the span (default: refined until converged)")


#: how six-by-six blade sections reach the FE (:data:`bladefem.builders.section6x6.SECTION_MODELS`)
SECTION_MODELS: tuple[str, ...] = ("full", "condensed", "reduced")


def add_sections_option(group: argparse._ActionsContainer) -> None:
    group.add_argument("--sections", choices=SECTION_MODELS,
                       help="six-by-six blades (BeamDyn, HAWC2, windIO): 'full' (default) puts the whole 6x6 "
                            "stiffness and mass in the FE (every coupling and the transverse shear: a Timoshenko "
                            "beam), 'condensed' the same with the shear condensed (Euler-Bernoulli), 'reduced' "
                            "bladefem's "
                            "diagonal beam (tension centre, principal axes, chordwise c.m.; drops the couplings the "
                            "notes name)")
    group.add_argument("--straight-axis", action="store_const", const="straight", dest="axis",
                       help="six-by-six blades: straighten the reference axis onto the pitch axis (prebend and sweep "
                            "left out, the length the pitch axis's, as ElastoDyn and a straightened BeamDyn have it; "
                            "default: the curved axis of the file)")


def add_gravity_options(parser: argparse.ArgumentParser) -> None:
    """``--gravity`` and ``--azimuth-deg``: the blade's weight at one rotor azimuth (``modes``, ``campbell``)."""
    group = parser.add_argument_group("gravity (blades; default off)")
    group.add_argument("--gravity", action="store_true",
                       help="the blade's weight (9.80665 m/s^2) at --azimuth-deg: its axial force's geometric "
                            "stiffness (a blade hanging down stiffens, one standing up softens), and with "
                            "--operating-point its static deflection and its static moments' stiffness; the shaft "
                            "taken horizontal (tilt not modelled), the azimuth frozen (a rotating blade as it "
                            "passes that azimuth)")
    group.add_argument("--azimuth-deg", dest="gravity_azimuth_deg", type=options.finite, metavar="DEG",
                       help="with --gravity: rotor azimuth of the blade, degrees: 0 pointing up (default), 180 "
                            "pointing down, 90 horizontal with the leading edge down (the azimuth grows in the "
                            "direction of rotation)")


def with_gravity(args: argparse.Namespace, blade: object) -> object:
    """``blade`` with its weight at ``--azimuth-deg`` when ``--gravity`` is given."""
    azimuth = getattr(args, "gravity_azimuth_deg", None)
    if not getattr(args, "gravity", False):
        if azimuth is not None:
            raise InputError("--azimuth-deg places the blade's weight: add --gravity", field="--azimuth-deg")
        return blade
    from ..sections import Gravity
    gravity = Gravity(azimuth=math.radians(azimuth or 0.0))
    note = (f"gravity {gravity.acceleration:g} m/s^2 at {azimuth or 0.0:g} deg azimuth: the weight's axial force "
            "in the stiffness (and its deflection at the operating point); shaft tilt not modelled")
    return blade.with_(gravity=gravity, notes=blade.notes + (note,))


def add_tower_options(parser: argparse.ArgumentParser) -> None:
    """Options for towers (YAML ``kind: tower``, ElastoDyn tower files, BModes and windIO towers)."""
    group = parser.add_argument_group("towers")
    group.add_argument("--tower-height", type=options.positive, metavar="M",
                       help="flexible tower length for an ElastoDyn tower file without --elastodyn-main, m")
    group.add_argument("--no-gravity", action="store_true", help="leave out gravity (axial load, pendulum effect)")
    group.add_argument("--point-top-mass", action="store_true",
                       help="with an ElastoDyn main file: the rotor-nacelle mass as a point mass, as ElastoDyn uses "
                            "it (default: a rigid body with offset and inertia)")
    group.add_argument("--rotor-azimuth-deg", type=options.finite, default=0.0, metavar="DEG",
                       help="azimuth of blade 1 for the rigid rotor-nacelle body, degrees (default 0)")


def positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got '{text}'") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got '{text}'")
    return value


def rpm_range(text: str) -> tuple[float, ...]:
    """START:STOP:COUNT (rpm) -> evenly spaced rotor speeds, rpm."""
    parts = text.split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected START:STOP:COUNT in rpm (e.g. 0:15:16), got '{text}'") from None
    if not (math.isfinite(start) and math.isfinite(stop)) or count < 1 or start < 0 or stop < start:
        raise argparse.ArgumentTypeError(f"need 0 <= START <= STOP and COUNT >= 1, got '{text}'")
    if count == 1:
        return (start,)
    return tuple(start + (stop - start) * k / (count - 1) for k in range(count))


def rpm_band(text: str) -> tuple[float, float]:
    """R or LOW:HIGH (rpm) -> (low, high): an operating speed or an operating range."""
    parts = text.split(":")
    try:
        if len(parts) not in (1, 2):
            raise ValueError
        low, high = float(parts[0]), float(parts[-1])
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a rotor speed R or a range LOW:HIGH in rpm, got '{text}'") from None
    if not (math.isfinite(low) and math.isfinite(high)) or low < 0 or high < low:
        raise argparse.ArgumentTypeError(f"need 0 <= LOW <= HIGH, got '{text}'")
    return low, high


def deck_settings(path: str) -> tuple[float | None, int | None]:
    """(rotor speed in rpm, number of modes) that INPUT carries: a BModes deck's ``rot_rpm x rpm_mult`` (0 for a
    tower) and ``modepr``; (None, None) for other inputs or when the file cannot be read (the reader then says
    why)."""
    from ..builders.detect import detect_format
    try:
        if detect_format(path) != "bmodes":
            return None, None
        from ..formats.bmodes import read_bmodes
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
    """The blade (:class:`bladefem.sections.Blade`) or tower (:class:`bladefem.sections.tower.Tower`) described by
    INPUT and the options; ``--part`` chooses for inputs that hold both."""
    from ..builders.detect import Geometry, read_model
    from ..sections import Blade
    from ..sections.tower import as_tower
    from .tower import is_tower_input, read_tower

    if args.tip_mass is not None and not (math.isfinite(args.tip_mass) and args.tip_mass >= 0):
        raise InputError(f"must be a non-negative number, got {args.tip_mass}", field="--tip-mass")
    part = getattr(args, "part", None)
    if part == "tower" or (part is None and is_tower_input(args.input)):
        model = read_tower(args)
    else:
        geometry = Geometry(tip_radius=args.tip_radius, hub_radius=args.hub_radius, tip_mass=args.tip_mass,
                            elastodyn_main=args.elastodyn_main, htc=getattr(args, "htc", None),
                            sections=getattr(args, "sections", None), axis=getattr(args, "axis", None),
                            precone=None if args.precone_deg is None else math.radians(args.precone_deg),
                            pitch=None if args.pitch_deg is None else math.radians(args.pitch_deg))
        model = read_model(args.input, part, geometry)
    options.check_applicable(args, tower=not isinstance(model, Blade))
    if isinstance(model, Blade):
        return with_gravity(args, model.with_(root=args.root) if args.root is not None else model)
    if part == "blade":
        raise InputError("this input describes a tower, not a blade", file=str(args.input), field="--part")
    tower = as_tower(model)
    return tower.with_(gravity=0.0) if getattr(args, "no_gravity", False) else tower


def is_blade(model: object) -> bool:
    from ..sections import Blade
    return isinstance(model, Blade)
