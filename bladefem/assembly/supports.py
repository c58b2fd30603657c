"""Tower supports: the base coordinates and how the beam is tied to them, wires, foundation, platform, soil.

The model's DOFs are the beam's finite-element DOFs followed by six **base coordinates** ``q = (t, theta)``: the
translation and rotation (tower frame) of the foundation at the tower base, or of the floating platform at its
reference point, which sits ``h`` below the beam's bottom. The beam's bottom node moves with them,
``d_base = (t + theta x h e_x, theta)`` in the kinematic vector ``d = (u, v, w, phi, -w', v')``, and a field that is
rigid in the model (torsion without GJ, extension without EA) equals its base value everywhere. Both are exact
linear constraints: the constrained DOFs are eliminated by ``x = Z r`` (no penalty stiffness). A clamped base fixes
``q = 0``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..elements import SectionMotion, projected_inertia
from ..elements.rigid_slice import uniform_field_second_order
from ..sections.tower import Supports, Tower, openfast_to_tower
from .dofs import DofMap

#: names of the base coordinates of a floating platform (tower frame: x up, y side-side, z downwind)
PLATFORM_KINDS: tuple[str, ...] = ("heave", "sway", "surge", "yaw", "pitch", "roll")
#: the beam field each base coordinate moves (for a foundation the base motion counts as beam motion)
BASE_FIELDS: tuple[str, ...] = ("u", "v", "w", "phi", "w", "v")
BASE_SIZE = 6


def base_kinematics(height: float) -> NDArray[np.float64]:
    """6x6 ``A`` with ``d_base = A q``: a point ``height`` m above the reference point of a rigid base."""
    A = np.eye(6)
    A[1, 5] = height      # v = t_y + h theta_z
    A[2, 4] = -height     # w = t_z - h theta_y
    return A


def base_constraint(dofs: DofMap, rigid_fields: tuple[str, ...], moving: bool, height: float) -> sp.csr_matrix:
    """``Z`` with ``(x, q) = Z r``: the independent coordinates ``r`` are the unconstrained beam DOFs followed by
    ``q`` (when the base moves). The bottom node follows the base; rigid fields equal their base value."""
    n = dofs.size
    A = base_kinematics(height)
    # beam DOF -> row of A giving it (sign for the slope of w, since d[4] = -w')
    tied: dict[int, tuple[int, float]] = {}
    for name, row in (("u", 0), ("v", 1), ("w", 2), ("phi", 3)):
        tied[int(dofs.value[name][0])] = (row, 1.0)
    tied[int(dofs.slope["w"][0])] = (4, -1.0)
    tied[int(dofs.slope["v"][0])] = (5, 1.0)
    for name in rigid_fields:
        row = 0 if name == "u" else 3
        for dof in dofs.field_dofs[name]:
            tied[int(dof)] = (row, 1.0)
    independent = np.setdiff1d(np.arange(n), np.fromiter(tied, dtype=np.int64))
    rows, cols, values = list(independent), list(range(len(independent))), [1.0] * len(independent)
    if moving:
        first_q = len(independent)
        for dof, (row, sign) in tied.items():
            for k in np.flatnonzero(A[row]):
                rows.append(dof)
                cols.append(first_q + k)
                values.append(sign * A[row, k])
        rows += list(range(n, n + BASE_SIZE))
        cols += list(range(first_q, first_q + BASE_SIZE))
        values += [1.0] * BASE_SIZE
    width = len(independent) + (BASE_SIZE if moving else 0)
    return sp.csr_matrix((values, (rows, cols)), shape=(n + BASE_SIZE, width))


def base_height(supports: Supports) -> float:
    """Height of the beam's bottom above the base reference point, m (0 for a foundation)."""
    return supports.platform.base_height if supports.platform is not None else 0.0


@dataclass(frozen=True)
class BaseMatrices:
    """6x6 matrices on the base coordinates q (tower frame).

    stiffness : foundation springs, or platform hydrostatics plus mooring
    mass : foundation mass, or platform rigid body plus added mass
    gravity : gravity's second-order potential of the platform's weight and of the weight above the base lifted
        by the platform's tilt (the beam itself measures foreshortening from its bottom node)
    """

    stiffness: NDArray[np.float64]
    mass: NDArray[np.float64]
    gravity: NDArray[np.float64]


def base_matrices(tower: Tower, weight_above_base: float) -> BaseMatrices:
    """The base coordinates' own matrices; ``weight_above_base`` is the mass of beam plus top mass, kg."""
    supports = tower.supports
    zero = np.zeros((6, 6))
    if supports.foundation is not None:
        f = supports.foundation
        return BaseMatrices(openfast_to_tower(f.stiffness), openfast_to_tower(f.mass), zero)
    if supports.platform is None:
        return BaseMatrices(zero, zero, zero)
    p = supports.platform
    body = p.body()
    rigid = projected_inertia(np.eye(3), np.float64(body.mass), body.mass * body.offset, body.second_moment)
    first_moment = body.mass * body.offset + weight_above_base * np.array([p.base_height, 0.0, 0.0])
    gravity = np.zeros((6, 6))
    gravity[3:, 3:] = uniform_field_second_order(np.array([tower.gravity, 0.0, 0.0]), first_moment)
    return BaseMatrices(stiffness=openfast_to_tower(p.hydrostatic + p.mooring),
                        mass=rigid + openfast_to_tower(p.added_mass), gravity=gravity)


def node_matrix(dofs: DofMap, node: int, block: NDArray, size: int) -> sp.csr_matrix:
    """A 6x6 matrix on the kinematic vector of ``node`` as a ``size`` x ``size`` global matrix."""
    T = dofs.kinematic_selector(node)
    T = sp.hstack([T, sp.csr_matrix((6, size - dofs.size))]).tocsr()
    return (T.T @ sp.csr_matrix(block) @ T).tocsr()


def wire_stiffness(supports: Supports, dofs: DofMap, size: int) -> sp.csr_matrix:
    """Wire springs on the translations (u, v, w) of their attachment nodes."""
    K = sp.csr_matrix((size, size))
    for wires in supports.wires:
        node = int(np.argmin(np.abs(dofs.nodes - wires.height)))
        block = np.zeros((6, 6))
        block[:3, :3] = wires.stiffness_matrix()
        K = K + node_matrix(dofs, node, block, size)
    return K


@dataclass(frozen=True)
class SoilParameters:
    """Soil-spring stiffness per length at the quadrature points (zero above the embedded length)."""

    lateral: NDArray
    axial: NDArray
    torsional: NDArray


def soil_parameters(supports: Supports, x: NDArray) -> SoilParameters:
    soil = supports.soil
    zero = np.zeros_like(x)
    if soil is None:
        return SoilParameters(zero, zero, zero)
    return SoilParameters(soil.at(x, "lateral"), soil.at(x, "axial"), soil.at(x, "torsional"))


def soil_springs(trial: SectionMotion, test: SectionMotion, p: SoilParameters) -> NDArray:
    """Distributed (Winkler) springs along the embedded length: k_lat (v dv + w dw) + k_ax u du + k_t phi dphi."""
    return (p.lateral * (test.v * trial.v + test.w * trial.w) + p.axial * test.u * trial.u
            + p.torsional * test.phi * trial.phi)
