"""The exact natural frequencies of a uniform cantilever with bend-twist (material) coupling, in the form Banerjee
gave them for composite wings (J. R. Banerjee, "Explicit analytical expressions for frequency equation and mode
shapes of composite beams", Int. J. Solids Struct. 38 (2001) 2415-2426): numpy and scipy only, no bladefem, and
none of tests/uniform_beam_exact.py (a second, independent exact solution).

Beam: bending displacement ``w``, twist ``psi``; strain energy ``1/2 int EI w''^2 + 2 K w'' psi' + GJ psi'^2``,
kinetic ``1/2 int m w_t^2 + I_a psi_t^2`` (no rotary inertia in bending, the centre of mass on the axis). Harmonic
motion at ``omega``:

    EI w'''' + K psi''' = m omega^2 w,        GJ psi'' + K w''' = -I_a omega^2 psi,

clamped at ``x = 0`` (``w = w' = psi = 0``) and free at ``x = L`` (bending moment ``EI w'' + K psi'``, shear force
``EI w''' + K psi''`` and torque ``GJ psi' + K w''`` zero). With ``w, psi ~ exp(lambda x)`` and ``s = lambda^2``,
``(EI GJ - K^2) s^3 + EI I_a omega^2 s^2 - m GJ omega^2 s - m I_a omega^4 = 0``: one positive root ``alpha^2`` and
two negative, ``-beta^2``, ``-gamma^2`` (Banerjee's sec. 2), so that
``w = C1 cosh(alpha x) + C2 sinh(alpha x) + C3 cos(beta x) + C4 sin(beta x) + C5 cos(gamma x) + C6 sin(gamma x)``
and ``psi`` follows from the first equation term by term. The six boundary conditions on ``C`` make a real 6x6
matrix whose determinant (Banerjee's frequency equation) changes sign at each natural frequency; Brent's method
finds the roots.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq


@dataclass(frozen=True)
class CoupledBeam:
    """EI, GJ, K (N m^2), m (kg/m), I_a (kg m), L (m)."""

    EI: float
    GJ: float
    K: float
    m: float
    I_a: float
    L: float


def _exponentials(beam: CoupledBeam, omega: float) -> list[list[tuple[complex, complex, complex]]]:
    """Each of the six real basis functions as terms ``(a, b, lambda)``: ``w = Re sum a exp(lambda x)``, ``psi =
    Re sum b exp(lambda x)``."""
    c = [beam.EI * beam.GJ - beam.K**2, beam.EI * beam.I_a * omega**2, -beam.m * beam.GJ * omega**2,
         -beam.m * beam.I_a * omega**4]
    s = np.sort(np.roots(c).real)              # -gamma^2 < -beta^2 < 0 < alpha^2
    assert s[0] < 0 < s[2] and s[1] < 0, s

    def psi(lam: complex) -> complex:          # psi's amplitude per unit w amplitude: from the first equation
        return -(beam.EI * lam**4 - beam.m * omega**2) / (beam.K * lam**3)

    basis: list[list[tuple[complex, complex, complex]]] = []
    alpha = np.sqrt(s[2])
    for sign in (1.0, -1.0):                   # cosh, sinh
        terms = [(0.5, alpha), (0.5 * sign, -alpha)]
        basis.append([(a, a * psi(lam), lam) for a, lam in terms])
    for root in (s[1], s[0]):                  # cos, sin of beta x and gamma x
        k = np.sqrt(-root)
        for a in (1.0, -1j):
            basis.append([(a, a * psi(1j * k), 1j * k)])
    return basis


def _derivative(terms: list[tuple[complex, complex, complex]], field: int, order: int, x: float) -> float:
    return float(sum((t[field] * t[2] ** order * np.exp(t[2] * x)).real for t in terms))


def frequency_determinant(beam: CoupledBeam, omega: float) -> float:
    """Banerjee's frequency equation: the determinant of the boundary conditions, columns scaled to unit norm."""
    L, EI, GJ, K = beam.L, beam.EI, beam.GJ, beam.K
    columns = []
    for terms in _exponentials(beam, omega):
        def d(field: int, order: int, x: float, terms=terms) -> float:
            return _derivative(terms, field, order, x)

        column = np.array([d(0, 0, 0.0), d(0, 1, 0.0), d(1, 0, 0.0),
                           EI * d(0, 2, L) + K * d(1, 1, L), EI * d(0, 3, L) + K * d(1, 2, L),
                           GJ * d(1, 1, L) + K * d(0, 2, L)])
        scale = np.array([1.0, L, 1.0, L**2 / EI, L**3 / EI, L / GJ])
        column = column * scale
        columns.append(column / np.linalg.norm(column))
    return float(np.linalg.det(np.column_stack(columns)))


def natural_frequencies(beam: CoupledBeam, count: int, upper: float, samples: int = 2000) -> np.ndarray:
    """The lowest ``count`` natural frequencies (rad/s) below ``upper``: sign changes of the determinant on a grid
    (a pole, where a column's scale jumps, is told from a root by the determinant's size on either side), refined
    by Brent's method."""
    grid = np.linspace(upper * 1e-4, upper, samples)
    values = np.array([frequency_determinant(beam, w) for w in grid])
    roots = []
    for a, b, fa, fb in zip(grid[:-1], grid[1:], values[:-1], values[1:]):
        if fa * fb < 0:
            root = brentq(lambda w: frequency_determinant(beam, w), a, b, xtol=1e-14, rtol=1e-15)
            if abs(frequency_determinant(beam, root)) < 1e-8:
                roots.append(root)
    return np.array(roots[:count])
