"""Modal solve and results: ``modes`` at one rotor speed and ``campbell`` sweeps over rotor speed."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from ..assembly import BladeMatrices, assemble_blade
from ..sections import Blade
from .campbell import campbell_sweep, mac_matrix, track_families
from .refinement import refine_until_converged
from .results import KINDS, CampbellResult, ModalResult, Mode, ModeFamily, ModeShape
from .solve import solve_modes

#: default relative frequency change accepted by the automatic mesh refinement
MESH_RTOL = 1e-6
#: automatic refinement stops here: finer Hermite meshes gain less than round-off costs
MAX_ELEMENTS = 800


def converged_matrices(blade: Blade, n_modes: int = 10, rtol: float = MESH_RTOL, rpm: float = 0.0,
                       start: int | None = None, max_elements: int = MAX_ELEMENTS) -> BladeMatrices:
    """Matrices on the coarsest mesh (of ``start`` elements doubled) whose lowest ``n_modes`` frequencies at rotor
    speed ``rpm`` (rpm) are within ``rtol`` (relative) of the converged ones (see
    :func:`~bladefem.modal.refinement.refine_until_converged`); if refinement stops at ``max_elements`` first, the
    matrices carry a note with the last change."""
    matrices, change = refine_until_converged(
        lambda elements: assemble_blade(blade, elements),
        lambda matrices: solve_modes(matrices, rpm, n_modes).frequencies_hz,
        start or max(24, blade.sections.stations - 1), rtol, max_elements)
    if change is None:
        return matrices
    note = (f"mesh refinement stopped at {len(matrices.dofs.nodes) - 1} elements with a last frequency change "
            f"of {change:.1e} (above {rtol:g}): rough section properties; check with --elements")
    return replace(matrices, notes=matrices.notes + (note,))


def blade_matrices(blade: Blade, elements: int | None = None, n_modes: int = 10, rpm: float = 0.0) -> BladeMatrices:
    """Matrices on a mesh of about ``elements`` elements, or on a mesh converged at ``rpm`` (None)."""
    return converged_matrices(blade, n_modes, rpm=rpm) if elements is None else assemble_blade(blade, elements)


def modes(blade: Blade, rpm: float = 0.0, n_modes: int = 10, elements: int | None = None) -> ModalResult:
    """Natural frequencies and mode shapes of ``blade`` at rotor speed ``rpm`` (rpm).

    ``elements``: target number of elements over the span (stations are always nodes), or None for a mesh refined
    until the frequencies converge to 1e-6.
    """
    matrices = blade_matrices(blade, elements, n_modes, rpm)
    return solve_modes(matrices, rpm, n_modes, blade.notes + matrices.notes)


def campbell(blade: Blade, rpm: Sequence[float], n_modes: int = 6, elements: int | None = None) -> CampbellResult:
    """Modes over rotor speeds ``rpm`` (rpm), families tracked by MAC; the matrices are assembled once."""
    matrices = blade_matrices(blade, elements, n_modes, float(np.max(rpm)))
    return campbell_sweep(matrices, rpm, n_modes, blade.notes + matrices.notes)


__all__ = ["KINDS", "BladeMatrices", "CampbellResult", "ModalResult", "Mode", "ModeFamily", "ModeShape",
           "blade_matrices", "campbell", "campbell_sweep", "converged_matrices", "mac_matrix", "modes",
           "solve_modes", "track_families"]
