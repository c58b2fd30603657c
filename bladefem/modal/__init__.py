"""Modal solve and results: ``modes`` at one rotor speed and ``campbell`` sweeps over rotor speed."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from ..assembly import BladeMatrices, assemble_blade, blade_graded_nodes, subdivide
from ..limits import check_elements, check_n_modes, check_rpm, check_speeds
from ..sections import Blade
from .campbell import RITZ_GUARD, TRACKING_MARGIN, campbell_sweep, mac_matrix, track_families
from .estimate import frequency_errors
from .refinement import MeshChoice, Solved, choose_mesh
from .results import KINDS, CampbellResult, ModalResult, Mode, ModeFamily, ModeShape
from .solve import SolverError, cached_pairs, roundoff_errors, rpm_to_rad_s, solve_modes

#: default relative frequency error accepted by the automatic mesh choice
MESH_RTOL = 1e-6
#: target element count of the starting mesh, before grading by the section properties
START_ELEMENTS = 24
#: the automatic mesh choice stays at or below this many elements (beyond it, round-off and cost grow)
MAX_ELEMENTS = 1600


def converged_mesh(blade: Blade, n_modes: int = 10, rtol: float = MESH_RTOL, rpm: float = 0.0,
                   start: int | None = None, max_elements: int = MAX_ELEMENTS) -> MeshChoice[BladeMatrices]:
    """The coarsest nested refinement of the graded starting mesh (:func:`~bladefem.assembly.blade_graded_nodes`
    on ``start`` elements) whose lowest ``n_modes`` frequencies at rotor speed ``rpm`` (rpm) are estimated within
    ``rtol`` (relative) of the converged ones, by :func:`~bladefem.modal.refinement.choose_mesh`."""
    nodes = blade_graded_nodes(blade, start or START_ELEMENTS)
    count = n_modes + TRACKING_MARGIN + RITZ_GUARD     # the Campbell sweep's anchor at this speed is this solve

    def solve(matrices: BladeMatrices) -> Solved:
        values, vectors = cached_pairs(matrices, rpm, count)
        K, _ = matrices.reduced(rpm_to_rad_s(rpm))
        frequencies = np.sign(values) * np.sqrt(np.abs(values)) / (2 * np.pi)
        return Solved(frequencies[:n_modes], roundoff_errors(K, values, vectors)[:n_modes], (values, vectors))

    def predict(matrices: BladeMatrices, solved: Solved) -> NDArray:
        values, vectors = solved.result
        return frequency_errors(matrices, values[:n_modes], vectors[:, :n_modes])

    return choose_mesh(lambda level: assemble_blade(blade, nodes=subdivide(nodes, level)), solve, rtol,
                       max(2, max_elements // (len(nodes) - 1)), predict)


def converged_matrices(blade: Blade, n_modes: int = 10, rtol: float = MESH_RTOL, rpm: float = 0.0,
                       start: int | None = None, max_elements: int = MAX_ELEMENTS) -> BladeMatrices:
    """Matrices on the automatically chosen mesh (:func:`converged_mesh`); when the tolerance could not be reached
    the matrices carry a note with the estimated error."""
    choice = converged_mesh(blade, n_modes, rtol, rpm, start, max_elements)
    if choice.note is None:
        return choice.matrices
    return replace(choice.matrices, notes=choice.matrices.notes + (choice.note,))


def _require_blade(model: object, name: str) -> None:
    if not isinstance(model, Blade):
        raise TypeError(f"bladefem.modal.{name} solves blades, got a {type(model).__name__}; bladefem.{name} takes "
                        "blades and towers")


def blade_matrices(blade: Blade, elements: int | None = None, n_modes: int = 10, rpm: float = 0.0) -> BladeMatrices:
    """Matrices on a mesh of about ``elements`` elements, or on a mesh converged at ``rpm`` (None). Arguments
    outside :mod:`bladefem.limits` raise a ``ValueError``."""
    rpm, n_modes, elements = check_rpm(rpm), check_n_modes(n_modes), check_elements(elements)
    return converged_matrices(blade, n_modes, rpm=rpm) if elements is None else assemble_blade(blade, elements)


def modes(blade: Blade, rpm: float = 0.0, n_modes: int = 10, elements: int | None = None) -> ModalResult:
    """Natural frequencies and mode shapes of ``blade`` at rotor speed ``rpm`` (rpm).

    ``elements``: target number of elements over the span (stations are always nodes), or None for the mesh
    chosen automatically so that the frequencies are within 1e-6 of the converged ones. For blades and towers
    alike: :func:`bladefem.modes`. Arguments outside :mod:`bladefem.limits` raise a ``ValueError``.
    """
    _require_blade(blade, "modes")
    matrices = blade_matrices(blade, elements, n_modes, rpm)
    return solve_modes(matrices, float(rpm), n_modes, blade.notes + matrices.notes)


def campbell(blade: Blade, rpm: Sequence[float], n_modes: int = 6, elements: int | None = None) -> CampbellResult:
    """Modes over rotor speeds ``rpm`` (rpm), families tracked by MAC; the matrices are assembled once. For blades
    and towers alike: :func:`bladefem.campbell`. Arguments outside :mod:`bladefem.limits` raise a ``ValueError``."""
    _require_blade(blade, "campbell")
    speeds = check_speeds(rpm, check_n_modes(n_modes), check_elements(elements))
    matrices = blade_matrices(blade, elements, n_modes, max(speeds))
    return campbell_sweep(matrices, speeds, n_modes, blade.notes + matrices.notes)


__all__ = ["KINDS", "BladeMatrices", "CampbellResult", "MeshChoice", "ModalResult", "Mode", "ModeFamily",
           "ModeShape", "SolverError", "blade_matrices", "campbell", "campbell_sweep", "converged_matrices",
           "converged_mesh", "mac_matrix", "modes", "solve_modes", "track_families"]
