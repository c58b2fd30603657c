"""Kinematics evaluated numerically at one state: positions, velocities, partial velocities, bias accelerations.

For generalized coordinates ``q`` with generalized speeds ``u = dq/dt``, every point has a velocity
``v = J u`` (the columns of ``J`` are its partial velocities) and an acceleration ``a = J du/dt + a_b``; every frame
has an angular velocity ``omega = W u`` (partial angular velocities) and angular acceleration
``alpha = W du/dt + alpha_b``. These are carried down the chain earth -> tower -> tower top -> nacelle -> shaft ->
rotor -> blades by the two exact rules of rigid-body kinematics (a rotation about a body axis by an angle linear in
``q``; a point carried by a frame with its own motion relative to it), vectorised over span nodes and blades.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray


@dataclass(frozen=True)
class FrameMotion:
    """Orientation and angular motion of a frame (all vectors in earth components).

    R : (3, 3), or (B, 3, 3) for B frames sharing the same angular motion; columns are the frame's axes
    omega : (3,) angular velocity, rad/s
    W : (3, n) partial angular velocities
    alpha : (3,) angular acceleration at zero generalized accelerations, rad/s^2
    """

    R: NDArray
    omega: NDArray
    W: NDArray
    alpha: NDArray


@dataclass(frozen=True)
class PointMotion:
    """Position and motion of points (any leading shape ``...``), earth components.

    r : (..., 3) m; v : (..., 3) m/s; J : (..., 3, n) partial velocities; a : (..., 3) acceleration at zero
    generalized accelerations, m/s^2
    """

    r: NDArray
    v: NDArray
    J: NDArray
    a: NDArray


def axis_rotation(axis: int, angle: float) -> NDArray:
    """Rotation matrix by ``angle`` (rad) about coordinate axis 0 (x), 1 (y) or 2 (z)."""
    c, s = np.cos(angle), np.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    R = np.eye(3)
    R[i, i] = R[j, j] = c
    R[j, i], R[i, j] = s, -s
    return R


def earth(n: int) -> FrameMotion:
    """The inertial frame."""
    return FrameMotion(R=np.eye(3), omega=np.zeros(3), W=np.zeros((3, n)), alpha=np.zeros(3))


def at_rest(r: NDArray, n: int) -> PointMotion:
    """A fixed point."""
    r = np.asarray(r, dtype=float)
    return PointMotion(r=r, v=np.zeros_like(r), J=np.zeros(r.shape + (n,)), a=np.zeros_like(r))


def skew(w: NDArray) -> NDArray:
    """The matrix of ``w x``: ``skew(w) @ r = w x r``."""
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def cross_columns(W: NDArray) -> NDArray:
    """(3, 3 n) matrix A with ``(r @ A).reshape(3, n)[:, k] = W[:, k] x r`` for row vectors r."""
    n = W.shape[1]
    S = np.zeros((n, 3, 3))
    S[:, 0, 1], S[:, 0, 2], S[:, 1, 2] = -W[2], W[1], -W[0]
    S[:, 1, 0], S[:, 2, 0], S[:, 2, 1] = W[2], -W[1], W[0]
    return S.transpose(2, 1, 0).reshape(3, 3 * n)


def rotate(frame: FrameMotion, axis: int, coefficients: NDArray, q: NDArray, u: NDArray,
           offset: float = 0.0) -> FrameMotion:
    """The frame turned about its own axis ``axis`` by the angle ``offset + coefficients . q`` (rad).

    Its angular velocity gains ``k dtheta/dt`` along the turned axis ``k``; the angular acceleration gains the
    transport term ``omega x k dtheta/dt`` (``k`` is fixed in the parent).
    """
    angle = offset + coefficients @ q
    rate = coefficients @ u
    k = frame.R[..., axis]
    return FrameMotion(R=frame.R @ axis_rotation(axis, angle), omega=frame.omega + k * rate,
                       W=frame.W + np.outer(k, coefficients), alpha=frame.alpha + skew(frame.omega) @ k * rate)


def turn(frame: FrameMotion, rotation: NDArray) -> FrameMotion:
    """The frame turned by a constant rotation (3, 3), or by B constant rotations (B, 3, 3)."""
    return FrameMotion(R=frame.R @ rotation, omega=frame.omega, W=frame.W, alpha=frame.alpha)


def to_earth(R: NDArray, local: NDArray) -> NDArray:
    """Earth components of vectors given in a frame's components; R (3, 3) or (B, 3, 3) with local (B, ..., 3)."""
    if R.ndim == 2:
        return local @ R.T
    return np.einsum("bij,b...j->b...i", R, local)


def carry(origin: PointMotion, frame: FrameMotion, offset: NDArray, partials: NDArray | None = None,
          local_velocity: NDArray | None = None, local_bias: NDArray | None = None) -> PointMotion:
    """Points at ``offset`` (..., 3) from ``origin`` in ``frame`` components, possibly moving in the frame.

    partials : (..., 3, n) derivatives of the offset with respect to ``q`` (frame components), or None if fixed
    local_velocity : (..., 3) the offset's rate in the frame, ``partials @ u``
    local_bias : (..., 3) its second rate at zero generalized accelerations
    """
    n = frame.W.shape[1]
    rho = to_earth(frame.R, offset)
    spin = skew(frame.omega).T                 # row vectors: r @ spin = omega x r
    w_x_rho = rho @ spin
    v = origin.v + w_x_rho
    J = origin.J + (rho @ cross_columns(frame.W)).reshape(rho.shape[:-1] + (3, n))
    a = origin.a + rho @ skew(frame.alpha).T + w_x_rho @ spin
    if partials is not None:
        R = frame.R if frame.R.ndim == 2 else frame.R.reshape(frame.R.shape[:1] + (1,) * (offset.ndim - 2) + (3, 3))
        rate = to_earth(frame.R, local_velocity)
        v = v + rate
        J = J + R @ partials
        a = a + 2.0 * rate @ spin + to_earth(frame.R, local_bias)
    return PointMotion(r=origin.r + rho, v=v, J=J, a=a)


@dataclass(frozen=True)
class BeamDeflection:
    """Deflection of a modal beam's nodes in its own frame, for given modal amplitudes and rates.

    offset : (..., P, 3) node positions relative to the beam's origin, m
    partials : (..., P, 3, n) derivatives with respect to all n generalized coordinates
    velocity : (..., P, 3); bias : (..., P, 3) second rate at zero generalized accelerations
    """

    offset: NDArray
    partials: NDArray
    velocity: NDArray
    bias: NDArray


class BeamNodes:
    """A modal beam's nodes: undeflected axial positions ``axial`` (P,), shapes ``value`` (k, P, 2) and
    shortening integrals ``shortening`` (k, k, P); the node offset is ``axial - s(x)`` along the beam axis plus
    the modal displacement across it, ``s = 1/2 q^T S q``.

    order : frame axes of (axial, transverse 1, transverse 2); selection : (k, n) or (B, k, n) matrix picking the
    beam's amplitudes out of the generalized coordinates (B beams alike, e.g. blades).
    """

    def __init__(self, axial: NDArray, value: NDArray, shortening: NDArray, order: tuple[int, int, int],
                 selection: NDArray) -> None:
        k, P = value.shape[:2]
        self.k, self.P = k, P
        self.axial = axial
        self.value_flat = value.reshape(k, P * 2)
        self.shortening_flat = shortening.reshape(k, k * P)
        self.permutation = np.argsort(order)          # standard (axial, t1, t2) -> frame axes
        self.axial_axis = order[0]
        self.value_rows = np.moveaxis(value, 0, -1)   # (P, 2, k)
        self.selection = selection if selection.ndim == 2 else selection[:, None]

    def deflect(self, q: NDArray, u: NDArray) -> BeamDeflection:
        """Offsets, partials over all coordinates, velocities and bias accelerations for amplitudes q, rates u
        (each (..., k))."""
        lead = q.shape[:-1]
        transverse = (q @ self.value_flat).reshape(lead + (self.P, 2))
        Sq = (q @ self.shortening_flat).reshape(lead + (self.k, self.P))
        Su = (u @ self.shortening_flat).reshape(lead + (self.k, self.P))
        s = 0.5 * np.einsum("...i,...ip->...p", q, Sq)
        offset = np.concatenate([(self.axial - s)[..., None], transverse], axis=-1)[..., self.permutation]
        rows = np.concatenate([-np.swapaxes(Sq, -1, -2)[..., None, :],
                               np.broadcast_to(self.value_rows, lead + self.value_rows.shape)], axis=-2)
        local = rows[..., self.permutation, :]
        velocity = local @ u[..., None, :, None]
        bias = np.zeros(lead + (self.P, 3))
        bias[..., self.axial_axis] = -np.einsum("...i,...ip->...p", u, Su)
        return BeamDeflection(offset=offset, partials=local @ self.selection, velocity=velocity[..., 0], bias=bias)
