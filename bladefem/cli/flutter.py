"""``bladefem flutter INPUT --aero AERODYN_PRIMARY``: the damping and frequency of each blade mode along a sweep of
rotor speed or wind speed, with unsteady section aerodynamics (Theodorsen, p-k), and the flutter onset.

    bladefem flutter BLADE --aero AD.dat --rpm START:STOP:COUNT [--wind-speed U] [--pitch-deg P] [--json]
    bladefem flutter BLADE --aero AD.dat --wind-speed START:STOP:COUNT [--rpm R] [--plot F.png] [--vtk DIR]

A rotor-speed sweep runs at ``--wind-speed`` (default 0: the blade turning in still air, no induction); a
wind-speed sweep at ``--rpm`` (default 0: parked). The aerodynamic centre sits at the quarter chord where the blade
input gives the reference axis's chordwise position (``pitch_axis``) and chord, else on AeroDyn's reference line
(OpenFAST's convention).
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from ..errors import InputError
from . import options
from .inputs import add_blade_options, positive_int, read_structure

def add_parser(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "flutter", help="blade flutter: damping of each mode over rotor or wind speed (unsteady aerodynamics)",
        description="Damping and frequency of each blade mode along a sweep of rotor speed or wind speed, with "
                    "the sections' unsteady aerodynamics (Theodorsen's function in a p-k iteration, apparent mass, "
                    "pitch rate) about the BEM operating point; the first zero crossing of damping is the flutter "
                    "onset.")
    add_blade_options(parser)
    parser.add_argument("--aero", metavar="AERODYN_PRIMARY", required=True,
                        help="AeroDyn primary file: its first blade file and airfoils")
    parser.add_argument("--rpm", metavar="RPM|START:STOP:COUNT",
                        help="rotor speed, rpm, or a sweep of rotor speeds (default 0 with a wind-speed sweep)")
    parser.add_argument("--wind-speed", metavar="M_S|START:STOP:COUNT",
                        help="wind speed along the shaft, m/s, or a sweep (default 0 with a rotor-speed sweep)")
    parser.add_argument("--blades", type=positive_int, default=3, metavar="N",
                        help="number of blades for the BEM induction (default 3)")
    parser.add_argument("--n-modes", type=options.n_modes, default=6, metavar="N",
                        help="blade modes tracked (default 6)")
    parser.add_argument("--plot", metavar="FILE.png", help="frequency and damping against the swept speed")
    parser.add_argument("--vtk", metavar="DIR", help="write the shape of the mode that goes unstable (VTK)")
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    parser.set_defaults(run=run_flutter)


def speeds(text: str | None, option: str) -> tuple[float, ...] | None:
    """A value or START:STOP:COUNT (non-negative, finite) -> the speeds; InputError naming ``option``."""
    from ..limits import MAX_SPEEDS

    if text is None:
        return None
    try:
        parts = [float(part) for part in text.split(":")]
        if len(parts) == 3:
            start, stop, count = parts[0], parts[1], int(parts[2])
            if count != parts[2] or not 2 <= count <= MAX_SPEEDS or not start < stop:
                raise ValueError
            values = tuple(start + (stop - start) * k / (count - 1) for k in range(count))
        elif len(parts) == 1:
            values = (parts[0],)
        else:
            raise ValueError
    except ValueError:
        raise InputError(f"expected a value or START:STOP:COUNT (START < STOP, 2 <= COUNT <= {MAX_SPEEDS}), got "
                         f"'{text}'", field=option) from None
    if not all(math.isfinite(v) and v >= 0 for v in values):
        raise InputError(f"must be non-negative numbers, got '{text}'", field=option)
    return values


def conditions(args: argparse.Namespace, pitch: float):
    """The sweep's operating conditions from ``--rpm`` and ``--wind-speed`` (exactly one a sweep)."""
    from ..models.flutter import OperatingCondition

    rpm, wind = speeds(args.rpm, "--rpm"), speeds(args.wind_speed, "--wind-speed")
    swept = [name for name, values in (("--rpm", rpm), ("--wind-speed", wind)) if values and len(values) > 1]
    if len(swept) != 1:
        raise InputError("sweep exactly one of --rpm and --wind-speed (START:STOP:COUNT); the other is one value",
                         field="--rpm" if not swept else "--wind-speed")
    rpm, wind = rpm or (0.0,), wind or (0.0,)
    if max(rpm) > 0 and min(wind) == 0 and len(wind) > 1:
        raise InputError("a turning rotor's wind-speed sweep must start above 0 m/s (the BEM has no operating "
                         "point there with induction): start the sweep higher", field="--wind-speed")
    return [OperatingCondition(u, r * math.pi / 30.0, pitch) for r in rpm for u in wind]


def run_flutter(args: argparse.Namespace) -> int:
    from ..builders.flutter_inputs import flutter_rotor, structure_notes
    from ..modal import blade_matrices
    from ..models.flutter import flutter_sweep
    from ..report import progress_bar
    from .inputs import is_blade

    for path, field in ((args.plot, "--plot"), (args.vtk, "--vtk")):
        if path is not None:
            (options.check_folder if field == "--vtk" else options.check_output)(path, field)
    blade = read_structure(args)
    if not is_blade(blade):
        raise InputError("flutter is a blade analysis: give a blade input", file=str(args.input), field="INPUT")
    sweep = conditions(args, blade.pitch)
    rotor, centre, notes = flutter_rotor(args.aero, blade, args.blades, all(c.wind_speed == 0.0 for c in sweep))
    matrices = blade_matrices(blade, args.elements, args.n_modes, max(c.rpm for c in sweep))
    notes += structure_notes(matrices)
    progress = progress_bar("Flutter sweep", args.quiet)
    result = flutter_sweep(matrices, rotor, sweep, args.n_modes, centre, tuple(notes), progress)
    if args.plot:
        from ..plots.flutter import save_flutter_plot
        save_flutter_plot(result, args.plot)
    if args.vtk and result.onset is not None:
        write_unstable_mode(blade, matrices, result, args.vtk)
    if args.json:
        for note in result.notes:
            print(f"# {note}", file=sys.stderr)
        print(json.dumps(result.as_dict(), indent=1))
    else:
        print(flutter_text(result))
    return 0


def flutter_text(result) -> str:
    """The sweep as a table (frequency Hz / damping % per mode) and the onset line."""
    lines = [f"# {note}" for note in result.notes]
    count = len(result.points[0].frequency_hz)
    lines.append(f"{'rpm':>8} {'wind m/s':>9}  " + "  ".join(f"{f'mode {j + 1} Hz / %':>18}" for j in range(count)))
    for point in result.points:
        cells = "  ".join(f"{f:8.4f} / {100 * z:7.3f}" + ("" if ok else "?")
                          for f, z, ok in zip(point.frequency_hz, point.damping_ratio, point.converged))
        lines.append(f"{point.condition.rpm:8.3f} {point.condition.wind_speed:9.3f}  {cells}")
    onset = result.onset
    if onset is None:
        lines.append("flutter onset: none in the sweep (every tracked mode stays damped)")
    else:
        shares = ", ".join(f"{name} {share:.2f}" for name, share in onset.shares.items())
        lines.append(f"flutter onset: mode {onset.mode} at {onset.rpm:.5g} rpm, {onset.wind_speed_m_s:.5g} m/s, "
                     f"{onset.frequency_hz:.5g} Hz ({shares})")
    return "\n".join(lines)


def write_unstable_mode(blade, matrices, result, directory: str) -> None:
    """VTK of the mode that goes unstable, at the first unstable point: the real part of its complex shape turned
    so that its largest component is real."""
    import numpy as np

    from ..modal.results import Mode, ModalResult
    from ..modal.solve import mode_shape
    from ..outputs.vtk import write_vtk

    onset = result.onset
    point = result.points[onset.after]
    vector = point.shapes[:, onset.mode - 1]
    vector = vector * np.exp(-1j * np.angle(vector[np.argmax(np.abs(vector))]))
    kind = max(onset.shares, key=onset.shares.get)
    mode = Mode(frequency_hz=float(point.frequency_hz[onset.mode - 1]), kind=kind, energy_fractions={
        **{k: 0.0 for k in ("flap", "edge", "torsion", "axial")}, **onset.shares}, residual=0.0,
        shape=mode_shape(matrices, vector.real, kind),
        damping_ratio=float(point.damping_ratio[onset.mode - 1]),
        damped_frequency_hz=float(point.frequency_hz[onset.mode - 1]))
    modal = ModalResult(rotor_speed_rpm=point.condition.rpm, modes=[mode], stations=blade.sections.span.copy(),
                        vectors=vector.real[:, None], n_dofs=len(matrices.free), notes=result.notes)
    write_vtk(blade, modal, directory, stem="flutter_mode")
