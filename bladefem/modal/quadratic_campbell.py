"""Campbell sweep of the quadratic eigenproblem (Coriolis coupling): modes over rotor speed, families followed by
the MAC of their complex shapes.

Like :func:`~bladefem.modal.campbell.campbell_sweep`, it solves the lowest and highest speeds in full
(:func:`~bladefem.modal.quadratic.full_pairs`) and every speed first in the Ritz basis of those shapes (their real
and imaginary parts): a dense problem of a few dozen DOFs. Where a Ritz pair's residual exceeds
:data:`~bladefem.modal.campbell.RITZ_RESIDUAL` the speed gets a full solve whose shapes join the basis. Without
damping matrices ``Q(i omega)`` is Hermitian, so Ritz values err by about the square of the residual.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace

import numpy as np

from ..assembly import BladeMatrices
from .campbell import RITZ_RESIDUAL, TRACKING_MARGIN, ritz_basis, track_families
from .quadratic import full_pairs, quadratic_problem, quadratic_result, ritz_pairs
from .results import CampbellResult, ModalResult


def quadratic_campbell_sweep(matrices: BladeMatrices, rpm: Sequence[float], n_modes: int = 6,
                             notes: tuple[str, ...] = (),
                             progress: Callable[[Iterable[float]], Iterable[float]] | None = None) -> CampbellResult:
    """Modes with Coriolis coupling at each rotor speed in ``rpm`` (rpm); families followed by MAC on the complex
    shapes, each with its frequencies and damping ratios. ``progress`` optionally wraps the loop over speeds."""
    rpm = np.asarray(rpm, dtype=float)
    count = n_modes + TRACKING_MARGIN
    M = matrices.free_parts[2]

    def full(speed: float) -> tuple[ModalResult, np.ndarray]:
        problem = quadratic_problem(matrices, speed)
        values, vectors = full_pairs(problem, count)
        return quadratic_result(matrices, problem, speed, values, vectors, notes), vectors

    anchors = [full(speed)[1] for speed in (rpm.min(), rpm.max())]
    basis = ritz_basis([part for vectors in anchors for part in (vectors.real, vectors.imag)], M)
    results = []
    for speed in (progress or iter)(rpm):
        problem = quadratic_problem(matrices, speed)
        values, vectors = ritz_pairs(problem, basis, count)
        if len(values) < count or problem.residuals(values, vectors).max() > RITZ_RESIDUAL:
            result, vectors = full(speed)
            basis = ritz_basis([basis, vectors.real, vectors.imag], M)
            results.append(result)
        else:
            results.append(quadratic_result(matrices, problem, speed, values, vectors, notes))
    n_families = min(n_modes, len(results[0].modes))
    families = [replace(family, damping_ratios=np.array([results[k].modes[i].damping_ratio
                                                         for k, i in enumerate(family.indices)]))
                for family in track_families(results, M, n_families)]
    return CampbellResult(rpm=rpm, families=families, results=results, notes=notes)
