"""``bladefem standstill INPUT --aero AERODYN_PRIMARY --wind-speed U``: stall-induced vibration of a parked blade,
the quasi-steady damping of each blade mode against the wind direction (yaw misalignment, rotor azimuth).

    bladefem standstill BLADE --aero AERODYN.dat --wind-speed 50 --pitch-deg 90 [--yaw-deg -180:180:73]
                        [--azimuth-deg 0] [--tilt-deg 0] [--structural-damping-percent 0.5,0.5]
                        [--n-modes 6] [--json] [--plot FILE.png] [-o FILE]
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from ..errors import InputError
from ..limits import MAX_SPEEDS
from . import options
from .inputs import add_blade_options, positive_int, read_structure


def angles(text: str) -> tuple[float, ...]:
    """A, A1,A2,... or START:STOP:COUNT (deg) -> angles, deg."""
    try:
        if ":" in text:
            start, stop, count = text.split(":")
            a, b, n = float(start), float(stop), int(count)
            if not (1 <= n <= MAX_SPEEDS and a <= b):
                raise argparse.ArgumentTypeError(f"need START <= STOP and 1 <= COUNT <= {MAX_SPEEDS}, got '{text}'")
            values = (a,) if n == 1 else tuple(a + (b - a) * k / (n - 1) for k in range(n))
        else:
            values = tuple(float(part) for part in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected A, A1,A2,... or START:STOP:COUNT in degrees, got '{text}'") \
            from None
    if not all(math.isfinite(v) and abs(v) <= 360.0 for v in values) or len(values) > MAX_SPEEDS:
        raise argparse.ArgumentTypeError(f"angles must be finite, within -360..360 deg and at most {MAX_SPEEDS}, got "
                                         f"'{text}'")
    if any(b <= a for a, b in zip(values, values[1:])):
        raise argparse.ArgumentTypeError(f"angles must increase, got '{text}'")
    return values


def damping_percents(text: str) -> dict[str, float]:
    """FLAP,EDGE[,TORSION] percent of critical -> {'flap': ratio, ...}."""
    try:
        values = [float(part) for part in text.split(",")]
    except ValueError:
        values = []
    if not 2 <= len(values) <= 3 or not all(math.isfinite(v) and 0 <= v < 100 for v in values):
        raise argparse.ArgumentTypeError(f"expected FLAP,EDGE[,TORSION] in percent of critical (0 to 100), got "
                                         f"'{text}'")
    return {kind: value / 100 for kind, value in zip(("flap", "edge", "torsion"), values)}


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "standstill", help="stall-induced vibration of a parked blade: damping of each mode against wind direction",
        description="Quasi-steady aerodynamic damping of each mode of a parked blade in a steady wind, against the "
                    "yaw misalignment (and rotor azimuth), from the airfoil polars' slopes at every section; the "
                    "yaw sectors where a mode's total damping (structural + aerodynamic) is negative.")
    add_blade_options(parser)
    group = parser.add_argument_group("parked rotor and wind")
    group.add_argument("--aero", metavar="AERODYN_PRIMARY", required=True,
                       help="AeroDyn primary file: its first blade file and airfoils (first table of each)")
    group.add_argument("--wind-speed", type=options.positive, required=True, metavar="M_S",
                       help="steady wind speed, m/s")
    group.add_argument("--yaw-deg", type=angles, default=angles("-180:180:73"), metavar="START:STOP:COUNT",
                       help="yaw misalignments, deg: the nacelle yaw from the wind direction, positive anticlockwise "
                            "seen from above (ElastoDyn NacYaw); also A or A1,A2,... (default -180:180:73)")
    group.add_argument("--azimuth-deg", type=angles, default=(0.0,), metavar="A",
                       help="rotor azimuth of the blade, deg (0 up, positive with the rotation); several: A1,A2,... "
                            "or START:STOP:COUNT (default 0)")
    group.add_argument("--tilt-deg", type=options.finite, default=0.0, metavar="DEG",
                       help="shaft tilt, deg, ElastoDyn's ShftTilt sign (default 0)")
    group.add_argument("--structural-damping-percent", type=damping_percents, default=None, metavar="FLAP,EDGE",
                       help="structural damping ratio of the flapwise, edgewise [and torsion] modes, percent of "
                            "critical, added to the aerodynamic (default: an ElastoDyn blade's BldFlDmp(1) and "
                            "BldEdDmp(1), else 0)")
    group.add_argument("--quasi-steady", action="store_true",
                       help="run with the polars' static tables where the AeroDyn file asks for unsteady airfoil "
                            "aerodynamics or a dynamic wake (this analysis is quasi-steady by construction)")
    group.add_argument("--damping-only", action="store_true",
                       help="leave out the aerodynamic stiffness (the section loads of the elastic twist): the "
                            "polars' damping alone, as the classical stall-induced vibration analysis")
    group.add_argument("--blades", type=positive_int, default=3, metavar="N", help="number of blades (default 3)")
    parser.add_argument("--n-modes", type=options.n_modes, default=6, metavar="N", help="modes (default 6)")
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")
    parser.add_argument("--plot", metavar="FILE.png",
                        help="polar plot of each mode's total damping against yaw (and, for several azimuths, the "
                             "least-damped mode's map over yaw and azimuth)")
    parser.add_argument("-o", "--output", metavar="FILE", help="write the table or JSON to FILE instead of stdout")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    parser.set_defaults(run=run_standstill)


def run_standstill(args: argparse.Namespace) -> int:
    options.check_output(args.plot, "--plot")
    options.check_output(args.output, "--output")
    blade = read_structure(args)
    from ..sections import Blade
    if not isinstance(blade, Blade):
        raise InputError("standstill analyses a blade; INPUT describes a tower", file=args.input, field="INPUT")
    from ..builders.aerodyn_rotor import aerodyn_rotor
    from ..modal import blade_matrices
    from ..models.standstill import standstill_sweep, with_tilt
    from ..report import progress_bar

    way = frozenset({"--quasi-steady"})
    rotor = with_tilt(aerodyn_rotor(args.aero, blade, args.blades, way, way if args.quasi_steady else frozenset()),
                      math.radians(args.tilt_deg))
    matrices = blade_matrices(blade, args.elements, args.n_modes, 0.0)
    structural = args.structural_damping_percent
    if structural is None:
        structural = elastodyn_damping(args.input, args.elastodyn_main)
    notes = blade.notes + matrices.notes + rotor.notes[1:] + (
        f"parked rotor (no rotation, no induction), quasi-steady polars of {args.aero}; the spanwise wind "
        "component left out (independence principle); no dynamic stall, no gravity or static deflection",
        "aerodynamic damping alone (--damping-only)" if args.damping_only else
        "aerodynamic damping and stiffness (the loads of the elastic twist; --damping-only leaves the stiffness out)",
        "structural damping " + (", ".join(f"{k} {100 * v:g} %" for k, v in structural.items()) if structural
                                 else "none (aerodynamic damping alone; --structural-damping-percent adds it)")
        + (" (the ElastoDyn blade file's BldFlDmp(1), BldEdDmp(1))" if structural and
           args.structural_damping_percent is None else ""))
    progress = progress_bar("Standstill sweep", args.quiet or args.json)
    result = standstill_sweep(matrices, rotor, args.wind_speed, blade.pitch, args.yaw_deg, args.azimuth_deg,
                              args.n_modes, structural, notes, progress, not args.damping_only)
    if args.plot:
        from ..plots.standstill import save_standstill_plot
        save_standstill_plot(result, args.plot)
    options.emit(json.dumps(result_dict(result), indent=1) + "\n" if args.json else standstill_text(result),
                 args.output)
    if args.plot:
        print(f"# plot written to {args.plot}", file=sys.stderr)
    return 0


def elastodyn_damping(path: str, main: str | None) -> dict[str, float]:
    """The flapwise and edgewise structural damping ratios of an ElastoDyn blade (its main file, or a blade file
    with --elastodyn-main), or none for other inputs."""
    from ..builders.detect import detect_format
    from ..builders.elastodyn_blade import read_elastodyn_blade
    from ..formats.elastodyn_main import read_elastodyn_main

    kind = detect_format(path)
    if kind == "elastodyn-main":
        blade_file = read_elastodyn_main(path).blade_files[0]
    elif kind == "elastodyn-blade" and main is not None:
        blade_file = path
    else:
        return {}
    record = read_elastodyn_blade(blade_file)
    return {"flap": record.flap_damping_percent[0] / 100, "edge": record.edge_damping_percent / 100}


def result_dict(result) -> dict:
    """The sweep as JSON: the negative sectors per mode and azimuth, the minimum, every point."""
    value, mode, point = result.minimum()
    return {
        "wind_speed_m_s": result.wind_speed, "pitch_deg": result.pitch_deg, "modes": list(result.names),
        "minimum": {"total_damping_ratio": value, "mode": mode.name, "yaw_deg": point.yaw_deg,
                    "azimuth_deg": point.azimuth_deg},
        "negative_sectors": {name: {f"{a:g}": [list(s) for s in result.negative_sectors(name, j)]
                                    for j, a in enumerate(result.azimuth_deg)} for name in result.names},
        "points": [{"yaw_deg": p.yaw_deg, "azimuth_deg": p.azimuth_deg, "alpha_deg": list(p.alpha_deg),
                    "modes": [{"name": m.name, "frequency_hz": m.frequency_hz, "divergent": m.divergent,
                               "aerodynamic_damping_ratio": m.aerodynamic, "structural_damping_ratio": m.structural,
                               "total_damping_ratio": m.total, "mac": m.mac, "shares": m.shares} for m in p.modes]}
                   for row in result.points for p in row],
        "notes": list(result.notes)}


def standstill_text(result) -> str:
    """Notes, the total damping ratios (percent) per yaw and azimuth, and the negative sectors."""
    lines = [f"# {note}" for note in result.notes]
    lines.append(f"# parked blade at {result.wind_speed:g} m/s, pitch {result.pitch_deg:g} deg: total damping ratio, "
                 "percent of critical (structural + aerodynamic)")
    lines.append(",".join(["yaw_deg", "azimuth_deg", *result.names]))
    for row in result.points:
        for p in row:
            lines.append(",".join([f"{p.yaw_deg:g}", f"{p.azimuth_deg:g}", *(f"{100 * m.total:.3f}" for m in p.modes)]))
    for j, azimuth in enumerate(result.azimuth_deg):
        for name in result.names:
            sectors = result.negative_sectors(name, j)
            if sectors:
                spans = ", ".join(f"{a:.1f} to {b:.1f}" for a, b in sectors)
                lines.append(f"# negative total damping, {name} at azimuth {azimuth:g} deg: yaw {spans} deg")
    value, mode, point = result.minimum()
    what = "divergence (a real eigenvalue above zero)" if mode.divergent else f"{mode.frequency_hz:.4f} Hz"
    lines.append(f"# least damped: {mode.name} at yaw {point.yaw_deg:g} deg, azimuth {point.azimuth_deg:g} deg: "
                 f"{100 * value:.3f} % ({what})")
    return "\n".join(lines) + "\n"
