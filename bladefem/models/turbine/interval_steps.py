"""The fixed-step integrators of a controlled run's intervals in Python, twins of :mod:`.compiled_control`'s
``rk4_interval`` and ``abm4_interval`` (the loop of :mod:`.controlled` that runs the controller in a process of its
own), and the stability check that lets ``--method auto`` choose Adams-Bashforth-Moulton.

Adams-Bashforth-Moulton as ElastoDyn's ``Method`` 3 (ED_ABM4) takes one right-hand side per step after the start
(the derivative at the predicted end; the derivative at the step's start is the one the controller's new commands
give there), against RK4's four. Its price is a small stability region and, on an undamped oscillation, a growth
instead of RK4's decay: per step ``|rho(i w h)| - 1`` is 1.6e-7 at ``w h = 0.1``, 1e-4 at 0.3, 5e-3 at 0.7 (RK4:
-7e-9, -5e-6, -8e-4). A structural mode damped by ``zeta`` decays by ``zeta w h`` per step, so the method is
stable where the physics is damped a little more than the scheme grows: :func:`abm4_stable` asks it of every mode
of the linearized system with a margin.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from .compiled import Integration
from .compiled_control import ABM4_CORRECTOR, ABM4_PREDICTOR
from .outputs import LOAD_COLUMNS
from .simulate import rk4_step
from .system import FreeSystem

#: "auto" takes ABM4 where every mode stays stable at this many times the step (a margin for the operating point's
#: changes of the modes, as RK4's 0.5 of its limit)
ABM4_MARGIN = 2.0
#: amplification taken as 1 (the roots' rounding at z = 0, a rigid-body mode)
ROUNDING = 1e-12


def abm4_growth(z: NDArray) -> NDArray:
    """The amplification per step (largest root of the characteristic polynomial) of ABM4 on ``y' = lambda y``,
    ``z = h lambda`` (complex, any shape): the predictor, the derivative at the predicted end, the corrector, the
    derivative at the corrected state starting the next step."""
    z = np.asarray(z, dtype=complex)
    P, C = ABM4_PREDICTOR, ABM4_CORRECTOR
    growth = np.empty(z.shape)
    for position, value in np.ndenumerate(z):
        predicted = np.array([1.0, 0.0, 0.0, 0.0]) + value * P          # y_p in terms of y_n .. y_{n-3}
        corrected = np.array([1.0, 0.0, 0.0, 0.0]) + value * np.append(C[1:], 0.0) + value * C[0] * predicted
        growth[position] = np.max(np.abs(np.roots(np.concatenate([[1.0], -corrected]))))
    return growth


def abm4_stable(eigenvalues: NDArray, step: float) -> bool:
    """Whether ABM4 at ``step`` s (and at :data:`ABM4_MARGIN` times it) lets none of the modes of ``eigenvalues``
    (rad/s, the state matrix's) that do not grow grow: amplification at most 1 where the real part is not positive
    (an undamped oscillation grows under ABM4); growing modes (the physics grows too) are not asked."""
    return all(abm4_grows_none(factor * step, eigenvalues) for factor in (1.0, ABM4_MARGIN))


def abm4_grows_none(step: float, eigenvalues: NDArray) -> bool:
    """Whether ABM4 at ``step`` s keeps every mode of ``eigenvalues`` (rad/s) whose real part is not positive from
    growing (amplification at most 1, to :data:`ROUNDING`)."""
    return bool(np.all(abm4_growth(step * eigenvalues[np.real(eigenvalues) <= 0]) <= 1.0 + ROUNDING))


def rk4_interval(system: FreeSystem, compiled, chunk: NDArray, x: NDArray, step: float, limit: NDArray,
                 rows: int, first: NDArray | None = None) -> Integration:
    """Classical RK4 over the times ``chunk`` (steps no longer than ``step``, landing on each), the compiled
    right-hand side, the BEM's induction of each step's first stage held over the other three; the load channels at
    the first ``rows`` times after the start (the output rows). ``first``: the derivative at the start, evaluated
    already (not counted again). Stops at a state beyond ``limit`` or not finite (status 1, 2), as the adaptive
    kernel does."""
    q0, u0, index, hold = system.q0, system.u0, system.index, compiled.state[13]

    def rate(t: float, x: NDArray) -> NDArray:
        return compiled.rate(t, x, q0, u0, index)

    states, count = np.full((len(chunk), len(x)), np.nan), 0 if first is None else -1
    states[0] = x
    for i, (a, b) in enumerate(zip(chunk[:-1], chunk[1:])):
        n = max(1, int(math.ceil((b - a) / step - 1e-9)))
        h, t = (b - a) / n, a
        for _ in range(n):
            x = rk4_step(rate, t, x, h, hold, first)      # the induction of the first stage's solve held
            t, first = t + h, None
        count += 4 * n
        bad = np.flatnonzero(~np.isfinite(x) | (np.abs(x) > limit))
        if bad.size:
            status = 1 if not np.isfinite(x[bad[0]]) else 2
            loads = np.full((len(chunk), len(LOAD_COLUMNS)), np.nan)
            return Integration(states, loads, i + 1, count, status, float(b), int(bad[0]))
        states[i + 1] = x
    loads = np.full((len(chunk), len(LOAD_COLUMNS)), np.nan)
    if rows:
        loads[1:1 + rows] = compiled.outputs(chunk[1:1 + rows], states[1:1 + rows], q0, u0, index)
    return Integration(states, loads, len(chunk), count)


def abm4_interval(system: FreeSystem, compiled, t: float, end: float, x: NDArray, first: NDArray,
                  history: NDArray, limit: NDArray) -> tuple[Integration, NDArray]:
    """One ABM4 step from ``t`` to ``end`` (the twin of :func:`.compiled_control.abm4_interval`): the predictor from
    ``first`` (the derivative at t, evaluated already) and ``history`` (at the three boundaries before, newest
    first), the derivative and load channels at the predicted end with the BEM's induction of ``first``'s solve
    held (returned as the Integration's ``rate`` and the second value: what the next call measures), the
    corrector."""
    q0, u0, index, hold = system.q0, system.u0, system.index, compiled.state[13]
    h = end - t
    predicted = x + h * (ABM4_PREDICTOR[0] * first + ABM4_PREDICTOR[1:] @ history)
    hold[2] = 1.0
    rate = compiled.rate(end, predicted, q0, u0, index)
    measured = compiled.outputs(np.array([end]), predicted[None], q0, u0, index)[0]
    hold[2] = 0.0
    new = x + h * (ABM4_CORRECTOR[0] * rate + ABM4_CORRECTOR[1] * first + ABM4_CORRECTOR[2:] @ history[:2])
    states, loads = np.array([x, new]), np.full((2, len(LOAD_COLUMNS)), np.nan)
    bad = np.flatnonzero(~np.isfinite(new) | (np.abs(new) > limit))
    if bad.size:
        status = 1 if not np.isfinite(new[bad[0]]) else 2
        return Integration(states, loads, 1, 1, status, float(end), int(bad[0])), measured
    return Integration(states, loads, 2, 1, rate=rate), measured
