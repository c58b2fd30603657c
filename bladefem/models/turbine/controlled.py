"""A simulation with a Bladed-style controller library (ServoDyn ``PCMode`` 5, ``VSContrl`` 5): the controller is
called every ``DLL_DT`` seconds with the turbine's state and its pitch and torque demands are held until the next
call (zero-order hold: ServoDyn with ``DLL_Ramp`` False), the equations integrated in between.

Each interval ``[t_k, t_k + DLL_DT]`` is one call of the compiled adaptive integrator (Dormand-Prince 5(4)) with
the pitch set on the kernels' arrays (:mod:`.pitching`) and the generator torque held (the torque-law vector of
:func:`.control.law_torque` with a rated speed of zero: the demanded torque at every positive speed). The output rows
that fall inside the interval are taken from the integrator's dense output, with the pitch held over it; a row at
a call's time is taken after the call, with its new demands (a zero-order hold's value at its switching time; the
run's last row has one more call at the end). Needs numba (the numpy equations would take hours for a controlled
run).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ...errors import InputError
from .discon import ControllerError, DisconController, Measurements
from .outputs import LOAD_COLUMNS
from .pitching import CompiledPitch
from .compiled_control import ABM4_HISTORY
from .interval_steps import abm4_grows_none, abm4_interval, abm4_stable, rk4_interval
from .simulate import (
    SimulationResult,
    UnstableStep,
    diverged,
    divergence_limits,
    generator_free,
    initial_modes,
    output_times,
    result_of,
    rk4_stable_step,
)
from .system import FreeSystem
from .watch import Interrupted, Monitor, SimulationStopped

#: largest spread of the blades' pitch demands (rad) taken as collective; beyond, individual pitch is refused
COLLECTIVE_TOLERANCE = 1e-6


class Controlled:
    """The state of a controlled run: kernels, pitch setter, held torque, and what the controller is sent."""

    def __init__(self, system: FreeSystem, hub_wind: float, efficiency: float) -> None:
        self.system, self.model = system, system.model
        self.compiled = self.model.fast_equations()
        if not hasattr(self.compiled, "integrate"):
            raise RuntimeError("a controlled simulation needs numba (pip install numba; unset BLADEFEM_NO_NUMBA)")
        self.compiled.forget_solutions()
        self.pitcher = CompiledPitch(self.model, self.compiled)
        self.law = self.compiled.law
        self.law[:] = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
        self.hub_wind, self.efficiency = hub_wind, efficiency
        self.generator = self.model.dofs.index("generator_azimuth")
        self.ratio = self.model.params.gearbox_ratio
        self.last_call = 0.0

    @property
    def torque(self) -> float:
        return float(self.law[2])

    def measure(self, t: float, x: NDArray, loads: NDArray | None = None, rate: NDArray | None = None,
                individual: bool = False) -> Measurements:
        """What ServoDyn sends the controller at state ``x``: speeds, pitch, wind, blade-root moments, shaft power,
        tower-top accelerations and the nacelle's tilting ones (from the equations' accelerations at x: the tower's
        modal accelerations times its tip shapes and slopes; the shaft tilt is neglected). ``loads`` (blade 1's
        load columns at x) and ``rate`` (dx/dt) are computed unless given (the integrator's own at an interval's
        end). The other blades' root moments only for ``individual`` pitch control; with collective pitch their
        records repeat blade 1's (the controller uses them only for individual pitch)."""
        system, model, compiled = self.system, self.model, self.compiled
        q, u = system.full(t, x)
        blades = model.params.n_blades
        if loads is None:
            loads = compiled.outputs(np.array([t]), x[None], system.q0, system.u0, system.index)[0]
        others = [compiled.outputs(np.array([t]), x[None], system.q0, system.u0, system.index, b)[0]
                  for b in range(1, blades)] if individual else [loads] * (blades - 1)
        rows = np.array([loads, *others])
        if rate is None:
            rate = compiled.derivative(t, x, system.q0, system.u0, system.index)
        du = np.zeros(model.n)
        du[system.index] = rate[system.size:2 * system.size]
        top = du[model.tower_columns] @ model.params.tower.tip_value
        turn = du[model.tower_columns] @ model.params.tower.tip_slope       # about y (fore-aft), x (side-side)
        rotor_speed = u[5] + u[6]
        generator_speed = self.ratio * u[self.generator]
        pitch = np.full(blades, self.pitcher.pitch)
        return Measurements(
            pitch=pitch, rotor_speed=rotor_speed, generator_speed=generator_speed, wind_speed=self.hub_wind,
            azimuth=(q[5] + q[6]) % (2 * math.pi), shaft_power=rows[0, 3] * rotor_speed,
            generator_torque=self.torque, electrical_power=self.torque * generator_speed * self.efficiency,
            root_oop=rows[:, 0], root_ip=rows[:, 1], tower_top_fa=float(top[0]), tower_top_ss=float(top[1]),
            nacelle_roll=-float(turn[1]), nacelle_nod=float(turn[0]), yaw=float(q[4]))

    def apply(self, t: float, pitch: NDArray, torque: float) -> None:
        """Hold the controller's demands: collective pitch (refused when the blades' demands differ), torque."""
        if np.ptp(pitch) > COLLECTIVE_TOLERANCE:
            raise ControllerError(f"the controller demands individual pitch (blades at "
                                  f"{', '.join(f'{math.degrees(p):.4g}' for p in pitch)} deg at t = {t:.4g} s), "
                                  "which is not modelled: switch its individual pitch control off", t)
        if not np.all(np.isfinite(pitch)) or not math.isfinite(torque):
            raise ControllerError(f"the controller returned a non-finite demand at t = {t:.4g} s", t)
        self.pitcher.set(float(pitch[0]))
        self.law[2] = torque


#: the share of RK4's stability limit (at the initial state) that "auto" allows one step per controller interval:
#: a margin for the operating point's changes of the fastest mode
RK4_MARGIN = 0.5


def simulate_controlled(system: FreeSystem, controller: DisconController, duration: float,
                        dt_output: float = 0.05, rtol: float = 1e-6, atol: float = 1e-8, hub_wind: float = 0.0,
                        efficiency: float = 1.0, progress: Callable[[float], None] | None = None,
                        method: str = "DP54", rk4_step: float = 0.01) -> SimulationResult:
    """Integrate from 0 to ``duration`` (s) with the controller called every ``controller.setup.time_step``
    seconds (zero-order hold between calls); outputs every ``dt_output`` s. ``hub_wind``: the horizontal wind speed
    at the hub sent to the controller, m/s; ``efficiency``: ServoDyn's GenEff (the electrical power sent back);
    ``method``: "DP54" (adaptive), "RK4" (fixed steps no longer than ``rk4_step`` s, through a start-up transient
    whose loads jump; refused with :class:`UnstableStep` beyond the fastest mode's limit), "ABM4" (one
    Adams-Bashforth-Moulton step per controller interval, ElastoDyn's default; refused where a decaying mode would
    grow, :func:`.interval_steps.abm4_stable`) or "auto" (ABM4 where it is stable with a margin, else one RK4 step
    per interval where the interval is within ``RK4_MARGIN`` of RK4's limit, else DP54).
    Stops with :class:`SimulationStopped` (and the rows so far) on a physical bound, a divergence, a controller
    failure or Ctrl-C; a controller that fails on its first call (its library or input file) is an
    :class:`InputError`."""
    run = Controlled(system, hub_wind, efficiency)
    compiled, step = run.compiled, controller.setup.time_step
    if method in ("auto", "RK4", "ABM4"):
        modes = initial_modes(system)
        stable, dof = rk4_stable_step(system, modes)
        if method == "auto":
            method, rk4_step = ("ABM4", step) if abm4_stable(modes[0], step) else (
                ("RK4", step) if step <= RK4_MARGIN * stable else ("DP54", rk4_step))
        if method == "ABM4":
            if not abm4_grows_none(step, modes[0]):
                raise UnstableStep(f"ABM4 with the controller's interval of {step:g} s as its step lets a damped mode "
                                   "grow: use --method RK4 or DP54, or a shorter --controller-dt", "--method")
            rk4_step = step                            # its first three intervals: one RK4 step each
        if method == "RK4" and rk4_step > stable:
            raise UnstableStep(f"RK4 with a step of {rk4_step:g} s is unstable for the fastest mode ({dof}): the "
                               f"step must be below {stable:.3g} s")
    times = output_times(duration, dt_output)
    limit = divergence_limits(system)
    monitor = Monitor(system.model, LOAD_COLUMNS, generator_free(system))
    calls = int(math.floor(duration / step + 1e-9))
    boundaries = np.append(np.arange(calls + 1) * step, duration) if calls * step < duration * (1 - 1e-12) else (
        np.arange(calls + 1) * step)
    if controller.library is not None and not controller.setup.individual:
        try:
            return replace(compiled_loop(run, controller, times, boundaries, rtol, atol, limit, monitor, progress,
                                         rk4_step if method in ("RK4", "ABM4") else 0.0, method == "ABM4"),
                           integrator=method)
        finally:
            controller.close(run.last_call)
    x = system.initial_state()
    states, loads, pitch = [x], [], []
    end_loads = end_rate = None
    history, known = np.zeros((ABM4_HISTORY, len(x))), 0
    evaluations, row = 0, 0
    t = 0.0

    def steps(start: float, end: float, row_times, rows, row_loads, count: int):
        return monitor.steps(count, start, end)          # the step-count bound, between kernel calls

    def stop(error: SimulationStopped) -> SimulationStopped:
        error.result = finish(run, system, times[:len(states)], states, loads, pitch, evaluations)
        return error

    def boundary_row(t: float, k: int) -> None:
        """The controller's call at the boundary t, and the output row there after it (a zero-order hold's value
        at its switching time is the new one)."""
        nonlocal row
        measured = run.measure(t, x, end_loads, end_rate, controller.setup.individual)
        commands = controller.call(t, measured)
        run.apply(t, commands.pitch, commands.torque)
        if row < len(times) and times[row] <= t + 1e-9 * step:
            if k:
                states.append(x)
            loads.append(compiled.outputs(times[row:row + 1], x[None], system.q0, system.u0, system.index)[0])
            pitch.append(run.pitcher.pitch)
            watch(row, row + 1)
            row += 1

    def watch(first: int, last: int) -> None:
        u = np.tile(system.u0, (last - first, 1))
        u[:, system.index] = np.asarray(states[first:last])[:, system.size:2 * system.size]
        reason = monitor.rows(times[first:last], u, np.asarray(loads[first:last]))
        if reason:
            raise stop(SimulationStopped(*reason))

    try:
        for k in range(len(boundaries) - 1):
            t, end = float(boundaries[k]), float(boundaries[k + 1])
            boundary_row(t, k)
            last = row
            while last < len(times) and times[last] < end - 1e-9 * step:
                last += 1
            inner = times[row:last]
            chunk = np.concatenate([[t], inner[inner < end - 1e-9 * step], [end]])
            measured = None
            if method == "ABM4":
                first = compiled.rate(t, x, system.q0, system.u0, system.index)
                if known >= ABM4_HISTORY and len(chunk) == 2 and abs(end - t - step) <= 1e-9 * step:
                    out, measured = abm4_interval(system, compiled, t, end, x, first, history, limit)
                else:
                    out = rk4_interval(system, compiled, chunk, x, rk4_step, limit, last - row, first)
                history, known = np.concatenate([first[None], history[:-1]]), known + 1
                evaluations += 1
            elif method == "RK4":
                out = rk4_interval(system, compiled, chunk, x, rk4_step, limit, last - row)
            else:
                out = compiled.integrate(chunk, x, rtol, atol, system.q0, system.u0, system.index, order=5,
                                         limit=limit, first_step=end - t, watch=steps)
            evaluations += out.evaluations + (method != "DP54" and measured is None)  # RK4: the end measured afresh
            if out.status == 4:
                raise stop(SimulationStopped(*out.reason))
            if out.status:
                rows = min(out.rows, len(chunk)) - 1
                states.extend(out.states[1:rows][:last - row])
                loads.extend(out.loads[1:rows][:last - row])
                pitch.extend([run.pitcher.pitch] * (len(states) - len(pitch)))
                raise stop(diverged(system, out.offending, out.time, out.status, method))
            x, end_loads, end_rate = out.states[-1], out.loads[len(chunk) - 1], out.rate
            if measured is not None:                          # ABM4: at the predicted end
                end_loads = measured
            elif not np.all(np.isfinite(end_loads)):          # RK4 between output rows: measured afresh
                end_loads = None
            taken = out.states[1:1 + (last - row)]
            states.extend(taken)
            loads.extend(out.loads[1:1 + (last - row)])
            pitch.extend([run.pitcher.pitch] * len(taken))
            if len(taken):
                watch(row, last)
            row = last
            if progress is not None:
                progress(end)
        t = float(boundaries[-1])
        if row < len(times):
            boundary_row(t, len(boundaries) - 1)                 # the last row's commands
            evaluations += 1
    except ControllerError as error:
        if len(loads) == 0:                          # the first call: the library or its input file is bad
            raise InputError(str(error), file=controller.setup.infile, field="DLL_InFile") from None
        raise stop(SimulationStopped(str(error), error.time)) from None
    except KeyboardInterrupt:
        raise stop(Interrupted(f"interrupted (Ctrl-C) at t = {t:.4g} s", t)) from None
    finally:
        controller.close(t)
    return replace(finish(run, system, times, states, loads, pitch, evaluations), integrator=method)


def compiled_loop(run: Controlled, controller: DisconController, times: NDArray, boundaries: NDArray, rtol: float,
                  atol: float, limit: NDArray, monitor: Monitor, progress: Callable[[float], None] | None,
                  rk4_step: float = 0.0, multistep: bool = False) -> SimulationResult:
    """The loop of :func:`simulate_controlled` compiled (:mod:`.compiled_control`: the library called from the
    kernel) for a library loaded in this process and collective pitch (DP54, or RK4 with steps up to ``rk4_step``
    s where it is positive, or with ``multistep`` ABM4 after RK4's first three intervals); its first call made here
    (a library or
    input file that fails there is an :class:`InputError`). Between kernel calls (about ``BUDGET`` right-hand
    sides) the new rows are watched, progress told and Ctrl-C looked for."""
    from .compiled import _dp54_tableau
    from .compiled_control import FAILED, OVERRIDE, controlled_chunk
    from .compiled_outputs import MEASURED
    from .watch import BUDGET, interruptible
    system, compiled, model = run.system, run.compiled, run.model
    x = system.initial_state().astype(float)
    try:
        commands = controller.call(0.0, run.measure(0.0, x))
        run.apply(0.0, commands.pitch, commands.torque)
    except ControllerError as error:
        raise InputError(str(error), file=controller.setup.infile, field="DLL_InFile") from None
    run.last_call = 0.0
    states = np.full((len(times), len(x)), np.nan)
    states[0] = x
    first = compiled.outputs(times[:1], x[None], system.q0, system.u0, system.index)
    loads = np.full((len(times), first.shape[1]), np.nan)
    loads[0] = first[0]
    held = np.full(len(times), run.pitcher.pitch)
    rate, row, held_commands = np.zeros(len(x)), np.zeros(MEASURED), np.array([run.pitcher.pitch, run.torque])
    function, buffers = controller.library.raw()
    constant = controller.constant_records()
    p = model.params
    constants = (np.array(list(constant), dtype=np.int64), np.array(list(constant.values()), dtype=np.float32),
                 np.ascontiguousarray(p.tower.tip_value, dtype=float), np.ascontiguousarray(p.tower.tip_slope,
                                                                                            dtype=float),
                 np.asarray(model.tower_columns, dtype=np.int64))
    turbine = np.array([run.generator, run.ratio, run.efficiency, run.hub_wind, p.n_blades], dtype=float)
    pitcher = run.pitcher
    pitching = (float(pitcher.base), pitcher.references)
    K, tableau = np.zeros((7, len(x))), _dp54_tableau()
    index, q0, u0 = (np.ascontiguousarray(a) for a in (system.index, system.q0, system.u0))
    k, t, rows, evaluations, call_first = 0, 0.0, 1, 0, False
    history, known = np.zeros((ABM4_HISTORY, len(x))), np.array([0 if multistep else -1], dtype=np.int64)

    def result(count: int) -> SimulationResult:
        return finish(run, system, times[:count], states[:count], loads[:count], held[:count], evaluations)

    with interruptible() as interrupted:
        while k < len(boundaries) - 1:
            start, before = t, rows
            args = (k, boundaries, x, rate, row, held_commands, call_first, times, states, loads, held, rows, BUDGET,
                    float(rtol), float(atol), float(rk4_step), limit, tableau, K, q0, u0, index, compiled.loaded,
                    compiled.all_work, float(compiled.hub_radius), pitching, function, controller.records, buffers,
                    turbine, constants, history, known)
            k, t, rows, count, status, bad = compiled.joined("controlled loop", "controlled simulation kernels",
                                                             controlled_chunk, args, with_rate=True)
            call_first, evaluations = True, evaluations + count
            pitcher.pitch = float(held_commands[0])
            controller.pitch_command[:] = held_commands[0]
            run.last_call = float(t) if status or k == len(boundaries) - 1 else float(boundaries[max(k - 1, 0)])
            if status in (1, 2, 3):
                error = diverged(system, int(bad), t, status, "ABM4" if multistep else "RK4" if rk4_step > 0 else "DP54")
                error.result = result(rows)
                raise error
            if status:
                name = f"{Path(controller.setup.library).name} with {controller.setup.infile}"
                text = (f"the controller ({name}) failed at t = {t:.4g} s: "
                        f"{buffers[3].tobytes().split(bytes(1), 1)[0].decode(errors='replace').strip() or 'no message'}"
                        if status == FAILED else "the controller asks for a built-in pitch or torque override "
                        "(records 55, 56), which ServoDyn refuses too" if status == OVERRIDE else
                        f"the controller returned a non-finite demand at t = {t:.4g} s")
                raise SimulationStopped(text, float(t), result(rows))
            u = np.tile(system.u0, (rows - before, 1))
            u[:, system.index] = states[before:rows, system.size:2 * system.size]
            reason = monitor.rows(times[before:rows], u, loads[before:rows]) or monitor.steps(count, start, t)
            if reason:
                raise SimulationStopped(reason[0], reason[1], result(int(np.searchsorted(times[:rows], reason[1],
                                                                                          "right"))))
            if progress is not None:
                progress(float(t))
            if interrupted():
                raise Interrupted(f"interrupted (Ctrl-C) at t = {t:.4g} s", float(t), result(rows))
    return result(rows)


def finish(run: Controlled, system: FreeSystem, times: NDArray, states: list, loads: list, pitch: list,
           evaluations: int) -> SimulationResult:
    """The result of the rows done, with the pitch of each row and the tip deflections at that pitch."""
    count = min(len(times), len(states), len(loads), len(pitch))
    result = result_of(system, times[:count], np.asarray(states[:count]), np.asarray(loads[:count]), evaluations)
    angles = np.asarray(pitch[:count], dtype=float)
    model = system.model
    blade = result.q[:, model.blade_columns[0]]
    tip = np.array([blade[i] @ run.pitcher.tip_values(angles[i]) for i in range(count)]).reshape(count, 2)
    result.outputs["BldPitch1"] = np.degrees(angles)
    result.outputs["OoPDefl1"] = tip[:, 1]
    result.outputs["IPDefl1"] = -tip[:, 0]
    return result
