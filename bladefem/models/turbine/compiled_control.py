"""The controlled run's loop compiled: the controller library called from the kernel (through its ``DISCON`` function
pointer), the integrator stepping on between its calls without a return to Python.

The twin of the Python loop of :mod:`.controlled` (which runs a controller in a process of its own, individual pitch
and RK4): per controller interval ``[t_k, t_k + DLL_DT]``, the records ServoDyn's ``Fill_avrSWAP`` sets that change
from call to call are written (those that do not are the Python loop's first call's,
:meth:`.discon.DisconController.constant_records`, written again before each call), the library called, its
collective pitch (record 45) and torque (47) held over the interval, the pitch set on the kernels' arrays as
:class:`.pitching.CompiledPitch` sets it (one definition), and the equations integrated with Dormand-Prince 5(4)
(the steps and the error control of :func:`.compiled_integrators.dp54_chunk`, the first step the whole interval) or
with classical RK4 at fixed steps (one per interval where the interval is no longer than the step) with the BEM
solved at each step's start and its induction held over the step's other stages, or with Adams-Bashforth-Moulton,
one step per interval, as ElastoDyn steps at DT with its default ``Method`` 3 (ED_ABM4: RK4 for the first three
intervals, then the predictor from the derivatives at the last four boundaries, one right-hand side at the predicted
end with the BEM's induction of the step's start held, the corrector; the derivative at the next boundary, with the
next interval's commands, starts the next step). The load channels and the derivative at an interval's end, which
the next call measures, come from the last stage of the step that ends there (evaluated with its output row), not
from one more right-hand side. The kernel returns after ``budget`` right-hand sides (the caller watches the rows,
polls Ctrl-C) or with a status.
"""

from __future__ import annotations

import math

import numpy as np

from ...numba_cache import cached_njit

njit = cached_njit()

#: statuses beyond the integrator's (1 not finite, 2 beyond the limit, 3 step size underflow): the library's aviFAIL
#: < 0, a pitch or torque override asked for (records 55, 56), a demand that is not finite
FAILED, OVERRIDE, NOT_FINITE = 6, 7, 8

#: classical RK4: the stages' weights (rows 0-2: stages 2-4 from the rates before) and the step's (row 3); the
#: stages' times as fractions of the step
RK4 = np.array([[0.5, 0.0, 0.0, 0.0], [0.0, 0.5, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [1 / 6, 1 / 3, 1 / 3, 1 / 6]])
RK4_C = np.array([0.0, 0.5, 0.5, 1.0])
#: Adams-Bashforth-Moulton (ElastoDyn's ED_ABM4), per step h: the predictor's weights of the derivatives at t, t - h,
#: t - 2h, t - 3h, and the corrector's of the derivatives at the predicted t + h, at t, t - h, t - 2h
ABM4_PREDICTOR = np.array([55.0, -59.0, 37.0, -9.0]) / 24.0
ABM4_CORRECTOR = np.array([9.0, 19.0, -5.0, 1.0]) / 24.0
#: the derivatives an ABM4 step needs from before its start (RK4 steps the intervals until they are known)
ABM4_HISTORY = 3

if njit is not None:
    from .compiled_integrators import check_state, combination, dense_output, error_norm
    from .compiled_kernels import store_row
    from .compiled_state import full_state
    from .pitching import set_pitch

if njit is not None:                                   # module-level kernels: numba caches them on disk

    @njit(cache=True)
    def fill(records, t, x, rate_x, row, pitch, torque, q0, u0, index, turbine, constants):
        """The records of one call that change (1-based numbers in the comments) from the state x, its derivative
        and load channels with the commands held, and the constant ones."""
        rows, values, tip_value, tip_slope, tower = constants
        for i in range(rows.shape[0]):
            records[rows[i] - 1] = values[i]
        generator, ratio, efficiency, wind, blades = int(turbine[0]), turbine[1], turbine[2], turbine[3], \
            int(turbine[4])
        q, u = full_state(t, x, q0, u0, index)
        size = index.shape[0]
        du = np.zeros(q.shape[0])
        for i in range(size):
            du[index[i]] = rate_x[size + i]
        fa, ss, nod, roll = 0.0, 0.0, 0.0, 0.0
        for i in range(tower.shape[0]):
            fa += du[tower[i]] * tip_value[i, 0]
            ss += du[tower[i]] * tip_value[i, 1]
            nod += du[tower[i]] * tip_slope[i, 0]
            roll -= du[tower[i]] * tip_slope[i, 1]
        rotor_speed, generator_speed = u[5] + u[6], ratio * u[generator]
        records[0], records[1], records[3], records[10] = 1.0, t, pitch, pitch                  # 1, 2, 4, 11
        records[13], records[14] = row[3] * rotor_speed, torque * generator_speed * efficiency   # 14, 15
        records[19], records[20], records[22], records[26] = generator_speed, rotor_speed, torque, wind  # 20-27
        for b in range(min(blades, 3)):
            records[29 + b], records[68 + b] = row[0], row[1]                                # 30-32, 69-71
        for b in range(1, min(blades, 3)):
            records[31 + b] = pitch                                                          # 33, 34
        records[36], records[52], records[53] = q[4], fa, ss                                 # 37, 53, 54
        records[59] = (q[5] + q[6]) % (2.0 * math.pi)                                        # 60
        records[81], records[82] = roll, nod                                                 # 82, 83

    @njit(cache=True)
    def call_library(function, records, buffers):
        """One ``DISCON`` call on the records: aviFAIL (the message is left in its buffer)."""
        fail, infile, outname, message = buffers
        fail[0] = 0
        message[:] = 0
        function(records.ctypes.data, fail.ctypes.data, infile.ctypes.data, outname.ctypes.data,
                 message.ctypes.data)
        return fail[0]

    @njit(cache=True)
    def dp54_interval(rate, kernels, t, x, f0, t_end, spacing, times, out, loads, next_out, end_row, K, rtol, atol,
                      limit, tableau, q0, u0, index, data, work, hub_radius):
        """Dormand-Prince 5(4) from t to t_end (first step the whole interval, the error control of
        :func:`.compiled_integrators.dp54_chunk`): the output rows ``times[next_out:]`` before t_end (by more than
        1e-9 ``spacing``: a row at t_end is the next interval's, after the controller's call) from the dense
        output; the end's load channels in ``end_row``. Returns (x, derivative at the end, next_out, right-hand
        sides, status, offending index)."""
        A, B, C, E, P = tableau
        store_row(K, 0, f0)
        count = 0
        h = t_end - t
        near = 1e-9 * spacing
        while t < t_end:
            h = min(h, t_end - t)
            if h <= 1e-14 * max(1.0, abs(t)):
                return x, K[0], next_out, count, 3, -1
            for s in range(1, 6):
                stage = combination(x, h, A[s], K, s)
                store_row(K, s, rate(kernels, t + C[s] * h, stage, q0, u0, index, data, work, hub_radius,
                                     loads[0, :0]))
            new = combination(x, h, B, K, 6)
            last = t + h >= t_end
            store_row(K, 6, rate(kernels, t + h, new, q0, u0, index, data, work, hub_radius, end_row if last else
                                 end_row[:0]))
            count += 6
            norm = error_norm(x, new, K, E, h, rtol, atol)
            if norm <= 1.0:
                bad = check_state(new, limit)
                if bad >= 0:
                    return new, K[6], next_out, count, 1 if not np.isfinite(new[bad]) else 2, bad
                t_new = t_end if last else t + h
                while next_out < times.shape[0] and (times[next_out] < t_end - near if last else
                                                     times[next_out] <= t_new):
                    y = dense_output(x, K, P, h, (times[next_out] - t) / h)
                    store_row(out, next_out, y)
                    rate(kernels, times[next_out], y, q0, u0, index, data, work, hub_radius, loads[next_out])
                    next_out += 1
                t = t_new
                x = new
                store_row(K, 0, K[6])
                factor = 5.0 if norm == 0.0 else min(5.0, 0.9 * norm ** -0.2)
            else:
                factor = max(0.2, 0.9 * norm ** -0.2)
            h *= factor
        return x, K[0], next_out, count, 0, -1

    @njit(cache=True)
    def rk4_interval(rate, kernels, t, x, f0, t_end, spacing, step, times, out, loads, next_out, end_row, K, limit,
                     q0, u0, index, data, work, hub_radius):
        """Classical RK4 from t to t_end (ElastoDyn's fixed steps, the twin of :func:`.controlled.rk4_interval`):
        steps no longer than ``step`` landing on each output time ``times[next_out:]`` inside the interval, whose
        load row is the right-hand side that starts the next step; the BEM solved at each step's start (``f0`` for
        the first: solved there with the interval's commands) and its induced velocities held over the other three
        stages (AeroDyn solves once per step too; without the dynamic wake, whose states carry the induction); the
        end's load channels in ``end_row``, with the derivative there (one more right-hand side). Returns (x,
        derivative at the end, next_out, right-hand sides, status, offending index) as :func:`dp54_interval`
        does."""
        near = 1e-9 * spacing
        store_row(K, 0, f0)
        count = 0
        hold = work[1][13]
        while True:
            inner = next_out < times.shape[0] and times[next_out] < t_end - near
            target = times[next_out] if inner else t_end
            n = max(1, int(math.ceil((target - t) / step - 1e-9)))
            h = (target - t) / n
            for i in range(n):
                if i > 0:
                    store_row(K, 0, rate(kernels, t, x, q0, u0, index, data, work, hub_radius, end_row[:0]))
                    count += 1
                hold[2] = 1.0                          # stages 2-4: the induction of the step's first
                for s in range(1, 4):
                    stage = combination(x, h, RK4[s - 1], K, s)
                    store_row(K, s, rate(kernels, t + RK4_C[s] * h, stage, q0, u0, index, data, work, hub_radius,
                                         end_row[:0]))
                hold[2] = 0.0
                x = combination(x, h, RK4[3], K, 4)
                t = target if i == n - 1 else t + h
                count += 3
            bad = check_state(x, limit)
            if bad >= 0:
                return x, K[0], next_out, count, 1 if not np.isfinite(x[bad]) else 2, bad
            if not inner:
                break
            store_row(out, next_out, x)
            store_row(K, 0, rate(kernels, t, x, q0, u0, index, data, work, hub_radius, loads[next_out]))
            count += 1
            next_out += 1
        f_end = rate(kernels, t_end, x, q0, u0, index, data, work, hub_radius, end_row)
        return x, f_end, next_out, count + 1, 0, -1

    @njit(cache=True)
    def abm4_interval(rate, kernels, t, x, f0, t_end, next_out, end_row, history, limit, q0, u0, index, data, work,
                      hub_radius):
        """One step of Adams-Bashforth-Moulton from t to t_end (ElastoDyn's ED_ABM4): the predictor from the
        derivatives at t (``f0``, with the interval's commands) and at the three boundaries before (``history``),
        the rate at the predicted end with the BEM's induction of ``f0``'s solve held (its load channels in
        ``end_row``: what the next call measures), the corrector. Writes no output row (``next_out`` returned as it
        came). Returns as :func:`dp54_interval`."""
        h = t_end - t
        n = x.shape[0]
        P, C = ABM4_PREDICTOR, ABM4_CORRECTOR
        predicted = np.empty(n)
        for i in range(n):
            predicted[i] = x[i] + h * (P[0] * f0[i] + P[1] * history[0, i] + P[2] * history[1, i]
                                       + P[3] * history[2, i])
        hold = work[1][13]
        hold[2] = 1.0
        f_end = rate(kernels, t_end, predicted, q0, u0, index, data, work, hub_radius, end_row)
        hold[2] = 0.0
        new = np.empty(n)
        for i in range(n):
            new[i] = x[i] + h * (C[0] * f_end[i] + C[1] * f0[i] + C[2] * history[0, i] + C[3] * history[1, i])
        bad = check_state(new, limit)
        if bad >= 0:
            return new, f_end, next_out, 1, 1 if not np.isfinite(new[bad]) else 2, bad
        return new, f_end, next_out, 1, 0, -1

    @njit(cache=True)
    def call_controller(t, x, rate_x, row, commands, q0, u0, index, data, pitching, function, records, buffers,
                        turbine, constants):
        """The controller's call at t with the state ``x``, its derivative ``rate_x`` and load channels ``row``: its
        demands held (``commands`` = pitch, torque, updated; the pitch set on the kernels' arrays, the torque on
        the law). Returns 0 or the status of a failed call."""
        structure, aero, law = data
        fill(records, t, x, rate_x, row, commands[0], commands[1], q0, u0, index, turbine, constants)
        if call_library(function, records, buffers) < 0:
            return FAILED
        if records[54] != 0.0 or records[55] != 0.0:
            return OVERRIDE
        pitch, torque = np.float64(records[44]), np.float64(records[46])
        if not (np.isfinite(pitch) and np.isfinite(torque)):
            return NOT_FINITE
        if pitch != commands[0]:
            set_pitch(pitch, pitching[0], pitching[1], structure, aero)
        commands[0], commands[1] = pitch, torque
        law[2] = torque
        return 0

    @njit(cache=True)
    def controlled_chunk(rate, kernels, k, boundaries, x, rate_x, row, commands, call_first, times, out, loads, held,
                         next_out, budget, rtol, atol, step, limit, tableau, K, q0, u0, index, data, work, hub_radius,
                         pitching, function, records, buffers, turbine, constants, history, taken):
        """Controller intervals from ``k`` on until ``budget`` right-hand sides are spent or the run ends: at each, the
        controller called (but for the first interval of a call without ``call_first``: its commands set
        already) with the state ``x``, its derivative ``rate_x`` and load channels ``row`` (updated in place
        to the interval's end), its demands held (``commands`` = pitch, torque, updated), an output row at the
        interval's start written from the derivative there (after the call: a zero-order hold's value at its
        switching time is the new one, as the first row's), the interval integrated (``rate``, given
        ``kernels``: the state rate and the kernels it calls, as first-class functions or as dispatchers,
        :mod:`.compiled_calls`; :func:`dp54_interval`; :func:`rk4_interval` where ``step`` is positive;
        :func:`abm4_interval` where ``taken[0]``, the boundaries whose derivatives ``history`` holds, newest
        first, is at least :data:`ABM4_HISTORY`, the interval whole and no output row inside it; ``taken[0]``
        negative: no ABM4), the pitch of each output row in ``held``; at the run's end the controller called
        once more for the last row. ``pitching`` = (base pitch, reference arrays) of
        :func:`.pitching.pitch_arrays`. Returns (next interval, its start time, next output row, right-hand
        sides, status, offending index)."""
        count = 0
        t = boundaries[k]
        spacing = boundaries[1] - boundaries[0]
        near = 1e-9 * spacing
        controls = (q0, u0, index, data, pitching, function, records, buffers, turbine, constants)
        while k < boundaries.shape[0] - 1 and count < budget:
            t, end = boundaries[k], boundaries[k + 1]
            if call_first:
                status = call_controller(t, x, rate_x, row, commands, *controls)
                if status:
                    return k, t, next_out, count, status, -1
            call_first = True
            if next_out < times.shape[0] and times[next_out] <= t + near:
                store_row(out, next_out, x)
                held[next_out] = commands[0]
                f0 = rate(kernels, t, x, q0, u0, index, data, work, hub_radius, loads[next_out])
                next_out += 1
            else:
                f0 = rate(kernels, t, x, q0, u0, index, data, work, hub_radius, row[:0])
            first = next_out
            inner = next_out < times.shape[0] and times[next_out] < end - near
            if taken[0] >= ABM4_HISTORY and not inner and abs(end - t - spacing) <= near:
                new, f_end, next_out, used, status, bad = abm4_interval(
                    rate, kernels, t, x, f0, end, next_out, row, history, limit, q0, u0, index, data, work,
                    hub_radius)
            elif step > 0.0:
                new, f_end, next_out, used, status, bad = rk4_interval(
                    rate, kernels, t, x, f0, end, spacing, step, times, out, loads, next_out, row, K, limit, q0, u0,
                    index, data, work, hub_radius)
            else:
                new, f_end, next_out, used, status, bad = dp54_interval(
                    rate, kernels, t, x, f0, end, spacing, times, out, loads, next_out, row, K, rtol, atol, limit,
                    tableau, q0, u0, index, data, work, hub_radius)
            count += used + 1
            if taken[0] >= 0:                          # ABM4: the derivatives at the boundaries, newest first
                for i in range(x.shape[0]):
                    history[2, i], history[1, i], history[0, i] = history[1, i], history[0, i], f0[i]
                taken[0] += 1
            for j in range(first, next_out):
                held[j] = commands[0]
            if status:
                return k, t, next_out, count, status, bad
            for i in range(x.shape[0]):                # x, rate_x <- the end of the interval
                x[i] = new[i]
                rate_x[i] = f_end[i]
            k += 1
            t = end
        if k == boundaries.shape[0] - 1 and next_out < times.shape[0] and times[next_out] <= t + near:
            status = call_controller(t, x, rate_x, row, commands, *controls)      # the last row's commands
            if status:
                return k, t, next_out, count, status, -1
            store_row(out, next_out, x)
            held[next_out] = commands[0]
            rate(kernels, t, x, q0, u0, index, data, work, hub_radius, loads[next_out])
            next_out += 1
            count += 1
        return k, t, next_out, count, 0, -1
