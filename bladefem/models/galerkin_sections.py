"""Section stiffness and mass moments of the Galerkin model, derived here from the raw section table.

The Galerkin model computes its own section properties so that agreement with the finite elements (which use
:mod:`bladefem.sections.moments`) checks those too: only the raw columns of :class:`SectionTable` are shared.

The section frame ``(eta, zeta)`` (chord toward the leading edge, thickness toward the pressure side) is turned
about the span axis by ``theta`` = structural twist + pitch; positive ``theta`` turns the leading edge upwind
(``-z``). The rotation ``R(theta)`` maps section coordinates to blade coordinates ``(y, z)``:
``(y, z) = R (eta, zeta)``, ``R = [[cos, sin], [-sin, cos]]``.

- Bending (seed paper 002 eqs. 25-26 after Hodges and Dowell; Euler-Bernoulli): a fibre at ``(y, z)`` strains by
  ``-(y v'' + z w'') = -(eta, zeta) . R^T (v'', w'')``, so the curvatures in the section frame are
  ``R^T (v'', w'')`` and the stiffness for ``(v'', w'')`` is ``R diag(EI_edge, EI_flap) R^T``
  (``EI_edge = int E eta^2``, ``EI_flap = int E zeta^2`` about the tension centre).
- Mass: a section symmetric about its chord (the seed's assumption) has its centre of mass at ``(e_g, 0)`` and the
  second moments ``diag(i_edge, i_flap)`` about it in the section frame; about the reference axis
  ``J_section = diag(i_edge, i_flap) + m (e_g, 0)(e_g, 0)^T`` (parallel axes), turned into the blade frame as
  ``R J_section R^T``; the first moment is ``S = m R (e_g, 0)``.
- Six-by-six sections (:attr:`SectionTable.full`), derived here from the raw matrices (axes and order of
  :mod:`bladefem.sections.full_section`: strains ``(eps, gamma_eta, gamma_zeta, kappa_x, kappa_eta, kappa_zeta)``,
  fibre strain ``eps + zeta kappa_eta - eta kappa_zeta``). The classical compliance is the ``(eps, kappa)`` block of
  ``K^-1`` (shear forces free). This model is inextensible in its coordinates but the section is free to stretch:
  the axial force of low modes is nil (axial inertia left out), so ``eps`` is eliminated too: the compliance block of
  ``(kappa_x, kappa_eta, kappa_zeta)``, inverted, is the stiffness for them (this carries the tension-centre offsets
  in both directions). In the notation above ``k = R^T (v'', w'') = (kappa_zeta, -kappa_eta)``; the stiffness on
  ``(phi', k)`` is turned into the blade frame as GJ, the bend-twist vector ``R g`` and ``R D_k R^T``. The mass:
  ``m = M_00``, ``S_section`` from ``M[3:, :3] = [S]x``, ``J = tr(I_rot)/2 1 - I_rot``, turned by ``R``.
  At zero axial force the reference axis stretches with the curvatures and twist rate (a tension centre or an
  extension-twist coupling off it): ``u' = a . (phi', v'', w'')``; with ``a`` constant along the span that is
  ``u = a . (phi, v', w')``, the axial motion whose inertia this model then carries (exact for uniform sections,
  the local value of ``a`` otherwise).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..sections import Blade, SectionTable


@dataclass(frozen=True)
class SectionProperties:
    """Galerkin section properties at points ``x`` (n,): mass ``m`` (kg/m), first moment ``S`` (3, n) in kg,
    second moment ``J`` (3, 3, n) in kg m, both about the reference axis in the blade frame, and the bending
    stiffness ``D`` (n, 2, 2) for the curvatures ``(v'', w'')``, N m^2; six-by-six sections also give GJ
    ``torsion`` (n,), the bend-twist coupling ``bend_twist`` (n, 2) of phi' with ``(v'', w'')``, N m^2, and
    ``axial`` (n, 3): the reference axis's strain at zero axial force per ``(phi', v'', w'')``, (m, m, m)."""

    m: NDArray[np.float64]
    S: NDArray[np.float64]
    J: NDArray[np.float64]
    D: NDArray[np.float64]
    torsion: NDArray[np.float64] | None = None
    bend_twist: NDArray[np.float64] | None = None
    axial: NDArray[np.float64] | None = None


def column(sections: SectionTable, name: str, x: NDArray) -> NDArray:
    """Column ``name`` of the raw table, linear between stations, at span positions ``x`` (m)."""
    return np.interp(x, sections.span, getattr(sections, name))


def inertias_about_the_axis(sections: SectionTable, x: NDArray, m: NDArray) -> tuple[NDArray, NDArray]:
    """(int rho eta^2, int rho zeta^2) about the reference axis at ``x``, kg m: the edgewise inertia about the centre of
    mass plus ``m e_g^2``, and the flapwise one. Linear between stations, or, for a table with ``inertia_per_mass``
    (BModes decks), their ratios to the mass linear and times the interpolated mass."""
    if not sections.inertia_per_mass:
        e_g = column(sections, "cm_offset", x)
        return column(sections, "edge_inertia", x) + m * e_g**2, column(sections, "flap_inertia", x)
    reference = (sections.edge_inertia + sections.mass * sections.cm_offset**2) / sections.mass
    return m * np.interp(x, sections.span, reference), m * np.interp(x, sections.span, sections.flap_inertia /
                                                                      sections.mass)


def section_rotation(theta: NDArray) -> NDArray:
    """``R(theta)`` of shape (..., 2, 2): section coordinates ``(eta, zeta)`` to blade coordinates ``(y, z)``."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([np.stack([c, s], -1), np.stack([-s, c], -1)], -2)


def principal_to_blade(R: NDArray, first: NDArray, second: NDArray) -> NDArray:
    """``R diag(first, second) R^T`` (..., 2, 2): a symmetric tensor given on the section axes, in the blade
    frame."""
    return np.einsum("...ik,...k,...jk->...ij", R, np.stack([first, second], -1), R)


def section_properties(blade: Blade, x: NDArray) -> SectionProperties:
    """Mass moments and bending stiffness of ``blade`` at span positions ``x`` (m), see the module text."""
    sections = blade.sections
    x = np.asarray(x, dtype=float)
    if sections.full is not None:
        return six_by_six_properties(blade, x)
    R = section_rotation(column(sections, "twist", x) + blade.pitch)
    m = column(sections, "mass", x)
    e_g = column(sections, "cm_offset", x)
    D = principal_to_blade(R, column(sections, "edge_stiffness", x), column(sections, "flap_stiffness", x))
    J_yz = principal_to_blade(R, *inertias_about_the_axis(sections, x, m))
    S_yz = R[..., 0] * (m * e_g)[..., None]                 # m R (e_g, 0): the first column of R times m e_g
    S = np.zeros((3,) + m.shape)
    S[1:] = np.moveaxis(S_yz, -1, 0)
    J = np.zeros((3, 3) + m.shape)
    J[1:, 1:] = np.moveaxis(J_yz, (-2, -1), (0, 1))
    return SectionProperties(m=m, S=S, J=J, D=D)


def six_by_six_properties(blade: Blade, x: NDArray) -> SectionProperties:
    """Section properties of six-by-six sections at ``x`` (m), see the module text."""
    full = blade.sections.full
    K, M = (np.moveaxis(np.array([[np.interp(x, full.span, A[:, i, j]) for j in range(6)] for i in range(6)]),
                        (0, 1), (-2, -1)) for A in (full.stiffness, full.mass))   # (..., 6, 6), linear in x
    flexibility = np.linalg.inv(K)                                   # shear forces and axial force free
    C = np.linalg.inv(flexibility[..., 3:, 3:])                      # kappa_x, kappa_eta, kappa_zeta
    strain = np.einsum("...j,...jk->...k", flexibility[..., 0, 3:], C)      # eps per kappa at N = 0
    to_k = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])   # (kappa) = to_k (phi', k1, k2)
    C = to_k.T @ C @ to_k
    strain = strain @ to_k
    R = section_rotation(np.interp(x, full.span, full.twist) + blade.pitch)
    D = R @ C[..., 1:, 1:] @ np.swapaxes(R, -1, -2)
    bend_twist = np.einsum("...ij,...j->...i", R, C[..., 0, 1:])
    axial = np.concatenate([strain[..., :1], np.einsum("...ij,...j->...i", R, strain[..., 1:])], -1)
    m = M[..., 0, 0]
    S_section = np.stack([M[..., 5, 1], M[..., 3, 2], M[..., 4, 0]], -1)
    I_rot = M[..., 3:, 3:]
    J_section = 0.5 * np.trace(I_rot, axis1=-2, axis2=-1)[..., None, None] * np.eye(3) - I_rot
    Q = np.zeros(x.shape + (3, 3))
    Q[..., 0, 0] = 1.0
    Q[..., 1:, 1:] = R
    S = np.einsum("...ij,...j->i...", Q, S_section)
    J = np.moveaxis(Q @ J_section @ np.swapaxes(Q, -1, -2), (-2, -1), (0, 1))
    return SectionProperties(m=m, S=S, J=J, D=D, torsion=C[..., 0, 0], bend_twist=bend_twist, axial=axial)


def body_second_moment(mass: float, offset: NDArray, inertia: NDArray) -> NDArray:
    """``int rho s s^T`` (kg m^2) of a rigid body about its attachment point, from its inertia tensor about its
    centre of mass ``I`` (kg m^2) and the offset ``p`` (m): ``int rho s' s'^T = tr(I)/2 1 - I`` about the centre
    (since ``I = int rho (|s'|^2 1 - s' s'^T)``) plus ``mass p p^T``."""
    inertia = np.asarray(inertia, dtype=float)
    offset = np.asarray(offset, dtype=float)
    return 0.5 * np.trace(inertia) * np.eye(3) - inertia + mass * np.outer(offset, offset)
