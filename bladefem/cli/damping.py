"""``--coriolis`` for ``bladefem modes`` and ``bladefem campbell``: the blade's quadratic eigenproblem with the
gyroscopic (Coriolis) matrix, reporting frequency and damping ratio per mode."""

from __future__ import annotations

import argparse
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING

from ..errors import InputError

if TYPE_CHECKING:                       # the CLI imports heavy modules only in the command that needs them
    from ..modal.results import CampbellResult, ModalResult
    from ..sections import Blade


def add_coriolis_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--coriolis", action="store_true",
                        help="keep the Coriolis (gyroscopic) coupling: quadratic eigenproblem, frequency and damping "
                             "ratio per mode (fe method, blades)")


def reject_for_towers(args: argparse.Namespace) -> None:
    """Towers do not rotate: --coriolis is a mistake there."""
    if getattr(args, "coriolis", False):
        raise InputError("applies to rotating blades only, not to towers", field="--coriolis")


def coriolis_modes(blade: Blade, args: argparse.Namespace) -> ModalResult:
    """Modes of the quadratic eigenproblem at ``args.rpm`` on the mesh asked for (or converged at that speed)."""
    if args.method != "fe":
        raise InputError("the Coriolis coupling is in the finite-element model only; use --method fe",
                         field="--coriolis")
    from ..modal import blade_matrices
    from ..modal.quadratic import solve_quadratic_modes
    matrices = blade_matrices(blade, args.elements, args.n_modes, args.rpm)
    return solve_quadratic_modes(matrices, args.rpm, args.n_modes, blade.notes + matrices.notes)


def coriolis_campbell(blade: Blade, args: argparse.Namespace,
                      progress: Callable[[Iterable[float]], Iterable[float]]) -> CampbellResult:
    """Campbell sweep of the quadratic eigenproblem over ``args.rpm``, families tracked by MAC on complex shapes."""
    import numpy as np

    from ..modal import blade_matrices
    from ..modal.quadratic_campbell import quadratic_campbell_sweep
    rpm = np.asarray(args.rpm)
    matrices = blade_matrices(blade, args.elements, args.n_modes, float(rpm.max()))
    return quadratic_campbell_sweep(matrices, rpm, args.n_modes, blade.notes + matrices.notes, progress)
