"""Quadratic eigenproblem of the rotating blade with Coriolis (gyroscopic) and optional extra damping/stiffness:

    (lambda^2 M + lambda C + K) x = 0,    C = Omega G (+ D),    K = K0 + Omega^2 K2 (+ K_a)

``G`` is the skew gyroscopic matrix (:func:`~bladefem.assembly.terms.coriolis`), ``D`` and ``K_a`` optional
free-DOF matrices (e.g. aerodynamic damping and stiffness). A mode is an eigenvalue
``lambda = -zeta omega_n + i omega_n sqrt(1 - zeta^2)`` with its (complex) shape: undamped natural frequency
``omega_n = |lambda|``, damped frequency ``Im(lambda)``, damping ratio ``zeta = -Re(lambda) / |lambda|``.

The solver (:func:`full_pairs`) works on the first-order (state-space) form of size 2n, by shift-invert
Arnoldi (ARPACK) about ``sigma`` near zero with one sparse LU of ``sigma^2 M + sigma C + K`` (dense LAPACK for
small systems). Measured on the NREL 5MW blade (268 to 908 free DOFs) it costs about what the symmetric solve does
(20-30 ms) and its residuals sit at the symmetric solver's round-off floor, while Rayleigh-Ritz on the undamped
modes and their static corrections ``K^-1 C V`` took three to five times longer and left residuals of 5e-6
(truncation; frequencies within 4e-9 of the full solve). :func:`ritz_pairs` (Rayleigh-Ritz in a given basis)
remains for modal reductions, e.g. to compare with an assumed-modes model on the same shapes.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..assembly import BladeMatrices
from ..errors import InputError
from .results import KINDS, ModalResult, Mode, dominant_kind
from .solve import DENSE_LIMIT, mode_shape, rpm_to_rad_s

#: an eigenvalue is real when |Im lambda| is below this fraction of |lambda|
REAL_TOLERANCE = 1e-9
#: rigid-body shapes closer than this to the span of the others are the same motion
INDEPENDENT = 1e-6
#: regularising shift of the first factorisation, relative to the largest sqrt(K_ii / M_ii) of the scaled problem
#: (the stiffest element's rate): far below the stiff end, it keeps Q(sigma) regular when K is (nearly) singular
REGULAR_SHIFT = 1e-6
#: Arnoldi's shift below zero, relative to the rate of the lowest elastic modes (:func:`spectral_rate`)
SHIFT = 1e-2
#: eigenvalues below this fraction of that rate are rigid-body motion (a rigid Jordan pair splits by round-off
#: only, measured 1e-5 of it)
RIGID = 1e-3
#: largest system solved densely when Arnoldi fails (the state-space form has twice as many unknowns)
DENSE_FALLBACK_LIMIT = 600


class QuadraticSolverError(InputError):
    """No eigen-solver converged on the quadratic problem (printed by the CLI as one line)."""


@dataclass(frozen=True)
class QuadraticProblem:
    """The free-DOF matrices of ``(lambda^2 M + lambda C + K) x = 0`` at one rotor speed.

    symmetric : the symmetric structural stiffness K0 + Omega^2 K2 (its diagonal scales the problem)
    conservative : C is skew and K symmetric (Coriolis only): the spectrum is symmetric about the imaginary axis
    stiffness_energy : optional ``x^T K_s x`` of real vectors (columns) free of the assembled product's
        cancellation (:meth:`~bladefem.assembly.BladeMatrices.stiffness_gram`), for :func:`rayleigh_values`
    """

    M: sp.csc_matrix
    C: sp.csc_matrix
    K: sp.csc_matrix
    symmetric: sp.csc_matrix
    conservative: bool
    stiffness_energy: Callable[[NDArray], NDArray] | None = None

    @property
    def size(self) -> int:
        return self.M.shape[0]

    def residuals(self, values: NDArray, vectors: NDArray) -> NDArray:
        """||(lambda^2 M + lambda C + K) x|| / ||K x|| of each pair (columns of ``vectors``)."""
        Kx = self.K @ vectors
        r = Kx + (self.C @ vectors) * values + (self.M @ vectors) * values**2
        return np.linalg.norm(r, axis=0) / np.maximum(np.linalg.norm(Kx, axis=0), 1e-300)


def quadratic_problem(matrices: BladeMatrices, rpm: float, coriolis: bool = True,
                      damping: sp.spmatrix | None = None, stiffness: sp.spmatrix | None = None) -> QuadraticProblem:
    """The problem at rotor speed ``rpm`` (rpm): Coriolis ``Omega G`` if ``coriolis``, plus optional free-DOF
    ``damping`` (N s/m-type) and ``stiffness`` (N/m-type) matrices."""
    speed = rpm_to_rad_s(rpm)
    K_s, M = matrices.reduced(speed)
    n = M.shape[0]
    C = speed * matrices.free_gyroscopic if coriolis else sp.csc_matrix((n, n))
    K = K_s
    if damping is not None:
        C = C + sp.csc_matrix(damping)
    if stiffness is not None:
        K = K + sp.csc_matrix(stiffness)
    K2 = matrices.free_parts[1]

    def stiffness_energy(vectors: NDArray) -> NDArray:
        return np.diag(matrices.stiffness_gram(vectors)) + speed**2 * np.einsum("ij,ij->j", vectors, K2 @ vectors)

    return QuadraticProblem(M=M, C=sp.csc_matrix(C), K=sp.csc_matrix(K), symmetric=K_s,
                            conservative=damping is None and stiffness is None, stiffness_energy=stiffness_energy)


def select_modes(values: NDArray, vectors: NDArray, conservative: bool, zero: float = 0.0) -> tuple[NDArray,
                                                                                                  NDArray]:
    """One eigenvalue per mode, sorted by |lambda|: those with Im(lambda) > 0, and the real ones. Eigenvalues within
    ``zero`` (rad/s) of zero are rigid-body motion, set to 0, one per independent shape (an undamped rigid motion is
    a Jordan pair whose two shapes nearly coincide). A conservative (undamped gyroscopic) spectrum is symmetric,
    lambda <-> -conj(lambda): of a real pair +-mu only +mu is kept (static divergence)."""
    scale = np.abs(values)
    rigid = scale <= zero
    real = rigid | (np.abs(values.imag) <= REAL_TOLERANCE * scale)
    keep = ~real & (values.imag > 0)
    keep |= real & ~rigid & ((values.real > 0) if conservative else True)
    keep[independent(vectors, np.flatnonzero(rigid))] = True
    values = np.where(rigid, 0.0, np.where(real, values.real, values))
    chosen = np.flatnonzero(keep)
    chosen = chosen[np.argsort(scale[chosen], kind="stable")]
    return values[chosen], vectors[:, chosen]


def independent(vectors: NDArray, columns: NDArray) -> NDArray:
    """The linearly independent ones among the given columns (QR with column pivoting; a column within 1e-6 of the
    span of those before it is dropped)."""
    if len(columns) == 0:
        return columns
    chosen = vectors[:, columns] / np.linalg.norm(vectors[:, columns], axis=0)
    _, R, pivots = la.qr(chosen, mode="economic", pivoting=True)
    rank = int(np.sum(np.abs(np.diag(R)) > INDEPENDENT * abs(R[0, 0])))
    return columns[np.sort(pivots[:rank])]


def _scaling(problem: QuadraticProblem) -> sp.dia_matrix:
    """Jacobi scaling 1 / sqrt|K_ii| of the symmetric stiffness (Hermite DOFs mix values and slopes)."""
    diagonal = np.abs(problem.symmetric.diagonal())
    return sp.diags(1.0 / np.sqrt(np.where(diagonal > 0, diagonal, 1.0)))


def full_pairs(problem: QuadraticProblem, count: int) -> tuple[NDArray, NDArray]:
    """The ``count`` modes of smallest |lambda| of the whole problem (:func:`select_modes`), from its state-space
    form ``A z = lambda B z``, ``z = (x, lambda x)``, ``A = [[0, I], [-K, -C]]``, ``B = [[I, 0], [0, M]]``.

    Dense LAPACK for small systems; otherwise shift-invert Arnoldi about a real ``sigma`` just below zero (K may be
    singular): ``(A - sigma B)^-1 B`` needs only the LU of ``Q(sigma) = sigma^2 M + sigma C + K``.
    """
    n = problem.size
    S = _scaling(problem)
    M, C, K = ((S @ A @ S).tocsc() for A in (problem.M, problem.C, problem.K))
    count = min(count, n)
    rate = spectral_rate(M, C, K)
    try:
        if n <= DENSE_LIMIT or 2 * count >= n:
            values, Z = dense_state_pairs(M, C, K)
        else:
            try:
                values, Z = arnoldi_state_pairs(M, C, K, count, rate)
            except (spla.ArpackError, spla.ArpackNoConvergence):
                if n > DENSE_FALLBACK_LIMIT:
                    raise
                values, Z = dense_state_pairs(M, C, K)
    except (spla.ArpackError, spla.ArpackNoConvergence, la.LinAlgError) as error:
        raise QuadraticSolverError(f"no eigen-solver converged on this {n}-DOF quadratic problem ({error}); try "
                                   "fewer elements (--elements)") from None
    finite = np.isfinite(values)
    values, vectors = select_modes(values[finite], S @ Z[:, finite], problem.conservative, RIGID * rate)
    vectors = normalised(problem, vectors[:, :count])
    values = values[:count]
    return (rayleigh_values(problem, values, vectors) if problem.conservative else values), vectors


def spectral_rate(M: sp.spmatrix, C: sp.spmatrix, K: sp.spmatrix) -> float:
    """A rate (rad/s) among the lowest elastic eigenvalues (:func:`time_scale`), from a factorisation of ``Q`` at a
    small regularising shift (:data:`REGULAR_SHIFT`)."""
    ratio = np.abs(K.diagonal()) / np.maximum(np.abs(M.diagonal()), 1e-300)
    sigma = -REGULAR_SHIFT * float(np.sqrt(ratio.max()))
    return time_scale(spla.splu((K + sigma * C + sigma**2 * M).tocsc()), K, M)


def dense_state_pairs(M: sp.spmatrix, C: sp.spmatrix, K: sp.spmatrix) -> tuple[NDArray, NDArray]:
    """All eigenvalues and the displacement part of the eigenvectors of the state-space form, dense LAPACK."""
    n = M.shape[0]
    identity, zero = np.eye(n), np.zeros((n, n))
    A = np.block([[zero, identity], [-K.toarray(), -C.toarray()]])
    B = np.block([[identity, zero], [zero, M.toarray()]])
    values, Z = la.eig(A, B, check_finite=False)
    return values, Z[:n]


def arnoldi_state_pairs(M: sp.spmatrix, C: sp.spmatrix, K: sp.spmatrix, count: int,
                        rate: float) -> tuple[NDArray, NDArray]:
    """About ``2 count`` eigenvalues nearest zero of the state-space form with the displacement part of their
    eigenvectors: shift-invert Arnoldi on ``(A - sigma B)^-1 B`` with the state ``(x, lambda x / rate)``, ``rate``
    from :func:`spectral_rate`, ``sigma = -SHIFT rate``: below the elastic modes, yet far enough from zero that a
    rigid-body motion's Jordan pair does not swamp them."""
    n = M.shape[0]
    sigma = -SHIFT * rate
    factor = spla.splu((K + sigma * C + sigma**2 * M).tocsc())
    damping = (C + sigma * M).tocsc()

    def shift_invert(z: NDArray) -> NDArray:
        b1, b2 = z[:n], z[n:]
        y1 = -factor.solve(rate * (M @ b2) + damping @ b1)
        return np.concatenate([y1, (b1 + sigma * y1) / rate])

    operator = spla.LinearOperator((2 * n, 2 * n), matvec=shift_invert, dtype=float)
    start = np.random.default_rng(0).standard_normal(2 * n)   # fixed start: identical results run to run
    k = min(2 * count + 2, 2 * n - 2)
    # three Lanczos vectors per wanted eigenvalue: half the iterations of ARPACK's default 2k + 1, twice as fast
    mu, Z = spla.eigs(operator, k=k, ncv=min(3 * k + 1, 2 * n - 1), which="LM", v0=start)
    return sigma + 1.0 / mu, Z[:n]


def rayleigh_values(problem: QuadraticProblem, values: NDArray, vectors: NDArray) -> NDArray:
    """Eigenvalues of a conservative problem again from their shapes: the root nearest each of the scalar equation
    ``m lambda^2 + i g lambda + k = 0`` with ``m = x^H M x``, ``i g = x^H C x`` (C skew), ``k = x^H K x``.

    ``Q(i omega)`` is Hermitian, so this errs only to second order in the shape's error, and ``k`` summed at the
    quadrature points (``stiffness_energy``) loses only (L / h)^2 digits where the assembled product loses (L / h)^4;
    for a stable mode (``g^2 + 4 m k > 0``) the root is purely imaginary: zero damping exactly. Other modes keep
    their values."""
    a, b = vectors.real, vectors.imag
    m = np.einsum("ij,ij->j", a, problem.M @ a) + np.einsum("ij,ij->j", b, problem.M @ b)
    if problem.stiffness_energy is not None:
        k = problem.stiffness_energy(a) + problem.stiffness_energy(b)
    else:
        k = np.einsum("ij,ij->j", a, problem.K @ a) + np.einsum("ij,ij->j", b, problem.K @ b)
    g = 2.0 * np.einsum("ij,ij->j", a, problem.C @ b)
    discriminant = g**2 + 4 * m * k
    out = values.copy()
    for j in np.flatnonzero((discriminant > 0) & (values.imag > 0)):
        roots = 1j * (-g[j] + np.array([1.0, -1.0]) * np.sqrt(discriminant[j])) / (2 * m[j])
        out[j] = roots[np.argmin(np.abs(roots - values[j]))]
    return out


def ritz_pairs(problem: QuadraticProblem, basis: NDArray, count: int) -> tuple[NDArray, NDArray]:
    """The ``count`` modes of smallest |lambda| of the problem reduced to the columns of ``basis`` (Rayleigh-Ritz,
    dense), as full-size complex shapes."""
    M_r = basis.T @ (problem.M @ basis)
    C_r, K_r = basis.T @ (problem.C @ basis), basis.T @ (problem.K @ basis)
    m = len(M_r)
    A = np.block([[np.zeros((m, m)), np.eye(m)], [-la.solve(M_r, K_r), -la.solve(M_r, C_r)]])
    values, Z = la.eig(A, check_finite=False)
    values, reduced = select_modes(values, Z[:m], problem.conservative,
                                   REGULAR_SHIFT * float(np.abs(values).max()))
    count = min(count, len(values))
    vectors = normalised(problem, basis @ reduced[:, :count])
    values = values[:count]
    return (rayleigh_values(problem, values, vectors) if problem.conservative else values), vectors


def normalised(problem: QuadraticProblem, vectors: NDArray) -> NDArray:
    """Complex shapes scaled to x^H M x = 1 and turned so that their largest component is real and positive."""
    vectors = np.asarray(vectors, dtype=complex)
    norms = np.sqrt(np.real(np.einsum("ij,ij->j", vectors.conj(), problem.M @ vectors)))
    vectors = vectors / norms
    largest = vectors[np.argmax(np.abs(vectors), axis=0), np.arange(vectors.shape[1])]
    return vectors * (np.abs(largest) / largest)


def complex_energy_fractions(matrices: BladeMatrices, vectors: NDArray) -> list[dict[str, float]]:
    """Kinetic-energy share x_f^H M_ff x_f / sum of each field in each complex mode (diagonal field blocks)."""
    shares = {}
    for kind, local in matrices.free_kind_dofs.items():
        part = vectors[local]
        block = matrices.kind_mass_blocks[kind]
        shares[kind] = np.real(np.einsum("ij,ij->j", part.conj(), block @ part))
    total = sum(shares.values())
    return [{kind: float(shares[kind][j] / total[j]) if kind in shares else 0.0 for kind in KINDS}
            for j in range(vectors.shape[1])]


def natural_frequency_hz(value: complex) -> float:
    """|lambda| / 2 pi; for a real eigenvalue -lambda / 2 pi (negative: a divergent, non-oscillating mode)."""
    if value.imag == 0.0:
        return float(-value.real / (2 * np.pi)) + 0.0
    return float(abs(value) / (2 * np.pi))


def quadratic_result(matrices: BladeMatrices, problem: QuadraticProblem, rpm: float, values: NDArray,
                     vectors: NDArray, notes: tuple[str, ...] = ()) -> ModalResult:
    """Frequencies, damping ratios, kinds, residuals and shapes from the pairs (lambda, x) at ``rpm``."""
    residuals = problem.residuals(values, vectors)
    fractions = complex_energy_fractions(matrices, vectors)
    modes = []
    for j, value in enumerate(values):
        kind = dominant_kind(fractions[j])
        modes.append(Mode(frequency_hz=natural_frequency_hz(value), kind=kind, energy_fractions=fractions[j],
                          residual=float(residuals[j]), shape=mode_shape(matrices, vectors[:, j].real, kind),
                          damping_ratio=float(-value.real / abs(value)) + 0.0 if value != 0 else 0.0,
                          damped_frequency_hz=float(value.imag / (2 * np.pi))))
    return ModalResult(rotor_speed_rpm=float(rpm), modes=modes, stations=matrices.blade.sections.span.copy(),
                       vectors=vectors, n_dofs=len(matrices.free), notes=notes)


def solve_quadratic_modes(matrices: BladeMatrices, rpm: float = 0.0, n_modes: int = 10,
                          notes: tuple[str, ...] = (), damping: sp.spmatrix | None = None,
                          stiffness: sp.spmatrix | None = None, coriolis: bool = True) -> ModalResult:
    """Modes of the blade at ``rpm`` (rotor speed, rpm) with Coriolis coupling (unless ``coriolis`` is False) and
    optional free-DOF ``damping`` and ``stiffness`` matrices: frequency, damping ratio, kind and residual of each."""
    if n_modes < 1:
        raise ValueError("n_modes must be at least 1")
    problem = quadratic_problem(matrices, rpm, coriolis, damping, stiffness)
    values, vectors = full_pairs(problem, n_modes)
    return quadratic_result(matrices, problem, rpm, values, vectors, notes)


def time_scale(factor: spla.SuperLU, K: sp.spmatrix, M: sp.spmatrix) -> float:
    """A rate (rad/s) among the lowest non-zero eigenvalues: the square root of the Rayleigh quotient
    |x^T K x| / x^T M x of ``x = Q^-1 M Q^-1 K r`` from a fixed random ``r``. ``K r`` holds no rigid-body motion, so
    the quotient is that of the lowest elastic modes even when K is singular. It balances the state
    ``(x, lambda x / rate)``: with rate 1 the halves differ by the modes' frequencies and Arnoldi stalls short of
    its tolerance; with a rigid mode's zero rate the shapes of all others are lost."""
    x = factor.solve(K @ np.random.default_rng(1).standard_normal(M.shape[0]))
    x = factor.solve(M @ (x / np.linalg.norm(x)))
    return float(np.sqrt(max(abs(x @ (K @ x)) / (x @ (M @ x)), 1e-12)))
