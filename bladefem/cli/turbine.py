"""``bladefem turbine``: the 16-DOF Kane turbine model of an ElastoDyn main file.

    bladefem turbine MAIN --linearize [--rpm R] [--dof ...]            table of full-system modes
    bladefem turbine MAIN --campbell 0:15:1.5 [--plot campbell.png]     full-system Campbell diagram
    bladefem turbine MAIN --simulate SECONDS [--dof ...] [--initial NAME=VALUE ...] [--output out.csv]
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import InputError

if TYPE_CHECKING:
    import numpy as np

#: initial-condition names given in degrees, converted to rad
DEGREE_NAMES = {"yaw_deg": "yaw", "azimuth_deg": "generator_azimuth", "drivetrain_deg": "drivetrain"}


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "turbine", help="16-DOF Kane turbine model (ElastoDyn structure) fed by bladefem modes",
        description="Linearize or simulate the 16-DOF structural turbine model (tower FA/SS 1-2, yaw, generator "
                    "azimuth, drivetrain, blade flap 1, edge 1, flap 2) of an ElastoDyn main file; no "
                    "aerodynamics.")
    parser.add_argument("main", metavar="ELASTODYN_MAIN", help="ElastoDyn main input file")
    action = parser.add_mutually_exclusive_group(required=True)
    action.add_argument("--linearize", action="store_true", help="print the full-system modes at --rpm")
    action.add_argument("--campbell", metavar="START:STOP:STEP", help="full-system Campbell diagram over rpm")
    action.add_argument("--simulate", type=float, metavar="SECONDS", help="integrate in time for SECONDS")
    parser.add_argument("--rpm", type=float, default=None,
                        help="rotor speed, rpm (default: RotSpeed of the main file); also the speed of the FE "
                             "blade shapes")
    parser.add_argument("--dof", nargs="+", default=["all"], metavar="NAME",
                        help="free DOFs: all, tower, tower1, yaw, generator, drivetrain, blades, flap1, edge1, "
                             "flap2, or coordinates such as tower_fa1, blade2_edge1 (default: all); the others "
                             "are locked (the generator at constant speed)")
    parser.add_argument("--initial", nargs="+", default=[], metavar="NAME=VALUE",
                        help="initial coordinates: modal amplitudes in m (tower_fa1=0.3, blade1_flap1=1.0), "
                             "yaw_deg, azimuth_deg, drivetrain_deg in degrees")
    parser.add_argument("--shapes", choices=("fe", "fe-polynomial", "polynomial"), default="fe",
                        help="blade mode shapes: bladefem FE at --rpm (default), ElastoDyn polynomials fitted to "
                             "them, or the blade file's polynomials")
    parser.add_argument("--tower-shapes", choices=("fe", "fe-polynomial", "polynomial"), default="polynomial",
                        help="tower mode shapes: the tower file's polynomials (default), bladefem's tower FE with "
                             "the rotor-nacelle on top, or ElastoDyn polynomials fitted to those")
    parser.add_argument("--no-gravity", action="store_true", help="switch gravity off")
    parser.add_argument("--no-damping", action="store_true", help="switch structural, drivetrain, yaw damping off")
    parser.add_argument("--yaw-stiffness", type=float, default=None, metavar="N_M_PER_RAD",
                        help="nacelle-yaw spring (ServoDyn YawSpr; default NREL 5MW 9.02832e9)")
    parser.add_argument("--yaw-damping", type=float, default=None, metavar="N_M_S_PER_RAD",
                        help="nacelle-yaw damper (ServoDyn YawDamp; default NREL 5MW 1.916e7)")
    parser.add_argument("--dt", type=float, default=0.05, help="output interval of --simulate, s")
    parser.add_argument("--rtol", type=float, default=1e-6, help="relative tolerance of the time integration")
    parser.add_argument("--method", choices=("auto", "DP853", "DP54", "RK45", "DOP853", "RK4"), default="auto",
                        help="time integrator: auto (compiled 8th-order Dormand-Prince with numba, else scipy "
                             "DOP853), DP853 or DP54 (compiled, need numba), scipy RK45 or DOP853, or fixed-step "
                             "RK4 (--step)")
    parser.add_argument("--step", type=float, default=0.01, help="step of --method RK4, s")
    parser.add_argument("--output", "-o", metavar="FILE", help="CSV table of --simulate or --campbell")
    parser.add_argument("--plot", metavar="FILE", help="figure of --simulate or --campbell (PNG, PDF, SVG)")
    parser.set_defaults(run=run)


def _positive(value: float | None, field: str) -> None:
    if value is not None and not (math.isfinite(value) and value > 0):
        raise InputError(f"must be a positive number, got {value}", field=field)


def parse_sweep(text: str) -> np.ndarray:
    """'START:STOP:STEP' (rpm, inclusive) -> speeds."""
    try:
        start, stop, step = (float(part) for part in text.split(":"))
    except ValueError:
        raise InputError(f"expected START:STOP:STEP in rpm, got '{text}'", field="--campbell") from None
    if not (all(map(math.isfinite, (start, stop, step))) and step > 0 and stop >= start >= 0):
        raise InputError(f"need 0 <= START <= STOP and STEP > 0, got '{text}'", field="--campbell")
    import numpy as np
    return np.arange(start, stop + 0.5 * step, step)


def initial_state(dofs: tuple[str, ...], entries: list[str]) -> np.ndarray:
    """Coordinates from NAME=VALUE entries (modal amplitudes in m, angles named *_deg in degrees)."""
    import numpy as np
    q = np.zeros(len(dofs))
    for entry in entries:
        name, sep, text = entry.partition("=")
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not sep or not math.isfinite(value):
            raise InputError(f"expected NAME=NUMBER, got '{entry}'", field="--initial")
        if name in DEGREE_NAMES:
            name, value = DEGREE_NAMES[name], math.radians(value)
        elif name in ("yaw", "generator_azimuth", "drivetrain"):
            raise InputError(f"give angles in degrees as {name.split('_')[0]}_deg", field="--initial")
        if name not in dofs:
            raise InputError(f"unknown coordinate '{name}' (one of {', '.join(dofs)}, yaw_deg, azimuth_deg, "
                             f"drivetrain_deg)", field="--initial")
        q[dofs.index(name)] = value
    return q


def build_model(args: argparse.Namespace):
    from ..io.turbine_elastodyn import (
        NREL5MW_YAW_DAMPING,
        NREL5MW_YAW_STIFFNESS,
        turbine_from_elastodyn,
    )
    from ..models.turbine import TurbineModel

    for name in ("yaw_stiffness", "yaw_damping"):
        value = getattr(args, name)
        if value is not None and not (math.isfinite(value) and value >= 0):
            raise InputError(f"must be a non-negative number, got {value}", field="--" + name.replace("_", "-"))
    if args.rpm is not None and not (math.isfinite(args.rpm) and args.rpm >= 0):
        raise InputError(f"must be a non-negative number, got {args.rpm}", field="--rpm")
    params = turbine_from_elastodyn(
        args.main, args.shapes, rpm=args.rpm, tower_shapes=args.tower_shapes,
        yaw_stiffness=NREL5MW_YAW_STIFFNESS if args.yaw_stiffness is None else args.yaw_stiffness,
        yaw_damping=NREL5MW_YAW_DAMPING if args.yaw_damping is None else args.yaw_damping)
    if args.no_gravity:
        params = params.with_(gravity=0.0)
    if args.no_damping:
        params = params.without_damping()
    return params, TurbineModel(params)


def rotor_rpm(args: argparse.Namespace) -> float:
    from ..io.elastodyn_main import read_elastodyn_main
    return read_elastodyn_main(args.main).rotor_speed_rpm if args.rpm is None else args.rpm


def run(args: argparse.Namespace) -> int:
    from ..models.turbine import select_dofs

    _positive(args.simulate, "--simulate")
    _positive(args.dt, "--dt")
    _positive(args.rtol, "--rtol")
    _positive(args.step, "--step")
    sweep = parse_sweep(args.campbell) if args.campbell else None
    params, model = build_model(args)
    free = select_dofs(model.dofs, args.dof)
    if not free.any():
        raise InputError("no free degree of freedom", field="--dof")
    q0 = initial_state(model.dofs, args.initial)
    rpm = rotor_rpm(args)
    for note in params.notes:
        print(f"# {note}")
    if args.linearize:
        return linearize_command(model, free, rpm)
    if sweep is not None:
        return campbell_command(model, free, sweep, args)
    return simulate_command(model, free, q0, rpm, args)


def linearize_command(model, free, rpm: float) -> int:
    from ..models.turbine.linearize import linearize

    result = linearize(model, free, rpm)
    print(f"# full-system modes at {rpm:g} rpm, {int(free.sum())} free DOFs; blades in multi-blade coordinates "
          f"(azimuth-averaged) when all three are free")
    print(f"{'mode':<45} {'frequency [Hz]':>15} {'damping [%]':>12}")
    for mode in result.modes:
        print(f"{mode.name:<45} {mode.frequency_hz:>15.4f} {100 * mode.damping_ratio:>12.3f}")
    return 0


def campbell_command(model, free, sweep: np.ndarray, args: argparse.Namespace) -> int:
    from ..files import write_atomic
    from ..models.turbine.campbell import campbell, campbell_text
    from ..plots.turbine_campbell import save_turbine_campbell_plot

    result = campbell(model, free, sweep)
    text = campbell_text(result)
    if args.output:
        write_atomic(args.output, text)
    else:
        sys.stdout.write(text)
    if args.plot:
        save_turbine_campbell_plot(result, args.plot)
    return 0


def simulate_command(model, free, q0: np.ndarray, rpm: float, args: argparse.Namespace) -> int:
    import numpy as np

    from ..files import write_atomic
    from ..models.turbine import FreeSystem
    from ..models.turbine.simulate import plot_outputs, simulate, table_text

    u0 = np.zeros(model.n)
    u0[5] = rpm * np.pi / 30.0
    if args.method in ("DP54", "DP853") and not hasattr(model.fast_equations(), "integrate"):
        raise InputError(f"{args.method} needs numba (pip install numba); use auto, RK45, DOP853 or RK4",
                         field="--method")
    result = simulate(FreeSystem(model, free, q0, u0), args.simulate, dt_output=args.dt, rtol=args.rtol,
                      atol=args.rtol * 1e-2, method=args.method, step=args.step)
    text = table_text(result)
    if args.output:
        write_atomic(args.output, text)
        print(f"# {len(result.time)} rows written to {Path(args.output)}; {result.evaluations} right-hand sides")
    else:
        sys.stdout.write(text)
    if args.plot:
        plot_outputs(result, args.plot)
    return 0
