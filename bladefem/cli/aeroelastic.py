"""``bladefem turbine DECK.fst --linearize|--campbell [--wind-speed ...]``: aeroelastic modes of the turbine with
the quasi-steady BEM of the OpenFAST deck, about the operating point at each wind speed.

    bladefem turbine DECK.fst --linearize [--wind-speed 11.4] [--rpm 12.1] [--pitch-deg 0] [--json]
    bladefem turbine DECK.fst --campbell --wind-speed 3:25:12 [--schedule FILE] [--plot campbell.png] [--json]

The wind speed of ``--linearize`` defaults to InflowWind's ``HWindSpeed``; ``--shear-exp`` replaces ``PLExp``.

Rotor speed and pitch: ``--schedule`` (wind speed, rpm, pitch table), else ``--rpm`` imposed or, with the
generator free, the deck's torque law (ServoDyn ``VSContrl`` 1), else the deck's ``RotSpeed``; the pitch is
``--pitch-deg`` or the deck's ``BlPitch``. An imposed rotor speed locks the generator azimuth (OpenFAST's
fixed-speed linearization with ``GenDOF`` False).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import replace
from pathlib import Path

from ..errors import InputError
from ..limits import MAX_SPEEDS
from .options import emit

INDUCTIONS = ("frozen", "quasi-steady")
#: options that only the aeroelastic analysis reads
AEROELASTIC_ONLY = ("schedule", "induction")


def add_aeroelastic_options(parser: argparse.ArgumentParser) -> None:
    """The options of the aeroelastic analysis (an OpenFAST deck with AeroDyn); ``--wind-speed`` and ``--pitch-deg``
    are the turbine command's."""
    group = parser.add_argument_group("aeroelastic modes (--linearize, --campbell of an OpenFAST .fst deck with "
                                      "AeroDyn and InflowWind)")
    group.add_argument("--schedule", metavar="FILE",
                       help="rotor speed and pitch against wind speed (lines: wind speed m/s, rpm, pitch deg), "
                            "interpolated linearly; e.g. cases/nrel5mw/table_7_1_schedule.csv")
    group.add_argument("--induction", choices=INDUCTIONS, default=None,
                       help="BEM induction in the linearization: frozen (default: the induced velocities held at "
                            "the operating point, OpenFAST's frozen wake) or quasi-steady (re-solved)")


def wind_speeds(text: str) -> tuple[float, ...]:
    """U, START:STOP:COUNT or U1,U2,... (m/s) -> wind speeds."""
    try:
        if ":" in text:
            start, stop, count = text.split(":")
            start_, stop_, n = float(start), float(stop), int(count)
            if n < 1 or not (math.isfinite(start_) and math.isfinite(stop_)) or stop_ < start_:
                raise ValueError
            if n > MAX_SPEEDS:
                raise argparse.ArgumentTypeError(f"at most {MAX_SPEEDS} wind speeds (MAX_SPEEDS), got {n}")
            values = tuple(start_ + (stop_ - start_) * k / (n - 1) for k in range(n)) if n > 1 else (start_,)
        else:
            values = tuple(float(part) for part in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected U, START:STOP:COUNT or U1,U2,... in m/s, got '{text}'") from None
    if not values or not all(math.isfinite(v) and v >= 0 for v in values):
        raise argparse.ArgumentTypeError(f"wind speeds must be non-negative numbers, got '{text}'")
    if len(values) > MAX_SPEEDS:
        raise argparse.ArgumentTypeError(f"at most {MAX_SPEEDS} wind speeds (MAX_SPEEDS), got {len(values)}")
    return values


def leave_out(args: argparse.Namespace) -> frozenset[str]:
    """The ways forward the command line takes (options of :data:`bladefem.builders.aerodyn_primary.WAYS`): what the deck
    asks for and bladefem does not model is left out (and named) instead of refused."""
    taken = set()
    if getattr(args, "foundation", None) == "rigid":
        taken.add("--foundation rigid")
    if getattr(args, "quasi_steady", False):
        taken.add("--quasi-steady")
    if getattr(args, "rpm", None) is not None:
        taken.add("--rpm")
    if getattr(args, "elastodyn_blades", False):
        taken.add("--elastodyn-blades")
    return frozenset(taken)


def wants_aeroelastic(args: argparse.Namespace) -> bool:
    """True for --linearize or --campbell with aerodynamics: --wind-speed given (:func:`read_deck` refuses a deck
    without them), or a .fst whose AeroDyn is on, unless --no-aero."""
    from ..builders.openfast_fst import read_openfast_deck
    from ..builders.turbine_deck import is_openfast_deck

    if args.simulate is not None or args.no_aero:
        return False
    if args.wind_speed is not None:
        return True
    return Path(args.main).is_file() and is_openfast_deck(args.main) and (
        read_openfast_deck(args.main, leave_out=leave_out(args)).aerodyn is not None)


def check_aeroelastic_options(args: argparse.Namespace) -> None:
    """Refuse options the chosen action would ignore, and bad combinations."""
    if not wants_aeroelastic(args):
        for name in AEROELASTIC_ONLY:
            if getattr(args, name) is not None:
                raise InputError("applies to the aeroelastic --linearize and --campbell of a .fst with aerodynamics",
                                 field="--" + name.replace("_", "-"))
        if args.campbell == ():
            raise InputError("give the rotor speeds START:STOP:COUNT (with aerodynamics: the wind speeds with "
                             "--wind-speed)", field="--campbell")
        return
    if args.campbell:
        raise InputError("with aerodynamics the Campbell diagram runs over the wind speeds: give --campbell without "
                         "rotor speeds and --wind-speed START:STOP:COUNT (or --no-aero for the structure's over "
                         "rotor speeds)", field="--campbell")
    if args.campbell == () and args.wind_speed is None:
        raise InputError("give the wind speeds of the Campbell diagram (START:STOP:COUNT)", field="--wind-speed")
    if args.linearize and args.wind_speed is not None and len(args.wind_speed) > 1:
        raise InputError("--linearize takes one wind speed: use --campbell for several", field="--wind-speed")
    if args.schedule is not None:
        for name, value in (("rpm", args.rpm), ("pitch-deg", args.pitch_deg)):
            if value is not None:
                raise InputError("the schedule gives the rotor speed and pitch", field="--" + name)
    if args.azimuth_deg is not None and (args.rpm != 0.0 or not math.isfinite(args.azimuth_deg)):
        raise InputError("a turning rotor's model is averaged over the azimuth: --azimuth-deg places a parked one "
                         "(--rpm 0)", field="--azimuth-deg")


def read_deck(path: str, taken: frozenset[str] = frozenset()):
    """The OpenFAST deck (with aerodynamics) of ``path``, with the ways forward ``taken`` (:func:`leave_out`)."""
    from ..builders.openfast_fst import read_openfast_deck
    from ..builders.turbine_deck import is_openfast_deck
    from ..formats._labels import Labels

    if Path(path).is_file() and not is_openfast_deck(path) and Labels.read(path).has("NumBl", "TwrFile"):
        raise InputError("aerodynamics come from an OpenFAST main file (.fst) naming ElastoDyn, AeroDyn and "
                         "InflowWind: give that instead of an ElastoDyn file", file=path, field="--wind-speed")
    deck = read_openfast_deck(path, leave_out=taken)
    if deck.aerodyn is None:
        raise InputError("the deck has no aerodynamics (CompAero 0)", file=deck.path, field="CompAero")
    return deck


def run_aeroelastic(args: argparse.Namespace) -> int:
    """The aeroelastic ``--linearize`` or ``--campbell`` of an OpenFAST deck."""
    from ..builders.turbine_elastodyn import deck_conditions, platform_note
    from ..models.turbine.aeroelastic_campbell import AeroelasticTurbine
    from ..models.turbine.control import Generator
    from ..models.turbine.initial import free_from_switches
    from ..models.turbine.parameters import dof_names
    from .options import dof_option

    taken = leave_out(args)
    deck = read_deck(args.main, taken)
    if args.wind_speed is None:
        args.wind_speed = (deck.inflow.speed,)
    rigid = "--foundation rigid" in taken
    switches, conditions = deck_conditions(deck.elastodyn.path, rigid)
    notes: list[str] = ([platform_note(deck.elastodyn.path)] if rigid else []) + list(deck.left_out)
    structure_notes: list[str] = []
    structure = structure_builder(deck, args, structure_notes)
    dofs = dof_names(deck.elastodyn.num_blades)
    free = dof_option(dofs, args.dof, free_from_switches(dofs, switches))
    if not free.any():
        raise InputError("no free degree of freedom", field="--dof")
    generator = Generator.from_servodyn(deck.servodyn) if deck.servodyn is not None else None
    requests = operating_requests(args, deck, conditions, free, dofs, generator, notes)
    inflow = deck.inflow if args.shear_exp is None else replace(deck.inflow, shear_exponent=args.shear_exp)
    turbine = AeroelasticTurbine(structure=structure, rotor=deck.rotor(), inflow=inflow, free=free,
                                 generator=generator)
    turbine.model(requests[0].pitch)                 # the first build reports the structure's notes
    return sweep_command(turbine, requests, args, list(dict.fromkeys(structure_notes + notes)))


def structure_builder(deck, args: argparse.Namespace, notes: list[str]):
    """``pitch (rad) -> TurbineModel`` of the deck's ElastoDyn structure with the command's options; the notes of
    the first build go to ``notes``."""
    from ..builders.turbine_elastodyn import (
        NREL5MW_YAW_DAMPING,
        NREL5MW_YAW_STIFFNESS,
        turbine_from_elastodyn,
    )
    from ..models.turbine import TurbineModel

    servo = deck.servodyn
    yaw_stiffness = args.yaw_stiffness if args.yaw_stiffness is not None else (
        servo.yaw_spring if servo is not None else NREL5MW_YAW_STIFFNESS)
    yaw_damping = args.yaw_damping if args.yaw_damping is not None else (
        servo.yaw_damper if servo is not None else NREL5MW_YAW_DAMPING)
    shapes = args.shapes or ("polynomial" if args.elastodyn_compatible else "fe")

    def build(pitch: float) -> TurbineModel:
        params = turbine_from_elastodyn(
            deck.elastodyn.path, shapes, rpm=args.rpm, pitch=pitch, tower_shapes=args.tower_shapes,
            yaw_stiffness=yaw_stiffness, yaw_damping=yaw_damping, elastodyn_compatible=args.elastodyn_compatible,
            damping=args.damping, gauss_points=1 if args.elastodyn_compatible else 2)
        if args.no_gravity:
            params = params.with_(gravity=0.0)
        if args.no_damping:
            params = params.without_damping()
        if not notes:
            notes.extend(params.notes)
        return TurbineModel(params)
    return build


def operating_requests(args: argparse.Namespace, deck, conditions, free, dofs, generator, notes: list[str]):
    """An :class:`OperatingRequest` per wind speed (module description; ``conditions`` the deck's initial ones);
    locks the generator azimuth in ``free`` when the rotor speed is imposed."""
    from ..formats.schedule import read_schedule
    from ..models.turbine.aeroelastic_campbell import OperatingRequest, rotor_speed

    gen = dofs.index("generator_azimuth")
    if args.schedule is not None:
        schedule = read_schedule(args.schedule)
        notes.append(f"rotor speed and pitch from the schedule {args.schedule}")
        points = [(u, *schedule.at(u)) for u in args.wind_speed]
    else:
        if args.pitch_deg is None and len(set(deck.pitch)) > 1:
            raise InputError("the blades have different BlPitch: give --pitch-deg", file=deck.elastodyn.path,
                             field="BlPitch(2)")
        pitch = math.radians(args.pitch_deg) if args.pitch_deg is not None else deck.pitch[0]
        try:
            speed, note = rotor_speed(args.rpm, bool(free[gen]), generator, conditions.rotor_speed)
        except ValueError as error:
            raise InputError(f"{error}: give --rpm, a --schedule, or lock it (--dof GenDOF=off)", file=deck.path,
                             field="--rpm") from None
        notes.extend([note] if note else [])
        points = [(u, speed, pitch) for u in args.wind_speed]
    if any(u == 0.0 and speed != 0.0 for u, speed, _ in points):
        raise InputError("a turning rotor in still air has no operating point of the BEM: give a positive wind "
                         "speed, --rpm 0 (parked), or --no-aero for the structure alone", field="--wind-speed")
    if any(speed is not None for _, speed, _ in points) and free[gen]:
        free[gen] = False
        notes.append("rotor speed imposed: the generator azimuth is locked")
    azimuth = conditions.azimuth if args.azimuth_deg is None else math.radians(args.azimuth_deg)
    return [OperatingRequest(wind_speed=u, rotor_speed=speed, pitch=pitch, azimuth=azimuth) for u, speed, pitch in
            points]


def sweep_command(turbine, requests, args: argparse.Namespace, notes: list[str]) -> int:
    """Linearize at every request, then print the notes (stderr with --json) and the results: nothing on stdout
    when a point fails."""
    from ..models.turbine.aeroelastic_campbell import (
        aeroelastic_campbell,
        campbell_text,
    )
    from ..report import progress_bar

    progress = progress_bar("Aeroelastic sweep", args.quiet or len(requests) == 1)
    result = aeroelastic_campbell(turbine, requests, args.induction or "frozen", progress=progress)
    for note in notes:
        print(f"# {note}", file=sys.stderr if args.json else sys.stdout)
    emit(linearization_text(result, args, lambda linear: aeroelastic_table(linear, int(turbine.free.sum())),
                            campbell_text), args.output)
    if args.plot:
        from ..plots.aeroelastic_campbell import save_aeroelastic_campbell_plot
        save_aeroelastic_campbell_plot(result, args.plot)
    return 0


def linearization_text(result, args: argparse.Namespace, table, campbell_text) -> str:
    """The text of a linearization (``--linearize``: ``table`` of its one point) or a Campbell sweep
    (``campbell_text``), or with ``--json`` its points' dicts (one, or a list)."""
    if args.json:
        data = [linear.as_dict() for linear in result.linearizations]
        return json.dumps(data[0] if args.linearize else data, indent=1) + "\n"
    if args.linearize:
        return table(result.linearizations[0])
    return campbell_text(result)


def aeroelastic_table(linear, free_count: int) -> str:
    """The modes of one aeroelastic linearization as a text table, with its operating point."""
    point, d = linear.point, linear.deflections
    speed = "trimmed by the torque law" if point.trimmed else "imposed"
    if linear.averaged:
        where = f"multi-blade coordinates averaged over {3 * len(point.azimuths)} azimuths a revolution"
    elif point.rotor_speed == 0.0:
        where = f"parked at azimuth {math.degrees(point.azimuths[0]):g} deg"
    else:
        where = "blade coordinates at azimuth 0"
    induction = "frozen wake" if linear.induction == "frozen" else "quasi-steady induction"
    lines = [f"# aeroelastic modes at {point.wind_speed:g} m/s, {point.rpm:.4g} rpm ({speed}), pitch "
             f"{point.pitch_deg:.4g} deg; {induction}; {free_count} free DOFs; {where}",
             f"# operating point ({'static' if point.rotor_speed == 0.0 else 'azimuth-averaged'} equilibrium): "
             f"thrust {point.thrust / 1e3:.1f} kN, aerodynamic "
             f"torque {point.torque / 1e3:.1f} kN m, power {point.power / 1e6:.3f} MW; blade tip {d['OoPDefl']:.3f} m "
             f"out of plane, {d['IPDefl']:.3f} m in plane; tower top {d['TTDspFA']:.3f} m fore-aft, "
             f"{d['TTDspSS']:.3f} m side-side"]
    if linear.rigid:
        lines.append(f"# rigid-body motions (not listed): {', '.join(linear.rigid)}")
    return "\n".join(lines + mode_lines(linear.modes)) + "\n"


def mode_lines(modes) -> list[str]:
    """A table of named modes: frequency (Hz), damping ratio (per cent) and the two largest participations; a mode
    that does not oscillate (a real root: overdamped, or the rotor speed settling) says so and gives its decay time
    instead of a frequency."""
    width = max([45, *(len(mode.name) for mode in modes)])
    lines = [f"{'mode':<{width}} {'frequency [Hz]':>15} {'damping [%]':>12}  main participation"]
    for mode in modes:
        top = sorted(mode.participation.items(), key=lambda item: -item[1])[:2]
        shares = ", ".join(f"{name} {share:.2f}" for name, share in top)
        if getattr(mode, "oscillating", True):
            lines.append(f"{mode.name:<{width}} {mode.frequency_hz:>15.4f} {100 * mode.damping_ratio:>12.3f}  "
                         f"{shares}")
        else:
            lines.append(f"{mode.name:<{width}} {'no oscillation':>15} {'-':>12}  decay time "
                         f"{mode.time_constant:.3g} s; {shares}")
    return lines
