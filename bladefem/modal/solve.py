"""Generalized symmetric eigenproblem K x = omega^2 M x: dense for small systems, sparse shift-invert for large."""

from __future__ import annotations

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..assembly import BladeMatrices
from ..errors import InputError
from .results import (
    KINDS,
    ModalResult,
    Mode,
    ModeShape,
    dominant_kind,
    signed_frequency_hz,
)

#: Systems up to this many free DOFs (or asking for a third of all modes) use dense LAPACK; larger ones use
#: ARPACK shift-invert Lanczos, which is faster there
DENSE_LIMIT = 60
#: largest system the dense solver takes when Lanczos fails (O(n^3): about a second at this size)
DENSE_FALLBACK_LIMIT = 2500
#: ARPACK's convergence tolerance: eigenvectors to about this, eigenvalues (Rayleigh quotients) to its square;
#: it bounds the backward error of the pairs, far below LANCZOS_BACKWARD_ERROR
LANCZOS_TOLERANCE = 1e-10
#: a Lanczos eigenpair whose normwise backward error exceeds this is a failure, solved again densely (converged
#: pairs sit near 1e-15)
LANCZOS_BACKWARD_ERROR = 1e-8
#: shift below zero when K is singular (rigid-body motion), relative to the largest diagonal ratio K_ii / M_ii of
#: the scaled problem: far below any elastic eigenvalue, yet large enough to make K - sigma M factorable
SINGULAR_SHIFT = 1e-12
#: modes whose omega^2 is below this fraction of the largest count as rigid (no round-off estimate): frequencies
#: below 1e-6 of the highest
ZERO_EIGENVALUE = 1e-12
#: tenfold increases of the dense solver's shift tried when K - sigma M is not positive definite
SHIFT_ATTEMPTS = 8


class SolverError(InputError):
    """No eigen-solver converged on the model (printed by the CLI as one line, like an input error)."""


def rpm_to_rad_s(rpm: float) -> float:
    return float(rpm) * np.pi / 30.0


def jacobi_scaling(K: sp.spmatrix, M: sp.spmatrix) -> tuple[sp.csc_matrix, sp.csc_matrix, sp.dia_matrix]:
    """(S K S, S M S, S) with S = diag(1 / sqrt|K_ii|): Hermite DOFs mix values and slopes of very different size,
    and the scaling lowers the round-off floor of the lowest eigenvalues on fine meshes about a hundredfold."""
    diagonal = np.abs(K.diagonal())
    factors = 1.0 / np.sqrt(np.where(diagonal > 0, diagonal, 1.0))

    def scaled(A: sp.spmatrix) -> sp.csc_matrix:
        A = sp.csc_matrix(A, copy=True)
        columns = np.repeat(np.arange(A.shape[1]), np.diff(A.indptr))
        A.data *= factors[A.indices] * factors[columns]
        return A

    return scaled(K), scaled(M), sp.diags(factors)


def singular_shift(K: sp.spmatrix | NDArray, M: sp.spmatrix | NDArray) -> float:
    """|sigma| below zero that makes a singular K - sigma M factorable: SINGULAR_SHIFT times the largest diagonal
    ratio K_ii / M_ii over the DOFs that have inertia (a field without any has no finite eigenvalue)."""
    k, m = np.asarray(K.diagonal()), np.asarray(M.diagonal())
    inertial = m > 0
    return SINGULAR_SHIFT * float(np.max(k[inertial] / m[inertial])) if inertial.any() else SINGULAR_SHIFT


def lanczos_pairs(K: sp.csc_matrix, M: sp.csc_matrix, n_modes: int) -> tuple[NDArray, NDArray]:
    """Lowest eigenpairs by shift-invert Lanczos (ARPACK) about sigma = 0, or just below zero when K is singular.

    The shift must sit near the wanted end of the spectrum: Lanczos converges in a few dozen steps when the wanted
    eigenvalues are far nearer sigma than the rest, and crawls (minutes, then ArpackNoConvergence) when sigma lies
    far below them, as a shift scaled by the stiffest element modes does on stiff axial or torsion fields.
    Eigenvalues nearest zero come first, so a statically unstable mode (omega^2 < 0, small) is found too.
    """
    n = K.shape[0]
    sigma = 0.0
    try:
        factor = spla.splu(K)
    except RuntimeError:                    # exactly singular: a free rigid-body motion
        sigma = -singular_shift(K, M)
        factor = spla.splu((K - sigma * M).tocsc())
    inverse = spla.LinearOperator((n, n), matvec=factor.solve, dtype=float)
    start = np.random.default_rng(0).standard_normal(n)     # fixed start: identical results run to run
    values, vectors = spla.eigsh(K, k=n_modes, M=M, sigma=sigma, which="LM", v0=start, OPinv=inverse,
                                 tol=LANCZOS_TOLERANCE)
    order = np.argsort(values)
    values, vectors = values[order], vectors[:, order]
    vectors = vectors / np.sqrt(np.einsum("ij,ij->j", vectors, M @ vectors))
    if not np.all(np.isfinite(values)) or backward_errors(K, M, values, vectors).max() > LANCZOS_BACKWARD_ERROR:
        raise la.LinAlgError("Lanczos eigenpairs failed the backward-error check")
    return values, vectors


def dense_pairs(K: sp.spmatrix, M: sp.spmatrix, n_modes: int) -> tuple[NDArray, NDArray]:
    """Lowest eigenpairs by dense LAPACK from the inverse problem ``M x = mu (K - sigma M) x``,
    ``mu = 1 / (omega^2 - sigma)``.

    The lowest omega^2 are the largest mu, found to relative accuracy even when the stiffest element modes are
    1e15 times stiffer (the direct problem through a Cholesky factor of M loses them to round-off). sigma is 0 when
    K is positive definite, else below the lowest eigenvalue the direct problem estimates (tenfold lower until
    K - sigma M is definite).
    """
    n = K.shape[0]
    K, M = K.toarray(), M.toarray()
    sigma = 0.0
    for _ in range(SHIFT_ATTEMPTS):
        try:
            mu, vectors = la.eigh(M, K - sigma * M, subset_by_index=[n - n_modes, n - 1], check_finite=False)
        except la.LinAlgError:
            if sigma == 0.0:
                try:
                    lowest = la.eigh(K, M, eigvals_only=True, subset_by_index=[0, 0], check_finite=False)[0]
                except la.LinAlgError:      # M singular too (a field without inertia): K - sigma M is then definite
                    lowest = 0.0
                floor = singular_shift(K, M)
                sigma = min(lowest, 0.0) * 2 - floor
            else:
                sigma *= 10
            continue
        values = sigma + 1.0 / mu[::-1]
        vectors = vectors[:, ::-1]
        return values, vectors / np.sqrt(np.einsum("ij,ij->j", vectors, M @ vectors))
    raise la.LinAlgError("no shift makes K - sigma M positive definite")


def eigen_pairs(K: sp.spmatrix, M: sp.spmatrix, n_modes: int) -> tuple[NDArray, NDArray]:
    """Lowest ``n_modes`` eigenvalues (omega^2) and M-normalised eigenvectors of K x = lambda M x.

    Jacobi-scaled (:func:`jacobi_scaling`); dense LAPACK for small systems, else shift-invert Lanczos
    (:func:`lanczos_pairs`) with a dense fallback (:func:`dense_pairs`) when Lanczos fails to converge or its
    residuals are poor. Raises :class:`SolverError` (never an ARPACK traceback) if no solver succeeds.
    """
    n = K.shape[0]
    n_modes = min(n_modes, n)
    K, M, scale = jacobi_scaling(K, M)
    try:
        if n <= DENSE_LIMIT or 3 * n_modes >= n:
            values, vectors = dense_pairs(K, M, n_modes)
        else:
            try:
                values, vectors = lanczos_pairs(K, M, n_modes)
            except (spla.ArpackError, spla.ArpackNoConvergence, RuntimeError, la.LinAlgError):
                if n > DENSE_FALLBACK_LIMIT:
                    raise
                values, vectors = dense_pairs(K, M, n_modes)
    except (spla.ArpackError, spla.ArpackNoConvergence, RuntimeError, la.LinAlgError) as error:
        raise SolverError(f"no eigen-solver converged on this {n}-DOF model ({error}); try fewer elements "
                          "(--elements)") from None
    return values, scale @ vectors


def backward_errors(K: sp.spmatrix, M: sp.spmatrix, values: NDArray, vectors: NDArray) -> NDArray:
    """Normwise backward error ``||K x - lambda M x|| / ((||K|| + |lambda| ||M||) ||x||)`` (1-norms of the
    matrices) of each eigenpair: the relative change of K and M that makes the pair exact. Unlike the relative
    residual it is not swamped by the round-off of ``K x`` when the stiffest element modes are many orders above
    the lowest modes."""
    r = K @ vectors - (M @ vectors) * values
    scale = (spla.norm(K, 1) + np.abs(values) * spla.norm(M, 1)) * np.linalg.norm(vectors, axis=0)
    return np.linalg.norm(r, axis=0) / scale


def relative_residuals(K: sp.spmatrix, M: sp.spmatrix, values: NDArray, vectors: NDArray) -> NDArray:
    """||K x - lambda M x|| / ||K x|| for each eigenpair."""
    Kx = K @ vectors
    return np.linalg.norm(Kx - (M @ vectors) * values, axis=0) / np.maximum(np.linalg.norm(Kx, axis=0), 1e-300)


def energy_fractions(matrices: BladeMatrices, vectors: NDArray) -> list[dict[str, float]]:
    """Kinetic-energy share of each field (flap, edge, torsion, axial) in each mode (diagonal field blocks)."""
    shares = {}
    for kind, local in matrices.free_kind_dofs.items():
        part = vectors[local]
        shares[kind] = np.einsum("ij,ij->j", part, matrices.kind_mass_blocks[kind] @ part)
    total = sum(shares.values())
    return [{kind: float(shares[kind][j] / total[j]) if kind in shares else 0.0 for kind in KINDS}
            for j in range(vectors.shape[1])]


def mode_shapes(matrices: BladeMatrices, vectors: NDArray, kinds: list[str]) -> list[ModeShape]:
    """Nodal mode shapes from free-DOF eigenvectors (columns): a torsion mode scaled to a largest twist of +1 rad,
    any other to a largest displacement (flap, edge or axial) of +1; a mode without motion in these DOFs (a floating
    platform's yaw under a torsionally rigid tower) keeps its zero shape."""
    full = np.zeros((matrices.dofs.size, vectors.shape[1]))
    full[matrices.free] = vectors
    dofs = matrices.dofs
    zero = np.zeros((len(dofs.nodes), vectors.shape[1]))

    def take(table: dict[str, NDArray], name: str) -> NDArray:
        return full[table[name]] if name in table else zero

    def deflection(name: str) -> NDArray:
        return dofs.displacement(full, name) if name in dofs.value else zero

    shape = {"flap": deflection("w"), "flap_slope": take(dofs.slope, "w"), "edge": deflection("v"),
             "edge_slope": take(dofs.slope, "v"), "twist": take(dofs.value, "phi"), "axial": take(dofs.value, "u")}
    translations = np.concatenate([shape["flap"], shape["edge"], shape["axial"]])
    torsion = np.array([kind == "torsion" for kind in kinds])

    def largest(values: NDArray) -> NDArray:
        return values[np.argmax(np.abs(values), axis=0), np.arange(values.shape[1])]

    scale = np.where(torsion, largest(shape["twist"]), largest(translations))
    scale = np.where(scale == 0, 1.0, scale)       # no motion in these DOFs (a floating platform's yaw): all zero
    scaled = {key: (value / scale).T for key, value in shape.items()}        # rows: modes
    return [ModeShape(x=dofs.nodes, **{key: value[j] for key, value in scaled.items()}) for j in range(len(kinds))]


def mode_shape(matrices: BladeMatrices, vector: NDArray, kind: str) -> ModeShape:
    """Nodal mode shape of one free-DOF eigenvector (see :func:`mode_shapes`)."""
    return mode_shapes(matrices, vector[:, None], [kind])[0]


def modal_result(matrices: BladeMatrices, rpm: float, values: NDArray, vectors: NDArray,
                 notes: tuple[str, ...] = (), residuals: NDArray | None = None) -> ModalResult:
    """Frequencies, kinds, residuals and shapes from eigenpairs (omega^2, M-normalised vectors) at ``rpm``; the
    relative residuals are computed unless given."""
    if residuals is None:
        K0, K2, M = matrices.free_parts
        stiffness = K0 @ vectors + rpm_to_rad_s(rpm) ** 2 * (K2 @ vectors)
        residuals = (np.linalg.norm(stiffness - (M @ vectors) * values, axis=0)
                     / np.maximum(np.linalg.norm(stiffness, axis=0), 1e-300))
    fractions = energy_fractions(matrices, vectors)
    kinds = [dominant_kind(fraction) for fraction in fractions]
    shapes = mode_shapes(matrices, vectors, kinds)
    modes = [Mode(frequency_hz=signed_frequency_hz(value), kind=kind, energy_fractions=fraction,
                  residual=float(residual), shape=shape)
             for value, kind, fraction, residual, shape in zip(values, kinds, fractions, residuals, shapes)]
    return ModalResult(rotor_speed_rpm=float(rpm), modes=modes, stations=matrices.blade.sections.span.copy(),
                       vectors=vectors, n_dofs=len(matrices.free), notes=notes)


def rayleigh_quotients(matrices: BladeMatrices, rpm: float, vectors: NDArray) -> NDArray:
    """omega^2 = (x^T K0 x + Omega^2 x^T K2 x) / x^T M x of each free-DOF vector at ``rpm``, with the energies
    summed at the quadrature points (:meth:`~bladefem.assembly.BladeMatrices.stiffness_gram`).

    An eigen-solver's eigenvalue errs to first order in its linear solves' round-off, which on Hermite meshes grows
    as (L / h)^4 (1e-6 relative at 300 elements); this quotient errs only to second order in the eigenvector's
    error, and its energies lose only (L / h)^2 digits: 1e-13 at 300 elements.
    """
    _, K2, M = matrices.free_parts
    stiffness = np.diag(matrices.stiffness_gram(vectors))
    centrifugal = np.einsum("ij,ij->j", vectors, K2 @ vectors)
    return (stiffness + rpm_to_rad_s(rpm) ** 2 * centrifugal) / np.einsum("ij,ij->j", vectors, M @ vectors)


def roundoff_errors(K: sp.spmatrix, values: NDArray, vectors: NDArray) -> NDArray:
    """Estimated relative round-off error of each frequency from :func:`rayleigh_quotients`: the square of
    ``b = eps |x|^T |K| |x| / (2 |x^T K x|)``, the first-order bound of a solver's eigenvalue error (the cancellation
    in the assembled strain energy), since the quotient errs to second order. On the 22 reference decks' blades the
    quotients of two factorisation orderings differ by 1e-2 to 1e-3 of this estimate. Zero for rigid-body modes
    (omega^2 below ZERO_EIGENVALUE of the largest)."""
    absolute = np.einsum("ij,ij->j", np.abs(vectors), abs(K) @ np.abs(vectors))
    energy = np.abs(np.einsum("ij,ij->j", vectors, K @ vectors))
    rigid = np.abs(values) <= ZERO_EIGENVALUE * np.max(np.abs(values))
    first_order = np.finfo(float).eps * absolute / (2 * np.maximum(energy, 1e-300))
    return np.where(rigid, 0.0, first_order**2)


def cached_pairs(matrices: BladeMatrices, rpm: float, n_modes: int) -> tuple[NDArray, NDArray]:
    """Lowest eigenpairs at ``rpm``, solved once per speed and kept with the matrices (the mesh choice solves at
    the highest speed; ``modes`` and the Campbell sweep re-use that solve)."""
    cached = matrices.eigenpairs.get(float(rpm))
    if cached is None or cached[0].size < min(n_modes, len(matrices.free)):
        K, M = matrices.reduced(rpm_to_rad_s(rpm))
        _, vectors = eigen_pairs(K, M, n_modes)
        values = rayleigh_quotients(matrices, rpm, vectors)
        order = np.argsort(values)
        cached = values[order], vectors[:, order]
        matrices.eigenpairs[float(rpm)] = cached
    return cached[0][:n_modes], cached[1][:, :n_modes]


def solve_modes(matrices: BladeMatrices, rpm: float = 0.0, n_modes: int = 10,
                notes: tuple[str, ...] = ()) -> ModalResult:
    """Natural modes of the assembled blade at ``rpm`` (rotor speed, rpm)."""
    if n_modes < 1:
        raise ValueError("n_modes must be at least 1")
    values, vectors = cached_pairs(matrices, rpm, n_modes)
    return modal_result(matrices, rpm, values, vectors, notes)
