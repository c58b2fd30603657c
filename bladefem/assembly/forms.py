"""Weak forms evaluated two ways: assembled into sparse matrices, or as the energies ``x^T A x`` of given DOF
vectors, summed at the quadrature points.

The second way is what makes fine meshes usable. In ``x^T K x`` formed from the assembled Hermite stiffness, the
element terms (EI / h^3 times nodal values) cancel down to the strain energy (EI times curvature^2): about
(L / h)^4 of the digits are lost, 1e-6 relative at 300 elements. Curvatures formed at the quadrature points first
lose only (L / h)^2, so a Rayleigh quotient evaluated this way is accurate to round-off squared (the eigenvector's
own error enters at second order).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from skfem import Basis

from ..elements import basis_motions, interpolated_motion

Term = Callable[..., NDArray]


def assemble_terms(basis: Basis, fields: tuple[str, ...], parameters: object,
                   parts: Sequence[Term]) -> sp.csr_matrix:
    """Assemble the sum of weak-form terms into one sparse matrix.

    Each term is evaluated once on the motions of all (test, trial) pairs of local basis functions
    (:func:`~bladefem.elements.basis_motions`), integrated over every element with the basis's quadrature weights
    and scattered to the global DOFs (rows: test functions)."""
    test, trial = basis_motions(fields, basis)
    n = basis.Nbfun
    integrand = sum(np.broadcast_to(part(trial, test, parameters), (n, n) + basis.dx.shape) for part in parts)
    local = np.einsum("ijeq,eq->ije", integrand, basis.dx)
    rows = np.broadcast_to(basis.element_dofs[:, None, :], local.shape)
    cols = np.broadcast_to(basis.element_dofs[None, :, :], local.shape)
    return sp.coo_matrix((local.ravel(), (rows.ravel(), cols.ravel())), shape=(basis.N, basis.N)).tocsr()


def term_energies(basis: Basis, fields: tuple[str, ...], parameters: object, parts: Sequence[Term],
                  vectors: NDArray) -> NDArray:
    """``x^T A x`` of each column of ``vectors`` (over all DOFs) for the matrix A the terms assemble, summed at the
    quadrature points."""
    motion = interpolated_motion(fields, basis, vectors)
    shape = (np.shape(vectors)[1],) + basis.dx.shape
    return sum(np.einsum("meq,eq->m", np.broadcast_to(part(motion, motion, parameters), shape), basis.dx)
               for part in parts)


@dataclass(frozen=True)
class EnergyForms:
    """The weak forms of a beam's three matrices and their point (rigid-body) parts, kept with the matrices to
    evaluate energies (:func:`term_energies`): ``K0 = stiffness``, ``K2 = centrifugal + K2_points``,
    ``M = inertia + M_points``."""

    basis: Basis
    fields: tuple[str, ...]
    parameters: object
    stiffness: tuple[Term, ...]
    centrifugal: tuple[Term, ...]
    inertia: tuple[Term, ...]
    K2_points: sp.csr_matrix
    M_points: sp.csr_matrix

    def energies(self, vectors: NDArray) -> tuple[NDArray, NDArray, NDArray]:
        """(x^T K0 x, x^T K2 x, x^T M x) of each column of ``vectors`` (over all DOFs)."""
        def energy(parts: Sequence[Term], points: sp.csr_matrix | None = None) -> NDArray:
            total = term_energies(self.basis, self.fields, self.parameters, parts, vectors)
            if points is not None:
                total = total + np.einsum("ij,ij->j", vectors, points @ vectors)
            return total

        return (energy(self.stiffness), energy(self.centrifugal, self.K2_points),
                energy(self.inertia, self.M_points))
