"""Compiled output channels that need the equations of motion (the blade root bending moments), for all output
rows in one call (see :func:`bladefem.models.turbine.simulate.root_moments` for the numpy version)."""

from __future__ import annotations

import numpy as np

try:
    from numba import njit
except ImportError:                                    # pragma: no cover - numba is optional
    njit = None

if njit is not None:
    from .compiled_kernels import equations, free_accelerations, full_state, work_arrays

if njit is not None:                                   # module-level kernels: numba caches them on disk

    @njit(cache=True)
    def root_moments(times, states, q0, u0, index, data, hub_radius, blade):
        """Out-of-plane and in-plane root bending moments (T, 2), N m, of ``blade`` at each output row:
        ``sum_p (r_p - r_root) x m_p (g - a_p)`` over its nodes, in the blade frame (out-of-plane positive for
        downwind loads, in-plane positive for loads toward the leading edge)."""
        n, b_mass, gravity = data[0], data[8], data[20]
        work = work_arrays(data)
        rho_w, bias_w, RD_w, Z_w, frame_w = work[0], work[2], work[3], work[4], work[5]
        k = RD_w.shape[3]
        out = np.zeros((times.shape[0], 2))
        for row in range(times.shape[0]):
            q, u = full_state(times[row], states[row], q0, u0, index)
            M, f = equations(q, u, data, work)
            du = np.zeros(n)
            free = free_accelerations(M, f, index)
            for i in range(index.shape[0]):
                du[index[i]] = free[i]
            Z = Z_w[blade]
            shared = np.zeros(6 + k)
            for r in range(6 + k):
                for c in range(n):
                    shared[r] += Z[r, c] * du[c]
            R = frame_w[blade]
            moment = np.zeros(3)
            arm, a, load = np.zeros(3), np.zeros(3), np.zeros(3)
            for p in range(rho_w.shape[1]):
                rho = rho_w[blade, p]
                for r in range(3):
                    arm[r] = rho[r] - hub_radius * R[r, 0]
                a[0] = shared[0] + shared[4] * rho[2] - shared[5] * rho[1]
                a[1] = shared[1] + shared[5] * rho[0] - shared[3] * rho[2]
                a[2] = shared[2] + shared[3] * rho[1] - shared[4] * rho[0]
                for r in range(3):
                    for i in range(k):
                        a[r] += RD_w[blade, p, r, i] * shared[6 + i]
                    load[r] = b_mass[p] * (gravity[r] - a[r] - bias_w[blade, p, r])
                moment[0] += arm[1] * load[2] - arm[2] * load[1]
                moment[1] += arm[2] * load[0] - arm[0] * load[2]
                moment[2] += arm[0] * load[1] - arm[1] * load[0]
            local_y = R[0, 1] * moment[0] + R[1, 1] * moment[1] + R[2, 1] * moment[2]
            local_z = R[0, 2] * moment[0] + R[1, 2] * moment[1] + R[2, 2] * moment[2]
            out[row, 0] = -local_y
            out[row, 1] = local_z
        return out
