"""``bladefem turbine``: the 16-DOF Kane turbine model of an OpenFAST deck (.fst) or an ElastoDyn main file.

    bladefem turbine DECK --linearize [--rpm R] [--azimuth-deg A] [--dof ...] [--json]   full-system modes
    bladefem turbine DECK --campbell 0:15:16 [--json] [--plot campbell.png]              Campbell diagram
    bladefem turbine DECK --simulate SECONDS [--wind-speed U] [--rpm R] [--dof ...] [--output out.csv]
    bladefem turbine DECK.fst --linearize|--campbell [--wind-speed ...]   aeroelastic modes (see cli/aeroelastic.py)

The deck is honoured: its DOF switches set the free coordinates and its initial conditions the initial state
(``--dof`` and ``--initial`` override them); a .fst brings aerodynamics (AeroDyn, InflowWind), the generator torque
law and the yaw spring (ServoDyn): its --linearize and --campbell are aeroelastic, about the operating point at the
wind speed(s) (``--no-aero`` for the structure alone).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import InputError
from .aeroelastic import (
    add_aeroelastic_options,
    check_aeroelastic_options,
    leave_out,
    linearization_text,
    mode_lines,
    run_aeroelastic,
    wants_aeroelastic,
)
from .aeroelastic import wind_speeds as wind_speeds_type
from .options import check_output, check_turbine_bounds, emit, positive, rpm_sweep
from .threads import one_blas_thread
from .wind_options import add_wind_options, apply_wind, check_wind_options

if TYPE_CHECKING:
    import numpy as np

#: --initial names in ElastoDyn's terms -> (field of InitialConditions, factor to SI)
ELASTODYN_INITIAL = {"OoPDefl": ("oop_deflection", 1.0), "IPDefl": ("ip_deflection", 1.0),
                     "TTDspFA": ("tower_top_fa", 1.0), "TTDspSS": ("tower_top_ss", 1.0),
                     "NacYaw": ("nacelle_yaw", math.pi / 180), "Azimuth": ("azimuth", math.pi / 180),
                     "RotSpeed": ("rotor_speed", math.pi / 30)}
#: coordinates that are angles, given in degrees as NAME_deg
ANGLES = ("yaw", "generator_azimuth", "drivetrain")
#: figure formats of --plot (by suffix)
PLOT_SUFFIXES = (".png", ".pdf", ".svg")
SIMULATION_ONLY = ("dt", "rtol", "method", "step", "initial", "discon_library", "controller_dt")
AERO_ONLY = ("wind_speed", "shear_exp")


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "turbine", help="16-DOF Kane turbine model (ElastoDyn structure, AeroDyn BEM) fed by bladefem modes",
        description="Simulate or linearize the 16-DOF turbine model (tower FA/SS 1-2, yaw, generator azimuth, "
                    "drivetrain, blade flap 1, edge 1, flap 2) of an OpenFAST deck (.fst: with quasi-steady BEM "
                    "aerodynamics, the generator torque law and the yaw spring) or of an ElastoDyn main file "
                    "(structure only). The deck's DOF switches and initial conditions are used unless overridden.")
    parser.add_argument("main", metavar="DECK", help="OpenFAST main file (.fst) or ElastoDyn main input file")
    action = parser.add_mutually_exclusive_group(required=True)
    action.add_argument("--linearize", action="store_true", help="the full-system modes at --rpm")
    action.add_argument("--campbell", type=rpm_sweep, nargs="?", const=(), metavar="START:STOP:COUNT",
                        help="full-system Campbell diagram at COUNT rotor speeds from START to STOP rpm (with "
                             "aerodynamics: over the wind speeds of --wind-speed, no rotor speeds given)")
    action.add_argument("--simulate", type=float, metavar="SECONDS", help="integrate in time for SECONDS")
    parser.add_argument("--rpm", type=float, default=None,
                        help="rotor speed, rpm (default: RotSpeed of the main file); also the speed of the FE "
                             "blade shapes. With --simulate the generator is locked at this speed (add --dof "
                             "GenDOF=on to start at it with the generator free)")
    parser.add_argument("--wind-speed", type=wind_speeds_type, default=None, metavar="U|START:STOP:COUNT|U1,U2,...",
                        help="steady wind speed at the reference height, m/s (default: InflowWind's HWindSpeed); "
                             "--linearize: the operating point's, --campbell: a sweep over several")
    parser.add_argument("--shear-exp", type=float, default=None, metavar="EXPONENT",
                        help="power-law wind shear exponent (default: InflowWind's PLExp)")
    parser.add_argument("--pitch-deg", type=float, default=None, metavar="DEG",
                        help="collective blade pitch, deg (default: ElastoDyn's BlPitch)")
    parser.add_argument("--no-aero", action="store_true", help="leave the aerodynamic loads of a .fst out")
    parser.add_argument("--foundation", choices=("rigid",), default=None,
                        help="rigid: the tower clamped at its base, the deck's platform DOFs, hydrodynamics, "
                             "mooring and substructure (HydroDyn, SubDyn, MoorDyn, ...) left out, said in the header")
    parser.add_argument("--quasi-steady", action="store_true",
                        help="run the aerodynamics quasi-steady: the deck's dynamic wake (DBEMT_Mod 1-3, modelled "
                             "in --simulate) and the unsteady airfoil aerodynamics, tower and nacelle aerodynamics "
                             "that bladefem does not model are left out, listed in one note")
    parser.add_argument("--elastodyn-blades", action="store_true",
                        help="for a deck with BeamDyn blades (CompElast 2): use the ElastoDyn blade files (BldFile) "
                             "the deck also carries")
    parser.add_argument("--azimuth-deg", type=float, default=None, metavar="DEG",
                        help="rotor azimuth of a parked (0 rpm) linearization, deg, blade 1 up at 0 (default: "
                             "Azimuth - AzimB1Up of the main file)")
    parser.add_argument("--dof", nargs="+", default=None, metavar="NAME",
                        help="free DOFs (default: the deck's switches): all, tower, tower1, yaw, generator, "
                             "drivetrain, blades, flap1, edge1, flap2, coordinates such as tower_fa1, "
                             "blade2_edge1, or ElastoDyn switches (GenDOF, FlapDOF1, ...); NAME=off or NAME=on "
                             "changes the deck's set (e.g. GenDOF=off); locked DOFs keep their initial rate")
    parser.add_argument("--initial", nargs="+", default=None, metavar="NAME=VALUE",
                        help="initial state of --simulate (over the deck's): ElastoDyn's OoPDefl, IPDefl, "
                             "TTDspFA, TTDspSS (m), NacYaw, Azimuth (deg), RotSpeed (rpm); or coordinates: modal "
                             "amplitudes in m (tower_fa1=0.3, blade1_flap1=1.0), angles in degrees (yaw_deg, "
                             "generator_azimuth_deg, drivetrain_deg)")
    parser.add_argument("--elastodyn-compatible", action="store_true",
                        help="ElastoDyn's own choices: the files' polynomial shapes, its discretization at "
                             "BldNodes/TwrNodes element midpoints and its damping convention")
    parser.add_argument("--shapes", choices=("fe", "fe-polynomial", "polynomial"), default=None,
                        help="blade mode shapes: bladefem FE at --rpm (default), ElastoDyn polynomials fitted to "
                             "them, or the blade file's polynomials (default with --elastodyn-compatible)")
    parser.add_argument("--tower-shapes", choices=("fe", "fe-polynomial", "polynomial"), default="polynomial",
                        help="tower mode shapes: the tower file's polynomials (default), bladefem's tower FE with "
                             "the rotor-nacelle on top, or ElastoDyn polynomials fitted to those")
    parser.add_argument("--damping", choices=("elastodyn", "rna"), default="elastodyn",
                        help="structural damping convention: elastodyn (default: ElastoDyn's, each mode's "
                             "frequency of the beam alone) or rna (modal masses with the tip mass and the "
                             "rotor-nacelle assembly on the tower)")
    parser.add_argument("--no-gravity", action="store_true", help="switch gravity off")
    parser.add_argument("--no-damping", action="store_true", help="switch structural, drivetrain, yaw damping off")
    parser.add_argument("--yaw-stiffness", type=float, default=None, metavar="N_M_PER_RAD",
                        help="nacelle-yaw spring (default: ServoDyn's YawSpr, else the NREL 5MW's 9.02832e9)")
    parser.add_argument("--yaw-damping", type=float, default=None, metavar="N_M_S_PER_RAD",
                        help="nacelle-yaw damper (default: ServoDyn's YawDamp, else the NREL 5MW's 1.916e7)")
    parser.add_argument("--json", action="store_true", help="--linearize or --campbell results as JSON")
    parser.add_argument("--dt", type=float, default=None, help="output interval of --simulate, s (default 0.05)")
    parser.add_argument("--rtol", type=float, default=None,
                        help="relative tolerance of --simulate (default 1e-6, absolute 0.1 times it; 1e-5: 0.7 times "
                             "the work, docs/turbine-aero.md#speed; with a controller library it selects DP54)")
    parser.add_argument("--method", choices=("auto", "DP853", "DP54", "RK45", "DOP853", "RK4", "ABM4"),
                        default=None,
                        help="time integrator: auto (with numba the compiled Dormand-Prince 8(5,3), or 5(4) with "
                             "aerodynamics; else scipy DOP853; with the controller library one ABM4 step per "
                             "controller interval where stable, else one RK4 step, the BEM solved once per step, "
                             "else DP54; DP54 with --rtol), DP853 or DP54 (compiled, need numba), "
                             "scipy RK45 or DOP853, fixed-step RK4 (--step), or ABM4 (with the controller library: "
                             "ElastoDyn's Adams-Bashforth-Moulton, one step per controller interval)")
    parser.add_argument("--discon-library", metavar="PATH", default=None,
                        help="the Bladed-style controller library (DISCON entry point) a deck with PCMode and "
                             "VSContrl 5 runs (default: ServoDyn's DLL_FileName, else an installed ROSCO's "
                             "libdiscon.so)")
    parser.add_argument("--controller-dt", type=positive, default=None, metavar="SECONDS",
                        help="interval between calls of the controller library, s (default: ServoDyn's DLL_DT; "
                             "its 'default' is the deck's DT)")
    parser.add_argument("--step", type=float, default=None, help="step of --method RK4, s (default 0.01)")
    parser.add_argument("--output", "-o", metavar="FILE", help="write the table (or JSON) to FILE")
    parser.add_argument("--plot", metavar="FILE", help="figure of --simulate or --campbell (PNG, PDF, SVG)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    add_wind_options(parser)
    add_aeroelastic_options(parser)
    parser.set_defaults(run=one_blas_thread(run))


def check_options(args: argparse.Namespace) -> None:
    """Refuse options the chosen action would ignore, and bad values."""
    if not args.simulate:
        for name in SIMULATION_ONLY:
            if getattr(args, name) is not None:
                raise InputError("applies to --simulate only", field="--" + name)
    else:
        for name, flag in (("json", args.json), ("azimuth-deg", args.azimuth_deg is not None)):
            if flag:
                raise InputError("applies to --linearize and --campbell only" + (
                    " (set the initial azimuth with --initial Azimuth=DEG)" if name == "azimuth-deg" else ""),
                                 field="--" + name)
    if args.linearize and args.plot:
        raise InputError("there is no figure of a single linearization: use --campbell for a plot", field="--plot")
    for name in ("simulate", "dt", "rtol", "step"):
        value = getattr(args, name)
        if value is not None and not (math.isfinite(value) and value > 0):
            raise InputError(f"must be a positive number, got {value}", field="--" + name)
    check_duration(args.simulate, args.dt)
    check_wind_options(args)
    if args.plot and Path(args.plot).suffix.lower() not in PLOT_SUFFIXES:
        raise InputError(f"the figure's format goes by its suffix: one of {', '.join(PLOT_SUFFIXES)}",
                         file=args.plot, field="--plot")
    check_output(args.output, "--output")
    check_output(args.plot, "--plot")
    if args.no_aero:
        for name in AERO_ONLY:
            if getattr(args, name) is not None:
                raise InputError("has no effect with --no-aero", field="--" + name.replace("_", "-"))
    if args.elastodyn_compatible:
        for option, value, wrong in (("--shapes", args.shapes, "fe"), ("--tower-shapes", args.tower_shapes, "fe"),
                                     ("--damping", args.damping, "rna")):
            if value == wrong:
                raise InputError(f"--elastodyn-compatible takes ElastoDyn's own choice here, not '{wrong}'",
                                 field=option)
    check_turbine_bounds(args)
    if args.simulate and args.wind_speed is not None:
        if len(args.wind_speed) > 1:
            raise InputError("--simulate takes one wind speed", field="--wind-speed")
        args.wind_speed = args.wind_speed[0]
    for name in ("rpm", "yaw_stiffness", "yaw_damping"):
        value = getattr(args, name)
        if value is not None and not (math.isfinite(value) and value >= 0):
            raise InputError(f"must be a non-negative number, got {value}", field="--" + name.replace("_", "-"))
    for name in ("azimuth_deg", "shear_exp", "pitch_deg"):
        value = getattr(args, name)
        if value is not None and not math.isfinite(value):
            raise InputError(f"must be a number, got {value}", field="--" + name.replace("_", "-"))


def check_duration(seconds: float | None, dt: float | None) -> None:
    """Refuse a --simulate longer than :data:`~bladefem.limits.MAX_SIMULATION_SECONDS` or with more output rows
    than :data:`~bladefem.limits.MAX_OUTPUT_ROWS`, before the model is built."""
    from ..limits import MAX_OUTPUT_ROWS, MAX_SIMULATION_SECONDS

    if seconds is None:
        return
    if seconds > MAX_SIMULATION_SECONDS:
        raise InputError(f"at most {MAX_SIMULATION_SECONDS:g} s (a day of turbine time) in one run, got {seconds:g}",
                         field="--simulate")
    rows = seconds / (0.05 if dt is None else dt)
    if rows > MAX_OUTPUT_ROWS:
        raise InputError(f"{rows:.3g} output rows (at most {MAX_OUTPUT_ROWS:g}): give a larger --dt or a shorter "
                         "--simulate", field="--dt" if dt is not None else "--simulate")


def parse_initial(entries: list[str], dofs: tuple[str, ...]) -> tuple[dict[str, float], dict[str, float]]:
    """NAME=VALUE entries -> (ElastoDyn initial conditions, SI; coordinates, SI). Coordinates are modal
    amplitudes (m) or angles given as NAME_deg."""
    conditions: dict[str, float] = {}
    coordinates: dict[str, float] = {}
    for entry in entries:
        name, sep, text = entry.partition("=")
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not sep or not math.isfinite(value):
            raise InputError(f"expected NAME=NUMBER, got '{entry}'", field="--initial")
        if name in ELASTODYN_INITIAL:
            field, factor = ELASTODYN_INITIAL[name]
            conditions[field] = value * factor
        elif name.endswith("_deg") and name[:-4] in ANGLES:
            coordinates[name[:-4]] = math.radians(value)
        elif name in ANGLES:
            raise InputError(f"'{name}' is an angle: give {name}_deg=DEGREES", field="--initial")
        elif name in dofs:
            coordinates[name] = value
        else:
            known = [*ELASTODYN_INITIAL, *(f"{a}_deg" for a in ANGLES),
                     *(d for d in dofs if d not in ANGLES)]
            raise InputError(f"unknown initial value '{name}' (one of {', '.join(known)})", field="--initial")
    return conditions, coordinates


def refuse_overwriting_inputs(args: argparse.Namespace) -> None:
    """Parse the deck's chain of files (nothing computed yet) and refuse an output that names one of them."""
    from ..files import input_problem, note_input
    from ..formats.elastodyn_main import read_elastodyn_main
    from ..builders.openfast_fst import read_openfast_deck
    from ..builders.turbine_deck import is_openfast_deck

    from .aeroelastic import leave_out

    taken = leave_out(args) | ({"--no-aero"} if args.no_aero else set())
    main = (read_openfast_deck(args.main, leave_out=taken, controller=runs_controller(args),
                               dynamic_wake=bool(args.simulate)).elastodyn
            if is_openfast_deck(args.main) else read_elastodyn_main(args.main))
    keys = [f"BldFile({i + 1})" for i in range(len(main.blade_files))] + ["TwrFile"]
    for key, file in zip(keys, (*main.blade_files, main.tower_file)):
        problem = input_problem(file)
        if problem is not None:                     # a folder, a link loop or a pipe says so, at the line naming it
            raise InputError(f"{problem}: {file}", file=main.path, line=main.key_lines.get(key), field=key)
        note_input(file)
    check_output(args.output, "--output")
    check_output(args.plot, "--plot")


def runs_controller(args: argparse.Namespace) -> bool:
    """Whether a deck's Bladed-style DLL runs: in a simulation whose rotor speed is not held at --rpm."""
    return bool(args.simulate) and args.rpm is None


def build_model(args: argparse.Namespace):
    """The deck's turbine (:class:`~bladefem.builders.turbine_deck.TurbineDeck`) and its model, with the options."""
    from ..builders.turbine_deck import read_turbine_deck
    from ..models.turbine import TurbineModel

    shapes = args.shapes or ("polynomial" if args.elastodyn_compatible else "fe")
    deck = read_turbine_deck(
        args.main, aero=not args.no_aero, wind_speed=args.wind_speed, shear_exponent=args.shear_exp,
        pitch=None if args.pitch_deg is None else math.radians(args.pitch_deg), yaw_stiffness=args.yaw_stiffness,
        yaw_damping=args.yaw_damping, blade_shapes=shapes, rpm=args.rpm, tower_shapes=args.tower_shapes,
        elastodyn_compatible=args.elastodyn_compatible, damping=args.damping,
        gauss_points=1 if args.elastodyn_compatible else 2, leave_out=leave_out(args),
        controller=runs_controller(args), dynamic_wake=bool(args.simulate))
    params = deck.params
    if args.no_gravity:
        params = params.with_(gravity=0.0)
    if args.no_damping:
        params = params.without_damping()
    return deck, params, TurbineModel(params, aero=deck.aero, generator=deck.generator)


def run(args: argparse.Namespace) -> int:
    import numpy as np

    from .options import dof_option
    from ..models.turbine.initial import free_from_switches, initial_state

    check_options(args)
    check_aeroelastic_options(args)
    refuse_overwriting_inputs(args)
    if wants_aeroelastic(args):
        return run_aeroelastic(args)
    if args.simulate:
        from ..models.turbine.parallel_compile import prestart
        prestart()                                             # a cold first run: the compile helper warms up now
    deck, params, model = build_model(args)
    if args.simulate:
        model = apply_wind(args, model)
    switches, conditions = deck.switches, deck.conditions
    if args.rpm is not None:
        conditions = conditions.with_(rotor_speed=args.rpm * math.pi / 30)
        if args.simulate:
            switches = {**switches, "GenDOF": False}           # the generator held at --rpm
    free = dof_option(model.dofs, args.dof, free_from_switches(model.dofs, switches))
    if not free.any():
        raise InputError("no free degree of freedom", field="--dof")
    notes = sys.stderr if args.json else sys.stdout            # JSON on stdout stays pure
    for note in params.notes:
        print(f"# {note}", file=notes)
    if model.aero is not None:
        inflow = model.aero.inflow
        wake = model.aero.rotor.dynamic_wake
        kind = "quasi-steady BEM" if wake is None else f"BEM with the dynamic wake (DBEMT_Mod {wake.model})"
        print(f"# aerodynamics: {kind} at {model.aero.n_nodes} AeroDyn nodes per blade, {inflow.kind} wind "
              f"{inflow.speed:g} m/s at {inflow.reference_height:g} m, shear exponent {inflow.shear_exponent:g}, "
              f"pitch {math.degrees(model.aero.pitch):g} deg", file=notes)
    for note in deck.notes:
        print(f"# {note}", file=notes)
    generator = generator_line(model.generator, bool(free[model.dofs.index("generator_azimuth")]),
                               conditions.rotor_speed)
    if generator:
        print(f"# {generator}", file=notes)
    rpm = conditions.rotor_speed * 30 / math.pi
    if args.linearize or args.campbell is not None:
        azimuth = conditions.azimuth if args.azimuth_deg is None else math.radians(args.azimuth_deg)
        sweep = np.array([rpm]) if args.linearize else args.campbell
        return linearize_command(model, free, sweep, azimuth, conditions.nacelle_yaw, args, operating_rpm=rpm)
    overrides, coordinates = parse_initial(args.initial or [], model.dofs)
    check_bounds(model, conditions.with_(**overrides).rotor_speed, args)
    q0, u0, notes = initial_state(model, free, conditions.with_(**overrides))
    for name, value in coordinates.items():
        q0[model.dofs.index(name)] = value
    for note in notes:
        print(f"# {note}")
    from .turbine_simulate import controller_of, simulate_command

    return simulate_command(model, free, q0, u0, args, controller_of(deck, args))


def generator_line(generator, free: bool, rotor_speed: float) -> str | None:
    """The header line on the generator: its torque law when the generator azimuth is free, or that the speed is
    held (rotor speed in rad/s) and the deck's law is not used."""
    if generator is None or not generator.torque_law:
        return None
    if free:
        return "generator: ServoDyn's simple variable-speed torque law (VSContrl 1)"
    return (f"generator: locked at {rotor_speed * 30 / math.pi:g} rpm (GenDOF off); ServoDyn's torque law is not "
            "used")


def check_bounds(model, rotor_speed: float, args: argparse.Namespace) -> None:
    """Refuse, before a simulation starts, a supersonic blade tip and a generator rated beyond the rotor
    (:mod:`bladefem.models.turbine.watch`)."""
    from ..models.turbine.watch import check_generator, check_rotor_speed

    field = "--rpm" if args.rpm is not None else "--initial RotSpeed" if "RotSpeed=" in " ".join(
        args.initial or []) else "RotSpeed"
    check_rotor_speed(model, rotor_speed, field)
    check_generator(model)


def linearize_command(model, free, sweep: np.ndarray, azimuth: float, yaw: float, args: argparse.Namespace,
                      operating_rpm: float = 0.0) -> int:
    """The modes at one rotor speed, or the Campbell diagram over ``sweep`` (rpm) with the operating speed
    ``operating_rpm`` (the deck's RotSpeed or --rpm) marked on its plot."""
    from ..models.turbine.campbell import campbell, campbell_text
    from ..plots.turbine_campbell import TITLE, save_turbine_campbell_plot
    from ..report import progress_bar

    progress = progress_bar("Campbell sweep", args.quiet or len(sweep) == 1)
    result = campbell(model, free, sweep, azimuth=azimuth, yaw=yaw, progress=progress)
    emit(linearization_text(result, args, lambda linear: modes_table(linear, int(free.sum())), campbell_text),
         args.output)
    if args.plot:
        save_turbine_campbell_plot(result, args.plot, title=f"{TITLE}\n{Path(args.main).name}",
                                   operating_rpm=operating_rpm or None)
    return 0


def modes_table(linear, free_count: int) -> str:
    """The modes of one linearization as a text table."""
    where = (f"parked at azimuth {linear.azimuth_deg:g} deg, blades named in multi-blade coordinates"
             if linear.rpm == 0 else "multi-blade coordinates averaged over the azimuth" if linear.azimuth_deg is
             None else f"at azimuth {linear.azimuth_deg:g} deg")
    lines = [f"# full-system modes at {linear.rpm:g} rpm, {free_count} free DOFs; {where}"]
    if linear.rigid:
        lines.append(f"# rigid-body motions (0 Hz, not listed): {', '.join(linear.rigid)}")
    return "\n".join(lines + mode_lines(linear.modes)) + "\n"
