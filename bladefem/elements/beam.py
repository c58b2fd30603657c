"""The beam element: Hermite cubic bending in two planes, quadratic torsion and axial fields.

Fields: ``v`` edgewise (in-plane) and ``w`` flapwise (out-of-plane) deflection, C1 Hermite cubics; ``phi`` elastic
twist and ``u`` axial displacement, quadratic Lagrange. A model may drop ``phi`` or ``u`` (rigid torsion or axial).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from skfem import ElementComposite, ElementLineHermite, ElementLineP2
from skfem.element import Element

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


def section_motion(fields: tuple[str, ...], values: tuple) -> SectionMotion:
    """Build a :class:`SectionMotion` from scikit-fem DiscreteFields given in the order of ``fields``."""
    by_name = dict(zip(fields, values))
    zero = np.zeros(np.shape(values[0]))

    def value(name: str) -> NDArray:
        return np.asarray(by_name[name]) if name in by_name else zero

    def slope(name: str) -> NDArray:
        return by_name[name].grad[0] if name in by_name else zero

    def curvature(name: str) -> NDArray:
        return by_name[name].hess[0, 0]

    return SectionMotion(u=value("u"), v=value("v"), w=value("w"), phi=value("phi"), u_x=slope("u"),
                         v_x=slope("v"), w_x=slope("w"), phi_x=slope("phi"), v_xx=curvature("v"),
                         w_xx=curvature("w"))
