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
from functools import cached_property

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

    @cached_property
    def point_functions(self) -> NDArray:
        """The motion components of the local basis functions, shape (elements, points, component, local)."""
        shape = (len(self.element_dofs),) + self.weights.shape
        stacked = np.stack([np.broadcast_to(getattr(self.functions, name), shape)
                            for name in SectionMotion.__dataclass_fields__])
        return np.ascontiguousarray(stacked.transpose(2, 3, 0, 1))

    @cached_property
    def components(self) -> NDArray[np.int64]:
        """Indices of the motion components (fields of :class:`~bladefem.elements.SectionMotion`) that some basis
        function has at some quadrature point: the others are zero for every motion on this mesh."""
        return np.flatnonzero([np.any(getattr(self.functions, name)) for name in SectionMotion.__dataclass_fields__])


def _integrand(parts: Sequence[Term], test: SectionMotion, trial: SectionMotion, parameters: object,
               shape: tuple[int, ...]) -> NDArray:
    return sum(np.broadcast_to(part(trial, test, parameters), shape) for part in parts)


def assemble_terms(quadrature: Quadrature, parameters: object, parts: Sequence[Term]) -> sp.csr_matrix:
    """Assemble the sum of weak-form terms into one sparse matrix: the terms read off once at each quadrature point
    as a matrix over the motion components (:func:`pointwise_operator`), then :func:`assemble_operator`."""
    return assemble_operator(quadrature, pointwise_operator(quadrature, parameters, parts))


def assemble_operator(quadrature: Quadrature, operator: NDArray) -> sp.csr_matrix:
    """Assemble a form given pointwise (``A[f, g, e, q]``, weights included: :func:`pointwise_operator`) into one
    sparse matrix (rows: test functions): each element's ``sum_q B_q^T A_q B_q``, ``B_q`` the motion components of
    its local basis functions at point q, as batched matrix products over the components the form uses."""
    rows = np.flatnonzero(np.any(operator != 0, axis=(1, 2, 3)))
    cols = np.flatnonzero(np.any(operator != 0, axis=(0, 2, 3)))
    size = quadrature.size
    if rows.size == 0:
        return sp.csr_matrix((size, size))
    test, trial = quadrature.point_functions[:, :, rows], quadrature.point_functions[:, :, cols]
    A = np.ascontiguousarray(operator[np.ix_(rows, cols)].transpose(2, 3, 0, 1))  # (elements, points, f, g)
    elements, points, _, n = test.shape
    weighted = np.matmul(A, trial).reshape(elements, points * len(rows), n)
    local = np.matmul(test.reshape(elements, points * len(rows), n).transpose(0, 2, 1), weighted).transpose(1, 2, 0)
    rows_global = np.broadcast_to(quadrature.element_dofs[:, None, :], local.shape)
    cols_global = np.broadcast_to(quadrature.element_dofs[None, :, :], local.shape)
    return sp.coo_matrix((local.ravel(), (rows_global.ravel(), cols_global.ravel())), shape=(size, size)).tocsr()


def pointwise_operator(quadrature: Quadrature, parameters: object, parts: Sequence[Term]) -> NDArray:
    """The weak form at each quadrature point as a matrix over the motion components (the fields of
    :class:`~bladefem.elements.SectionMotion`): ``A[f, g, e, q]`` with integrand ``sum_fg test_f A_fg trial_g``,
    read off the terms by evaluating them once on unit motions of the components the mesh's functions have (zero
    for the others), times the quadrature weights."""
    names = tuple(SectionMotion.__dataclass_fields__)
    shape = quadrature.weights.shape
    present = quadrature.components
    unit = np.eye(len(present))[:, :, None, None]              # constant along the span: the terms broadcast
    zero = np.zeros((len(present), 1, 1))
    motion = SectionMotion(**{name: zero for name in names} | {names[f]: unit[k] for k, f in enumerate(present)})
    test, trial = pair_motions(motion)
    operator = np.zeros((len(names), len(names)) + shape)
    operator[np.ix_(present, present)] = (_integrand(parts, test, trial, parameters, (len(present),) * 2 + shape)
                                          * quadrature.weights)
    return operator


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
