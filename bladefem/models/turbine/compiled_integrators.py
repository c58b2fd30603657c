"""Compiled adaptive Dormand-Prince integrators, 8(5,3) and 5(4), with dense output, over the compiled right-hand
side.

Each call advances from ``t`` towards ``t_end`` and returns there or after ``budget`` right-hand sides, whichever
comes first (so that the caller regains control a few times a second, to look for Ctrl-C and watch the run); the
first call (``start``) evaluates the derivative and the outputs at the initial state. The steps are chosen by the
error control alone and the states at the output times inside a step come from the method's continuous extension
(DOP853: Hairer's 7th-order interpolant, three extra right-hand sides on the steps that hold an output time; DP54:
the free 4th-order one), so the output interval does not constrain the step; the load channels of each output row
(:func:`.compiled_outputs.output_row`) are computed as the row is written. After each accepted step the state is
checked: non-finite values or a coordinate beyond its ``limit`` stop the call with a status (1: not finite, 2:
beyond the limit, 3: step size underflow) and the index of the offending state.
"""

from __future__ import annotations

import numpy as np

from ...numba_cache import cached_njit

njit = cached_njit()

if njit is not None:
    from .compiled_kernels import equations, store_row
    from .compiled_state import full_state, state_rate
    from .compiled_loads import add_aero, load_wake, loaded_equations, store_wake_rate
    from .compiled_outputs import output_row

if njit is not None:                                   # module-level kernels: numba caches them on disk

    @njit(cache=True, inline="always")
    def rate_with(kernels, t, x, q0, u0, index, data, work, hub_radius, row):
        """dx/dt at (t, x) of the free coordinates and the dynamic wake, x = (q_f, u_f, w), and the load channels into ``row`` (from the
        same evaluation of the equations) if it is not empty, with ``kernels`` (structural equations, aerodynamic
        loads, output row) called directly or as first-class functions. Inlined by numba into its callers."""
        structural, aerodynamic, outputs = kernels
        q, u = full_state(t, x, q0, u0, index)
        load_wake(x, index.shape[0], work[1])
        M, f = loaded_equations(q, u, data, work, t, structural, aerodynamic)
        out = state_rate(x, M, f, index)
        store_wake_rate(out, index.shape[0], work[1])
        if row.shape[0]:
            outputs(q, u, M, f, index, data, work, hub_radius, 0, row)
        return out

    @njit(cache=True)
    def rate_function(kernels, t, x, q0, u0, index, data, work, hub_radius, row):
        """:func:`rate_with` as a library of its own, which the integrators call as a first-class function."""
        return rate_with(kernels, t, x, q0, u0, index, data, work, hub_radius, row)

    @njit(cache=True)
    def direct_rate(t, x, q0, u0, index, data, work, hub_radius):
        """:func:`rate_with` without load channels, its kernels called directly (linked in): the entry for callers
        in Python at every right-hand side (scipy's integrators, RK4 steps, the Python controlled loop), for which
        numba's conversion of first-class function arguments at each call costs more than the right-hand side."""
        return rate_with((equations, add_aero, output_row), t, x, q0, u0, index, data, work, hub_radius, np.zeros(0))

    @njit(cache=True)
    def check_state(x, limit):
        """-1 if every |x_i| <= limit_i and finite, else the first offending index (status via sign of the
        value: not finite or beyond the limit)."""
        for i in range(x.shape[0]):
            if not np.isfinite(x[i]) or abs(x[i]) > limit[i]:
                return i
        return -1

    @njit(cache=True)
    def error_norm(x, new, K, E, h, rtol, atol):
        """The step's RMS error estimate ``h sum_j E_j K_j`` scaled by ``atol + rtol max(|x|, |new|)`` (a step is
        taken when it is at most 1)."""
        total = 0.0
        for i in range(x.shape[0]):
            error = 0.0
            for j in range(7):
                error += E[j] * K[j, i]
            total += (h * error / (atol + rtol * max(abs(x[i]), abs(new[i])))) ** 2
        return np.sqrt(total / x.shape[0])

    @njit(cache=True)
    def dense_output(x, K, P, h, theta):
        """Dormand-Prince's continuous extension at ``theta`` (0 to 1) of the step ``h`` from ``x`` with the stages
        ``K`` (7, n) and the interpolation weights ``P`` (7, 4): ``x + h sum_r theta^(r+1) (P^T K)_r``."""
        y = x.copy()
        for i in range(x.shape[0]):
            power = 1.0
            for r in range(4):
                power *= theta
                value = 0.0
                for j in range(7):
                    value += K[j, i] * P[j, r]
                y[i] += h * value * power
        return y

    @njit(cache=True)
    def combination(x, h, weights, K, stages):
        """x + h sum_j weights_j K_j over the first ``stages`` rows of K."""
        out = x.copy()
        for j in range(stages):
            w = weights[j]
            if w != 0.0:
                for i in range(x.shape[0]):
                    out[i] += h * w * K[j, i]
        return out

    @njit(cache=True)
    def dop853_chunk(rate, kernels, t, x, f0, h, t_end, budget, start, times, out, loads, next_out, rtol, atol,
                     limit, tableau, q0, u0, index, data, work, hub_radius):
        """DOP853 (Hairer's 8(5,3) with scipy's tableau ``(A, B, C, E3, E5, D)``) from t to t_end (or ``budget``
        right-hand sides) with the first step h; fills ``out[k]`` and ``loads[k]`` for the output ``times[k] <=
        t_end``, k from ``next_out``; ``start``: f0 and the first row are computed here; ``rate``:
        :func:`rate_function` given ``kernels``, as first-class functions (:mod:`.compiled_calls`). Returns ``(t, x,
        f, h, next_out, evaluations, status, offending index)``."""
        A, B, C, E3, E5, D = tableau
        size = x.shape[0]
        stages = B.shape[0]
        K = np.zeros((A.shape[0], size))
        count = 0
        if start:
            f0 = rate(kernels, t, x, q0, u0, index, data, work, hub_radius, loads[0])
            count += 1
        store_row(K, 0, f0)
        while t < t_end and count < budget:
            h = min(h, t_end - t)
            if h <= 1e-14 * max(1.0, abs(t)):
                return t, x, K[0], h, next_out, count, 3, -1
            for s in range(1, stages):
                stage = combination(x, h, A[s], K, s)
                store_row(K, s, rate(kernels, t + C[s] * h, stage, q0, u0, index, data, work, hub_radius, loads[0, :0]))
            new = combination(x, h, B, K, stages)
            store_row(K, stages, rate(kernels, t + h, new, q0, u0, index, data, work, hub_radius, loads[0, :0]))
            count += stages
            e5, e3 = 0.0, 0.0
            for i in range(size):
                scale = atol + rtol * max(abs(x[i]), abs(new[i]))
                a5, a3 = 0.0, 0.0
                for j in range(stages + 1):
                    a5 += E5[j] * K[j, i]
                    a3 += E3[j] * K[j, i]
                e5 += (a5 / scale) ** 2
                e3 += (a3 / scale) ** 2
            norm = 0.0 if e5 == 0.0 and e3 == 0.0 else h * e5 / np.sqrt((e5 + 0.01 * e3) * size)
            if norm <= 1.0:
                t_new = t_end if t + h >= t_end else t + h
                if next_out < times.shape[0] and times[next_out] <= t_new:
                    for s in range(stages + 1, A.shape[0]):
                        stage = combination(x, h, A[s], K, s)
                        store_row(K, s, rate(kernels, t + C[s] * h, stage, q0, u0, index, data, work, hub_radius,
                                             loads[0, :0]))
                        count += 1
                    F = np.zeros((7, size))
                    for i in range(size):
                        delta = new[i] - x[i]
                        F[0, i] = delta
                        F[1, i] = h * K[0, i] - delta
                        F[2, i] = 2.0 * delta - h * (K[stages, i] + K[0, i])
                        for r in range(4):
                            value = 0.0
                            for j in range(A.shape[0]):
                                value += D[r, j] * K[j, i]
                            F[3 + r, i] = h * value
                    while next_out < times.shape[0] and times[next_out] <= t_new:
                        theta = (times[next_out] - t) / h
                        for i in range(size):
                            y = 0.0
                            for r in range(7):
                                y = (y + F[6 - r, i]) * (theta if r % 2 == 0 else 1.0 - theta)
                            out[next_out, i] = x[i] + y
                        rate(kernels, times[next_out], out[next_out], q0, u0, index, data, work, hub_radius,
                             loads[next_out])
                        next_out += 1
                t = t_new
                x = new
                store_row(K, 0, K[stages])
                bad = check_state(x, limit)
                if bad >= 0:
                    return t, x, K[0], h, next_out, count, 1 if not np.isfinite(x[bad]) else 2, bad
                factor = 10.0 if norm == 0.0 else min(10.0, 0.9 * norm ** -0.125)
            else:
                factor = max(0.2, 0.9 * norm ** -0.125)
            h *= factor
        return t, x, K[0], h, next_out, count, 0, -1

    @njit(cache=True)
    def dp54_chunk(rate, kernels, t, x, f0, h, t_end, budget, start, times, out, loads, next_out, rtol, atol,
                   limit, tableau, q0, u0, index, data, work, hub_radius):
        """Dormand-Prince 5(4) (scipy's RK45 scheme, tableau ``(A, B, C, E, P)``), as :func:`dop853_chunk`."""
        A, B, C, E, P = tableau
        size = x.shape[0]
        K = np.zeros((7, size))
        count = 0
        if start:
            f0 = rate(kernels, t, x, q0, u0, index, data, work, hub_radius, loads[0])
            count += 1
        store_row(K, 0, f0)
        while t < t_end and count < budget:
            h = min(h, t_end - t)
            if h <= 1e-14 * max(1.0, abs(t)):
                return t, x, K[0], h, next_out, count, 3, -1
            for s in range(1, 6):
                stage = combination(x, h, A[s], K, s)
                store_row(K, s, rate(kernels, t + C[s] * h, stage, q0, u0, index, data, work, hub_radius, loads[0, :0]))
            new = combination(x, h, B, K, 6)
            store_row(K, 6, rate(kernels, t + h, new, q0, u0, index, data, work, hub_radius, loads[0, :0]))
            count += 6
            norm = error_norm(x, new, K, E, h, rtol, atol)
            if norm <= 1.0:
                t_new = t_end if t + h >= t_end else t + h
                while next_out < times.shape[0] and times[next_out] <= t_new:
                    y = dense_output(x, K, P, h, (times[next_out] - t) / h)
                    store_row(out, next_out, y)
                    rate(kernels, times[next_out], y, q0, u0, index, data, work, hub_radius, loads[next_out])
                    next_out += 1
                t = t_new
                x = new
                store_row(K, 0, K[6])
                bad = check_state(x, limit)
                if bad >= 0:
                    return t, x, K[0], h, next_out, count, 1 if not np.isfinite(x[bad]) else 2, bad
                factor = 5.0 if norm == 0.0 else min(5.0, 0.9 * norm ** -0.2)
            else:
                factor = max(0.2, 0.9 * norm ** -0.2)
            h *= factor
        return t, x, K[0], h, next_out, count, 0, -1
