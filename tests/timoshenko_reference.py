"""A Timoshenko beam with the whole six-by-six section, as an independent reference for what bladefem's condensed
sections leave out on a real (tapered, twisted) blade: a straight cantilever, parked. Numpy and scipy only.

Fields ``q = (u, v, w, theta_x, theta_y, theta_z)`` in the blade frame (the section's rotations independent of the
slopes), strains ``(u', v' - theta_z, w' + theta_y, theta_x', theta_y', theta_z')``, kinetic vector ``q``. The
section matrices (bladefem's section axes, entries linear between stations) are turned into the blade frame by the
twist: the section axes ``eta = (cos, -sin)``, ``zeta = (sin, cos)`` in ``(y, z)``. Quadratic Lagrange elements for
every field; the stiffness by 2-point Gauss (reduced: the quadratic element does not lock when the shear is stiff),
the mass by 4-point Gauss.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla


def _turned(matrices: np.ndarray, twist: np.ndarray) -> np.ndarray:
    c, s = np.cos(twist), np.sin(twist)
    Q = np.zeros(twist.shape + (6, 6))
    for k in (0, 3):
        Q[..., k, k] = 1.0
        Q[..., k + 1, k + 1], Q[..., k + 1, k + 2] = c, s
        Q[..., k + 2, k + 1], Q[..., k + 2, k + 2] = -s, c
    return Q @ matrices @ np.swapaxes(Q, -1, -2)


def timoshenko_blade_frequencies(span: np.ndarray, stiffness: np.ndarray, mass: np.ndarray, twist: np.ndarray,
                                 count: int, elements: int = 120) -> np.ndarray:
    """Lowest ``count`` natural frequencies (Hz) of the parked cantilever."""
    span = np.asarray(span, float)
    nodes = np.linspace(0.0, span[-1], 2 * elements + 1)
    size = 6 * len(nodes)
    K, M = np.zeros((size, size)), np.zeros((size, size))
    for e in range(elements):
        a, b = nodes[2 * e], nodes[2 * e + 2]
        dofs = (6 * (2 * e + np.arange(3))[:, None] + np.arange(6)).ravel()                   # node-major
        for points, matrices, target, strains in ((2, stiffness, K, True), (4, mass, M, False)):
            t, w = np.polynomial.legendre.leggauss(points)
            xi = 0.5 * (t + 1)
            x = a + (b - a) * xi
            at = np.moveaxis(np.array([[np.interp(x, span, matrices[:, i, j]) for j in range(6)]
                                       for i in range(6)]), -1, 0)
            turned = _turned(at, np.interp(x, span, twist))
            for q in range(points):
                shape = np.array([2 * (xi[q] - 0.5) * (xi[q] - 1), -4 * xi[q] * (xi[q] - 1),
                                  2 * xi[q] * (xi[q] - 0.5)])
                value = np.kron(shape[None, :], np.eye(6))                                     # (6, 18)
                B = value
                if strains:
                    slope = np.array([4 * xi[q] - 3, -8 * xi[q] + 4, 4 * xi[q] - 1]) / (b - a)
                    B = np.kron(slope[None, :], np.eye(6))
                    B[1] -= value[5]                                                           # v' - theta_z
                    B[2] += value[4]                                                           # w' + theta_y
                target[np.ix_(dofs, dofs)] += 0.5 * (b - a) * w[q] * B.T @ turned[q] @ B
    free = np.arange(6, size)
    values = sla.eigh(K[np.ix_(free, free)], M[np.ix_(free, free)], subset_by_index=[0, count - 1],
                      eigvals_only=True)
    return np.sqrt(values) / (2 * np.pi)
