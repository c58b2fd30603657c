"""Time integration of the turbine's equations (structure, aerodynamic loads, generator) and the output channels of
:mod:`.outputs`.

Outputs are written every ``dt_output`` seconds exactly (``k dt_output <= duration``), taken from the integrator's
continuous extension: the adaptive steps are not forced onto the output times. The run stops with a
:class:`DivergenceError` as soon as the state is not finite or a beam deflects more than its length.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .outputs import CHANNELS, LOAD_COLUMNS, channels, load_row, plot_outputs, table_text, write_table
from .parameters import coordinate_label
from .system import FreeSystem
from .watch import Interrupted, Monitor, SimulationStopped

__all__ = ["ABSOLUTE_TOLERANCE", "CHANNELS", "METHODS", "DivergenceError", "Interrupted", "SimulationResult",
           "SimulationStopped", "UnstableStep", "plot_outputs", "simulate", "table_text", "write_table"]

#: largest |lambda| h for which classical RK4 stays stable on an undamped mode (2 sqrt(2) on the imaginary axis)
RK4_STABILITY = 2.8
#: The absolute tolerance of the command line's and the batch plans' runs as a fraction of their relative tolerance:
#: coordinates and rates (m, rad, m/s, rad/s) below 0.1 are held to 0.1 rtol. At 0.01 (before) the second flap
#: modes' rates, about 0.01 m/s, set the step of the NREL 5MW at rated wind (90 % of the error norm): 29 % more
#: right-hand sides for the same channel errors within a factor of 3 (docs/turbine-aero.md#speed).
ABSOLUTE_TOLERANCE = 0.1
#: integrators: the compiled ones (numba), scipy's, and fixed-step RK4
METHODS = ("auto", "DP853", "DP54", "RK45", "DOP853", "RK4")


class UnstableStep(ValueError):
    """A fixed step beyond the stability limit of the fastest mode; ``option``: the command-line option that sets
    the step."""

    def __init__(self, message: str, option: str = "--step") -> None:
        super().__init__(message)
        self.option = option


class DivergenceError(SimulationStopped):
    """The time integration blew up: ``time`` (s), the coordinate and why (and the rows up to then, ``result``)."""

    def __init__(self, message: str, time: float, coordinate: str, result=None) -> None:
        super().__init__(message, time, result)
        self.coordinate = coordinate


@dataclass(frozen=True)
class SimulationResult:
    """Time histories: time (T,) s, coordinates q and rates u (T, n), output channels (T,) each, the load columns
    (T, len(outputs.LOAD_COLUMNS)) in SI, and the dynamic wake's states (T, B, Na, 4), m/s (None without it:
    :mod:`bladefem.aero.dynamic_wake`); ``integrator``: the method a controlled run chose (empty otherwise)."""

    time: NDArray
    q: NDArray
    u: NDArray
    dofs: tuple[str, ...]
    free: NDArray
    outputs: dict[str, NDArray]
    evaluations: int
    loads: NDArray | None = None
    wake: NDArray | None = None
    integrator: str = ""


def output_times(duration: float, dt_output: float) -> NDArray:
    """``0, dt, 2 dt, ...`` up to ``duration`` (s; a last multiple within 1e-9 dt of it counts)."""
    if not (math.isfinite(duration) and duration > 0 and math.isfinite(dt_output) and dt_output > 0):
        raise ValueError(f"need a positive duration and output step, got {duration} and {dt_output}")
    if dt_output > duration * (1 + 1e-12):
        raise ValueError(f"the output step {dt_output:g} s exceeds the simulated time {duration:g} s")
    return np.arange(int(math.floor(duration / dt_output + 1e-9)) + 1) * dt_output


def divergence_limits(system: FreeSystem) -> NDArray:
    """Largest credible magnitude of each free state: a beam's modal amplitude whose tip deflection would exceed
    the beam's length, a drivetrain twist of 1 rad; rates and rigid rotations unbounded."""
    model = system.model
    p = model.params
    limit = np.full(model.n, np.inf)
    tower = np.linalg.norm(p.tower.tip_value, axis=1)
    limit[model.tower_columns] = p.tower.length / np.maximum(tower, 1e-12)
    blade = np.linalg.norm(p.blade.tip_value, axis=1)
    limit[model.blade_columns] = p.blade.length / np.maximum(blade, 1e-12)
    limit[model.dofs.index("drivetrain")] = 1.0
    return np.concatenate([limit[system.index], np.full(system.size + system.wake_size, np.inf)])


def diverged(system: FreeSystem, state: int, time: float, status: int, method: str) -> DivergenceError:
    """The error for a blown-up state (index into the free state) at ``time``."""
    position = state % system.size
    dof = system.model.dofs[system.index[position]]
    what = "is not finite" if status == 1 else "exceeds its physical limit (a deflection larger than the beam)"
    hint = " (reduce --step)" if method == "RK4" else " (tighten --rtol)"
    kind = "rate" if state >= system.size else "coordinate"
    return DivergenceError(f"the solution diverged at t = {time:.4g} s: the {kind} of {coordinate_label(dof)} "
                           f"({dof}) {what}{hint}", time, dof)


def auto_method(model) -> str:
    """The integrator 'auto' stands for: compiled Dormand-Prince 8(5,3) for the structure alone, 5(4) with
    aerodynamic loads (the polars' linear interpolation has kinks in alpha, which cost the 8th-order method its
    order: three times the right-hand sides at the same tolerance, measured); scipy's DOP853 without numba."""
    if not hasattr(model.fast_equations(), "integrate"):
        return "DOP853"
    return "DP54" if model.aero is not None else "DP853"


def initial_modes(system: FreeSystem) -> tuple[NDArray, NDArray]:
    """Eigenvalues (rad/s) and eigenvectors of the free system's state matrix at its initial state; the forcing's
    central differences from the compiled equations where numba is on (0.12 s of the NREL 5MW's numpy forcing at
    every controlled run's start), each BEM solve from scratch (a solve from the last perturbation's roots agrees
    only to the BEM's tolerance, which the differences would divide by their step)."""
    from .linearize import state_matrix
    q, u = system.full(0.0, system.initial_state())
    compiled = system.model.fast_equations()
    forcing = None
    if hasattr(compiled, "forget_solutions"):
        def forcing(qq: NDArray, uu: NDArray) -> NDArray:
            compiled.forget_solutions()
            return compiled(qq, uu)[1]
    return np.linalg.eig(state_matrix(system, q, u, forcing=forcing))


def rk4_stable_step(system: FreeSystem, modes: tuple[NDArray, NDArray] | None = None) -> tuple[float, str]:
    """Largest stable RK4 step (s) for the free system linearized at its initial state (``modes``: its
    :func:`initial_modes` if computed already), and the coordinate that dominates (by energy share) the mode with
    the largest |eigenvalue|, which sets it."""
    from .mode_names import participation
    model, ix = system.model, system.index
    q, u = system.full(0.0, system.initial_state())
    values, vectors = initial_modes(system) if modes is None else modes
    fastest = int(np.argmax(np.abs(values)))
    share = participation(vectors[:system.size, fastest], np.diag(model.K)[ix],
                          np.diag(model.equations(q, u)[0])[ix], abs(values[fastest]))
    dof = model.dofs[ix[int(np.argmax(share))]]
    return RK4_STABILITY / abs(values[fastest]), f"{coordinate_label(dof)}, {abs(values[fastest]) / 2 / np.pi:.3g} Hz"


def rk4_step(rhs, t: float, x: NDArray, h: float, hold: NDArray | None = None, first: NDArray | None = None
             ) -> NDArray:
    """One classical RK4 step of ``h`` s from ``(t, x)``; with ``hold`` (the aerodynamic state's flags) its third
    flag is set over the stages after the first, whose right-hand sides then take the induction of the first's BEM
    solve (:mod:`.compiled_loads`); ``first``: the derivative at ``(t, x)`` if evaluated already (with that solve)."""
    k1 = rhs(t, x) if first is None else first
    if hold is not None:
        hold[2] = 1.0
    k2 = rhs(t + h / 2, x + h / 2 * k1)
    k3 = rhs(t + h / 2, x + h / 2 * k2)
    k4 = rhs(t + h, x + h * k3)
    if hold is not None:
        hold[2] = 0.0
    return x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def runge_kutta4(rhs, states: list[NDArray], times: NDArray, step: float,
                 check: Callable[[float, NDArray], None]) -> None:
    """Classical fixed-step 4th-order Runge-Kutta (ElastoDyn's Method = 1) with steps no larger than ``step`` (s)
    landing on every output time; the state at each output time appended to ``states`` (which holds the initial
    one), so that an interrupted run keeps the rows done; ``check(t, x)`` after each output step."""
    x, t = states[-1], times[0]
    for target in times[1:]:
        count = max(1, int(np.ceil((target - t) / step - 1e-9)))
        h = (target - t) / count
        for _ in range(count):
            x = rk4_step(rhs, t, x, h)
            t += h
        t = target
        states.append(x)
        check(t, x)


def scipy_steps(method: str, rhs, states: list[NDArray], times: NDArray, rtol: float, atol: float,
                check: Callable[[float, NDArray], None]) -> None:
    """scipy's ``method`` (RK45, DOP853) stepped as ``solve_ivp`` steps it, each output time taken from the step's
    dense output as it passes, appended to ``states`` (so that an interrupted run keeps the rows done)."""
    from scipy import integrate

    solver = getattr(integrate, method)(rhs, times[0], states[-1], times[-1], rtol=rtol, atol=atol)
    k = len(states)
    while k < len(times):
        solver.step()
        if solver.status == "failed":
            raise RuntimeError(f"time integration failed at t = {solver.t:.4g} s")
        dense = solver.dense_output()
        while k < len(times) and (times[k] <= solver.t or solver.status == "finished"):
            states.append(dense(times[k]))
            check(times[k], states[-1])
            k += 1


def simulate(system: FreeSystem, duration: float, dt_output: float = 0.05, rtol: float = 1e-6,
             atol: float = 1e-8, method: str = "auto", step: float = 0.01,
             progress: Callable[[float], None] | None = None) -> SimulationResult:
    """Integrate from t = 0 to ``duration`` (s), outputs every ``dt_output`` s.

    method : 'auto' (:func:`auto_method`: the compiled Dormand-Prince 'DP853', or 'DP54' with aerodynamics, when
        numba is installed, else scipy's 'DOP853'), 'DP853' or 'DP54' (compiled Dormand-Prince 8(5,3) or 5(4),
        numba only), a scipy ``solve_ivp`` method ('RK45', 'DOP853', ...; tolerances ``rtol``, ``atol``), or 'RK4'
        with the fixed ``step`` (s; refused with :class:`UnstableStep` beyond the stability limit of the fastest mode)
    progress : called with the simulated time as the run advances (compiled integrators and RK4)

    A run that leaves a physical bound (:mod:`.watch`), diverges, or is interrupted with Ctrl-C (every
    integrator) raises :class:`SimulationStopped` (:class:`DivergenceError`, :class:`Interrupted`) carrying the
    rows computed up to then (``result``).
    """
    times = output_times(duration, dt_output)
    compiled = system.model.fast_equations()
    if hasattr(compiled, "forget_solutions"):
        compiled.forget_solutions()
    if method == "auto":
        method = auto_method(system.model)
    limit = divergence_limits(system)
    count = [0]

    def rhs(t: float, x: NDArray) -> NDArray:
        count[0] += 1
        return system(t, x)

    def check(t: float, x: NDArray) -> None:
        bad = np.flatnonzero(~np.isfinite(x) | (np.abs(x) > limit))
        if bad.size:
            raise diverged(system, int(bad[0]), t, 1 if not np.isfinite(x[bad[0]]) else 2, method)
        if progress is not None:
            progress(t)

    if method in ("DP54", "DP853"):
        if not hasattr(compiled, "integrate"):
            raise RuntimeError(f"method '{method}' needs numba (pip install numba)")
        return compiled_run(system, compiled, times, rtol, atol, 8 if method == "DP853" else 5, limit, progress)
    if method == "RK4":
        stable, dof = rk4_stable_step(system)
        if step > stable:
            raise UnstableStep(f"RK4 with a step of {step:g} s is unstable for the fastest mode ({dof}): the step must "
                             f"be below {stable:.3g} s")
    done = [system.initial_state()]
    try:
        if method == "RK4":
            runge_kutta4(rhs, done, times, step, check)
        else:
            scipy_steps(method, rhs, done, times, rtol, atol, check)
    except KeyboardInterrupt:
        rows = len(done)
        partial = np.array(done)
        loads = row_loads(system, times[:rows], partial)
        raise Interrupted(f"interrupted (Ctrl-C) at t = {times[rows - 1]:.4g} s", float(times[rows - 1]),
                          result_of(system, times[:rows], partial, loads, count[0])) from None
    states = np.array(done)
    loads = row_loads(system, times, states)
    result = result_of(system, times, states, loads, count[0])
    reason = Monitor(system.model, LOAD_COLUMNS, generator_free(system)).rows(times, result.u, loads)
    if reason:
        rows = int(np.searchsorted(times, reason[1], "right"))
        raise SimulationStopped(reason[0], reason[1], result_of(system, times[:rows], states[:rows], loads[:rows],
                                                                count[0]))
    return result


def row_loads(system: FreeSystem, times: NDArray, states: NDArray) -> NDArray:
    """The load columns at every output row of the free states: the compiled output rows in one call where numba
    is there (:meth:`.compiled.CompiledEquations.outputs`, the twin of :func:`.outputs.load_row`), else numpy's."""
    compiled = system.model.fast_equations()
    if hasattr(compiled, "outputs") and len(times):
        return compiled.outputs(times, states, system.q0, system.u0, system.index)
    rows = []
    for t, x in zip(times, states):
        q, u = system.full(t, x)
        wake = system.wake(x)
        rows.append(load_row(system.model, q, u, system.accelerations(q, u, t, wake), t=t, wake=wake))
    return np.array(rows)


def generator_free(system: FreeSystem) -> bool:
    """Whether the generator turns freely (not held at its speed)."""
    return bool(system.free[system.model.dofs.index("generator_azimuth")])


def result_of(system: FreeSystem, times: NDArray, states: NDArray, loads: NDArray, evaluations: int
              ) -> SimulationResult:
    """The :class:`SimulationResult` of the free states (T, 2 size) and load columns at ``times``."""
    full = [system.full(t, x) for t, x in zip(times, states)]
    q = np.array([a for a, _ in full]).reshape(len(times), system.model.n)
    u = np.array([b for _, b in full]).reshape(len(times), system.model.n)
    wake = None
    if system.wake_size:
        wake = np.asarray(states)[:, 2 * system.size:].reshape(len(times), system.model.params.n_blades, -1, 4)
    return SimulationResult(time=times, q=q, u=u, dofs=system.model.dofs, free=system.free,
                            outputs=channels(system.model, q, u, loads), evaluations=evaluations, loads=loads,
                            wake=wake)


def compiled_run(system: FreeSystem, compiled, times: NDArray, rtol: float, atol: float, order: int,
                 limit: NDArray, progress: Callable[[float], None] | None) -> SimulationResult:
    """The compiled Dormand-Prince run, watched between kernel calls (:class:`.watch.Monitor`: physical bounds of
    the new rows, step count) and stopped with the rows computed so far on a bound, a divergence or Ctrl-C."""
    monitor = Monitor(system.model, LOAD_COLUMNS, generator_free(system))

    def watch(start: float, end: float, row_times: NDArray, states: NDArray, loads: NDArray, count: int):
        if progress is not None:
            progress(end)
        u = np.tile(system.u0, (len(row_times), 1))
        u[:, system.index] = states[:, system.size:2 * system.size]
        return monitor.rows(row_times, u, loads) or monitor.steps(count, start, end)

    run = compiled.integrate(times, system.initial_state(), rtol, atol, system.q0, system.u0, system.index,
                             order=order, limit=limit, watch=watch)
    rows = run.rows if run.status != 4 else min(run.rows, int(np.searchsorted(times, run.reason[1], "right")))
    result = result_of(system, times[:rows], run.states[:rows], run.loads[:rows], run.evaluations)
    if run.status in (1, 2, 3):
        error = diverged(system, run.offending, run.time, run.status, "DP54" if order == 5 else "DP853")
        error.result = result
        raise error
    if run.status == 4:
        raise SimulationStopped(run.reason[0], run.reason[1], result)
    if run.status == 5:
        raise Interrupted(f"interrupted (Ctrl-C) at t = {run.time:.4g} s", run.time, result)
    return result
