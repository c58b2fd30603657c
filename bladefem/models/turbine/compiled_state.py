"""numba kernels between the equations and the integrators: the free state x = (q_f, u_f) of the locked and free
coordinates (:func:`full_state`), the free accelerations from M and f (:func:`free_accelerations`) and dx/dt
(:func:`state_rate`)."""

from __future__ import annotations

import numpy as np

from ...numba_cache import cached_njit

njit = cached_njit()

if njit is not None:                                   # module-level kernels: numba caches them on disk
    from .compiled_kernels import solve_spd

    @njit(cache=True)
    def free_accelerations(M, f, index):
        """du/dt of the free coordinates ``index`` (the locked ones have none)."""
        size = index.shape[0]
        Mf = np.empty((size, size))
        ff = np.empty(size)
        for i in range(size):
            ff[i] = f[index[i]]
            for j in range(size):
                Mf[i, j] = M[index[i], index[j]]
        return solve_spd(Mf, ff)

    @njit(cache=True)
    def state_rate(x, M, f, index):
        """dx/dt of the free state x = (q_f, u_f): its rates, then the free accelerations from M and f."""
        size = index.shape[0]
        out = np.empty(2 * size)
        du = free_accelerations(M, f, index)
        for i in range(size):
            out[i] = x[size + i]
            out[size + i] = du[i]
        return out

    @njit(cache=True)
    def full_state(t, x, q0, u0, index):
        """All coordinates and rates at time t for the free state x (locked ones move on at their initial
        rate)."""
        size = index.shape[0]
        q = q0 + u0 * t
        u = u0.copy()
        for i in range(size):
            q[index[i]] = x[i]
            u[index[i]] = x[size + i]
        return q, u
