"""Exact natural frequencies and static deflections of a uniform cantilever with a coupled six-by-six section, for
the closed-form tests of the section model (tests/test_full_sections.py). Independent of bladefem's finite
elements and of its section code: only numpy and scipy.

Beam (untwisted, not rotating): fields ``q = (u, v, w, phi)``; strains ``e = (u', phi', v'', w'')``; kinematic
vector ``d = (u, v, w, phi, -w', v')``. The section is given by its 6x6 stiffness ``K`` and mass ``M`` in the
order (extension, two shears, twist, bending about y, bending about z) at zero twist, where the section axes are
the beam's: the curvatures are ``kappa_y = -w''`` and ``kappa_z = v''``. The classical stiffness is the inverse of
the classical block of the compliance ``K^-1`` (equal to the Schur complement of the shear block, computed here the
other way round).

Frequencies: with constant coefficients the Euler-Lagrange equations of ``1/2 e^T D e - omega^2 / 2 d^T M d`` have
solutions ``a exp(lambda x)``: a matrix polynomial ``P(lambda) a = 0`` (12 finite roots). The clamped root
(``q = 0``, ``v' = w' = 0``) and the free tip (the natural conditions: forces and moments zero) give a 12x12 matrix
whose smallest singular value vanishes at a natural frequency.

Statics: under a tip force and moment the section forces are known along the span, the strains are the section
compliance times them and integrate in closed form (:func:`tip_deflection`), with or without the shear strains.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

CLASSICAL = [0, 3, 4, 5]


def classical_stiffness(K: np.ndarray) -> np.ndarray:
    """D for ``e = (u', phi', v'', w'')`` from the 6x6 K (untwisted section: ``kappa_y = -w''``, ``kappa_z = v''``)."""
    C = np.linalg.inv(np.linalg.inv(K)[np.ix_(CLASSICAL, CLASSICAL)])       # over (eps, kx, ky, kz)
    T = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, -1], [0, 0, 1, 0]], dtype=float)   # (eps,kx,ky,kz) = T e
    return T.T @ C @ T


def kinetic_matrix(M: np.ndarray) -> np.ndarray:
    """6x6 over ``d = (u, v, w, phi, -w', v')``: the section mass already is, in the beam axes."""
    return np.asarray(M, dtype=float)


def _blocks(D: np.ndarray, Mk: np.ndarray, omega: float) -> dict[tuple[int, int], np.ndarray]:
    """L_ij of the Lagrangian density 1/2 sum (d^i q)^T L_ij (d^j q), q = (u, v, w, phi)."""
    E1 = np.zeros((4, 4))
    E2 = np.zeros((4, 4))
    E1[0, 0] = E1[1, 3] = 1.0                  # u', phi'
    E2[2, 1] = E2[3, 2] = 1.0                  # v'', w''
    A0 = np.zeros((6, 4))
    A1 = np.zeros((6, 4))
    A0[0, 0] = A0[1, 1] = A0[2, 2] = A0[3, 3] = 1.0
    A1[4, 2] = -1.0                            # -w'
    A1[5, 1] = 1.0                             # v'
    w2 = omega**2
    return {(0, 0): -w2 * A0.T @ Mk @ A0, (0, 1): -w2 * A0.T @ Mk @ A1, (1, 0): -w2 * A1.T @ Mk @ A0,
            (1, 1): E1.T @ D @ E1 - w2 * A1.T @ Mk @ A1, (1, 2): E1.T @ D @ E2, (2, 1): E2.T @ D @ E1,
            (2, 2): E2.T @ D @ E2, (0, 2): np.zeros((4, 4)), (2, 0): np.zeros((4, 4))}


def _boundary_matrix(D: np.ndarray, Mk: np.ndarray, length: float, omega: float) -> np.ndarray:
    L = _blocks(D, Mk, omega)
    P = [sum((-1) ** i * L[i, k - i] for i in range(3) if 0 <= k - i <= 2) for k in range(5)]
    n = 4
    # balanced: lambda = mu / length, each field's equation divided by its largest coefficient
    P = [P[k] / length**k for k in range(5)]
    rows_scale = 1.0 / np.max([np.max(np.abs(p), axis=1) for p in P], axis=0)
    P = [rows_scale[:, None] * p for p in P]
    A = np.zeros((4 * n, 4 * n))
    B = np.eye(4 * n)
    A[: 3 * n, n:] = np.eye(3 * n)
    for k in range(4):
        A[3 * n:, k * n:(k + 1) * n] = -P[k]
    B[3 * n:, 3 * n:] = P[4]
    values, vectors = sla.eig(A, B)
    finite = np.isfinite(values) & (np.abs(values) < 1e12)
    lam, a = values[finite] / length, vectors[:n, finite]
    assert len(lam) == 12, len(lam)
    rows = []
    scale = np.exp(np.where(lam.real > 0, -lam * length, 0.0))           # exp(lambda (x - L)) for growing roots
    at_tip = np.exp(lam * length) * scale
    rows.append(a * scale)                                                # q(0)
    rows.append((lam * a * scale)[1:3])                                   # v'(0), w'(0)
    derivative = [a * lam**j * at_tip for j in range(4)]                  # d^j q at the tip
    force = sum(L[1, j] @ derivative[j] for j in range(3)) - sum(L[2, j] @ derivative[j + 1] for j in range(3))
    moment = sum(L[2, j] @ derivative[j] for j in range(3))
    rows.append(force)
    rows.append(moment[1:3])
    Z = np.vstack(rows)
    Z = Z / np.linalg.norm(Z, axis=1, keepdims=True)        # rows hold displacements, forces and moments
    return Z / np.linalg.norm(Z, axis=0)


def _smallest_singular(D: np.ndarray, Mk: np.ndarray, length: float, omega: float) -> float:
    return float(np.linalg.svd(_boundary_matrix(D, Mk, length, omega), compute_uv=False)[-1])


def _golden(f, a: float, b: float, tolerance: float = 1e-13) -> tuple[float, float]:
    """Golden-section minimum of a unimodal f on [a, b] (the smallest singular value is V-shaped at a root, which
    parabolic steps handle badly)."""
    g = (np.sqrt(5.0) - 1) / 2
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    while b - a > tolerance * abs(b):
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = f(d)
    x = 0.5 * (a + b)
    return x, f(x)


def natural_frequencies(K: np.ndarray, M: np.ndarray, length: float, count: int, upper: float,
                        samples: int = 4000) -> np.ndarray:
    """The lowest ``count`` natural frequencies (rad/s) below ``upper`` of the uniform cantilever."""
    D, Mk = classical_stiffness(K), kinetic_matrix(M)
    grid = np.linspace(upper * 1e-4, upper, samples)
    sigma = np.array([_smallest_singular(D, Mk, length, w) for w in grid])
    found = []
    for i in np.flatnonzero((sigma[1:-1] < sigma[:-2]) & (sigma[1:-1] < sigma[2:])) + 1:
        omega, smallest = _golden(lambda w: _smallest_singular(D, Mk, length, w), grid[i - 1], grid[i + 1])
        if smallest < 1e-6:
            found.append(omega)
    return np.array(found[:count])


def tip_deflection(K: np.ndarray, length: float, tip_load: np.ndarray, shear: bool = True) -> np.ndarray:
    """Tip ``(u, v, w, phi)`` and slopes ``(v', w')`` of the uniform cantilever under a tip load
    ``(F_x, F_y, F_z, M_x, M_y, M_z)`` at the reference axis, linear, exact: the section forces at ``x`` are
    ``F`` and ``M + (L - x) e_x x F``; the strains are ``K^-1`` times them (``shear=False``: the shear compliance of
    the shear forces left out, the classical beam with the transverse shear condensed)."""
    F, M_tip = np.asarray(tip_load[:3], float), np.asarray(tip_load[3:], float)
    lever = np.cross([1.0, 0.0, 0.0], F)                         # moment per length of lever arm
    compliance = np.linalg.inv(K)
    if not shear:
        compliance = _classical_compliance(K)
    # strains(x) = a + (L - x) b
    a = compliance @ np.concatenate([F, M_tip])
    b = compliance @ np.concatenate([np.zeros(3), lever])
    # rotation Theta(x) = int_0^x kappa, translation r' = gamma + Theta x e_x (small), r(0) = Theta(0) = 0
    kappa_a, kappa_b = a[3:], b[3:]
    gamma_a, gamma_b = a[:3], b[:3]
    L = length
    theta_tip = kappa_a * L + kappa_b * L**2 / 2                   # int_0^L (L - x) dx = L^2 / 2
    # int_0^L Theta(x) dx with Theta(x) = kappa_a x + kappa_b (L x - x^2 / 2): L^2/2 and L^3/3
    theta_integral = kappa_a * L**2 / 2 + kappa_b * L**3 / 3
    displacement = gamma_a * L + gamma_b * L**2 / 2 + np.cross(theta_integral, [1.0, 0.0, 0.0])
    u, v, w = displacement
    return np.array([u, v, w, theta_tip[0], theta_tip[2], -theta_tip[1]])


def _classical_compliance(K: np.ndarray) -> np.ndarray:
    """K^-1 with the shear rows and columns zeroed: the strains of the classical beam, the shear forces doing no
    work."""
    compliance = np.linalg.inv(K)
    compliance[[1, 2], :] = 0.0
    compliance[:, [1, 2]] = 0.0
    return compliance


def _timoshenko_boundary_matrix(K: np.ndarray, M: np.ndarray, length: float, omega: float) -> np.ndarray:
    """The Timoshenko beam: fields ``q = (u, v, w, theta_x, theta_y, theta_z)`` (the section's rotations free of
    the slopes), strains ``(u', v' - theta_z, w' + theta_y, theta')`` = ``E1 q' + E0 q``, kinetic vector ``q``."""
    E1, E0 = np.eye(6), np.zeros((6, 6))
    E0[1, 5], E0[2, 4] = -1.0, 1.0
    L = {(1, 1): E1.T @ K @ E1, (1, 0): E1.T @ K @ E0, (0, 1): E0.T @ K @ E1,
         (0, 0): E0.T @ K @ E0 - omega**2 * np.asarray(M, dtype=float)}
    P = [L[0, 0], L[0, 1] - L[1, 0], -L[1, 1]]
    P = [P[k] / length**k for k in range(3)]
    scale = 1.0 / np.max([np.max(np.abs(p), axis=1) for p in P], axis=0)
    P = [scale[:, None] * p for p in P]
    n = 6
    A = np.zeros((2 * n, 2 * n))
    B = np.eye(2 * n)
    A[:n, n:] = np.eye(n)
    A[n:, :n], A[n:, n:] = -P[0], -P[1]
    B[n:, n:] = P[2]
    values, vectors = sla.eig(A, B)
    lam, a = values / length, vectors[:n]
    scale_columns = np.exp(np.where(lam.real > 0, -lam * length, 0.0))
    at_tip = np.exp(lam * length) * scale_columns
    force = (L[1, 0] @ a + L[1, 1] @ (a * lam)) * at_tip
    Z = np.vstack([a * scale_columns, force])
    Z = Z / np.linalg.norm(Z, axis=1, keepdims=True)
    return Z / np.linalg.norm(Z, axis=0)


def timoshenko_frequencies(K: np.ndarray, M: np.ndarray, length: float, count: int, upper: float,
                           samples: int = 1500) -> np.ndarray:
    """The lowest ``count`` natural frequencies (rad/s) of the uniform Timoshenko cantilever with the full 6x6
    section (shear and every coupling kept; the rotary inertia of the mass matrix acts on the section's own
    rotations)."""
    def smallest(w: float) -> float:
        return float(np.linalg.svd(_timoshenko_boundary_matrix(K, M, length, w), compute_uv=False)[-1])

    return _minima(smallest, np.linspace(upper * 1e-4, upper, samples))[:count]


def _minima(smallest, grid: np.ndarray) -> np.ndarray:
    sigma = np.array([smallest(w) for w in grid])
    found = []
    for i in np.flatnonzero((sigma[1:-1] < sigma[:-2]) & (sigma[1:-1] < sigma[2:])) + 1:
        omega, value = _golden(smallest, grid[i - 1], grid[i + 1])
        if value < 1e-6:
            found.append(omega)
    return np.array(found)


def timoshenko_frequencies_near(K: np.ndarray, M: np.ndarray, length: float, guess: float, width: float = 0.02,
                                samples: int = 800) -> np.ndarray:
    """The Timoshenko cantilever's frequencies (rad/s) within ``guess (1 -+ width)``, on a fine grid (resolves a
    near-double pair such as the flap and edge modes of a round section)."""
    def smallest(w: float) -> float:
        return float(np.linalg.svd(_timoshenko_boundary_matrix(K, M, length, w), compute_uv=False)[-1])

    return _minima(smallest, np.linspace(guess * (1 - width), guess * (1 + width), samples))
