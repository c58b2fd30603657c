"""Assemble a tower's matrices: elastic stiffness with supports K, gravity stiffness K_g and mass M.

The tower is the blade's beam element, not rotating, in the tower frame (``x`` up, ``v`` side-side, ``w``
fore-aft). Gravity (``-g e_x``) enters as

* the axial force ``N(x) = -g (mass above x + top mass)`` in the geometric stiffness
  :func:`~bladefem.assembly.terms.axial_force_stiffness` (compression softens bending), and
* its work on the second-order displacement of rotated points
  (:func:`~bladefem.elements.rigid_slice.uniform_field_second_order`): the top mass's inverted-pendulum softening
  from the height of its centre of mass, and the same for section or platform centre-of-mass offsets.

``K + lambda K_g`` is the stiffness under ``lambda`` times the gravity load; ``lambda = 1`` is the tower as built.
All four fields are always present: a field without stiffness (no GJ or EA) is tied to its base value by the
constraint of :func:`~bladefem.assembly.supports.base_constraint`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from skfem import Basis

from ..elements import ALL_FIELDS, beam_element, projected_inertia
from ..elements.rigid_slice import uniform_field_second_order
from ..sections import bending_stiffness, extension_bending_stiffness, mass_moments
from ..sections.tower import Tower
from . import terms
from .blade import QUADRATURE_ORDER
from .forms import Quadrature, Term, assemble_terms
from .dofs import DofMap
from .mesh import span_mesh, span_nodes
from .parameters import SectionParameters
from .supports import (
    BASE_SIZE,
    added_mass_parameters,
    base_constraint,
    base_height,
    base_matrices,
    lateral_added_mass,
    node_matrix,
    soil_parameters,
    soil_springs,
    weight_in_restoring,
    wire_stiffness,
)


def rigid_fields(tower: Tower) -> tuple[str, ...]:
    """Fields without stiffness in the section table: 'phi' without GJ, 'u' without EA."""
    sections = tower.sections
    return tuple(name for name, column in (("phi", sections.torsion_stiffness), ("u", sections.axial_stiffness))
                 if column is None)


def mass_above(tower: Tower, x: NDArray) -> NDArray:
    """Mass of the beam above heights ``x`` plus the top mass, kg (exact for mass linear between stations)."""
    s = tower.sections
    x = np.asarray(x, dtype=float)
    pieces = np.diff(s.span) * (s.mass[:-1] + s.mass[1:]) / 2
    from_station = np.concatenate([np.cumsum(pieces[::-1])[::-1], [0.0]])   # from each station to the top
    k = np.clip(np.searchsorted(s.span, x, side="right"), 1, len(s.span) - 1)
    partial = (s.span[k] - x) * (s.at(x, "mass") + s.mass[k]) / 2
    top = tower.top_mass.mass if tower.top_mass is not None else 0.0
    return partial + from_station[k] + top


def gravity_axial_force(tower: Tower, x: NDArray) -> NDArray:
    """Axial force from self-weight and top mass, N (negative: compression)."""
    return -tower.gravity * mass_above(tower, x)


def section_parameters(tower: Tower, x: NDArray) -> SectionParameters:
    """Elastic and inertia matrices of the tower sections at heights ``x`` (no rotation: spin terms are zero)."""
    sections = tower.sections
    moments = mass_moments(sections, x)
    zero6 = np.zeros((6, 6) + np.shape(x))
    return SectionParameters(
        bending=bending_stiffness(sections, x),
        extension_bending=None if sections.axial_stiffness is None else extension_bending_stiffness(sections, x),
        torsion=None if sections.torsion_stiffness is None else sections.at(x, "torsion_stiffness"),
        inertia=projected_inertia(np.eye(3), moments.m, moments.S, moments.J),
        spin=zero6, rotation=np.zeros((3, 3) + np.shape(x)), tension=np.zeros(np.shape(x)))


def gravity_parameters(tower: Tower, x: NDArray) -> SectionParameters:
    """Gravity's geometric stiffness at heights ``x``: the axial force in ``tension`` and, in ``rotation``, minus
    the sections' second-order potential (``terms.rotation_second_order`` returns ``-Theta^T rotation Theta``)."""
    base = section_parameters(tower, x)
    S = mass_moments(tower.sections, x).S
    H = uniform_field_second_order(np.array([tower.gravity, 0.0, 0.0]), S)
    return SectionParameters(bending=base.bending, extension_bending=None, torsion=None, inertia=base.inertia,
                             spin=base.spin, rotation=-H, tension=gravity_axial_force(tower, x))


def elastic_terms(tower: Tower) -> list[Term]:
    parts: list[Term] = [terms.bending_stiffness if tower.sections.axial_stiffness is None
                         else terms.extension_bending_stiffness]
    if tower.sections.torsion_stiffness is not None:
        parts.append(terms.torsion_stiffness)
    return parts


def top_body_matrices(tower: Tower, dofs: DofMap, size: int) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Mass matrix and gravity stiffness of the top mass on the top node's kinematic vector."""
    top = tower.top_mass
    if top is None:
        zero = sp.csr_matrix((size, size))
        return zero, zero
    S = top.mass * top.offset
    inertia = projected_inertia(np.eye(3), np.float64(top.mass), S, top.second_moment)
    gravity = np.zeros((6, 6))
    gravity[3:, 3:] = uniform_field_second_order(np.array([tower.gravity, 0.0, 0.0]), S)
    last = len(dofs.nodes) - 1
    return node_matrix(dofs, last, inertia, size), node_matrix(dofs, last, gravity, size)


def _pad(matrix: sp.spmatrix, size: int) -> sp.csr_matrix:
    """A beam matrix extended by zero rows and columns for the base coordinates."""
    return sp.block_diag([matrix, sp.csr_matrix((size - matrix.shape[0],) * 2)]).tocsr()


def _base_block(block: NDArray, size: int) -> sp.csr_matrix:
    out = sp.lil_matrix((size, size))
    out[size - BASE_SIZE:, size - BASE_SIZE:] = block
    return out.tocsr()


@dataclass(frozen=True)
class TowerMatrices:
    """Matrices over the beam DOFs followed by the six base coordinates, and the constraint ``(x, q) = Z r``.

    K_elastic : the beam's elastic stiffness (zero on rigid motion, so it acts on the elastic columns of Z only)
    K : wires, soil and base springs (hydrostatics, mooring, foundation)
    K_gravity : geometric stiffness of the gravity load (zero when ``tower.gravity`` is 0)
    M : mass matrix with top mass, base mass (platform, added mass, foundation)
    Z : constraint matrix from the independent coordinates r
    dofs : the beam's DOF map
    """

    K_elastic: sp.csr_matrix
    K: sp.csr_matrix
    K_gravity: sp.csr_matrix
    M: sp.csr_matrix
    Z: sp.csr_matrix
    dofs: DofMap
    tower: Tower

    @property
    def size(self) -> int:
        return self.dofs.size + BASE_SIZE

    @property
    def n_free(self) -> int:
        return self.Z.shape[1]

    @property
    def n_elastic(self) -> int:
        """Number of elastic coordinates (the first columns of Z; the last six move the base, if it moves)."""
        return self.n_free - len(self.tower.supports.free_base)

    def reduced(self, load_factor: float = 1.0) -> tuple[sp.csc_matrix, sp.csc_matrix]:
        """(K, M) on the independent coordinates, with ``load_factor`` times the gravity load."""
        K = self.Z.T @ (self.K + load_factor * self.K_gravity) @ self.Z
        elastic = self.Z[:, :self.n_elastic]
        K = K + sp.block_diag([elastic.T @ self.K_elastic @ elastic,
                               sp.csr_matrix((self.n_free - self.n_elastic,) * 2)])
        M = self.Z.T @ self.M @ self.Z
        return sp.csc_matrix(0.5 * (K + K.T)), sp.csc_matrix(0.5 * (M + M.T))

    def expand(self, vectors: NDArray) -> NDArray:
        """Full vectors (beam DOFs then base coordinates) from independent coordinates (columns)."""
        return self.Z @ vectors


#: support points closer than this (fraction of the height) to a section station are placed at the station
SNAP = 1e-3


def tower_nodes(tower: Tower, elements: int) -> NDArray:
    """Mesh nodes: section stations, wire heights and soil points are all nodes (a support point within
    :data:`SNAP` of the height from a station is that station: a sliver element would ruin the conditioning)."""
    stations, support = tower.sections.nodes, np.unique(tower.supports.mesh_points())
    if support.size:
        gap = np.min(np.abs(support[:, None] - stations[None, :]), axis=1)
        apart = np.concatenate([[True], np.diff(support) > SNAP * tower.height])
        support = support[(gap > SNAP * tower.height) & apart]
    return span_nodes(np.union1d(stations, support), elements)


def assemble_tower(tower: Tower, elements: int = 60) -> TowerMatrices:
    """Assemble the tower on a mesh of about ``elements`` elements (stations and support points are nodes)."""
    fields = ALL_FIELDS
    basis = Basis(span_mesh(tower_nodes(tower, elements)), beam_element(fields), intorder=QUADRATURE_ORDER)
    x = np.asarray(basis.global_coordinates())[0]
    quadrature = Quadrature.from_basis(basis, fields)
    dofs = DofMap.from_basis(basis, fields)
    size = dofs.size + BASE_SIZE
    sections = section_parameters(tower, x)
    M_top, G_top = top_body_matrices(tower, dofs, size)
    base = base_matrices(tower, float(mass_above(tower, np.array([0.0]))[0]))
    K_elastic = _pad(assemble_terms(quadrature, sections, elastic_terms(tower)), size)
    K = (_pad(assemble_terms(quadrature, soil_parameters(tower.supports, x), [soil_springs]), size)
         + wire_stiffness(tower.supports, dofs, size) + _base_block(base.stiffness, size))
    M = _pad(assemble_terms(quadrature, sections, [terms.inertia]), size) + M_top + _base_block(base.mass, size)
    if tower.supports.added_mass is not None:
        M = M + _pad(assemble_terms(quadrature, added_mass_parameters(tower.supports, x), [lateral_added_mass]), size)
    if tower.gravity > 0:
        gravity = gravity_parameters(tower, x)
        K_gravity = (_pad(assemble_terms(quadrature, gravity, [terms.axial_force_stiffness,
                                                                  terms.rotation_second_order]), size)
                     + G_top + _base_block(base.gravity, size))
        platform = tower.supports.platform
        if platform is not None and platform.restoring_includes_weight:
            K_gravity = K_gravity + weight_in_restoring(K_gravity, dofs, base_height(tower.supports))
    else:
        K_gravity = sp.csr_matrix((size, size))
    Z = base_constraint(dofs, rigid_fields(tower), tower.supports.free_base, base_height(tower.supports))
    return TowerMatrices(K_elastic=K_elastic, K=K.tocsr(), K_gravity=K_gravity.tocsr(), M=M.tocsr(), Z=Z,
                         dofs=dofs, tower=tower)
