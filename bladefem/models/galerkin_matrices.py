"""Galerkin mass and stiffness matrices of a rotating cantilever blade by span quadrature.

Generalized coordinates ``q = (a_1..a_Nw, b_1..b_Nv, c_1..c_Nphi)``: ``w = sum a_j psi_j``, ``v = sum b_j psi_j``,
``phi = sum c_j chi_j`` (:mod:`bladefem.models.galerkin_basis`). The energies of docs/THEORY.md are integrated by
Gauss-Legendre quadrature on every station interval (subdivided so that the span has at least ``MIN_CELLS`` cells),
with the section columns interpolated linearly between stations exactly as :class:`SectionTable` defines them.
The section stiffness and mass moments are derived from those raw columns in :mod:`.galerkin_sections`, not taken
from :mod:`bladefem.sections.moments` (the finite elements' source), so that FE-Galerkin agreement checks them.
``K(Omega) = K0 + Omega^2 K2``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..sections import Blade
from .galerkin_basis import Basis, bending_shapes, torsion_shapes
from .galerkin_sections import SectionProperties, body_second_moment, column, section_properties
from .galerkin_terms import (
    axial_centrifugal_force,
    kinetic_form,
    rotation_second_order_form,
    spin_softening_form,
    tension_form,
)

#: The span is cut into at least this many quadrature cells (station intervals are subdivided evenly).
MIN_CELLS = 24


@dataclass(frozen=True)
class Terms:
    """Numbers of assumed modes: flap ``w``, lead-lag ``v`` and torsion ``phi`` (0 for rigid torsion)."""

    flap: int = 5
    edge: int = 5
    torsion: int = 3

    @property
    def size(self) -> int:
        return self.flap + self.edge + self.torsion

    def slices(self) -> dict[str, slice]:
        """Positions of each field's coefficients in ``q``."""
        return {"flap": slice(0, self.flap), "edge": slice(self.flap, self.flap + self.edge),
                "torsion": slice(self.flap + self.edge, self.size)}


@dataclass(frozen=True)
class SpanQuadrature:
    """Quadrature points ``x`` (m) and weights (m) over the flexible span."""

    x: NDArray[np.float64]
    weights: NDArray[np.float64]


@dataclass(frozen=True)
class GalerkinMatrices:
    """``M`` (kg-based), ``K0`` (elastic) and ``K2`` (per Omega^2) over ``q``, and the terms they use."""

    M: NDArray[np.float64]
    K0: NDArray[np.float64]
    K2: NDArray[np.float64]
    terms: Terms
    basis: Basis


def cell_edges(span: NDArray, min_cells: int = MIN_CELLS) -> NDArray:
    """Station positions with every interval split evenly so that the span has at least ``min_cells`` cells."""
    length = span[-1]
    edges = [span[:1]]
    for x0, x1 in zip(span[:-1], span[1:]):
        parts = int(np.ceil(min_cells * (x1 - x0) / length - 1e-9))
        edges.append(np.linspace(x0, x1, max(parts, 1) + 1)[1:])
    return np.concatenate(edges)


def gauss_on_cells(edges: NDArray, order: int) -> SpanQuadrature:
    """Gauss-Legendre rule of ``order`` points on each cell between consecutive ``edges``."""
    t, w = np.polynomial.legendre.leggauss(order)
    x0, h = edges[:-1, None], np.diff(edges)[:, None]
    return SpanQuadrature(x=(x0 + 0.5 * h * (t + 1)).ravel(), weights=(0.5 * h * w).ravel())


def axial_force_density(blade: Blade, x: NDArray) -> NDArray:
    """Centrifugal axial force per length and per Omega^2 at span positions ``x``, kg."""
    section = section_properties(blade, x)
    return axial_centrifugal_force(section.m, section.S, blade.hub_radius + x, blade.shaft_axis)


def tip_axial_force(blade: Blade) -> float:
    """Centrifugal axial force of the tip mass per Omega^2, ``M_t e_x^T P ((R + L) e_x + p_t)``, kg m."""
    tip = blade.tip_mass
    if tip is None:
        return 0.0
    return float(axial_centrifugal_force(tip.mass, tip.mass * tip.offset, blade.tip_radius, blade.shaft_axis))


def centrifugal_tension(blade: Blade, edges: NDArray, x: NDArray, order: int) -> NDArray:
    """``N(x) / Omega^2 = int_x^L f + tip``, kg m: the axial force density ``f`` integrated outboard of each point.

    Whole cells are integrated once; the part of a point's own cell outboard of it gets its own Gauss rule.
    """
    t, w = np.polynomial.legendre.leggauss(order)
    cells = gauss_on_cells(edges, order)
    per_cell = (axial_force_density(blade, cells.x) * cells.weights).reshape(len(edges) - 1, order).sum(1)
    outboard = np.concatenate([np.cumsum(per_cell[::-1])[::-1][1:], [0.0]])
    cell = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, len(edges) - 2)
    end = edges[cell + 1]
    half = 0.5 * (end - x)
    points = x[:, None] + half[:, None] * (t + 1)
    partial = (axial_force_density(blade, points) * half[:, None] * w).sum(1)
    return partial + outboard[cell] + tip_axial_force(blade)


def kinematics(x: NDArray, length: float, terms: Terms,
               basis: Basis) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """Maps from ``q`` at points ``x``: ``(U, Theta)`` (n, 6, dofs), slopes ``(v', w')`` and curvatures
    ``(v'', w'')`` (n, 2, dofs) and twist rate ``phi'`` (n, dofs)."""
    sl = terms.slices()
    psi_w, dpsi_w, ddpsi_w = bending_shapes(x, length, terms.flap, basis)
    psi_v, dpsi_v, ddpsi_v = bending_shapes(x, length, terms.edge, basis)
    chi, dchi, _ = torsion_shapes(x, length, terms.torsion)
    G = np.zeros((x.size, 6, terms.size))
    G[:, 1, sl["edge"]] = psi_v
    G[:, 2, sl["flap"]] = psi_w
    G[:, 3, sl["torsion"]] = chi
    G[:, 4, sl["flap"]] = -dpsi_w
    G[:, 5, sl["edge"]] = dpsi_v
    slopes = np.zeros((x.size, 2, terms.size))
    slopes[:, 0, sl["edge"]] = dpsi_v
    slopes[:, 1, sl["flap"]] = dpsi_w
    curvatures = np.zeros((x.size, 2, terms.size))
    curvatures[:, 0, sl["edge"]] = ddpsi_v
    curvatures[:, 1, sl["flap"]] = ddpsi_w
    twist_rate = np.zeros((x.size, terms.size))
    twist_rate[:, sl["torsion"]] = dchi
    return G, slopes, curvatures, twist_rate


def add_axial_motion(G: NDArray, section: SectionProperties) -> None:
    """Six-by-six sections: the axial motion ``u = a . (phi, v', w')`` of the reference axis at zero axial force
    (:mod:`.galerkin_sections`) into the first row of ``G`` (in place); column tables stay inextensible."""
    if section.axial is None:
        return
    a = section.axial
    G[:, 0, :] = a[:, :1] * G[:, 3, :] + a[:, 1:2] * G[:, 5, :] - a[:, 2:3] * G[:, 4, :]   # G4 = -w', G5 = v'


def integrate(B: NDArray, density: NDArray, weights: NDArray) -> NDArray:
    """``sum_q w_q B_q^T A_q B_q`` for maps ``B`` (n, k, dofs) and densities ``A`` (n, k, k)."""
    weighted = (weights[:, None, None] * B).reshape(-1, B.shape[-1])
    return weighted.T @ np.matmul(density, B).reshape(-1, B.shape[-1])


def galerkin_matrices(blade: Blade, terms: Terms, basis: Basis = "jacobi", order: int | None = None,
                      min_cells: int = MIN_CELLS) -> GalerkinMatrices:
    """Mass, elastic and centrifugal stiffness matrices of a cantilever blade.

    ``order`` is the Gauss rule per cell (default: exact for polynomial integrands of uniform cells plus margin).
    """
    sections, length, axis = blade.sections, blade.length, blade.shaft_axis
    order = order or max(terms.flap, terms.edge) + 6
    edges = cell_edges(sections.span, min_cells)
    quad = gauss_on_cells(edges, order)
    x, weights = quad.x, quad.weights
    G, slopes, curvatures, twist_rate = kinematics(x, length, terms, basis)
    section = section_properties(blade, x)
    add_axial_motion(G, section)
    X = blade.hub_radius + x

    M = integrate(G, kinetic_form(section.m, section.S, section.J), weights)
    K0 = integrate(curvatures, section.D, weights)
    if terms.torsion:
        GJ = column(sections, "torsion_stiffness", x) if section.torsion is None else section.torsion
        K0 += np.einsum("q,qi,qj->ij", weights * GJ, twist_rate, twist_rate)
        if section.bend_twist is not None:
            coupling = np.einsum("q,qi,qk,qkj->ij", weights, twist_rate, section.bend_twist, curvatures)
            K0 += coupling + coupling.T
    tension = centrifugal_tension(blade, edges, x, order)
    K2 = (integrate(slopes, tension_form(tension), weights)
          + integrate(G, spin_softening_form(section.m, section.S, section.J, axis), weights)
          + integrate(G, rotation_second_order_form(X, section.S, section.J, axis), weights))

    if blade.tip_mass is not None:
        tip = blade.tip_mass
        G_tip = kinematics(np.array([length]), length, terms, basis)[0]
        add_axial_motion(G_tip, section_properties(blade, np.array([length])))
        S_tip, J_tip = tip.mass * tip.offset, body_second_moment(tip.mass, tip.offset, tip.inertia)
        one = np.ones(1)
        M += integrate(G_tip, kinetic_form(tip.mass, S_tip, J_tip)[None], one)
        K2 += integrate(G_tip, (spin_softening_form(tip.mass, S_tip, J_tip, axis)
                                + rotation_second_order_form(blade.tip_radius, S_tip, J_tip, axis))[None], one)
    return GalerkinMatrices(M=sym(M), K0=sym(K0), K2=sym(K2), terms=terms, basis=basis)


def sym(A: NDArray) -> NDArray:
    """Symmetric part (removes round-off asymmetry of the quadrature sums)."""
    return 0.5 * (A + A.T)
