"""Automatic mesh refinement: double the element count until the frequencies stop changing."""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

import numpy as np
from numpy.typing import NDArray

Matrices = TypeVar("Matrices")

#: frequencies below this fraction of the highest one count as zero when comparing meshes (rigid-body modes)
ZERO_FREQUENCY = 1e-6


def refine_until_converged(assemble: Callable[[int], Matrices], frequencies: Callable[[Matrices], NDArray],
                           start: int, rtol: float, max_elements: int,
                           finer: bool = False) -> tuple[Matrices, float | None]:
    """Assemble on ``start`` elements, doubled until halving a mesh changes its frequencies by less than
    ``rtol / 2`` (relative); return that coarser mesh's matrices (or, with ``finer``, the finer mesh's) and None.

    Its error is then about the change where the error already falls as h^4, and at most twice it where rough
    section properties keep the mesh pre-asymptotic (error halving per doubling). If ``max_elements`` is reached
    first (beyond it round-off grows as h^-4), return the finest matrices and the last change.
    """
    elements = start
    coarse = assemble(elements)
    previous = frequencies(coarse)
    while True:
        elements *= 2
        fine = assemble(elements)
        current = frequencies(fine)
        floor = ZERO_FREQUENCY * np.max(np.abs(current))
        change = float(np.max(np.abs(current - previous) / np.maximum(np.abs(current), floor)))
        if change < rtol / 2:
            return (fine if finer else coarse), None
        if elements >= max_elements:
            return fine, change
        coarse, previous = fine, current
