"""Independent references for a uniform cantilever under its own weight along its axis, for tests/test_gravity.py:
numpy and scipy only, no bladefem.

The beam ``EI w'''' - (N w')' = m omega^2 w`` with the axial force of the weight outboard, ``N(x) = n (L - x)``
(``n = m g_x``: tension hanging down, compression standing up). In ``xi = x / L`` with ``gamma = n L^3 / EI`` and
``lambda = m omega^2 L^4 / EI``: ``w'''' - gamma (1 - xi) w'' + gamma w' = lambda w``, clamped at ``xi = 0``
(``w = w' = 0``), free at ``xi = 1`` (``w'' = 0`` and, the axial force vanishing there, ``w''' = 0``).

- :func:`frequency_parameters`: shooting. The two solutions that leave the clamped root with a unit second or
  third derivative are integrated to the tip (scipy's DOP853 at 1e-13); the 2x2 determinant of their tip
  conditions vanishes at a natural frequency.
- :func:`greenhill_parameter`: Greenhill's heavy column (1881), the load at which the standing column buckles under
  its weight, ``gamma_cr = 9 j^2 / 4`` with ``j`` the first zero of the Bessel function ``J_{-1/3}`` (Timoshenko &
  Gere, Theory of Elastic Stability, 2nd ed., 1961, sec. 2.10: ``q L^3 / EI = 7.837``).
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import jv


def _tip_determinant(lam: float, gamma: float) -> float:
    def rhs(xi: float, y: np.ndarray) -> np.ndarray:
        w, w1, w2, w3 = y
        return np.array([w1, w2, w3, lam * w + gamma * (1.0 - xi) * w2 - gamma * w1])

    tips = [solve_ivp(rhs, (0.0, 1.0), start, method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]
            for start in ([0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0])]
    return float(tips[0][2] * tips[1][3] - tips[0][3] * tips[1][2])


def frequency_parameters(gamma: float, count: int = 2, upper: float = 600.0) -> np.ndarray:
    """The lowest ``count`` values of ``lambda = m omega^2 L^4 / EI`` below ``upper`` at ``gamma = n L^3 / EI``
    (a grid finds the determinant's sign changes, Brent's method the roots)."""
    grid = np.linspace(-1.0, upper, 120)
    values = np.array([_tip_determinant(lam, gamma) for lam in grid])
    roots = [brentq(_tip_determinant, a, b, args=(gamma,), xtol=1e-12, rtol=1e-15)
             for a, b, fa, fb in zip(grid[:-1], grid[1:], values[:-1], values[1:]) if fa * fb < 0]
    return np.array(roots[:count])


def greenhill_parameter() -> float:
    """``gamma_cr``: the standing column buckles under its weight at ``m g L^3 / EI = 9 j^2 / 4`` (7.8373)."""
    j = brentq(lambda z: jv(-1.0 / 3.0, z), 1.0, 2.5, xtol=1e-15)
    return 9.0 * j**2 / 4.0
