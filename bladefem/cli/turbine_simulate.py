"""``bladefem turbine DECK --simulate``: the run with its progress bar, the table written whole (or the rows up to
an early stop, with the reason), and the figure titled with its case."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from ..errors import InputError


def controller_of(deck, args: argparse.Namespace):
    """The :class:`~bladefem.models.turbine.discon.ControllerSetup` of a deck whose ServoDyn runs a Bladed-style
    DLL (PCMode and VSContrl 5) in a simulation not held at --rpm; None otherwise."""
    from .turbine import runs_controller

    servo = getattr(deck, "servodyn", None)
    if servo is None or servo.dll is None or not runs_controller(args):
        for name, value in (("--discon-library", args.discon_library), ("--controller-dt", args.controller_dt)):
            if value is not None:
                raise InputError("the deck runs no Bladed-style DLL here (ServoDyn PCMode and VSContrl 5, without "
                                 "--rpm)", field=name)
        return None
    from ..builders.controller import controller_setup
    return controller_setup(deck, args.discon_library, args.controller_dt)


def simulate_command(model, free, q0: np.ndarray, u0: np.ndarray, args: argparse.Namespace,
                     controller=None) -> int:
    from ..files import write_atomic
    from ..models.turbine import FreeSystem
    from ..models.turbine.simulate import (
        ABSOLUTE_TOLERANCE,
        SimulationStopped,
        UnstableStep,
        output_times,
        plot_outputs,
        simulate,
        table_text,
    )

    method = args.method or "auto"
    if args.step is not None and method != "RK4":
        raise InputError("--step sets the step of --method RK4 (the other methods choose theirs): add --method RK4 "
                         "or leave --step out", field="--step")
    if method == "ABM4" and controller is None:
        raise InputError("ABM4 steps once per controller interval: it needs the controller library (ServoDyn "
                         "PCMode and VSContrl 5); use auto, DP54 or RK4", field="--method")
    if not hasattr(model.fast_equations(), "integrate"):
        print("# numba is switched off (BLADEFEM_NO_NUMBA) or not installed: the numpy equations, about 100 times "
              "slower", file=sys.stderr)
    if method in ("DP54", "DP853") and not hasattr(model.fast_equations(), "integrate"):
        raise InputError(f"{method} needs numba (pip install numba); use auto, RK45, DOP853 or RK4",
                         field="--method")
    rtol = 1e-6 if args.rtol is None else args.rtol
    atol = rtol * ABSOLUTE_TOLERANCE
    dt = 0.05 if args.dt is None else args.dt
    try:
        output_times(args.simulate, dt)
    except ValueError as error:
        raise InputError(str(error), field="--dt") from None
    try:
        with SimulationProgress(args.simulate, args.quiet) as progress:
            if controller is not None:
                result = controlled_run(FreeSystem(model, free, q0, u0), controller, args, dt, rtol, atol,
                                        progress)
            else:
                result = simulate(FreeSystem(model, free, q0, u0), args.simulate, dt_output=dt, rtol=rtol,
                                  atol=atol, method=method, step=0.01 if args.step is None else args.step,
                                  progress=progress)
    except UnstableStep as error:
        raise InputError(str(error), field=error.option) from None
    except SimulationStopped as stop:
        return stopped(stop, args)
    text = table_text(result)
    if args.output:
        write_atomic(args.output, text)
        print(f"# {len(result.time)} rows written to {Path(args.output)}; {result.evaluations} right-hand sides"
              + (f" ({result.integrator} between controller calls)" if result.integrator else ""), file=sys.stderr)
    else:
        sys.stdout.write(text)
    if args.plot:
        plot_outputs(result, args.plot, title=simulation_title(model, args))
    return 0


def controlled_run(system, setup, args: argparse.Namespace, dt: float, rtol: float, atol: float, progress):
    """The simulation with the deck's controller library (:mod:`bladefem.models.turbine.controlled`)."""
    from ..models.turbine.controlled import simulate_controlled
    from ..models.turbine.discon import DisconController

    if args.method not in (None, "auto", "DP54", "RK4", "ABM4"):
        raise InputError("a run with the controller library integrates with DP54, RK4 or ABM4 between controller "
                         "calls", field="--method")
    if not hasattr(system.model.fast_equations(), "integrate"):
        raise InputError("a run with the controller library needs numba (unset BLADEFEM_NO_NUMBA); or hold the "
                         "rotor with --rpm", field="--simulate")
    model = system.model
    inflow = model.aero.inflow if model.aero is not None else None
    hub_wind = 0.0 if inflow is None else inflow.speed * (
        setup.hub_height / inflow.reference_height) ** inflow.shear_exponent
    efficiency = model.generator.efficiency if model.generator is not None else 1.0
    print(f"# controller: {setup.library} with {setup.infile}, called every {setup.time_step:g} s "
          f"({setup.time_step_from}{'' if args.controller_dt else '; --controller-dt sets it'})", file=sys.stderr)
    with DisconController(setup, Path(args.main).stem) as controller:
        return simulate_controlled(system, controller, args.simulate, dt_output=dt, rtol=rtol, atol=atol,
                                   hub_wind=hub_wind, efficiency=efficiency, progress=progress,
                                   method=args.method if args.method in ("RK4", "DP54", "ABM4") else
                                   "DP54" if args.rtol is not None else "auto",
                                   rk4_step=0.01 if args.step is None else args.step)


def simulation_title(model, args: argparse.Namespace) -> str:
    """What a simulation's figure shows: the deck, the simulated time, the wind and how the rotor turns."""
    parts = [f"{Path(args.main).name}: {args.simulate:g} s simulated"]
    if model.aero is not None:
        parts.append(f"wind {model.aero.inflow.speed:g} m/s")
    else:
        parts.append("no aerodynamics")
    if args.rpm is not None:
        parts.append(f"rotor held at {args.rpm:g} rpm")
    return ", ".join(parts)


def stopped(stop, args: argparse.Namespace) -> int:
    """A run ended early (a physical bound, divergence, Ctrl-C): the rows computed up to then written whole (to
    --output, else stdout), one line on stderr saying why and where the rows went; exit 1 (130 for Ctrl-C)."""
    from ..files import write_atomic
    from ..models.turbine.simulate import table_text

    result = stop.result
    where = ""
    if result is not None and len(result.time):
        text = table_text(result)
        if args.output:
            write_atomic(args.output, text)
            where = f"; {len(result.time)} rows up to t = {result.time[-1]:g} s written to {Path(args.output)}"
        else:
            sys.stdout.write(text)
            where = f"; {len(result.time)} rows up to t = {result.time[-1]:g} s written"
    print(f"bladefem: {'' if stop.exit_code == 130 else 'error: '}{stop}{where}", file=sys.stderr)
    return stop.exit_code


class SimulationProgress:
    """A progress bar over simulated time on stderr (rich), or nothing when ``quiet`` or stderr is no terminal."""

    def __init__(self, duration: float, quiet: bool) -> None:
        self.duration, self.quiet = duration, quiet or not sys.stderr.isatty()
        self.bar = None

    def __enter__(self):
        if self.quiet:
            return None
        from rich.console import Console
        from rich.progress import Progress
        self.bar = Progress(console=Console(stderr=True), transient=True)
        self.bar.start()
        task = self.bar.add_task("Simulating", total=self.duration)
        return lambda t: self.bar.update(task, completed=t)

    def __exit__(self, *exc) -> None:
        if self.bar is not None:
            self.bar.stop()
