"""Energy densities of the rotating blade (docs/THEORY.md), written for the Galerkin integrals.

A body element with mass moments ``(m, S, J)`` about a point of the reference axis (``S = int rho s``,
``J = int rho s s^T``, ``s`` measured from that point) moves, to first order, by ``dr1 = U + Theta x s`` with the
point's translation ``U = (0, v, w)`` (inextensible) and the rotation ``Theta = (phi, -w', v')``. The quadratic
forms below act on the stacked vector ``(U, Theta)`` (6 components); each returns an array ``(..., 6, 6)`` such
that the energy is ``1/2 (U, Theta)^T A (U, Theta)`` per unit length (per Omega^2 for the centrifugal terms).

With ``Theta x s = -[s]x Theta`` and ``int rho [s]x^T [s]x = tr(J) I - J``:

- kinetic (mass):   ``m U.U + 2 U^T A(S) Theta + Theta^T (tr J I - J) Theta``, ``A(S) = -[S]x``
- spin softening:   ``-|P dr1|^2`` with ``P = I - a a^T``: the same with ``P`` inserted,
  ``int rho (a x s)(a x s)^T = [a]x J [a]x^T``
- rotation, second order: ``-2 (P r0) . (1/2 Theta x (Theta x s))`` with ``r0 = X e_x + s`` and
  ``Theta x (Theta x s) = Theta (Theta.s) - s |Theta|^2``.

The centrifugal tension ``N(x)`` (per Omega^2) comes from the axial foreshortening of the reference axis.
All quantities SI: kg, m, rad; ``X`` is the distance of the point from the rotor apex along the pitch axis, m.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

E_X = np.array([1.0, 0.0, 0.0])
#: Levi-Civita symbol
LEVI_CIVITA = np.zeros((3, 3, 3))
LEVI_CIVITA[0, 1, 2] = LEVI_CIVITA[1, 2, 0] = LEVI_CIVITA[2, 0, 1] = 1.0
LEVI_CIVITA[0, 2, 1] = LEVI_CIVITA[2, 1, 0] = LEVI_CIVITA[1, 0, 2] = -1.0


def skew(s: NDArray) -> NDArray:
    """``[s]x`` with ``[s]x b = s x b``, for ``s`` of shape (3, ...) -> (..., 3, 3)."""
    s = np.moveaxis(np.asarray(s, dtype=float), 0, -1)
    zero = np.zeros(s.shape[:-1])
    sx, sy, sz = s[..., 0], s[..., 1], s[..., 2]
    return np.stack([np.stack([zero, -sz, sy], -1),
                     np.stack([sz, zero, -sx], -1),
                     np.stack([-sy, sx, zero], -1)], -2)


def projection(axis: NDArray) -> NDArray:
    """``P = I - a a^T``: projection onto the plane of rotation of the unit shaft axis ``a``."""
    return np.eye(3) - np.outer(axis, axis)


def _as_last(J: NDArray) -> NDArray:
    """(3, 3, ...) -> (..., 3, 3)."""
    return np.moveaxis(np.moveaxis(np.asarray(J, dtype=float), 0, -1), 0, -2)


def _blocks(uu: NDArray, ut: NDArray, tt: NDArray) -> NDArray:
    """Assemble the symmetric 6x6 form from its (U,U), (U,Theta) and (Theta,Theta) blocks."""
    top = np.concatenate([uu, ut], -1)
    bottom = np.concatenate([np.swapaxes(ut, -1, -2), tt], -1)
    return np.concatenate([top, bottom], -2)


def rotary_inertia(J: NDArray) -> NDArray:
    """``int rho [s]x^T [s]x = tr(J) I - J``, the inertia tensor about the reference point, (..., 3, 3)."""
    J = _as_last(J)
    return np.trace(J, axis1=-2, axis2=-1)[..., None, None] * np.eye(3) - J


def kinetic_form(m: NDArray, S: NDArray, J: NDArray) -> NDArray:
    """Mass density of ``|d(dr1)/dt|^2``: translation, centre-of-mass offset coupling, section rotary inertia."""
    m = np.asarray(m, dtype=float)
    uu = m[..., None, None] * np.eye(3)
    ut = -skew(S)
    return _blocks(uu, ut, rotary_inertia(J))


def spin_softening_form(m: NDArray, S: NDArray, J: NDArray, axis: NDArray) -> NDArray:
    """Stiffness per Omega^2 of ``-1/2 int rho |P dr1|^2`` (negative semi-definite)."""
    m = np.asarray(m, dtype=float)
    P = projection(axis)
    a_x = skew(axis)
    uu = m[..., None, None] * P
    ut = -P @ skew(S)
    tt = rotary_inertia(J) - a_x @ _as_last(J) @ a_x.T
    return -_blocks(uu, ut, tt)


def rotation_second_order_form(X: NDArray, S: NDArray, J: NDArray, axis: NDArray) -> NDArray:
    """Stiffness per Omega^2 of ``-int rho (P r0) . (P 1/2 Theta x (Theta x s))``, ``r0 = X e_x + s``.

    Acts on Theta only: the propeller moment in torsion and the centrifugal coupling of a centre-of-mass offset
    with the bending slopes and twist.
    """
    X = np.asarray(X, dtype=float)
    P = projection(axis)
    S = np.moveaxis(np.asarray(S, dtype=float), 0, -1)
    PJ = P @ _as_last(J)
    pe = P @ E_X
    outer = X[..., None, None] * pe[:, None] * S[..., None, :]
    H = 0.5 * (outer + np.swapaxes(outer, -1, -2)) + 0.5 * (PJ + np.swapaxes(PJ, -1, -2))
    scalar = X * (S @ pe) + np.trace(PJ, axis1=-2, axis2=-1)
    # the section bends, then twists about the bent axis: second-order rotation 1/2 (0, phi v', phi w'), whose work
    # against the static moment M = int rho s x (P r0) couples twist and slopes
    moment = X[..., None] * np.cross(S, pe) + np.einsum("abc,cd,...bd->...a", LEVI_CIVITA, P, _as_last(J))
    H[..., 0, 2] += 0.5 * moment[..., 1]
    H[..., 2, 0] += 0.5 * moment[..., 1]
    H[..., 0, 1] -= 0.5 * moment[..., 2]
    H[..., 1, 0] -= 0.5 * moment[..., 2]
    tt = -(H - scalar[..., None, None] * np.eye(3))
    zero = np.zeros(tt.shape)
    return _blocks(zero, zero, tt)


def axial_centrifugal_force(m: NDArray, S: NDArray, X: NDArray, axis: NDArray) -> NDArray:
    """Axial component ``e_x^T P (m X e_x + S)`` of the centrifugal force per Omega^2 (kg m per unit length)."""
    pe = projection(axis) @ E_X
    return np.asarray(m, dtype=float) * X * pe[0] + np.tensordot(pe, np.asarray(S, dtype=float), axes=(0, 0))


def tension_form(tension: NDArray) -> NDArray:
    """Stiffness of ``1/2 N (v'^2 + w'^2)`` on the slopes: ``N`` times the (v', w') identity, (..., 2, 2)."""
    return np.asarray(tension, dtype=float)[..., None, None] * np.eye(2)
