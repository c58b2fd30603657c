"""The p-k iteration on a small (modal) system: the structure's ``M, C, K`` and aerodynamic matrices that depend on
the reduced frequency through Theodorsen's function.

For a mode tracked from a guess ``(omega, shape)``: evaluate the aerodynamic matrices at ``p = i omega`` (their
``C(k)`` at ``k = omega b / W``), solve the quadratic eigenproblem ``(p^2 (M + M_a) + p (C + D) + K + K_a) q = 0`` in
first-order form, take the root whose shape is closest (MAC) to the tracked one, and repeat with its damped
frequency ``Im(p)`` until that no longer changes. At zero damping ``p = i omega`` is exact, so the flutter point of
the p-k iteration is the flutter point of Theodorsen's theory (Hassig 1971, J. Aircraft 8(11) 885-889).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

#: relative change of the damped frequency that ends the iteration
PK_RTOL = 1e-9
#: iterations before the p-k loop gives up (it converges in 3 to 8 where the frequency is well separated)
PK_ITERATIONS = 60

Aero = Callable[[complex], tuple[NDArray, NDArray, NDArray]]


@dataclass(frozen=True)
class PkRoot:
    """One converged p-k root: ``p`` (1/s), its shape ``q`` (modal coordinates, unit norm), the iterations used and
    whether the frequency converged."""

    p: complex
    shape: NDArray
    iterations: int
    converged: bool

    @property
    def frequency(self) -> float:
        """Damped frequency Im(p), rad/s."""
        return float(self.p.imag)

    @property
    def damping_ratio(self) -> float:
        """-Re(p) / |p|: negative is unstable."""
        return float(-self.p.real / abs(self.p)) if self.p != 0 else 0.0


def state_roots(M: NDArray, C: NDArray, K: NDArray) -> tuple[NDArray, NDArray]:
    """Eigenvalues and displacement shapes (columns) of ``(p^2 M + p C + K) q = 0`` (dense, first-order form)."""
    n = M.shape[0]
    lower = -np.linalg.solve(M, np.hstack([K, C]))             # numpy's LAPACK call: microseconds at this size
    A = np.block([[np.zeros((n, n)), np.eye(n)], [lower]])
    values, vectors = np.linalg.eig(A)
    shapes = vectors[:n]
    return values, shapes / np.linalg.norm(shapes, axis=0)


def mac(a: NDArray, b: NDArray) -> NDArray:
    """Modal assurance criterion of the vector ``a`` against the columns of ``b`` (complex)."""
    return np.abs(b.conj().T @ a) ** 2 / (np.real(np.vdot(a, a)) * np.real(np.einsum("ij,ij->j", b.conj(), b)))


def pk_root(M: NDArray, C: NDArray, K: NDArray, aero: Aero, omega: float, shape: NDArray,
            rtol: float = PK_RTOL, taken: tuple[complex, ...] = ()) -> PkRoot:
    """The p-k root of the mode with damped frequency near ``omega`` (rad/s, > 0) and shape near ``shape``
    (module docstring); roots equal (to 1e-6 relative) to one of ``taken`` (other modes' converged roots) are not
    candidates, so that two tracked modes do not settle on one root."""
    p, q = complex(0.0, omega), shape
    history: list[tuple[float, float]] = []                  # (trial frequency, frequency of the root found there)
    for iteration in range(1, PK_ITERATIONS + 1):
        M_a, D_a, K_a = aero(complex(0.0, abs(p.imag)))
        values, shapes = state_roots(M + M_a, C + D_a, K + K_a)
        upper = values.imag > 0
        for other in taken:
            upper &= np.abs(values - other) > 1e-6 * abs(other)
        if not upper.any():
            break
        candidates, candidate_shapes = values[upper], shapes[:, upper]
        score = mac(q, candidate_shapes) - 1e-3 * np.abs(candidates.imag - p.imag) / max(abs(p.imag), 1e-12)
        best = int(np.argmax(score))
        new, q = candidates[best], candidate_shapes[:, best]
        if abs(new.imag - p.imag) <= rtol * abs(new.imag):
            return PkRoot(new, q, iteration, True)
        history.append((p.imag, new.imag))
        p = complex(new.real, secant(history))
    return PkRoot(p, q, PK_ITERATIONS, False)


def secant(history: list[tuple[float, float]]) -> float:
    """The next trial frequency of the fixed point ``omega = g(omega)``: the secant step on ``g(omega) - omega``
    through the last two trials when it stays between their images (superlinear), else the plain image ``g``."""
    trial, image = history[-1]
    if len(history) < 2:
        return image
    before, before_image = history[-2]
    slope = ((image - trial) - (before_image - before)) / (trial - before) if trial != before else 0.0
    if slope == 0.0:
        return image
    step = trial - (image - trial) / slope
    low, high = sorted((image, before_image))
    spread = max(high - low, abs(image - trial))
    return step if low - spread <= step <= high + spread and step > 0 else image
