"""The beam element: Hermite cubic bending in two planes, quadratic torsion and axial fields.

Fields: ``v`` edgewise (in-plane) and ``w`` flapwise (out-of-plane) deflection, C1 Hermite cubics; ``phi`` elastic
twist and ``u`` axial displacement, quadratic Lagrange. A model may drop ``phi`` or ``u`` (rigid torsion or axial).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from skfem import CellBasis, ElementComposite, ElementLineHermite, ElementLineP2
from skfem.element import DiscreteField, Element

BENDING_FIELDS: tuple[str, ...] = ("v", "w")
ALL_FIELDS: tuple[str, ...] = ("v", "w", "phi", "u")
FIELD_ELEMENTS: dict[str, type[Element]] = {"v": ElementLineHermite, "w": ElementLineHermite,
                                            "phi": ElementLineP2, "u": ElementLineP2}
#: what each field is called in results
FIELD_KINDS: dict[str, str] = {"v": "edge", "w": "flap", "phi": "torsion", "u": "axial"}


def beam_element(fields: tuple[str, ...]) -> ElementComposite:
    """Composite element with one sub-element per field, in the order given."""
    return ElementComposite(*(FIELD_ELEMENTS[name]() for name in fields))


@dataclass(frozen=True)
class SectionMotion:
    """Displacements and their span derivatives of one basis function at the quadrature points.

    Arrays have shape (elements, quadrature points); absent fields are zero.
    """

    u: NDArray
    v: NDArray
    w: NDArray
    phi: NDArray
    u_x: NDArray
    v_x: NDArray
    w_x: NDArray
    phi_x: NDArray
    v_xx: NDArray
    w_xx: NDArray

    @property
    def rotation(self) -> NDArray:
        """Small section rotation vector Theta = (phi, -w', v'), shape (3, ...)."""
        return np.stack([self.phi, -self.w_x, self.v_x])

    @property
    def kinematic(self) -> NDArray:
        """Section kinematic vector d = (u, v, w, phi, -w', v'): dr1(s) = d[:3] + d[3:] x s, shape (6, ...)."""
        return np.stack([self.u, self.v, self.w, self.phi, -self.w_x, self.v_x])

    @property
    def curvatures(self) -> NDArray:
        """(v'', w''), shape (2, ...)."""
        return np.stack([self.v_xx, self.w_xx])

    @property
    def extension_curvatures(self) -> NDArray:
        """(u', v'', w''), shape (3, ...)."""
        return np.stack([self.u_x, self.v_xx, self.w_xx])


def _derivative(field: DiscreteField, order: int) -> NDArray:
    """Value, span derivative or second span derivative of a scikit-fem field at the quadrature points."""
    if order == 0:
        return np.asarray(field)
    return field.grad[0] if order == 1 else field.hess[0, 0]


def basis_motions(fields: tuple[str, ...], basis: CellBasis) -> tuple[SectionMotion, SectionMotion]:
    """The motions of all local basis functions of ``basis`` at once, as (test, trial) with arrays of shape
    (local, 1, elements, points) and (1, local, elements, points).

    A weak-form term evaluated on them broadcasts to every (test, trial) pair of every element in one vectorised
    call, where scikit-fem's forms call the integrand once per pair. Absent fields are zero.
    """
    zero = np.zeros((basis.Nbfun,) + np.shape(basis.basis[0][0]))

    def stacked(name: str, order: int) -> NDArray:
        if name not in fields or order == 2 and name not in BENDING_FIELDS:
            return zero
        k = fields.index(name)
        return np.stack([_derivative(local[k], order) for local in basis.basis])

    arrays = {"u": stacked("u", 0), "v": stacked("v", 0), "w": stacked("w", 0), "phi": stacked("phi", 0),
              "u_x": stacked("u", 1), "v_x": stacked("v", 1), "w_x": stacked("w", 1), "phi_x": stacked("phi", 1),
              "v_xx": stacked("v", 2), "w_xx": stacked("w", 2)}
    test = SectionMotion(**{name: value[:, None] for name, value in arrays.items()})
    trial = SectionMotion(**{name: value[None, :] for name, value in arrays.items()})
    return test, trial


def interpolated_motion(fields: tuple[str, ...], basis: CellBasis, vectors: NDArray) -> SectionMotion:
    """The motion of DOF vectors (columns over all of ``basis``'s DOFs) at the quadrature points, arrays of shape
    (vectors, elements, points): curvatures formed point by point from the element's nodal values and slopes."""
    test, _ = basis_motions(fields, basis)
    local = np.asarray(vectors)[basis.element_dofs]                  # (local, elements, vectors)
    return SectionMotion(**{name: np.einsum("ieq,iem->meq", getattr(test, name)[:, 0], local)
                            for name in SectionMotion.__dataclass_fields__})
