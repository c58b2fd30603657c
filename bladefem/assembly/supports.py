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
from ..sections.tower import BASE_COORDINATES, Supports, Tower, openfast_to_tower
from .dofs import DofMap

#: names of the base coordinates of a floating platform (tower frame: x up, y side-side, z downwind)
PLATFORM_KINDS: tuple[str, ...] = BASE_COORDINATES
#: the beam field each base coordinate moves (for a foundation the base motion counts as beam motion)
BASE_FIELDS: tuple[str, ...] = ("u", "v", "w", "phi", "w", "v")
BASE_SIZE = 6


def base_constraint(dofs: DofMap, rigid_fields: tuple[str, ...], free_base: tuple[int, ...],
                    height: float) -> sp.csr_matrix:
    """``Z`` with ``(x, q) = Z r``. The independent coordinates ``r`` are the beam's elastic DOFs relative to the
    base (the bottom node held, rigid fields zero) followed by the base coordinates that move (``free_base``,
    indices into ``q``; the others are held at zero), each moving the whole tower rigidly (:func:`rigid_motion`).
    The total motion is the same as tying the bottom node to the base, but the elastic stiffness never has to
    cancel on a rigid motion: it acts on the elastic columns only."""
    n = dofs.size
    held = [dofs.value[name][0] for name in dofs.fields] + [dofs.slope[name][0] for name in dofs.slope]
    held += [dof for name in rigid_fields for dof in dofs.field_dofs[name]]
    independent = np.setdiff1d(np.arange(n), np.array(held, dtype=np.int64))
    elastic = sp.csr_matrix((np.ones(len(independent)), (independent, np.arange(len(independent)))),
                            shape=(n + BASE_SIZE, len(independent)))
    if not free_base:
        return elastic
    return sp.hstack([elastic, sp.csr_matrix(rigid_motion(dofs, height)[:, list(free_base)])]).tocsr()


def rigid_motion(dofs: DofMap, height: float) -> NDArray[np.float64]:
    """(size + 6) x 6 matrix: the full vector (beam DOFs, base coordinates) of the whole tower moving rigidly with
    unit base coordinates ``q`` of a base reference point ``height`` m below the beam's bottom."""
    R = np.zeros((dofs.size + BASE_SIZE, BASE_SIZE))
    arm = height + dofs.nodes
    R[dofs.field_dofs["u"], 0] = 1.0                                    # t_x
    R[dofs.field_dofs["phi"], 3] = 1.0                                  # theta_x
    R[dofs.value["v"], 1], R[dofs.value["v"], 5] = 1.0, arm             # v = t_y + (h + x) theta_z
    R[dofs.slope["v"], 5] = 1.0
    R[dofs.value["w"], 2], R[dofs.value["w"], 4] = 1.0, -arm            # w = t_z - (h + x) theta_y
    R[dofs.slope["w"], 4] = -1.0
    R[dofs.size:, :] = np.eye(BASE_SIZE)
    return R


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
    gravity[3:, 3:] = uniform_field_second_order(np.array([tower.gravity, 0.0, 0.0]), first_moment, beam_node=False)
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


def weight_in_restoring(K_gravity: sp.spmatrix, dofs: DofMap, height: float) -> sp.csr_matrix:
    """A base-coordinate block that removes gravity's stiffness on rigid motions of the whole tower, ``-R^T K_g R``
    with ``R`` = :func:`rigid_motion`: for a platform whose restoring matrices already hold the weight terms
    (:attr:`bladefem.sections.tower.Platform.restoring_includes_weight`). Elastic motions have zero base
    coordinates, so gravity still acts on them (axial load, top-mass pendulum) and on their coupling with the
    rigid motion."""
    R = rigid_motion(dofs, height)
    block = -(R.T @ (K_gravity @ R))
    size = dofs.size + BASE_SIZE
    out = sp.lil_matrix((size, size))
    out[dofs.size:, dofs.size:] = 0.5 * (block + block.T)
    return out.tocsr()


@dataclass(frozen=True)
class AddedMassParameters:
    """Distributed lateral added mass per length at the quadrature points, kg/m (zero outside its extent)."""

    lateral: NDArray


def added_mass_parameters(supports: Supports, x: NDArray) -> AddedMassParameters:
    mass = supports.added_mass
    return AddedMassParameters(np.zeros_like(x) if mass is None else mass.at(x))


def lateral_added_mass(trial: SectionMotion, test: SectionMotion, p: AddedMassParameters) -> NDArray:
    """Distributed added mass on the lateral translations: m_a (v dv + w dw) (inertia only, no weight)."""
    return p.lateral * (test.v * trial.v + test.w * trial.w)
