"""Compiled adaptive Dormand-Prince integrators, 5(4) and 8(5,3), over the compiled right-hand side."""

from __future__ import annotations

import numpy as np

try:
    from numba import njit
except ImportError:                                    # pragma: no cover - numba is optional
    njit = None

if njit is not None:
    from .compiled_kernels import derivative

if njit is not None:                                   # module-level kernels: numba caches them on disk

    # Dormand-Prince 5(4) tableau
    _C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
    _A = np.array([[0, 0, 0, 0, 0, 0],
                   [1 / 5, 0, 0, 0, 0, 0],
                   [3 / 40, 9 / 40, 0, 0, 0, 0],
                   [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
                   [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
                   [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0],
                   [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]])
    _B = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0])
    _E = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])

    @njit(cache=True)
    def dormand_prince(times, x0, rtol, atol, q0, u0, index, *data):
        """Adaptive Dormand-Prince 5(4) with local extrapolation (scipy's RK45 scheme), steps landing on the
        output times; returns the states at ``times`` and the number of right-hand sides."""
        size = x0.shape[0]
        out = np.empty((times.shape[0], size))
        out[0] = x0
        x = x0.copy()
        t = times[0]
        k = np.empty((7, size))
        k[0] = derivative(t, x, q0, u0, index, *data)
        count = 1
        h = min(1e-3, times[-1] - t) if times.shape[0] > 1 else 0.0
        for n in range(1, times.shape[0]):
            target = times[n]
            while t < target - 1e-12 * max(1.0, abs(target)):
                h = min(h, target - t)
                for i in range(1, 7):
                    stage = x.copy()
                    for j in range(i):
                        if _A[i, j] != 0.0:
                            stage += h * _A[i, j] * k[j]
                    k[i] = derivative(t + _C[i] * h, stage, q0, u0, index, *data)
                    count += 1
                new = x + h * (_B @ k)
                error = h * (_E @ k)
                scale = atol + rtol * np.maximum(np.abs(x), np.abs(new))
                norm = np.sqrt(np.mean((error / scale) ** 2))
                if norm <= 1.0:
                    t += h
                    x = new
                    k[0] = k[6]                          # first same as last
                    factor = 5.0 if norm == 0.0 else min(5.0, 0.9 * norm ** -0.2)
                else:
                    factor = max(0.2, 0.9 * norm ** -0.2)
                h *= factor
            out[n] = x
        return out, count

    @njit(cache=True)
    def dormand_prince_853(times, x0, rtol, atol, A, B, C, E3, E5, q0, u0, index, *data):
        """Adaptive 8th-order Dormand-Prince with the 5th/3rd-order error estimate (Hairer's DOP853, scipy's
        scheme and tableau), steps landing on the output times; states at ``times`` and right-hand sides."""
        size = x0.shape[0]
        stages = B.shape[0]
        out = np.empty((times.shape[0], size))
        out[0] = x0
        x = x0.copy()
        t = times[0]
        k = np.zeros((stages + 1, size))
        k[0] = derivative(t, x, q0, u0, index, *data)
        count = 1
        h = min(1e-3, times[-1] - t) if times.shape[0] > 1 else 0.0
        for n in range(1, times.shape[0]):
            target = times[n]
            while t < target - 1e-12 * max(1.0, abs(target)):
                h = min(h, target - t)
                for i in range(1, stages):
                    stage = x.copy()
                    for j in range(i):
                        if A[i, j] != 0.0:
                            stage += h * A[i, j] * k[j]
                    k[i] = derivative(t + C[i] * h, stage, q0, u0, index, *data)
                    count += 1
                new = x.copy()
                for j in range(stages):
                    new += h * B[j] * k[j]
                k[stages] = derivative(t + h, new, q0, u0, index, *data)
                count += 1
                scale = atol + rtol * np.maximum(np.abs(x), np.abs(new))
                err5 = (E5 @ k) / scale
                err3 = (E3 @ k) / scale
                e5, e3 = np.sum(err5**2), np.sum(err3**2)
                norm = 0.0 if e5 == 0.0 and e3 == 0.0 else h * e5 / np.sqrt((e5 + 0.01 * e3) * size)
                if norm <= 1.0:
                    t += h
                    x = new
                    k[0] = k[stages]
                    factor = 10.0 if norm == 0.0 else min(10.0, 0.9 * norm ** -0.125)
                else:
                    factor = max(0.2, 0.9 * norm ** -0.125)
                h *= factor
            out[n] = x
        return out, count
