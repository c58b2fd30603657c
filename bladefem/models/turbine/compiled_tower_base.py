"""The tower's, the nacelle's and the rotary bodies' share of the tower-base moment, compiled (the twin of
:func:`bladefem.models.turbine.outputs.tower_base_moment`, whose rotor share :mod:`.compiled_outputs` carries from
the apex): the tower nodes and the nacelle centre of mass with their gravity and d'Alembert forces, and the nacelle
(about the yaw axis), hub and generator (about the shaft) with ``-I [k (k . alpha) + (k . omega) omega x k]``, by the
kinematics of :func:`.compiled_kernels.equations` at the accelerations ``du``."""

from __future__ import annotations

import numpy as np

from ...numba_cache import cached_njit

njit = cached_njit()

if njit is not None:                                   # module-level kernels: numba caches them on disk
    from .compiled_kernels import beam_node, carried_point, rotate

    @njit(cache=True)
    def add_point(total, r, base_height, m, gravity, J, bias, du):
        """total += (r - r_base) x m (g - J du - bias) for a point at r (earth), base at (0, 0, base_height)."""
        load = np.zeros(3)
        for i in range(3):
            a = bias[i]
            for c in range(du.shape[0]):
                a += J[i, c] * du[c]
            load[i] = m * (gravity[i] - a)
        x, y, z = r[0], r[1], r[2] - base_height
        total[0] += y * load[2] - z * load[1]
        total[1] += z * load[0] - x * load[2]
        total[2] += x * load[1] - y * load[0]

    @njit(cache=True)
    def add_body(total, R, w, W, al, axis, inertia, du):
        """total -= I [k (k . alpha) + (k . omega) omega x k], alpha = W du + al, k the frame's axis ``axis``."""
        k = R[:, axis].copy()
        along = k[0] * al[0] + k[1] * al[1] + k[2] * al[2]
        for c in range(du.shape[0]):
            along += (k[0] * W[0, c] + k[1] * W[1, c] + k[2] * W[2, c]) * du[c]
        spin = k[0] * w[0] + k[1] * w[1] + k[2] * w[2]
        total[0] -= inertia * (k[0] * along + spin * (w[1] * k[2] - w[2] * k[1]))
        total[1] -= inertia * (k[1] * along + spin * (w[2] * k[0] - w[0] * k[2]))
        total[2] -= inertia * (k[2] * along + spin * (w[0] * k[1] - w[1] * k[0]))

    @njit(cache=True)
    def add_tower_and_nacelle(q, u, du, structure, total):
        """total += the moment about the tower base of the tower nodes, the nacelle centre of mass and the nacelle,
        hub and generator rotary inertias at (q, u) with accelerations du."""
        n, t_across, t_short, t_axial, t_mass = structure[0], structure[1], structure[2], structure[3], structure[4]
        fore_aft, side_side, yaw, azimuth, generator = structure[11], structure[12], structure[13], structure[14], \
            structure[15]
        tilt, rigid_offsets, rigid_mass, inertias, gravity = structure[16], structure[17], structure[18], \
            structure[19], structure[20]
        base_height = structure[23]
        D = np.zeros((3, 4))
        d, rate, bias, r = np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)
        J = np.zeros((3, n))
        for p in range(t_axial.shape[0]):
            beam_node(t_across, t_short, t_axial, p, q[:4], u[:4], 2, D, d, rate, bias)
            for i in range(3):
                for c in range(4):
                    J[i, c] = D[i, c]
            r[0], r[1], r[2] = d[0], d[1], d[2] + base_height
            add_point(total, r, base_height, t_mass[p], gravity, J, bias, du)
        R, w, W, al = np.zeros((3, 3)), np.zeros(3), np.zeros((3, n)), np.zeros(3)
        R[0, 0] = R[1, 1] = R[2, 2] = 1.0
        R, w, W, al = rotate(R, w, W, al, 1, fore_aft, q, u)
        R, w, W, al = rotate(R, w, W, al, 0, side_side, q, u)
        RN, wN, WN, alN = rotate(R, w, W, al, 2, yaw, q, u)
        # nacelle centre of mass, carried from the tower top (the last tower node: r, J, bias as left above)
        rho = np.zeros(3)
        for i in range(3):
            rho[i] = RN[i, 0] * rigid_offsets[0, 0] + RN[i, 1] * rigid_offsets[0, 1] + RN[i, 2] * rigid_offsets[0, 2]
        a = carried_point(J, bias, WN, wN, alN, rho)
        for i in range(3):
            r[i] += rho[i]
        add_point(total, r, base_height, rigid_mass[0], gravity, J, a, du)
        RS = np.zeros((3, 3))
        for i in range(3):
            for c in range(3):
                RS[i, c] = RN[i, 0] * tilt[0, c] + RN[i, 1] * tilt[1, c] + RN[i, 2] * tilt[2, c]
        RL, wL, WL, alL = rotate(RS, wN, WN, alN, 0, azimuth, q, u)
        RG, wG, WG, alG = rotate(RS, wN, WN, alN, 0, generator, q, u)
        add_body(total, RN, wN, WN, alN, 2, inertias[0], du)
        add_body(total, RL, wL, WL, alL, 0, inertias[1], du)
        add_body(total, RG, wG, WG, alG, 0, inertias[2], du)
