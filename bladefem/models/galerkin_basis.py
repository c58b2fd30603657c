"""Assumed-mode shape functions of the Galerkin blade model and their span derivatives.

Bending (flap ``w`` and lead-lag ``v``): the seed paper's polynomials ``(x/L)^(j+NP-1)``, ``j = 1..N``, with
``NP = 2`` so that deflection and slope vanish at a clamped root. They span ``xi^2 * (polynomials of degree < N)``,
``xi = x / L``. The same space is spanned, far better conditioned, by ``xi^2 P_k^(0,4)(2 xi - 1)``, ``k < N``: the
Jacobi polynomials with weight ``(1 + t)^4`` make these functions orthonormal on ``0 <= xi <= 1``, so a uniform
blade has a diagonal mass matrix. ``"jacobi"`` is the default; ``"monomial"`` reproduces the paper's functions.

Torsion: ``sin((2j - 1) pi xi / 2)``, ``j = 1..N_phi`` (zero twist at the root, zero torque at the tip).

Every function returns ``(value, first derivative, second derivative)`` with respect to ``x`` in m, each of shape
``(len(x), N)``.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import NDArray
from scipy.special import eval_jacobi

from ..errors import InputError

Basis = Literal["jacobi", "monomial"]
BASES: tuple[str, ...] = ("jacobi", "monomial")
Shapes = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]

#: Weight exponent of the Jacobi polynomials: (1 + t)^4 = (2 xi)^4 makes xi^2 P_k orthogonal on [0, 1].
JACOBI_BETA = 4


def jacobi_and_derivatives(k: int, t: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """``P_k^(0,4)(t)`` and its first two derivatives with respect to ``t``."""
    a, b = 0, JACOBI_BETA
    p = eval_jacobi(k, a, b, t)
    dp = 0.5 * (k + a + b + 1) * eval_jacobi(k - 1, a + 1, b + 1, t) if k >= 1 else np.zeros_like(t)
    ddp = (0.25 * (k + a + b + 1) * (k + a + b + 2) * eval_jacobi(k - 2, a + 2, b + 2, t)
           if k >= 2 else np.zeros_like(t))
    return p, dp, ddp


def jacobi_bending_shapes(x: NDArray, length: float, count: int) -> Shapes:
    """Orthonormal ``sqrt(2k + 5) xi^2 P_k^(0,4)(2 xi - 1)``, ``k = 0..count-1``, and x-derivatives (1/m, 1/m^2)."""
    xi = np.asarray(x, dtype=float) / length
    t = 2 * xi - 1
    value, slope, curvature = (np.empty((xi.size, count)) for _ in range(3))
    for k in range(count):
        scale = np.sqrt(2 * k + 5)
        p, dp, ddp = jacobi_and_derivatives(k, t)   # d/dxi = 2 d/dt
        value[:, k] = scale * xi**2 * p
        slope[:, k] = scale * (2 * xi * p + 2 * xi**2 * dp) / length
        curvature[:, k] = scale * (2 * p + 8 * xi * dp + 4 * xi**2 * ddp) / length**2
    return value, slope, curvature


def monomial_bending_shapes(x: NDArray, length: float, count: int) -> Shapes:
    """The seed paper's ``xi^(j+1)``, ``j = 1..count``, and x-derivatives (1/m, 1/m^2)."""
    xi = np.asarray(x, dtype=float)[:, None] / length
    power = np.arange(2, count + 2)[None, :]
    value = xi**power
    slope = power * xi ** (power - 1) / length
    curvature = power * (power - 1) * xi ** (power - 2) / length**2
    return value, slope, curvature


def bending_shapes(x: NDArray, length: float, count: int, basis: Basis = "jacobi") -> Shapes:
    """Bending shape functions of the chosen basis (both span the same space)."""
    if basis == "jacobi":
        return jacobi_bending_shapes(x, length, count)
    if basis == "monomial":
        return monomial_bending_shapes(x, length, count)
    raise InputError(f"unknown Galerkin basis '{basis}' (choose from {', '.join(BASES)})", field="basis")


def torsion_shapes(x: NDArray, length: float, count: int) -> Shapes:
    """``sin((2j - 1) pi x / 2L)``, ``j = 1..count``, and x-derivatives (1/m, 1/m^2)."""
    xi = np.asarray(x, dtype=float)[:, None] / length
    k = (2 * np.arange(1, count + 1)[None, :] - 1) * np.pi / 2
    return np.sin(k * xi), k / length * np.cos(k * xi), -(k / length) ** 2 * np.sin(k * xi)
