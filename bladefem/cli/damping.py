"""``--coriolis`` and ``--aero`` for ``bladefem modes`` (and ``--coriolis`` for ``bladefem campbell``): the blade's
quadratic eigenproblem with the gyroscopic (Coriolis) matrix and the quasi-steady aerodynamic damping and stiffness,
reporting frequency and damping ratio per mode."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable, Iterable
from dataclasses import replace
from typing import TYPE_CHECKING

from ..errors import InputError
from . import options
from .inputs import positive_int

if TYPE_CHECKING:                       # the CLI imports heavy modules only in the command that needs them
    from ..modal.results import CampbellResult, ModalResult
    from ..sections import Blade


def add_coriolis_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--coriolis", action="store_true",
                        help="keep the Coriolis (gyroscopic) coupling: quadratic eigenproblem, frequency and damping "
                             "ratio per mode (fe method, blades)")


def add_aero_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("aerodynamic damping (quasi-steady, induction frozen at the operating point)")
    group.add_argument("--aero", metavar="AERODYN_PRIMARY",
                       help="AeroDyn primary file: its first blade file and airfoils give the sections' aerodynamic "
                            "damping and stiffness at --wind-speed, --rpm and --pitch-deg")
    group.add_argument("--wind-speed", type=options.non_negative, metavar="M_S", help="wind speed along the shaft, m/s")
    group.add_argument("--blades", type=positive_int, default=3, metavar="N",
                       help="number of blades for the BEM induction (default 3)")
    group.add_argument("--quasi-steady", action="store_true",
                       help="run with the polars' static tables where the AeroDyn file asks for unsteady airfoil "
                            "aerodynamics or a dynamic wake (these modes are quasi-steady by construction)")


def reject_for_towers(args: argparse.Namespace) -> None:
    """Towers do not rotate: --coriolis and --aero are mistakes there."""
    for option in ("coriolis", "aero", "wind_speed", "quasi_steady"):
        if getattr(args, option, None) not in (None, False):
            raise InputError("applies to rotating blades only, not to towers", field=f"--{option.replace('_', '-')}")


def wants_quadratic(args: argparse.Namespace) -> bool:
    """--coriolis, --aero or --wind-speed asks for the quadratic eigenproblem (a lone --wind-speed or --quasi-steady
    is then refused)."""
    return bool(getattr(args, "coriolis", False) or getattr(args, "aero", None)
                or getattr(args, "wind_speed", None) is not None or getattr(args, "quasi_steady", False))


def quadratic_modes(blade: Blade, args: argparse.Namespace) -> ModalResult:
    """Modes of the quadratic eigenproblem at ``args.rpm`` on the mesh asked for (or converged at that speed), with
    Coriolis coupling (--coriolis) and aerodynamic damping and stiffness (--aero)."""
    option = "--coriolis" if args.coriolis else "--aero" if args.aero else "--wind-speed"
    if args.method != "fe":
        raise InputError("Coriolis coupling and aerodynamic damping are in the finite-element model only; use "
                         "--method fe", field=option)
    if args.quasi_steady and args.aero is None:
        raise InputError("applies to the aerodynamic damping of --aero only", field="--quasi-steady")
    if (args.aero is None) != (args.wind_speed is None):
        raise InputError("--aero and --wind-speed go together", field="--wind-speed" if args.aero else "--aero")
    if args.wind_speed is not None and args.wind_speed < 0:
        raise InputError(f"must not be negative, got {args.wind_speed}", field="--wind-speed")
    from ..modal import blade_matrices
    from ..modal.quadratic import solve_quadratic_modes
    matrices = blade_matrices(blade, args.elements, args.n_modes, args.rpm)
    notes = blade.notes + matrices.notes
    damping = stiffness = None
    if args.aero is not None:
        from ..builders.aerodyn_rotor import aerodyn_rotor, require_root_off_axis
        from ..models.blade_aero import aero_matrices, operating_point
        way = frozenset({"--quasi-steady"})
        rotor = aerodyn_rotor(args.aero, blade, args.blades, way, way if args.quasi_steady else frozenset())
        require_root_off_axis(rotor)
        point = operating_point(rotor, args.wind_speed, args.rpm * math.pi / 30.0, blade.pitch, blade)
        damping, stiffness = aero_matrices(matrices, point)
        left_out = rotor.notes[1:]                      # the first names the files; the next note does that
        notes += left_out + ((f"quasi-steady aerodynamic damping and stiffness from {args.aero} at "
                              f"{args.wind_speed:g} m/s, pitch {math.degrees(blade.pitch):g} deg, {args.blades} "
                              "blades (BEM induction frozen)"),)
    result = solve_quadratic_modes(matrices, args.rpm, args.n_modes, notes, damping, stiffness, args.coriolis)
    return replace(result, notes=result.notes + _pitch_rate_notes(result)) if args.aero is not None else result


#: torsion share of a mode above which its quasi-steady damping misses the pitch-rate term that matters
TORSION_SHARE = 0.1


def _pitch_rate_notes(result: ModalResult) -> tuple[str, ...]:
    """A note for each negatively damped mode with torsion: the quasi-steady model (AeroDyn's BEM without unsteady
    airfoil aerodynamics, as OpenFAST linearizes it) has no pitch-rate (three-quarter-chord) damping, which
    ``bladefem flutter`` adds with the unsteady lift."""
    return tuple(
        f"mode {k}: damping {mode.damping_ratio:.3g} with torsion share {mode.energy_fractions.get('torsion', 0.0):.2f}"
        ": the quasi-steady aerodynamics here (AeroDyn's BEM without unsteady airfoil aerodynamics, as OpenFAST "
        "linearizes it) leave out the pitch-rate (three-quarter-chord) damping of twisting sections; 'bladefem "
        "flutter' adds it with the unsteady lift"
        for k, mode in enumerate(result.modes, 1)
        if mode.damping_ratio is not None and mode.damping_ratio < 0
        and mode.energy_fractions.get("torsion", 0.0) > TORSION_SHARE)


def coriolis_campbell(blade: Blade, args: argparse.Namespace,
                      progress: Callable[[Iterable[float]], Iterable[float]]) -> CampbellResult:
    """Campbell sweep of the quadratic eigenproblem over ``args.rpm``, families tracked by MAC on complex shapes."""
    import numpy as np

    from ..modal import blade_matrices
    from ..modal.quadratic_campbell import quadratic_campbell_sweep
    rpm = np.asarray(args.rpm)
    matrices = blade_matrices(blade, args.elements, args.n_modes, float(rpm.max()))
    return quadratic_campbell_sweep(matrices, rpm, args.n_modes, blade.notes + matrices.notes, progress)
