"""Inertial and centrifugal terms of a rigid body (a section slice or the tip mass) moving with a beam node.

The body's points ``s`` (relative to the node) move by ``dr1 = t + Theta x s`` to first order, with
``d = (t, Theta)`` the node's kinematic vector, ``Theta = (phi, -w', v')``. To second order a beam section bends
(``Theta_b = (0, -w', v')`` takes the span axis along the bent beam) and then twists by ``phi`` about the bent axis,
so that it stays normal to the axis (Euler-Bernoulli): its rotation vector is ``Theta + 1/2 Theta_b x Theta_t`` and
``dr2 = 1/2 Theta x (Theta x s) + 1/2 (Theta_b x Theta_t) x s``. The second part does work only against a static
moment about the node (:func:`bend_twist_coupling`); without it a rigid turn of the whole blade would not have the
exact second-order energy. Everything needed is the body's mass ``m``, first moment ``S = int rho s`` and second
moment ``J = int rho s s^T``. Arrays may carry trailing dimensions (elements, quadrature points).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

#: Levi-Civita symbol
EPS = np.zeros((3, 3, 3))
EPS[0, 1, 2] = EPS[1, 2, 0] = EPS[2, 0, 1] = 1.0
EPS[0, 2, 1] = EPS[2, 1, 0] = EPS[1, 0, 2] = -1.0


def skew(a: NDArray) -> NDArray:
    """Cross-product matrix [a]x with [a]x b = a x b; a has shape (3, ...)."""
    return -np.einsum("ijk,k...->ij...", EPS, a)


def projected_inertia(Q: NDArray, m: NDArray, S: NDArray, J: NDArray) -> NDArray:
    """6x6 matrix G with ``int rho (dr1^T Q dr1) = d^T G d`` for a constant symmetric 3x3 ``Q``.

    ``Q = I`` gives the mass matrix; ``Q = P = I - a a^T`` gives the spin-softening matrix (divided by -Omega^2).
    ``Q`` may vary from point to point (shape (3, 3, ...): a curved axis's local components).
    """
    shape = np.broadcast_shapes(np.shape(m), np.shape(Q)[2:])
    G = np.zeros((6, 6) + shape)
    G[:3, :3] = np.einsum("ij...,...->ij...", Q, m)
    coupling = -np.einsum("ij...,jk...->ik...", Q, skew(S))          # Q (-[S]x)
    G[:3, 3:] = coupling
    G[3:, :3] = np.swapaxes(coupling, 0, 1)
    # int rho [s]x^T Q [s]x = eps_bac eps_edf Q_be J_cf (the constant part contracted first)
    G[3:, 3:] = np.einsum("acdf...,cf...->ad...", np.einsum("bac,edf,be...->acdf...", EPS, EPS, Q), J)
    return G


def rotation_second_order(Q: NDArray, r: NDArray, S: NDArray, J: NDArray) -> NDArray:
    """3x3 matrix H with ``int rho (Q r0) . dr2 = 1/2 Theta^T H Theta``, the body at node position ``r``.

    ``r0 = r + s`` is a point's position. The body turns with a beam section: first the bend that takes the span
    axis along the bent beam, ``Theta_b = (0, -w', v')``, then the twist ``phi`` about the bent axis (Euler-Bernoulli:
    the section stays normal to the axis). To second order this is the rotation vector
    ``Theta + 1/2 Theta_b x Theta_t``, ``Theta = (phi, -w', v')``, so ``dr2 = 1/2 Theta x (Theta x s) + 1/2 (Theta_b x
    Theta_t) x s``: the rigid-body term plus the static moment term of :func:`bend_twist_coupling`. ``r`` has shape
    (3, ...). The centrifugal potential's share is ``-Omega^2 / 2 Theta^T H Theta``. ``Q`` may vary from point to
    point (shape (3, 3, ...)).
    """
    QrS = np.einsum("ij...,j...,k...->ik...", Q, r, S)
    QJ = np.einsum("ij...,jk...->ik...", Q, J)
    outer = QrS + QJ
    symmetric = 0.5 * (outer + np.swapaxes(outer, 0, 1))
    trace = np.einsum("i...,ij...,j...->...", r, Q, S) + np.einsum("ij...,ji...->...", Q, J)
    # static moment about the node, int rho s x (Q r0) = S x Q r + int rho s x Q s
    moment = (np.einsum("abc,b...,cd...,d...->a...", EPS, S, Q, r)
              + np.einsum("abc,cd...,bd...->a...", EPS, Q, J))
    return symmetric - np.einsum("ij,...->ij...", np.eye(3), trace) + bend_twist_coupling(moment)


def bend_twist_coupling(moment: NDArray) -> NDArray:
    """3x3 matrix C with ``1/2 Theta^T C Theta = Theta_2 . M``: the work of a static moment ``M`` (shape (3, ...))
    on the second-order rotation ``Theta_2 = 1/2 Theta_b x Theta_t = 1/2 (0, phi v', phi w')`` of a section that
    bends and then twists about the bent axis. It couples the twist with the bending slopes."""
    C = np.zeros((3, 3) + np.shape(moment)[1:])
    C[0, 2] = C[2, 0] = 0.5 * moment[1]
    C[0, 1] = C[1, 0] = -0.5 * moment[2]
    return C


def uniform_field_second_order(f: NDArray, S: NDArray, beam_node: bool = True) -> NDArray:
    """3x3 matrix H with ``int rho f . dr2 = 1/2 Theta^T H Theta`` for a uniform force field ``f`` per unit mass.

    A rigid turn ``dr2 = 1/2 (Theta (Theta.s) - |Theta|^2 s)`` gives ``H = sym(f S^T) - (f.S) I``: only the first
    moment ``S = int rho s`` enters. Gravity's potential ``int rho g x`` (``x`` up) is ``f = g e_x``: a body whose
    centre of mass sits a height ``c`` above the node has ``H = -g m c`` for tilts, the inverted-pendulum softening.
    A body on a beam node (``beam_node``) turns with the section, bend then twist (see
    :func:`rotation_second_order`), which adds :func:`bend_twist_coupling` of the static moment ``S x f``; a body
    whose ``Theta`` is its own rotation vector (a platform) does not.
    """
    f = np.asarray(f, dtype=float)
    outer = np.einsum("i,j...->ij...", f, S)
    symmetric = 0.5 * (outer + np.swapaxes(outer, 0, 1))
    H = symmetric - np.einsum("ij,...->ij...", np.eye(3), np.einsum("i,i...->...", f, S))
    if beam_node:
        H = H + bend_twist_coupling(np.einsum("abc,b...,c->a...", EPS, S, f))
    return H


def gyroscopic_inertia(a: NDArray, m: NDArray, S: NDArray, J: NDArray) -> NDArray:
    """6x6 skew matrix G with ``2 int rho dr1(e) . (a x dr1(d)) = e^T G d`` for the body moving by ``d`` and ``e``.

    The kinetic energy in a frame turning at ``Omega a`` holds the cross term ``Omega int rho d(dr1)/dt . (a x
    dr1)``; its Lagrange equations give the gyroscopic (Coriolis) force ``Omega G dd/dt``. With
    ``dr1 = t - [s]x Theta``: ``G = 2 [[m A, -A [S]x], [[S]x A, int rho [s]x^T A [s]x]]``, ``A = [a]x``. ``a`` may
    vary from point to point (shape (3, ...): a curved axis's local components).
    """
    A = skew(np.asarray(a, dtype=float))
    S_cross = skew(S)
    G = np.zeros((6, 6) + np.broadcast_shapes(np.shape(m), np.shape(A)[2:]))
    G[:3, :3] = np.einsum("ij...,...->ij...", A, m)
    G[:3, 3:] = -np.einsum("ij...,jk...->ik...", A, S_cross)
    G[3:, :3] = np.einsum("ij...,jk...->ik...", S_cross, A)
    G[3:, 3:] = np.einsum("acdf...,cf...->ad...", np.einsum("bac,edf,be...->acdf...", EPS, EPS, A), J)
    return 2.0 * G
