"""Section aerodynamics for flutter: the quasi-steady loads of :mod:`bladefem.models.blade_aero` split into their
circulatory (lift-slope) part, which Theodorsen's function ``C(k)`` delays, and the rest, plus the two effects of
thin-airfoil theory that the quasi-steady model leaves out (derivation in docs/THEORY.md, "Flutter").

One effect per term, each a matrix per length on the kinematic vector ``d = (u, v, w, phi, -w', v')`` at every
AeroDyn node, with the aerodynamic centre at ``s_ac`` (AeroDyn's reference-line offsets plus a chordwise offset
``x_ac`` toward the leading edge, :func:`flutter_sections`):

- quasi-steady lift and moment at the aerodynamic centre (:func:`~bladefem.models.blade_aero.section_matrices`,
  the airfoil's ``cm`` included), split into the lift-slope part ``dcl dalpha`` (circulatory) and the rest (drag,
  dynamic pressure, turning of the lift direction, ``cm``): ``D = D_qs + D_c``, ``K = K_qs + K_c``;
- pitch rate: the circulatory lift follows the angle of attack at the three-quarter chord, ``c / 2`` behind the
  aerodynamic centre, so a twist rate adds ``dalpha = (c / 2) phi' / W``: the column of ``D_c`` on ``phi``;
- apparent mass (non-circulatory): ``L_nc = pi rho b^2 (h''_m + W alpha')`` normal to the chord at the mid-chord
  and ``M_nc = -pi rho b^2 (W b alpha' / 2 + b^2 alpha'' / 8)`` about it (``b = c / 2``, ``h_m`` the mid-chord's
  motion toward the pressure side): the matrices ``M_a`` and ``D_a``;
- unsteady lift: ``C(k) (D_c p + K_c)`` with ``k = omega b / W`` per section (:func:`theodorsen`).

The generalized aerodynamic forces are ``-(M_a p^2 + (D_qs + D_a) p + K_qs + C(k) (D_c p + K_c)) d`` for motion
``d e^(p t)``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray
from scipy.special import hankel2

from ..elements import skew
from .blade_aero import AeroOperatingPoint, load_derivatives, section_matrices

#: reduced frequency below which C(k) is taken as its quasi-steady limit 1 (the Hankel functions' log singularity)
STEADY_K = 1e-9


def theodorsen(k: NDArray | float) -> NDArray:
    """Theodorsen's function ``C(k) = H1(k) / (H1(k) + i H0(k))`` (Hankel functions of the second kind), ``C(0) =
    1``; ``k = omega b / W`` (rad, semi-chord b, relative speed W) is the reduced frequency, non-negative."""
    k = np.asarray(k, dtype=float)
    small = k < STEADY_K
    safe = np.where(small, 1.0, k)
    h1, h0 = hankel2(1, safe), hankel2(0, safe)
    return np.where(small, 1.0 + 0j, h1 / (h1 + 1j * h0))


@dataclass(frozen=True)
class FlutterSections:
    """The section matrices per length at each AeroDyn node (arrays (6, 6, nodes)), module docstring.

    span : node positions, m; semi_chord : b, m; speed : relative speed W, m/s
    quasi_steady_damping, quasi_steady_stiffness : D_qs, K_qs (not delayed)
    lift_damping, lift_stiffness : D_c (pitch rate included), K_c (times C(k))
    apparent_mass, apparent_damping : M_a, D_a
    """

    span: NDArray
    semi_chord: NDArray
    speed: NDArray
    quasi_steady_damping: NDArray
    quasi_steady_stiffness: NDArray
    lift_damping: NDArray
    lift_stiffness: NDArray
    apparent_mass: NDArray
    apparent_damping: NDArray

    def reduced_frequency(self, omega: float) -> NDArray:
        """k = omega b / W at each node (omega in rad/s; sections in still air: k = 0)."""
        return np.divide(abs(omega) * self.semi_chord, self.speed, out=np.zeros_like(self.speed),
                         where=self.speed > 0)

    def matrices(self, p: complex) -> tuple[NDArray, NDArray, NDArray]:
        """(M_a, D, K) per node for motion ``e^(p t)``, with ``C(k)`` at ``k = Im(p) b / W``: the harmonic
        (p-k) approximation of the unsteady lift."""
        c = theodorsen(self.reduced_frequency(p.imag))
        damping = self.quasi_steady_damping + self.apparent_damping + c * self.lift_damping
        stiffness = self.quasi_steady_stiffness + c * self.lift_stiffness
        return self.apparent_mass, damping, stiffness


def chord_axes(theta: NDArray) -> tuple[NDArray, NDArray]:
    """(e_le, n), each (3, nodes): the chord toward the leading edge and the chord normal toward the suction side
    (the lift's side), for the aerodynamic twist plus pitch ``theta`` (rad; positive turns the leading edge upwind)."""
    zero, c, s = np.zeros_like(theta), np.cos(theta), np.sin(theta)
    return np.stack([zero, c, -s]), np.stack([zero, s, c])


def point_operator(position: NDArray) -> NDArray:
    """(3, 6, nodes): the velocity of the section point at ``position`` (3, nodes) from d', ``[I, -[s]x]``."""
    nodes = position.shape[1]
    N = np.zeros((3, 6, nodes))
    N[:, :3] = np.eye(3)[..., None]
    N[:, 3:] = -skew(position)
    return N


def pitch_rate_damping(op: AeroOperatingPoint, slope_twist: NDArray, centre: NDArray) -> NDArray:
    """D of the twist rate through the three-quarter-chord angle of attack: the loads' lift-slope derivative with
    respect to twist ``slope_twist`` (4, nodes) (forces (0, ft, fn) and moment m) times ``(c / 2) / W``."""
    W = np.hypot(op.X, op.Y)
    lever = np.divide(0.5 * op.chord, W, out=np.zeros_like(W), where=W > 0)
    generalized = np.einsum("gpn,gn->pn", np.concatenate([point_operator(centre), _twist_row(len(W))]),
                            slope_twist)
    D = np.zeros((6, 6, len(W)))
    D[:, 3] = -generalized * lever
    return D


def _twist_row(nodes: int) -> NDArray:
    row = np.zeros((1, 6, nodes))
    row[0, 3] = 1.0
    return row


def apparent_mass(op: AeroOperatingPoint, centre: NDArray) -> tuple[NDArray, NDArray]:
    """(M_a, D_a) of the non-circulatory loads, the mid-chord ``c / 4`` behind the aerodynamic centre."""
    b = 0.5 * op.chord
    W = np.hypot(op.X, op.Y)
    e_le, n = chord_axes(op.theta)
    N_mid = point_operator(centre - 0.5 * b * e_le)
    normal = np.einsum("in,ipn->pn", n, N_mid)                  # (6, nodes): n^T N_mid
    mass_line = np.pi * op.air_density * b**2
    M = mass_line * np.einsum("pn,qn->pqn", normal, normal)
    M[3, 3] += mass_line * b**2 / 8
    D = np.zeros_like(M)
    D[:, 3] = -mass_line * W * normal
    D[3, 3] += mass_line * W * b / 2
    return M, D


def flutter_sections(op: AeroOperatingPoint, chordwise_centre: NDArray | float = 0.0) -> FlutterSections:
    """The flutter section matrices at the operating point ``op``, the aerodynamic centre ``chordwise_centre`` (m,
    per node or one value) ahead of AeroDyn's reference line along the chord (toward the leading edge)."""
    e_le, _ = chord_axes(op.theta)
    centre = op.centre + np.broadcast_to(chordwise_centre, op.span.shape) * e_le
    at_centre = replace(op, centre=centre)
    without_slope = replace(at_centre, dcl=np.zeros_like(op.dcl))
    D, K = section_matrices(at_centre)
    D_qs, K_qs = section_matrices(without_slope)
    slope = load_derivatives(at_centre) - load_derivatives(without_slope)
    M_a, D_a = apparent_mass(op, centre)
    return FlutterSections(span=op.span, semi_chord=0.5 * op.chord, speed=np.hypot(op.X, op.Y),
                           quasi_steady_damping=D_qs, quasi_steady_stiffness=K_qs,
                           lift_damping=D - D_qs + pitch_rate_damping(op, slope[:, 2], centre),
                           lift_stiffness=K - K_qs, apparent_mass=M_a, apparent_damping=D_a)
