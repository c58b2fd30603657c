"""The Galerkin model with as many terms as its answer needs.

The assumed-modes model converges as its numbers of terms grow; a fixed truncation (the 5, 5, 3 of the paper the
model follows) leaves the higher frequencies too stiff (the third flap frequency of a uniform blade 1.9 % high).
:func:`converged_galerkin_modes` grows all three numbers of terms by :data:`GROWTH` until the requested frequencies
change by less than the finite elements' mesh tolerance, and says which terms it used, as the finite elements
refine their mesh.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..modal import MESH_RTOL
from ..modal.results import ModalResult
from ..sections import Blade
from .galerkin import PAPER_TERMS, galerkin_modes

__all__ = ["GROWTH", "MAX_TERMS", "converged_galerkin_modes", "grown"]

#: each step multiplies the numbers of flap, lead-lag and torsion terms by this factor (rounded up)
GROWTH = 1.5
#: the growth stops at this many flap (and lead-lag) terms: the Jacobi basis is still well conditioned there, and
#: rough section properties converge only algebraically (the NREL 5MW blade changes by ~2e-4 from 27 to 40 terms)
MAX_TERMS = 40


def grown(terms: tuple[int, int, int]) -> tuple[int, int, int]:
    """The next numbers of terms: each multiplied by :data:`GROWTH`, rounded up, at least one more."""
    return tuple(max(n + 1, math.ceil(GROWTH * n)) if n else 0 for n in terms)  # type: ignore[return-value]


def _change(coarse: ModalResult, fine: ModalResult, count: int) -> float:
    a, b = coarse.frequencies_hz[:count], fine.frequencies_hz[:count]
    floor = 1e-6 * np.max(np.abs(b))
    return float(np.max(np.abs(b - a) / np.maximum(np.abs(b), floor)))


def converged_galerkin_modes(blade: Blade, rpm: float = 0.0, n_modes: int = 10, rtol: float = MESH_RTOL,
                             start: tuple[int, int, int] = PAPER_TERMS,
                             max_terms: int = MAX_TERMS) -> ModalResult:
    """Galerkin modes of ``blade`` at ``rpm`` (rpm) with terms grown from ``start`` until the lowest ``n_modes``
    frequencies change by less than ``rtol`` (relative) from one step to the next; the finer result is returned,
    with notes naming the terms used and the last change (or saying that ``max_terms`` stopped the growth)."""
    if n_modes < 1:
        raise ValueError("n_modes must be at least 1")
    terms = tuple(start)
    while sum(terms) < n_modes and max(terms[:2]) < max_terms:
        terms = grown(terms)                                           # enough terms for the modes asked
    previous = galerkin_modes(blade, rpm, n_modes, terms)              # type: ignore[arg-type]
    while True:
        if max(terms[:2]) >= max_terms:
            note = (f"Galerkin terms stopped at {terms[0]}, {terms[1]}, {terms[2]} before the frequencies settled "
                    f"to {rtol:g}: rough section properties; the finite elements are the converged answer")
            return replace(previous, notes=previous.notes + (note,))
        terms = grown(terms)                                           # type: ignore[arg-type]
        current = galerkin_modes(blade, rpm, n_modes, terms)           # type: ignore[arg-type]
        change = _change(previous, current, min(len(previous.modes), len(current.modes)))
        if change < rtol:
            note = (f"Galerkin terms grown until the lowest {len(current.modes)} frequencies changed by less than "
                    f"{rtol:g} (last change {change:.1e})")
            return replace(current, notes=current.notes + (note,))
        previous = current
