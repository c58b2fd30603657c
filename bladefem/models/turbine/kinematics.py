"""Kinematics evaluated numerically at one state: positions, velocities, partial velocities, bias accelerations.

For generalized coordinates ``q`` with generalized speeds ``u = dq/dt``, every point has a velocity
``v = J u`` (the columns of ``J`` are its partial velocities) and an acceleration ``a = J du/dt + a_b``; every frame
has an angular velocity ``omega = W u`` (partial angular velocities) and angular acceleration
``alpha = W du/dt + alpha_b``. These are carried down the chain earth -> tower -> tower top -> nacelle -> shaft ->
rotor -> blades by the two exact rules of rigid-body kinematics (a rotation about a body axis by an angle linear in
``q``; a point carried by a frame with its own motion relative to it), vectorised over span nodes and blades.
"""

from __future__ import annotations

import math
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
    c, s = math.cos(angle), math.sin(angle)
    if axis == 0:
        return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    if axis == 1:
        return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


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


def _cross_map() -> NDArray:
    c = np.zeros((3, 3, 3))
    c[2, 0, 1], c[1, 0, 2], c[2, 1, 0], c[0, 1, 2], c[1, 2, 0], c[0, 2, 1] = 1, -1, -1, 1, 1, -1
    return c.reshape(3, 9)


#: (3, 9) map with ``(r @ CROSS).reshape(3, 3) @ w = w x r`` for row vectors r
CROSS = _cross_map()


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
                       W=frame.W + k[:, None] * coefficients, alpha=frame.alpha + skew(frame.omega) @ k * rate)


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
    rho = to_earth(frame.R, offset)
    spin = skew(frame.omega).T                 # row vectors: r @ spin = omega x r
    w_x_rho = rho @ spin
    v = origin.v + w_x_rho
    J = origin.J + (rho @ CROSS).reshape(rho.shape + (3,)) @ frame.W
    a = origin.a + rho @ skew(frame.alpha).T + w_x_rho @ spin
    if partials is not None:
        R = frame.R if frame.R.ndim == 2 else frame.R.reshape(frame.R.shape[:1] + (1,) * (offset.ndim - 2) + (3, 3))
        rate = to_earth(frame.R, local_velocity)
        v = v + rate
        J = J + R @ partials
        a = a + 2.0 * rate @ spin + to_earth(frame.R, local_bias)
    return PointMotion(r=origin.r + rho, v=v, J=J, a=a)


@dataclass(frozen=True)
class NodeGroup:
    """Span nodes carried by a frame, with their partial velocities factored as ``J = G @ Z``.

    ``Z`` stacks the partials shared by the group (origin velocity J_o, frame angular velocity W, and the
    selection of the beam's own coordinates), ``G`` the per-node factors ``[I, -[rho]x, R L]``; so the group's
    contribution to Kane's equations is ``Z^T (sum_p m_p G_p^T G_p) Z``, summed over the nodes in small arrays.

    r : (..., P, 3) positions; G : (..., P, 3, m); Z : (m, n) or (B, m, n) for B beams; a : (..., P, 3) bias
    accelerations
    """

    r: NDArray
    G: NDArray
    Z: NDArray
    a: NDArray

    @property
    def J(self) -> NDArray:
        """Partial velocities (..., P, 3, n)."""
        return self.G @ (self.Z if self.Z.ndim == 2 else self.Z[:, None])

    def velocity(self, u: NDArray) -> NDArray:
        """Velocities (..., P, 3) at rates u."""
        shared = self.Z @ u
        if self.Z.ndim == 2:
            return self.G @ shared
        return (self.G @ shared[:, None, :, None])[..., 0]

    def point(self, index: int, u: NDArray) -> PointMotion:
        """One node of an unbatched group as a point with full partial velocities."""
        J = self.G[index] @ self.Z
        return PointMotion(r=self.r[index], v=J @ u, J=J, a=self.a[index])

    def generalized(self, masses: NDArray, loads: NDArray) -> tuple[NDArray, NDArray]:
        """``sum_p m_p J_p^T J_p`` and ``sum_p J_p^T F_p`` for node masses (..., P) and forces (..., P, 3)."""
        m = self.G.shape[-1]
        lead = self.G.shape[:-3]
        weighted = (self.G * np.sqrt(masses)[..., None, None]).reshape(lead + (-1, m))
        flat = self.G.reshape(lead + (-1, m))
        inner = np.swapaxes(weighted, -1, -2) @ weighted
        force = np.swapaxes(flat, -1, -2) @ loads.reshape(lead + (-1, 1))
        Zt = np.swapaxes(self.Z, -1, -2)
        M = Zt @ inner @ self.Z
        f = (Zt @ force)[..., 0]
        if M.ndim == 3:
            return M.sum(axis=0), f.sum(axis=0)
        return M, f


def carry_nodes(origin: PointMotion, frame: FrameMotion, offset: NDArray, partials: NDArray, selection: NDArray,
                local_velocity: NDArray, local_bias: NDArray) -> NodeGroup:
    """Beam nodes at ``offset`` (..., P, 3) from ``origin`` in ``frame`` components, moving in the frame with
    ``partials`` (..., P, 3, k) over the beam's own k coordinates (``selection`` (k, n), or (B, k, n) for B beams
    in B frames), velocity and bias in the frame."""
    batched = frame.R.ndim == 3
    R = frame.R[:, None] if batched else frame.R
    rho = to_earth(frame.R, offset)
    spin = skew(frame.omega).T
    rate = to_earth(frame.R, local_velocity)
    cross = (rho @ CROSS).reshape(rho.shape + (3,))
    identity = np.broadcast_to(np.eye(3), rho.shape + (3,))
    G = np.concatenate([identity, cross, R @ partials], axis=-1)
    shared = np.concatenate([origin.J, frame.W])
    if batched:
        shared = np.broadcast_to(shared, (len(selection),) + shared.shape)
    Z = np.concatenate([shared, selection], axis=-2)
    a = origin.a + rho @ skew(frame.alpha).T + (rho @ spin) @ spin + 2.0 * rate @ spin + to_earth(frame.R, local_bias)
    return NodeGroup(r=origin.r + rho, G=G, Z=Z, a=a)


@dataclass(frozen=True)
class BeamDeflection:
    """Deflection of a modal beam's nodes in its own frame, for given modal amplitudes and rates.

    offset : (..., P, 3) node positions relative to the beam's origin, m
    partials : (..., P, 3, k) derivatives with respect to the beam's own k modal amplitudes
    velocity : (..., P, 3); bias : (..., P, 3) second rate at zero generalized accelerations
    """

    offset: NDArray
    partials: NDArray
    velocity: NDArray
    bias: NDArray


class BeamNodes:
    """A modal beam's nodes: undeflected axial positions ``axial`` (P,), shapes ``value`` (k, P, 2) and
    shortening integrals ``shortening`` (k, k, P); the node offset is ``axial - s(x)`` along the beam axis plus
    the modal displacement across it, ``s = 1/2 q^T S q``; ``along`` (k, P), for points offset from the axis, their
    linear motion along it (the offset turned by the section's rotation).

    order : frame axes of (axial, transverse 1, transverse 2); selection : (k, n) or (B, k, n) matrix picking the
    beam's amplitudes out of the generalized coordinates (B beams alike, e.g. blades).
    """

    def __init__(self, axial: NDArray, value: NDArray, shortening: NDArray, order: tuple[int, int, int],
                 selection: NDArray, along: NDArray | None = None) -> None:
        k, P = value.shape[:2]
        self.k, self.P = k, P
        self.axial = axial
        self.axial_axis = order[0]
        across = np.zeros((k, P, 3))                  # the shapes in the frame's axes
        across[:, :, order[1]] = value[:, :, 0]
        across[:, :, order[2]] = value[:, :, 1]
        if along is not None:                         # (k, P) linear motion along the axis (offset points)
            across[:, :, order[0]] = along
        self.across_flat = across.reshape(k, P * 3)
        self.partials_template = np.moveaxis(across, 0, -1).copy()      # (P, 3, k), axial row filled per state
        self.shortening_flat = shortening.reshape(k, k * P)
        self.selection = selection

    def deflect(self, q: NDArray, u: NDArray) -> BeamDeflection:
        """Offsets, partials over the beam's own coordinates, velocities and bias accelerations for amplitudes
        q and rates u (each (..., k))."""
        lead = q.shape[:-1]
        shape = lead + (self.P, 3)
        Sq = (q @ self.shortening_flat).reshape(lead + (self.k, self.P))
        Su = (u @ self.shortening_flat).reshape(lead + (self.k, self.P))
        ax = self.axial_axis
        offset = (q @ self.across_flat).reshape(shape)
        offset[..., ax] += self.axial - 0.5 * np.einsum("...i,...ip->...p", q, Sq)
        velocity = (u @ self.across_flat).reshape(shape)
        velocity[..., ax] -= np.einsum("...i,...ip->...p", u, Sq)
        partials = np.broadcast_to(self.partials_template, lead + self.partials_template.shape).copy()
        partials[..., ax, :] -= np.swapaxes(Sq, -1, -2)
        bias = np.zeros(shape)
        bias[..., ax] = -np.einsum("...i,...ip->...p", u, Su)
        return BeamDeflection(offset=offset, partials=partials, velocity=velocity, bias=bias)


def turned_arms(slope: NDArray, arms: NDArray, q: NDArray, u: NDArray) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """The second-order motion across the blade axis of the nodes' arms (offsets o_v in-plane, o_w out-of-plane)
    turned by the bent section (:func:`bladefem.aero.polar.bent_axes` of the slopes v', w'): with
    a = o_v v' + o_w w' (-a along the axis: :attr:`.aero.TurbineAero.along`), -a v'/2 in-plane and -a w'/2
    out-of-plane. The thrust of a node upwind of the axis works on the bending through it (3.9 % of the IEA-22MW's
    tip deflection), as OpenFAST maps AeroDyn's loads onto ElastoDyn's nodes with the turned arms' moments.
    ``slope``: the modal slopes (k, Na, 2) at the nodes; ``arms``: the offsets (Na, 3) in the blade frame (span,
    toward the leading edge, downwind), m. Offsets (..., Na, 3), partials (..., Na, 3, k), velocities and bias
    accelerations (..., Na, 3) for amplitudes q and rates u (..., k)."""
    theta = np.einsum("...k,kpa->...pa", q, slope)
    rate = np.einsum("...k,kpa->...pa", u, slope)
    arm = arms[:, 1:]
    a = np.sum(arm * theta, axis=-1)[..., None]                      # (..., Na, 1)
    a_rate = np.sum(arm * rate, axis=-1)[..., None]
    lead = theta.shape[:-1]
    offset, velocity, bias = np.zeros(lead + (3,)), np.zeros(lead + (3,)), np.zeros(lead + (3,))
    offset[..., 1:] = -0.5 * a * theta
    velocity[..., 1:] = -0.5 * (a_rate * theta + a * rate)
    bias[..., 1:] = -a_rate * rate
    a_q = np.einsum("kpa,pa->pk", slope, arm)                          # (Na, k): da / dq
    partials = np.zeros(lead + (3, slope.shape[0]))
    partials[..., 1:, :] = -0.5 * (theta[..., None] * a_q[:, None, :] + a[..., None] * np.moveaxis(slope, 0, -1))
    return offset, partials, velocity, bias
