"""The reduction of a flutter sweep: one modal basis for the whole sweep and the section matrices of each operating
point integrated against it.

The basis is the lowest undamped modes at the sweep's lowest and highest rotor speeds together, made
mass-orthonormal (Rayleigh-Ritz): ``K0 + Omega^2 K2`` changes smoothly with the rotor speed, and the two ends' modes
span the modes in between to the Ritz error (the tests compare with the full solve). The basis's motion at the
blade mesh's quadrature points is formed once; each operating point then only interpolates its section matrices
to those points and multiplies them in (batched 6 x 6 products).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import scipy.linalg as la
from numpy.typing import NDArray
from skfem import Basis

from ..assembly import BladeMatrices, span_mesh
from ..assembly.blade import QUADRATURE_ORDER
from ..elements import SectionMotion, beam_element, interpolated_components
from ..modal.solve import eigen_pairs
from .flutter_aero import FlutterSections, theodorsen

#: basis vectors whose mass-norm falls below this fraction of the largest are the same motion twice (dropped)
INDEPENDENT = 1e-10


class SweepBasis:
    """The mass-orthonormal basis ``Phi`` (free DOFs, columns) of a sweep and the reduced structure:
    ``Phi^T M Phi = I``, ``K0_r``, ``K2_r`` (per Omega^2), ``G_r`` (Coriolis per Omega)."""

    def __init__(self, matrices: BladeMatrices, rotor_speeds: Sequence[float], count: int):
        K0, K2, M = matrices.free_parts
        ends = sorted({min(rotor_speeds), max(rotor_speeds)})
        stacked = np.hstack([eigen_pairs(K0 + speed**2 * K2, M, count)[1] for speed in ends])
        gram = stacked.T @ (M @ stacked)
        values, vectors = la.eigh(gram)
        keep = values > INDEPENDENT * values[-1]
        self.vectors = stacked @ (vectors[:, keep] / np.sqrt(values[keep]))
        Phi = self.vectors
        self.K0, self.K2 = Phi.T @ (K0 @ Phi), Phi.T @ (K2 @ Phi)
        self.G = Phi.T @ (matrices.free_gyroscopic @ Phi)
        full = np.zeros((matrices.dofs.size, Phi.shape[1]))
        full[matrices.free] = Phi
        quadrature = matrices.quadrature
        names = tuple(SectionMotion.__dataclass_fields__)
        values = interpolated_components(quadrature.functions, quadrature.element_dofs, full, names)
        motion = SectionMotion(**dict(zip(names, values))).kinematic
        self.motion = np.ascontiguousarray(motion.reshape(6, Phi.shape[1], -1).transpose(2, 0, 1))  # (q, 6, n)
        self.weights = quadrature.weights.ravel()
        basis = Basis(span_mesh(matrices.dofs.nodes), beam_element(matrices.dofs.fields), intorder=QUADRATURE_ORDER)
        self.x = np.asarray(basis.global_coordinates())[0].ravel()

    @property
    def size(self) -> int:
        return self.vectors.shape[1]

    def stiffness(self, rotor_speed: float) -> NDArray:
        """Reduced structural stiffness at ``rotor_speed`` (rad/s)."""
        return self.K0 + rotor_speed**2 * self.K2


class ReducedAero:
    """The section matrices of one operating point integrated against a :class:`SweepBasis`; calling it with ``p``
    gives the reduced (M_a, D, K) with ``C(k)`` at each quadrature point's own reduced frequency."""

    def __init__(self, basis: SweepBasis, sections: FlutterSections):
        inside = (basis.x >= sections.span[0]) & (basis.x <= sections.span[-1])
        self.points = np.flatnonzero(inside)
        x = basis.x[self.points]
        right = np.clip(np.searchsorted(sections.span, x, side="right"), 1, len(sections.span) - 1)
        left = right - 1
        gap = sections.span[right] - sections.span[left]
        t = np.divide(x - sections.span[left], gap, out=np.zeros_like(x), where=gap > 0)
        phi = basis.motion[self.points]                                        # (q, 6, n)
        weights = basis.weights[self.points]

        def project(A: NDArray) -> NDArray:                                    # (q, n, n)
            at = (A[:, :, left] * (1 - t) + A[:, :, right] * t).transpose(2, 0, 1) * weights[:, None, None]
            return np.swapaxes(phi, 1, 2) @ (at @ phi)

        self.mass = project(sections.apparent_mass).sum(axis=0)
        self.damping = project(sections.quasi_steady_damping + sections.apparent_damping).sum(axis=0)
        self.stiffness = project(sections.quasi_steady_stiffness).sum(axis=0)
        n = basis.size
        self.lift = np.stack([project(sections.lift_damping), project(sections.lift_stiffness)], axis=1).reshape(
            len(x), 2 * n * n)                                                  # C(k)-weighted: one product
        speed = np.interp(x, sections.span, sections.speed)
        self.frequency_scale = np.divide(np.interp(x, sections.span, sections.semi_chord), speed,
                                         out=np.zeros_like(x), where=speed > 0)

    def __call__(self, p: complex) -> tuple[NDArray, NDArray, NDArray]:
        c = theodorsen(abs(p.imag) * self.frequency_scale)
        damping, stiffness = (c @ self.lift).reshape(2, *self.mass.shape)
        return self.mass, self.damping + damping, self.stiffness + stiffness
