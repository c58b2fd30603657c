"""The seed paper's published NREL 5MW frequencies and a diagnostic for its rotating table.

Seed paper 002 (a Hodges-Dowell Galerkin model of a floating-turbine blade), Table 1 (non-rotating) and Table 2
(0-15 rpm), in Hz. Table 2 stiffens far more than ``K0 + Omega^2 K2`` with the physical centrifugal tension
``N(x) = Omega^2 int_x^L f`` (docs/THEORY.md). :func:`inboard_tension_matrices` builds the one alternative that
reproduces it: the tension integrated from the root to ``x`` (the centrifugal force of the inboard part, largest at
the free tip) instead of from ``x`` to the tip. This is a diagnostic for docs/seed-comparison.md, not a model
option: bladefem's models use the physical tension.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from ..sections import Blade
from .galerkin_matrices import (
    GalerkinMatrices,
    axial_force_density,
    cell_edges,
    centrifugal_tension,
    gauss_on_cells,
    integrate,
    kinematics,
    sym,
    tension_form,
)

#: Table 1: mode -> (FAST Modes, ADAMS, the paper's Galerkin model), Hz; None where the paper has no value.
SEED_TABLE1: dict[str, tuple[float | None, float | None, float]] = {
    "1st flap": (0.6830, 0.6745, 0.6824),
    "1st edge": (1.0968, 1.1033, 1.0925),
    "2nd flap": (1.9909, 1.8394, 1.9921),
    "2nd edge": (4.0714, 3.8997, 4.0464),
    "1st torsion": (None, None, 5.7446),
}
#: Table 2: rotor speed (rpm) -> (1st flap, 2nd flap, 1st edge, 2nd edge), Hz.
SEED_TABLE2: dict[float, tuple[float, float, float, float]] = {
    0.0: (0.6824, 1.9921, 1.0925, 4.0464),
    3.0: (0.7005, 2.0304, 1.0967, 4.0584),
    6.0: (0.7442, 2.1328, 1.1088, 4.0933),
    9.0: (0.7965, 2.2732, 1.1273, 4.1484),
    12.0: (0.8486, 2.4300, 1.1504, 4.2207),
    15.0: (0.8983, 2.5923, 1.1763, 4.3072),
}
TABLE2_MODES = ("1st flap", "2nd flap", "1st edge", "2nd edge")


def inboard_tension(blade: Blade, x: NDArray, order: int = 12) -> NDArray:
    """``int_0^x f`` per Omega^2 (kg m): the centrifugal force of the blade inboard of each point ``x``."""
    t, w = np.polynomial.legendre.leggauss(order)
    x = np.asarray(x, dtype=float)
    total = np.zeros_like(x)
    # split [0, x] at the stations so that every sub-rule sees linear properties
    stations = blade.sections.span
    for x0, x1 in zip(stations[:-1], stations[1:]):
        a, b = np.minimum(x0, x), np.minimum(x1, x)
        h = 0.5 * (b - a)
        points = a[:, None] + h[:, None] * (t + 1)
        total += (axial_force_density(blade, points) * h[:, None] * w).sum(1)
    return total


def physical_tension(blade: Blade, x: NDArray) -> NDArray:
    """``int_x^L f`` plus the tip body per Omega^2 (kg m): bladefem's tension (docs/THEORY.md)."""
    edges = cell_edges(blade.sections.span)
    return centrifugal_tension(blade, edges, np.asarray(x, dtype=float), 12)


def constant_root_tension(blade: Blade, x: NDArray) -> NDArray:
    """The root tension applied along the whole span (an alternative tried against Table 2)."""
    return np.full(np.shape(x), physical_tension(blade, np.zeros(1))[0])


def linear_root_tension(blade: Blade, x: NDArray) -> NDArray:
    """The root tension falling linearly to zero at the tip (an alternative tried against Table 2)."""
    return constant_root_tension(blade, x) * (1 - np.asarray(x) / blade.length)


#: Tension distributions compared with Table 2 in docs/seed-comparison.md (per Omega^2, kg m).
TENSION_VARIANTS: dict[str, Callable[[Blade, NDArray], NDArray]] = {
    "physical, int_x^L": physical_tension,
    "root-integrated, int_0^x": inboard_tension,
    "root tension everywhere": constant_root_tension,
    "root tension falling linearly to the tip": linear_root_tension,
}


def tension_variant_matrices(blade: Blade, matrices: GalerkinMatrices,
                             tension: Callable[[Blade, NDArray], NDArray]) -> GalerkinMatrices:
    """``matrices`` with the physical tension term of ``K2`` replaced by another distribution ``tension``."""
    terms, basis = matrices.terms, matrices.basis
    order = max(terms.flap, terms.edge) + 6
    edges = cell_edges(blade.sections.span)
    quad = gauss_on_cells(edges, order)
    slopes = kinematics(quad.x, blade.length, terms, basis)[1]
    physical = integrate(slopes, tension_form(centrifugal_tension(blade, edges, quad.x, order)), quad.weights)
    replaced = integrate(slopes, tension_form(tension(blade, quad.x)), quad.weights)
    return GalerkinMatrices(M=matrices.M, K0=matrices.K0, K2=sym(matrices.K2 - physical + replaced), terms=terms,
                            basis=basis)


def inboard_tension_matrices(blade: Blade, matrices: GalerkinMatrices) -> GalerkinMatrices:
    """``matrices`` with the physical tension term of ``K2`` replaced by the root-integrated tension."""
    return tension_variant_matrices(blade, matrices, inboard_tension)


def implied_southwell(rest_hz: float, frequency_hz: NDArray, rpm: NDArray) -> NDArray:
    """Southwell coefficient ``K = (f^2 - f_0^2) / (Omega / 2 pi)^2`` implied by frequencies at rotor speeds."""
    rotor_hz = np.asarray(rpm, dtype=float) / 60.0
    return (np.asarray(frequency_hz) ** 2 - rest_hz**2) / rotor_hz**2
