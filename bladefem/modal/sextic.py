"""ElastoDyn's mode-shape polynomial ``phi(x) = sum_{i=2..6} c_i x^i`` on the normalised span, tip-normalised
(``sum c_i = 1``), and its fits to a target shape.

:func:`fit_sextic` is the plain constrained least-squares fit of the displacement. A displacement fit can miss the
curvature: its Rayleigh quotient, which is what a Rayleigh-Ritz model such as ElastoDyn makes of it, may be far
from the target's frequency (the NREL 5MW second flap mode: +5.6 %). :func:`fit_sextic_at_frequency` fits the
displacement under the further constraint that the polynomial's own generalized stiffness and mass give the target
frequency exactly: ``c^T (K - w^2 M) c = 0`` with ``K``, ``M`` the quadratic forms of the consumer's integrals.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

POWERS = np.arange(2, 7)
#: Gauss points per finite element: (sextic - cubic)^2 is a polynomial of degree 12, integrated exactly by 7.
GAUSS_POINTS = 7


def polynomial(coefficients: NDArray, x: NDArray, derivative: int = 0) -> NDArray:
    """``d^k/dx^k sum_i c_i x^i`` (i = 2..6) at normalised positions ``x``."""
    x = np.asarray(x, dtype=float)
    total = np.zeros_like(x)
    for c, power in zip(coefficients, POWERS):
        if power >= derivative:
            total = total + c * math.perm(int(power), derivative) * x ** (power - derivative)
    return total


def monomials(x: NDArray, derivative: int = 0) -> NDArray:
    """(len(x), 5): the derivative of each x^i, i = 2..6, so that ``polynomial(c, x, k) = monomials(x, k) @ c``."""
    return np.stack([polynomial(np.eye(5)[i], x, derivative) for i in range(5)], axis=-1)


def composite_gauss(breakpoints: NDArray, order: int = GAUSS_POINTS) -> tuple[NDArray, NDArray]:
    """Points and weights of ``order``-point Gauss-Legendre rules on every interval between ``breakpoints``."""
    xi, wi = np.polynomial.legendre.leggauss(order)
    a, b = breakpoints[:-1, None], breakpoints[1:, None]
    points = (a + b) / 2 + (b - a) / 2 * xi[None, :]
    weights = (b - a) / 2 * wi[None, :]
    return points.ravel(), weights.ravel()


@dataclass(frozen=True)
class PolynomialFit:
    """A tip-normalised sextic and how well it reproduces a target shape.

    coefficients : c_2 .. c_6 (sum exactly 1 up to rounding)
    rms_error : sqrt(int_0^1 (phi - y)^2 dx), y the target normalised by its tip displacement
    tip_slope_error : phi'(1) - y'(1), slopes per unit normalised span (so relative to tip displacement / length)
    condition_number : 2-norm condition number of the weighted least-squares design matrix
    frequency_preserved : True when the fit was constrained to the target's frequency
    """

    coefficients: NDArray[np.float64]
    rms_error: float
    tip_slope_error: float
    condition_number: float
    frequency_preserved: bool = False


def least_squares_system(points: NDArray, weights: NDArray, target: NDArray) -> tuple[NDArray, NDArray]:
    """The weighted design matrix and right-hand side over the free coefficients c_2..c_5 (c_6 = 1 - their
    sum)."""
    basis = points[:, None] ** POWERS[None, :-1] - points[:, None] ** 6      # x^i - x^6, i = 2..5
    root_w = np.sqrt(weights)
    return root_w[:, None] * basis, root_w * (target - points**6)


def fit_sextic(points: NDArray, weights: NDArray, target: NDArray, tip_slope: float) -> PolynomialFit:
    """Least-squares fit of ``sum c_i x^i`` with ``sum c_i = 1`` to ``target`` (tip-normalised) at quadrature
    ``points`` with ``weights`` over [0, 1]; ``tip_slope`` is the target's slope at x = 1."""
    design, rhs = least_squares_system(points, weights, target)
    free, *_ = np.linalg.lstsq(design, rhs, rcond=None)
    coefficients = np.append(free, 1.0 - free.sum())
    return quality(coefficients, points, weights, target, tip_slope, float(np.linalg.cond(design)))


def fit_sextic_at_frequency(points: NDArray, weights: NDArray, target: NDArray, tip_slope: float,
                            stiffness: NDArray, mass: NDArray, omega: float) -> PolynomialFit:
    """The least-squares fit of :func:`fit_sextic` constrained to the frequency ``omega`` (rad/s) of the quadratic
    forms ``stiffness`` and ``mass`` (5 x 5 over c_2..c_6: ``K(c) = c^T stiffness c``, ``M(c) = c^T mass c``).
    When no sextic has that frequency (it lies below the lowest Rayleigh quotient the sextics reach) the result
    is the plain fit, with ``frequency_preserved`` False.

    With ``c = P z + e`` (``sum c = 1``) the Lagrange condition of ``min |A z - b|^2`` subject to
    ``g(z) = c^T Q c = 0``, ``Q = stiffness - omega^2 mass``, is ``(A^T A + mu P^T Q P) z = A^T b - mu P^T Q e``; the
    multiplier ``mu`` is found by bracketing the sign change of ``g`` from the plain fit (``mu = 0``) while
    ``A^T A + mu P^T Q P`` stays positive definite.
    """
    design, rhs = least_squares_system(points, weights, target)
    P = np.vstack([np.eye(4), -np.ones((1, 4))])
    e = np.eye(5)[4]
    Q = stiffness - omega**2 * mass
    scale = np.linalg.norm(design.T @ design) / max(np.linalg.norm(P.T @ Q @ P), 1e-300)
    normal, right = design.T @ design, design.T @ rhs
    QP, Qe = P.T @ Q @ P * scale, P.T @ Q @ e * scale

    def coefficients(mu: float) -> NDArray:
        return P @ np.linalg.solve(normal + mu * QP, right - mu * Qe) + e

    def g(mu: float) -> float:
        c = coefficients(mu)
        return float(c @ Q @ c) / float(c @ mass @ c)

    # the multipliers keeping the normal matrix positive definite form an interval around 0
    bounds = np.linalg.eigvals(np.linalg.solve(normal, -QP)).real
    upper = 1.0 / bounds[bounds > 0].max() if np.any(bounds > 0) else np.inf
    lower = 1.0 / bounds[bounds < 0].min() if np.any(bounds < 0) else -np.inf
    start = g(0.0)
    if start == 0.0:
        return quality(coefficients(0.0), points, weights, target, tip_slope, float(np.linalg.cond(design)), True)
    edge = upper if start > 0 else lower
    trials = [f * edge for f in (0.5, 0.9, 0.99, 0.999, 0.9999, 0.99999)] if math.isfinite(edge) else \
        [math.copysign(10.0**k, edge) for k in range(-3, 13)]
    mu = 0.0
    for trial in trials:
        if np.sign(g(trial)) != np.sign(start):
            from scipy.optimize import brentq           # imported here: scipy.optimize takes 0.1 s to import
            mu = brentq(g, mu, trial, xtol=1e-15 * abs(trial), rtol=1e-14)
            return quality(coefficients(mu), points, weights, target, tip_slope, float(np.linalg.cond(design)),
                           True)
        mu = trial
    return quality(coefficients(0.0), points, weights, target, tip_slope, float(np.linalg.cond(design)))


def quality(coefficients: NDArray, points: NDArray, weights: NDArray, target: NDArray, tip_slope: float,
            condition_number: float = float("nan"), frequency_preserved: bool = False) -> PolynomialFit:
    """RMS and tip-slope errors of given coefficients against a tip-normalised target."""
    residual = polynomial(coefficients, points) - target
    rms = math.sqrt(float(np.sum(weights * residual**2)))
    slope_error = float(polynomial(coefficients, np.array([1.0]), 1)[0]) - tip_slope
    return PolynomialFit(np.asarray(coefficients, dtype=float), rms, slope_error, condition_number,
                         frequency_preserved)
