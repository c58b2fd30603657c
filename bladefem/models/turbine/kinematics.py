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

    offset : (..., 3) node positions relative to the beam's origin (axial, transverse 1, transverse 2 in the
        beam's axis order), m
    partials : (..., 3, k) derivatives with respect to the beam's own k modal amplitudes
    velocity : (..., 3); bias : (..., 3) second rate at zero modal accelerations
    """

    offset: NDArray
    partials: NDArray
    velocity: NDArray
    bias: NDArray


def beam_deflection(axial: NDArray, value: NDArray, shortening: NDArray, q: NDArray, u: NDArray,
                    order: tuple[int, int, int]) -> BeamDeflection:
    """Node offsets ``axial - s(x)`` along the beam axis plus the modal displacement across it.

    axial : (P,) undeflected axial position; value : (k, P, 2) shapes; shortening : (k, k, P) S_ij;
    q, u : (..., k) modal amplitudes and rates (leading axes e.g. blades); order : frame axes of
    (axial, transverse 1, transverse 2).
    """
    transverse = np.einsum("...i,ipa->...pa", q, value)
    Sq = np.einsum("ijp,...j->...pi", shortening, q)
    s = 0.5 * np.einsum("...i,...pi->...p", q, Sq)
    Su = np.einsum("ijp,...j->...pi", shortening, u)
    k = value.shape[0]
    shape = transverse.shape[:-1]
    offset = np.empty(shape + (3,))
    partials = np.empty(shape + (3, k))
    axis, first, second = order
    offset[..., axis] = axial - s
    offset[..., first] = transverse[..., 0]
    offset[..., second] = transverse[..., 1]
    partials[..., axis, :] = -Sq
    partials[..., first, :] = np.broadcast_to(np.moveaxis(value[..., 0], 0, -1), shape + (k,))
    partials[..., second, :] = np.broadcast_to(np.moveaxis(value[..., 1], 0, -1), shape + (k,))
    velocity = np.einsum("...ik,...k->...i", partials, u[..., None, :])
    bias = np.zeros(shape + (3,))
    bias[..., axis] = -np.einsum("...i,...pi->...p", u, Su)
    return BeamDeflection(offset=offset, partials=partials, velocity=velocity, bias=bias)


def scatter(partials: NDArray, columns: NDArray, n: int) -> NDArray:
    """Place partials over a body's own coordinates (..., 3, k) into the n global columns ``columns`` (..., k)."""
    full = np.zeros(partials.shape[:-1] + (n,))
    if columns.ndim == 1:
        full[..., columns] = partials
    else:
        for b, cols in enumerate(columns):
            full[b][..., cols] = partials[b]
    return full
