"""Campbell sweep: modes over rotor speed, families followed by MAC between neighbouring speeds."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..assembly import BladeMatrices
from .results import CampbellResult, ModalResult, ModeFamily
from .solve import cached_pairs, modal_result, relative_residuals, rpm_to_rad_s, solve_modes

#: extra modes computed at every speed so that a family that drifts upward past the window is still matched
TRACKING_MARGIN = 4
#: further modes solved at the highest speed for the Ritz basis only: the window's upper edge may cut a cluster
#: (the IEA-15MW blade's 10th and 11th modes, an edge and a torsion mode at 7.54 and 7.65 Hz), and a basis without
#: the mode just above the window cannot resolve the last one in it at the other speeds (relative residuals of
#: 5e-3, which asked for three more full solves)
RITZ_GUARD = 2
#: largest relative residual ||K x - lambda M x|| / ||K x|| accepted from the Ritz basis before a full solve (or
#: ROUNDOFF_MARGIN times the full solves' own residuals, which on fine meshes are round-off in K x: 6e-4 at 1600
#: elements of the 5MW blade, where every speed would otherwise be solved in full)
RITZ_RESIDUAL = 1e-4
ROUNDOFF_MARGIN = 10.0
#: inverse-iteration steps at the lowest speed from the highest speed's modes: two bring the 5MW blade's Ritz
#: residuals from 4e-2 (none) to 1e-5 at every speed of 0-15 rpm
INVERSE_STEPS = 2


def mac_matrix(previous: NDArray, current: NDArray, M: sp.spmatrix) -> NDArray:
    """Modal assurance criterion |x_i^H M y_j|^2 / ((x_i^H M x_i)(y_j^H M y_j)) between two sets of (real or
    complex) vectors."""
    return mac_from_products(previous, M @ previous, current, M @ current)


def mac_from_products(previous: NDArray, M_previous: NDArray, current: NDArray, M_current: NDArray) -> NDArray:
    """:func:`mac_matrix` from the vectors and their products with M."""
    cross = previous.conj().T @ M_current
    norms = (np.real(np.einsum("ij,ij->j", previous.conj(), M_previous))[:, None]
             * np.real(np.einsum("ij,ij->j", current.conj(), M_current)))
    return np.abs(cross)**2 / norms


def best_assignment(mac: NDArray) -> tuple[NDArray, NDArray]:
    """Rows and columns of the assignment with maximum total MAC (each row to a different column)."""
    best = np.argmax(mac, axis=1)
    if len(np.unique(best)) == len(best):
        return np.arange(len(best)), best
    from scipy.optimize import linear_sum_assignment      # only where matches are ambiguous (a slow import)
    return linear_sum_assignment(-mac)


def track_families(results: Sequence[ModalResult], M: sp.spmatrix, n_families: int,
                   weighted: Sequence[NDArray] | None = None) -> list[ModeFamily]:
    """Follow the lowest ``n_families`` modes of the first speed through all speeds by maximum total MAC between
    neighbouring speeds, so crossings and veerings keep families continuous: each family takes its best match
    when those are all different (then that is the maximum), else the Hungarian assignment decides. ``weighted``:
    the products ``M @ vectors`` of each speed where the caller has them."""
    indices = np.zeros((len(results), n_families), dtype=np.int64)
    macs = np.ones((len(results), n_families))
    indices[0] = np.arange(n_families)
    weighted = [M @ result.vectors for result in results] if weighted is None else weighted
    for k in range(1, len(results)):
        mac = mac_from_products(results[k - 1].vectors[:, indices[k - 1]], weighted[k - 1][:, indices[k - 1]],
                                results[k].vectors, weighted[k])
        rows, cols = best_assignment(mac)
        indices[k, rows] = cols
        macs[k, rows] = mac[rows, cols]
    families = []
    for f in range(n_families):
        frequencies = np.array([results[k].modes[indices[k, f]].frequency_hz for k in range(len(results))])
        kind = results[0].modes[f].kind
        families.append(ModeFamily(kind=kind, frequencies_hz=frequencies, indices=indices[:, f], mac=macs[:, f]))
    return families


def ritz_basis(blocks: Sequence[NDArray], M: sp.spmatrix) -> NDArray:
    """An M-orthonormal basis of the span of the given vector blocks, dropping numerically dependent directions.

    Modes at neighbouring speeds differ only slightly, and those small differences are what the basis needs: the
    Gram matrix keeps directions down to 1e-10 of the largest singular value, and a second pass restores
    orthonormality to round-off."""
    V = np.hstack(blocks)
    for _ in range(2):
        values, rotation = np.linalg.eigh(V.T @ (M @ V))
        keep = values > 1e-20 * values.max()
        V = V @ (rotation[:, keep] / np.sqrt(values[keep]))
    return V


class RitzBasis:
    """An M-orthonormal basis V with the products the sweep needs at every speed: the reduced elastic stiffness
    V^T K0 V summed at the quadrature points (:meth:`~bladefem.assembly.BladeMatrices.stiffness_gram`), V^T K2 V,
    and K0 V, K2 V, M V for the residuals."""

    def __init__(self, matrices: BladeMatrices, vectors: NDArray) -> None:
        K0, K2, M = matrices.free_parts
        self.vectors = vectors
        self.K0V, self.K2V, self.MV = K0 @ vectors, K2 @ vectors, M @ vectors
        self.elastic = matrices.stiffness_gram(vectors)
        self.centrifugal = vectors.T @ self.K2V

    def pairs(self, omega2: float, count: int) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """Lowest ``count`` Ritz values (omega^2), vectors, relative residuals and the vectors' products with M at
        Omega^2 = ``omega2``."""
        reduced = self.elastic + omega2 * self.centrifugal
        values, rotation = la.eigh(0.5 * (reduced + reduced.T), subset_by_index=[0, min(count, len(reduced)) - 1])
        stiffness = (self.K0V + omega2 * self.K2V) @ rotation
        mass = self.MV @ rotation
        residuals = (np.linalg.norm(stiffness - mass * values, axis=0)
                     / np.maximum(np.linalg.norm(stiffness, axis=0), 1e-300))
        return values, self.vectors @ rotation, residuals, mass


def inverse_iterates(matrices: BladeMatrices, rpm: float, vectors: NDArray) -> list[NDArray]:
    """:data:`INVERSE_STEPS` steps of inverse iteration at ``rpm``, ``(K(Omega)^-1 M)^k X``, each M-normalised: with
    the modes X of another speed they span the modes at ``rpm`` closely (a singular K, rigid motion at rest, gives
    the modes of a full solve instead)."""
    K0, K2, M = matrices.free_parts
    try:
        factor = spla.splu((K0 + rpm_to_rad_s(rpm) ** 2 * K2).tocsc())
    except RuntimeError:
        return [solve_modes(matrices, rpm, vectors.shape[1]).vectors]
    steps = []
    for _ in range(INVERSE_STEPS):
        vectors = factor.solve(M @ vectors)
        vectors = vectors / np.sqrt(np.einsum("ij,ij->j", vectors, M @ vectors))
        steps.append(vectors)
    return steps


def campbell_sweep(matrices: BladeMatrices, rpm: Sequence[float], n_modes: int = 6, notes: tuple[str, ...] = (),
                   progress: Callable[[Iterable[float]], Iterable[float]] | None = None) -> CampbellResult:
    """Modes at each rotor speed in ``rpm`` (rpm), from one assembly: K(Omega) = K0 + Omega^2 K2.

    Exploits that structure: a full eigen-solve at the highest speed (with :data:`RITZ_GUARD` modes beyond the
    window) and two steps of inverse iteration from its modes at the lowest speed (:func:`inverse_iterates`) give a
    Ritz basis, and every speed is first solved in that small basis (a dense problem of a few dozen DOFs, its elastic
    part summed at the quadrature points as in :func:`~bladefem.modal.solve.rayleigh_quotients`). Where a Ritz
    pair's relative residual exceeds :data:`RITZ_RESIDUAL` (or, on meshes fine enough for round-off to dominate the
    residuals, :data:`ROUNDOFF_MARGIN` times the full solve's own), the speed gets a full solve whose modes join the
    basis.
    Ritz values err by about the square of the residual (1e-9 relative in omega^2 at the default), far below the
    mesh error; each mode's residual is reported. ``progress`` optionally wraps the loop over speeds (e.g. a progress bar).
    """
    rpm = np.asarray(rpm, dtype=float)
    count = n_modes + TRACKING_MARGIN
    M = matrices.free_parts[2]
    values, vectors = cached_pairs(matrices, rpm.max(), count + RITZ_GUARD)
    basis = RitzBasis(matrices, ritz_basis([vectors, *inverse_iterates(matrices, rpm.min(), vectors)], M))
    floor = ROUNDOFF_MARGIN * relative_residuals(*matrices.reduced(rpm_to_rad_s(rpm.max())), values[:count],
                                                 vectors[:, :count]).max()
    results, weighted = [], []
    for speed in (progress or iter)(rpm):
        values, vectors, residuals, mass = basis.pairs(rpm_to_rad_s(speed) ** 2, count)
        if residuals.max() > max(RITZ_RESIDUAL, floor):
            full = solve_modes(matrices, speed, count, notes)
            basis = RitzBasis(matrices, ritz_basis([basis.vectors, full.vectors], M))
            results.append(full)
            weighted.append(M @ full.vectors)
        else:
            results.append(modal_result(matrices, speed, values, vectors, notes, residuals))
            weighted.append(mass)
    n_families = min(n_modes, len(results[0].modes))
    return CampbellResult(rpm=rpm, families=track_families(results, M, n_families, weighted), results=results,
                          notes=notes)
