"""The beam element: Hermite cubic bending in two planes, quadratic torsion and axial fields, and optionally
quadratic transverse-shear deflections (a Timoshenko beam).

Fields: ``v`` edgewise (in-plane) and ``w`` flapwise (out-of-plane) bending deflection, C1 Hermite cubics; ``phi``
elastic twist and ``u`` axial displacement, quadratic Lagrange. A model may drop ``phi`` or ``u`` (rigid torsion or
axial). A shear-flexible model adds ``v_s`` and ``w_s``, quadratic Lagrange: the deflection is ``v + v_s`` (and
``w + w_s``), the section turns with the bending part only (``Theta = (phi, -w', v')``), so the transverse shear
strains are ``v_s'`` and ``w_s'``. Without them the beam is Euler-Bernoulli.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache

import numpy as np
from numpy.typing import NDArray
from skfem import CellBasis, ElementComposite, ElementLineP2
from skfem.element import DiscreteField, Element
from skfem.refdom import RefLine

class ElementLineHermiteReference(Element):
    """The C1 cubic Hermite line element (scikit-fem's ``ElementLineHermite``: same space, same DOFs: value and
    slope at each end) evaluated through the reference element: ``xi = (x - a) / h`` in [0, 1], the value shape
    functions of ``xi`` and the slope ones scaled by ``h``.

    scikit-fem's version inverts, per element, a Vandermonde matrix of global monomials ``1, x, x^2, x^3``, whose
    condition grows as ``(x / h)^3``: 1e-8 of the basis lost at 2000 elements on a 100 m blade, and a singular
    matrix for an element shorter than 1e-5 of its distance from the root.
    """

    nodal_dofs = 2
    maxdeg = 3
    dofnames = ["u", "u_x"]
    doflocs = np.array([[0.0], [0.0], [1.0], [1.0]])
    refdom = RefLine

    def gbasis(self, mapping: object, X: NDArray, i: int, tind: NDArray | None = None) -> tuple[DiscreteField]:
        h = mapping.DF(X, tind)[0, 0]                           # element length, (elements, points)
        xi = np.broadcast_to(X[0], h.shape)
        if i == 0:
            value, slope, curvature = 1 - 3 * xi**2 + 2 * xi**3, (-6 * xi + 6 * xi**2) / h, (-6 + 12 * xi) / h**2
        elif i == 1:
            value, slope, curvature = h * (xi - 2 * xi**2 + xi**3), 1 - 4 * xi + 3 * xi**2, (-4 + 6 * xi) / h
        elif i == 2:
            value, slope, curvature = 3 * xi**2 - 2 * xi**3, (6 * xi - 6 * xi**2) / h, (6 - 12 * xi) / h**2
        elif i == 3:
            value, slope, curvature = h * (-xi**2 + xi**3), -2 * xi + 3 * xi**2, (-2 + 6 * xi) / h
        else:
            self._index_error()
        return (DiscreteField(value=value, grad=slope[None], hess=curvature[None, None]),)


BENDING_FIELDS: tuple[str, ...] = ("v", "w")
#: the transverse-shear deflections of a shear-flexible (Timoshenko) beam, in the order of BENDING_FIELDS
SHEAR_FIELDS: tuple[str, ...] = ("v_s", "w_s")
ALL_FIELDS: tuple[str, ...] = ("v", "w", "phi", "u")
FIELD_ELEMENTS: dict[str, type[Element]] = {"v": ElementLineHermiteReference, "w": ElementLineHermiteReference,
                                            "phi": ElementLineP2, "u": ElementLineP2, "v_s": ElementLineP2,
                                            "w_s": ElementLineP2}
#: what each field is called in results
FIELD_KINDS: dict[str, str] = {"v": "edge", "w": "flap", "phi": "torsion", "u": "axial", "v_s": "edge",
                               "w_s": "flap"}


class ElementBeam(ElementComposite):
    """scikit-fem's composite element (same space, same DOFs), each local function evaluated on its own field's
    element only. scikit-fem's ``ElementComposite.gbasis`` evaluates every field's element for every local function
    and keeps zeros of all but one, a cost that grows with the square of the number of fields; here the other
    fields' zeros are made once per field and quadrature shape."""

    def __init__(self, *elems: Element) -> None:
        super().__init__(*elems)
        self._owners: dict[int, tuple[int, int]] = {}
        self._zeros: dict[tuple[int, tuple[int, ...]], DiscreteField] = {}

    def gbasis(self, mapping: object, X: NDArray, i: int, tind: NDArray | None = None) -> tuple[DiscreteField, ...]:
        if i not in self._owners:
            self._owners[i] = self._deduce_bfun(i)
        n, index = self._owners[i]
        own = self.elems[n].gbasis(mapping, X, index, tind)[0]

        def zero(k: int) -> DiscreteField:
            key = (k, np.shape(own))
            if key not in self._zeros:
                self._zeros[key] = self.elems[k].gbasis(mapping, X, 0, tind)[0].zeros()
            return self._zeros[key]

        return tuple(own if k == n else zero(k) for k in range(len(self.elems)))


@cache
def beam_element(fields: tuple[str, ...]) -> ElementComposite:
    """Composite element with one sub-element per field, in the order given; one instance per tuple of fields, so
    that its bookkeeping (which field owns each local function, the other fields' zeros) is done once."""
    return ElementBeam(*(FIELD_ELEMENTS[name]() for name in fields))


@dataclass(frozen=True)
class SectionMotion:
    """Displacements and their span derivatives of one basis function at the quadrature points.

    ``v``, ``w`` are the bending deflections (their slopes turn the section), ``v_s``, ``w_s`` the shear
    deflections (their slopes are the transverse shear strains). Arrays have shape (elements, quadrature points);
    absent fields are zero.
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
    v_s: NDArray
    w_s: NDArray
    v_s_x: NDArray
    w_s_x: NDArray

    @property
    def rotation(self) -> NDArray:
        """Small section rotation vector Theta = (phi, -w', v'), shape (3, ...)."""
        return np.stack([self.phi, -self.w_x, self.v_x])

    @property
    def kinematic(self) -> NDArray:
        """Section kinematic vector d = (u, v + v_s, w + w_s, phi, -w', v'): dr1(s) = d[:3] + d[3:] x s, shape
        (6, ...)."""
        return np.stack([self.u, self.v + self.v_s, self.w + self.w_s, self.phi, -self.w_x, self.v_x])

    @property
    def curvatures(self) -> NDArray:
        """(v'', w''), shape (2, ...)."""
        return np.stack([self.v_xx, self.w_xx])

    @property
    def extension_curvatures(self) -> NDArray:
        """(u', v'', w''), shape (3, ...)."""
        return np.stack([self.u_x, self.v_xx, self.w_xx])

    @property
    def strains(self) -> NDArray:
        """Generalised strains in the blade frame (u', gamma_y, gamma_z, phi', v'', w''), shape (6, ...): the
        transverse shear strains ``gamma = (v + v_s)' - v' = v_s'`` (and ``w_s'``)."""
        return np.stack([self.u_x, self.v_s_x, self.w_s_x, self.phi_x, self.v_xx, self.w_xx])


def _derivative(field: DiscreteField, order: int) -> NDArray:
    """Value, span derivative or second span derivative of a scikit-fem field at the quadrature points."""
    if order == 0:
        return np.asarray(field)
    return field.grad[0] if order == 1 else field.hess[0, 0]


def basis_functions(fields: tuple[str, ...], basis: CellBasis) -> SectionMotion:
    """The motions of all local basis functions of ``basis`` at the quadrature points: arrays of shape (local,
    elements, points), zero for absent fields."""
    zero = np.zeros((basis.Nbfun,) + np.shape(basis.basis[0][0]))

    def stacked(name: str, order: int) -> NDArray:
        if name not in fields or order == 2 and name not in BENDING_FIELDS:
            return zero
        k = fields.index(name)
        return np.stack([_derivative(local[k], order) for local in basis.basis])

    return SectionMotion(u=stacked("u", 0), v=stacked("v", 0), w=stacked("w", 0), phi=stacked("phi", 0),
                         u_x=stacked("u", 1), v_x=stacked("v", 1), w_x=stacked("w", 1), phi_x=stacked("phi", 1),
                         v_xx=stacked("v", 2), w_xx=stacked("w", 2), v_s=stacked("v_s", 0), w_s=stacked("w_s", 0),
                         v_s_x=stacked("v_s", 1), w_s_x=stacked("w_s", 1))


def _map(motion: SectionMotion, function: Callable[[NDArray], NDArray]) -> SectionMotion:
    return SectionMotion(**{name: function(getattr(motion, name)) for name in SectionMotion.__dataclass_fields__})


def pair_motions(motion: SectionMotion) -> tuple[SectionMotion, SectionMotion]:
    """(test, trial) views of a motion with a leading axis of n functions or vectors: shapes (n, 1, ...) and
    (1, n, ...). A weak-form term evaluated on them broadcasts to every (test, trial) pair at once (scikit-fem's
    forms call the integrand once per pair instead)."""
    return _map(motion, lambda a: a[:, None]), _map(motion, lambda a: a[None, :])


def interpolated_components(functions: SectionMotion, element_dofs: NDArray, vectors: NDArray,
                            names: tuple[str, ...]) -> NDArray:
    """The motion components ``names`` (fields of :class:`SectionMotion`) of DOF vectors (columns over all DOFs) at
    the quadrature points, shape (components, vectors, elements, points), from the basis ``functions``
    (:func:`basis_functions`) and each element's DOFs: curvatures are formed point by point from the element's
    nodal values and slopes."""
    local = np.asarray(vectors)[element_dofs].transpose(1, 0, 2)       # (elements, local, vectors)
    return np.stack([np.matmul(getattr(functions, name).transpose(1, 2, 0), local).transpose(2, 0, 1)
                     for name in names])
