"""Weak forms evaluated two ways: assembled into sparse matrices, or as the Gram matrix ``V^T A V`` of given DOF
vectors, summed at the quadrature points.

The second way is what makes fine meshes usable. In ``x^T K x`` formed from the assembled Hermite stiffness, the
element terms (EI / h^3 times nodal values) cancel down to the strain energy (EI times curvature^2): about
(L / h)^4 of the digits are lost, 1e-6 relative at 300 elements. Curvatures formed at the quadrature points first
lose only (L / h)^2, so a Rayleigh quotient evaluated this way is accurate to about round-off squared (the
eigenvector's own error enters at second order).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from skfem import Basis

from ..elements import (
    SectionMotion,
    basis_functions,
    curved_motion,
    interpolated_components,
    linear_projection,
    pair_motions,
)

Term = Callable[..., NDArray]


@dataclass(frozen=True)
class Quadrature:
    """What evaluating a form on a mesh needs: the motions of the local basis functions at the quadrature points
    (arrays of shape (local, elements, points)), the quadrature weights times the element Jacobian (elements,
    points), each element's global DOFs (local, elements) and the number of DOFs."""

    functions: SectionMotion
    weights: NDArray
    element_dofs: NDArray
    size: int
    points: NDArray | None = None            # span positions of the quadrature points (elements, points), m

    @classmethod
    def from_basis(cls, basis: Basis, fields: tuple[str, ...], curvature: NDArray | None = None) -> Quadrature:
        """The quadrature of ``basis``; on a curved reference axis (``curvature``: ``(K2, K3, K2', K3')`` at the
        quadrature points) the functions' derivatives are the curved beam's strains
        (:func:`~bladefem.elements.curved_motion`), which every form then takes as they are."""
        functions = basis_functions(fields, basis)
        points = np.asarray(basis.global_coordinates())[0]
        if curvature is not None:
            functions = curved_motion(functions, curvature, linear_projection(np.asarray(basis.dx), points))
        return cls(functions, np.asarray(basis.dx), basis.element_dofs, basis.N, points)


def _integrand(parts: Sequence[Term], test: SectionMotion, trial: SectionMotion, parameters: object,
               shape: tuple[int, ...]) -> NDArray:
    return sum(np.broadcast_to(part(trial, test, parameters), shape) for part in parts)


def assemble_terms(quadrature: Quadrature, parameters: object, parts: Sequence[Term]) -> sp.csr_matrix:
    """Assemble the sum of weak-form terms into one sparse matrix.

    Each term is evaluated once on all (test, trial) pairs of local basis functions
    (:func:`~bladefem.elements.pair_motions`), integrated over every element and scattered to the global DOFs
    (rows: test functions)."""
    n = len(quadrature.element_dofs)
    test, trial = pair_motions(quadrature.functions)
    integrand = _integrand(parts, test, trial, parameters, (n, n) + quadrature.weights.shape)
    local = np.einsum("ijeq,eq->ije", integrand, quadrature.weights)
    rows = np.broadcast_to(quadrature.element_dofs[:, None, :], local.shape)
    cols = np.broadcast_to(quadrature.element_dofs[None, :, :], local.shape)
    size = quadrature.size
    return sp.coo_matrix((local.ravel(), (rows.ravel(), cols.ravel())), shape=(size, size)).tocsr()


def pointwise_operator(quadrature: Quadrature, parameters: object, parts: Sequence[Term]) -> NDArray:
    """The weak form at each quadrature point as a matrix over the motion components (the fields of
    :class:`~bladefem.elements.SectionMotion`): ``A[f, g, e, q]`` with integrand ``sum_fg test_f A_fg trial_g``,
    read off the terms by evaluating them once on unit motions, times the quadrature weights."""
    names = tuple(SectionMotion.__dataclass_fields__)
    shape = quadrature.weights.shape
    unit = np.eye(len(names))
    motion = SectionMotion(**{name: np.broadcast_to(unit[k][:, None, None], (len(names),) + shape)
                              for k, name in enumerate(names)})
    test, trial = pair_motions(motion)
    return _integrand(parts, test, trial, parameters, (len(names), len(names)) + shape) * quadrature.weights


def gram_matrix(quadrature: Quadrature, operator: NDArray, vectors: NDArray) -> NDArray:
    """``V^T A V`` for the columns of ``vectors`` (over all DOFs) and the matrix A of a form given pointwise
    (:func:`pointwise_operator`), summed at the quadrature points from the vectors' own motions there."""
    names = tuple(SectionMotion.__dataclass_fields__)
    present = np.flatnonzero(np.any(operator != 0, axis=(1, 2, 3)))
    stacked = interpolated_components(quadrature.functions, quadrature.element_dofs, vectors,
                                      tuple(names[f] for f in present))               # (f, m, e, q)
    X = stacked.reshape(len(present), stacked.shape[1], -1)
    A = operator[np.ix_(present, present)].reshape(len(present), len(present), -1)
    return np.einsum("fmn,fgn,gkn->mk", X, A, X, optimize=True)
