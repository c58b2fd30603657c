"""The strains of a beam on a curved reference axis, from the straight beam's field derivatives.

On an axis whose frame turns at ``K = (0, K2, K3)`` per unit arc length (:mod:`bladefem.sections.axis`), with the
displacements ``(u, v, w)`` and the twist ``phi`` in the local frame, the linear strains of a curved beam are
``gamma = d' + K x d + e1 x Theta`` and ``kappa = Theta' + K x Theta`` (Hodges, Nonlinear Composite Beam Theory,
2006, the linearized strain measures of ch. 4). Zero transverse shear (Euler-Bernoulli) fixes the section's
rotation: ``Theta = (phi, -(w' - K2 u), v' + K3 u)``; then the extension is ``u' + K2 w - K3 v``, the twist rate
``phi' + K2 Theta_3 - K3 Theta_2`` and the bending curvatures ``Theta_2' + K3 phi`` and ``Theta_3' - K2 phi``.
A rigid motion of the curved beam strains nothing in these measures.

A shear-flexible beam (:mod:`bladefem.elements.beam`) deflects by ``v + v_s`` and ``w + w_s`` and its section
turns with the bending part: ``Theta = (phi, -(w' - K2 u), v' + K3 u)``, the rotation the Euler-Bernoulli beam
would have under ``v`` and ``w`` alone. Its transverse shear strains ``gamma_2 = (v + v_s)' + K3 u - Theta_3`` and
``gamma_3 = (w + w_s)' - K2 u + Theta_2`` are then ``v_s'`` and ``w_s'`` as on a straight axis, the twist rate and
curvatures are the ones above, and the extension takes the whole deflection: ``u' + K2 (w + w_s) - K3 (v + v_s)``.
"""


from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from .beam import SectionMotion


def linear_projection(weights: NDArray, position: NDArray) -> NDArray:
    """Per element, the L2 projection onto linear functions of values at the quadrature points: ``(elements,
    points, points)``, from the quadrature weights and the points' positions (elements, points)."""
    total = np.sum(weights, axis=1, keepdims=True)
    centred = position - np.sum(weights * position, axis=1, keepdims=True) / total
    norm = np.sum(weights * centred**2, axis=1, keepdims=True)
    return (weights[:, None, :] / total[:, :, None]
            + centred[:, :, None] * (weights * centred)[:, None, :] / norm[:, :, None])


def curved_motion(motion: SectionMotion, curvature: NDArray, projection: NDArray | None = None) -> SectionMotion:
    """The motion's strain measures on a curved axis, in the straight beam's slots: ``u_x`` the extension,
    ``-w_x`` and ``v_x`` the section's rotations ``Theta_2``, ``Theta_3``, ``phi_x`` the twist rate, ``v_xx`` and
    ``w_xx`` the curvatures ``kappa_3`` and ``-kappa_2``, ``v_s_x`` and ``w_s_x`` the transverse shear strains (unchanged);
    so every weak-form term of the straight beam holds as it is. ``curvature``: ``(K2, K3, K2', K3')`` at the quadrature points, shape (4, elements, points).

    ``projection`` (:func:`linear_projection`) takes the curvature's share of the extension, ``K2 w - K3 v``, onto
    the space of ``u'`` (linear in each element), so that an element can bend without stretching: evaluated as it
    is, the stiff extension locks the bending of a curved element (membrane locking; Stolarski and Belytschko,
    J. Appl. Mech. 49, 1982; the field-consistent remedy: Prathap, Int. J. Numer. Meth. Eng. 21, 1985)."""
    k2, k3, k2_s, k3_s = curvature
    m = motion
    v_x = m.v_x + k3 * m.u
    w_x = m.w_x - k2 * m.u
    stretch = k2 * (m.w + m.w_s) - k3 * (m.v + m.v_s)
    if projection is not None:
        stretch = np.einsum("eqp,...ep->...eq", projection, stretch)
    return replace(m, u_x=m.u_x + stretch,
                   v_x=v_x, w_x=w_x,
                   phi_x=m.phi_x + k2 * v_x + k3 * w_x,
                   v_xx=m.v_xx + k3_s * m.u + k3 * m.u_x - k2 * m.phi,
                   w_xx=m.w_xx - k2_s * m.u - k2 * m.u_x - k3 * m.phi)
