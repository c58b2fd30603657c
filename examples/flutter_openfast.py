"""The section of docs/flutter.md that sets bladefem's quasi-steady modes of the NREL 5MW and IEA-15MW BeamDyn blades
turning in still air beside OpenFAST v5.0.0's BeamDyn + AeroDyn linearizations (tests/data/openfast/
blade_aeroelastic_linearization.json and blade_aeroelastic_linearization_iea15.json); imported by
examples/flutter.py."""

from __future__ import annotations

import contextlib
import io
import json
import math
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
REFERENCE = ROOT / "tests/data/openfast/blade_aeroelastic_linearization.json"
BLADE = "tests/data/nrel5mw_beamdyn/bd_primary_nrel_5mw.inp"
AERODYN = "cases/nrel5mw/NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
COMMAND = f"bladefem modes {BLADE} --hub-radius 1.5 --aero {AERODYN} --wind-speed 0 --rpm RPM --n-modes 12"


def modes(rpm: float, command: str = COMMAND) -> list[dict]:
    """``command`` (``bladefem modes ... --aero --wind-speed 0``) with ``--json`` at ``rpm``: its modes."""
    from bladefem.cli import main

    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        code = main(command.replace("RPM", f"{rpm:g}").split()[1:] + ["--json"])
    if code != 0:
        raise SystemExit(f"bladefem modes at {rpm:g} rpm failed with exit {code}")
    return json.loads(out.getvalue())["modes"]


def pairs(rpm: float, theirs: list[dict], command: str = COMMAND) -> list[tuple[dict, dict, float]]:
    """OpenFAST's modes with bladefem's (the pairing of tests/test_flutter_openfast.py: least total relative
    frequency and damping difference, an edge mode's frequency with the spin softening added back)."""
    import numpy as np
    from scipy.optimize import linear_sum_assignment

    spin = rpm / 60
    ours = [m for m in modes(rpm, command) if m["damping_ratio"] < 1]
    shifted = [math.hypot(m["frequency_hz"], spin) if m["kind"] == "edge" else m["frequency_hz"] for m in ours]
    cost = np.array([[abs(f / t["natural_frequency_hz"] - 1) + abs(m["damping_ratio"] - t["damping_ratio"])
                      for m, f in zip(ours, shifted)] for t in theirs])
    rows, columns = linear_sum_assignment(cost)
    return [(theirs[i], ours[j], shifted[j]) for i, j in zip(rows, columns)]


def edge(modes: list[dict]) -> dict:
    """The first edge mode among OpenFAST's 5MW modes (1.1 to 1.3 Hz)."""
    return next(m for m in modes if 1.1 < m["natural_frequency_hz"] < 1.3)


def section() -> str:
    reference = json.loads(REFERENCE.read_text())
    lines = ["| rpm | bladefem mode | OpenFAST Hz | bladefem Hz | OpenFAST damping % | bladefem damping % |",
             "|---|---|---|---|---|---|"]
    for point in reference["points"]:
        for theirs, ours, shifted in sorted(pairs(point["rpm"], point["modes"][:6]),
                                            key=lambda pair: pair[0]["natural_frequency_hz"]):
            frequency = f"{ours['frequency_hz']:.4f}" + (f" ({shifted:.4f})" if ours["kind"] == "edge" else "")
            lines.append(f"| {point['rpm']:g} | {ours['kind']} | {theirs['natural_frequency_hz']:.4f} | {frequency} | "
                         f"{100 * theirs['damping_ratio']:.3f} | {100 * ours['damping_ratio']:.3f} |")
    table = "\n".join(lines)
    early = "OpenFAST's first edge mode's damping ratio is " + ", ".join(
        f"{100 * edge(point['modes'])['damping_ratio']:.3f} % at {point['rpm']:g} rpm"
        for point in reference.get("lin_time_0_points", [])) + (
        " against bladefem's " + ", ".join(f"{100 * ours['damping_ratio']:.3f} %" for ours in (
            next(o for t, o, f in pairs(point["rpm"], point["modes"][:6]) if o["kind"] == "edge" and f < 1.5)
            for point in reference.get("lin_time_0_points", []))) + ".")
    (coned_point,) = reference["coned_points"]
    coned = ", ".join(f"{100 * m['damping_ratio']:.2f} % at {m['natural_frequency_hz']:.2f} Hz"
                      for m in coned_point["modes"] if 1.0 < m["natural_frequency_hz"] < 1.3
                      or 3.7 < m["natural_frequency_hz"] < 3.9)
    return f"""## Against OpenFAST's linearization (quasi-steady)

OpenFAST v5.0.0 linearized the same NREL 5MW BeamDyn blade turning in still air (the hub held, every ElastoDyn DOF
off, no gravity, no precone, pitch 0; AeroDyn's polars without induction and without unsteady airfoil
aerodynamics, no tower; tests/data/openfast/blade_aeroelastic_linearization.json and the script that writes it).
Its state matrix's block on blade 1 gives the modes below, set beside bladefem's quasi-steady modes at the same
rotor speeds (`{COMMAND}`: the section loads with the induction frozen, no Theodorsen lag, no apparent mass, no
pitch-rate term, as AeroDyn linearizes them). An edge mode's bladefem frequency is followed by that frequency
with the spin softening added back (sqrt(f^2 + (rpm/60)^2)): BeamDyn's rotating-frame linearization does not show
the in-plane -Omega^2 term (tests/test_beamdyn_reference.py). The first flap mode is overdamped in both from 16 rpm
on and is left out.

{table}

Below the coalescence (12.1 to 24 rpm) the two linearizations agree mode by mode (frequencies within 2 %, damping
ratios within 8 % plus 0.15 percentage point, the first edge mode's to 20 rpm), the torsion-carrying mode (named
torsion at rated speed, flap above, as its kinetic energy turns flapwise) included: quasi-steady, it is unstable
from rated speed on in both, because AeroDyn's section loads, like bladefem's quasi-steady ones, leave out the
pitch-rate (three-quarter-chord) damping of a twisting section, which `bladefem flutter` keeps; with it, every
tracked mode between 3.5 and 5.5 Hz stays damped up to the coalescence near 28 rpm (the 5MW table above). At 28 rpm that mode has fallen onto the second edge mode in both, about equally
unstable, its frequency 5 % apart. The first edge mode's damping agrees to 20 rpm; above, bladefem's falls faster
than OpenFAST's (the same sign) because OpenFAST linearizes at 0.02 s, when the blade has started to twist under
the airfoils' pitching moment, suddenly applied at 0 s; linearized at 0 s, the undeflected blade bladefem models,
{early} With the deck's precone of -2.5 deg, OpenFAST
linearizes about the blade bent by its centrifugal load, and at 20 rpm both edge modes then lose their damping
({coned}): the steady flapwise bending couples the edgewise motion with twist (Kallesøe 2011, above); the
comparison sets the precone to 0, as bladefem's blade has it (tests/test_flutter_openfast.py).
"""


IEA15_REFERENCE = ROOT / "tests/data/openfast/blade_aeroelastic_linearization_iea15.json"
IEA15_COMMAND = ("bladefem modes tests/data/iea15/beamdyn/IEA-15-240-RWT_BeamDyn.dat --hub-radius 3.97 "
                 "--straight-axis --aero {deck}/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_AeroDyn15.dat "
                 "--wind-speed 0 --rpm RPM --n-modes 16")
#: OpenFAST's modes compared at each rotor speed (as tests/test_flutter_openfast_iea15.py)
IEA15_COMPARED = 7


def iea15_script():
    """tests/data/openfast/make_blade_aeroelastic_iea15.py as a module (its bladefem_aerodyn writes the deck)."""
    import importlib.util

    path = ROOT / "tests/data/openfast/make_blade_aeroelastic_iea15.py"
    spec = importlib.util.spec_from_file_location("make_blade_aeroelastic_iea15", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def crossing(rpms: list[float], modes: list[dict | None], damping: str, frequency: str) -> tuple[float, float]:
    """The first rotor speed (rpm) where a tracked mode's damping ratio turns negative and its frequency there (Hz),
    linear between the points; (nan, nan) if it does not."""
    for k in range(1, len(rpms)):
        a, b = modes[k - 1], modes[k]
        if a is not None and b is not None and a[damping] >= 0 > b[damping]:
            t = a[damping] / (a[damping] - b[damping])
            return rpms[k - 1] + t * (rpms[k] - rpms[k - 1]), a[frequency] + t * (b[frequency] - a[frequency])
    return math.nan, math.nan


def iea15_section() -> str:
    reference = json.loads(IEA15_REFERENCE.read_text())
    rows, paired = [], {}
    with tempfile.TemporaryDirectory() as folder:
        iea15_script().bladefem_aerodyn(Path(folder))
        command = IEA15_COMMAND.format(deck=folder)
        for point in reference["points"]:
            paired[point["rpm"]] = sorted(pairs(point["rpm"], point["modes"][:IEA15_COMPARED], command),
                                          key=lambda pair: pair[0]["natural_frequency_hz"])
    for rpm, found in paired.items():
        for theirs, ours, shifted in found:
            frequency = f"{ours['frequency_hz']:.4f}" + (f" ({shifted:.4f})" if ours["kind"] == "edge" else "")
            rows.append(f"| {rpm:g} | {ours['kind']} | {theirs['natural_frequency_hz']:.4f} | {frequency} | "
                        f"{100 * theirs['damping_ratio']:.3f} | {100 * ours['damping_ratio']:.3f} |")
    rpms = list(paired)

    def tracked(test) -> tuple[list, list]:
        """The OpenFAST modes and bladefem's (their frequency an edge mode's with the spin softening added back)
        of the pair ``test`` picks at each speed (None where none does)."""
        chosen = [next(((t, {**o, "frequency_hz": f}) for t, o, f in paired[rpm] if test(t, o)), (None, None))
                  for rpm in rpms]
        return [t for t, _ in chosen], [o for _, o in chosen]
    edge_theirs, edge_ours = tracked(lambda t, o: o["kind"] == "edge" and t["natural_frequency_hz"] < 1.5)
    torsion_theirs, torsion_ours = tracked(lambda t, o: 3.0 < t["natural_frequency_hz"] < 4.0)
    onsets = {name: (crossing(rpms[:k], theirs[:k], "damping_ratio", "natural_frequency_hz"),
                     crossing(rpms[:k], ours[:k], "damping_ratio", "frequency_hz"))
              for name, theirs, ours, k in (("torsion", torsion_theirs, torsion_ours, 3),
                                            ("edge", edge_theirs, edge_ours, len(rpms)))}
    (first_theirs, first_ours), at = (edge_theirs[rpms.index(13.5)], edge_ours[rpms.index(13.5)]), 13.5
    (structural,) = [p for p in reference["structural_points"] if p["rpm"] == at]
    structural_edge = max(structural["modes"][:IEA15_COMPARED], key=lambda m: m["damping_ratio"])

    def onset(name: str) -> str:
        (r1, f1), (r2, f2) = onsets[name]
        return f"OpenFAST {r1:.2f} rpm at {f1:.3f} Hz, bladefem {r2:.2f} rpm at {f2:.3f} Hz"
    late = {p["rpm"]: p for p in reference["lin_time_0.02_points"]}
    early_edges = [m for m in next(p for p in reference["points"] if p["rpm"] == at)["modes"]
                   if m["natural_frequency_hz"] < 2.4 and abs(m["damping_ratio"]) < 0.05]
    late_edges = [m for m in late[at]["modes"] if m["natural_frequency_hz"] < 2.4 and abs(m["damping_ratio"]) < 0.05]
    table = "\n".join(["| rpm | bladefem mode | OpenFAST Hz | bladefem Hz | OpenFAST damping % | bladefem damping % |",
                       "|---|---|---|---|---|---|"] + rows)
    return f"""### IEA-15MW

OpenFAST v5.0.0 linearized the IEA-15MW BeamDyn blade the same way (its six-by-six sections, all 50 polars;
tests/data/openfast/blade_aeroelastic_linearization_iea15.json and make_blade_aeroelastic_iea15.py), with the blade
straightened in both tools: BeamDyn's key points on the pitch axis (bladefem's `--straight-axis`) and the AeroDyn
blade's aerodynamic-centre offsets and cant zero. A prebent blade bends back under its centrifugal load and BeamDyn
linearizes about that bent blade, bladefem's quasi-steady modes about the undeflected one; straight and without
precone, both linearize about the same blade. OpenFAST linearizes at 0 s, the blade as BeamDyn's quasi-static
initialization leaves it (the centrifugal load alone), before the aerodynamic loads act. bladefem:
`{IEA15_COMMAND.format(deck="DECK")}`, `DECK` the AeroDyn files as the script's `bladefem_aerodyn` writes them
(quasi-steady polars, no tower, the blade file straightened).

{table}

The quasi-steady onsets (the damping's zero crossing, linear between the rotor speeds above): the torsion-carrying
mode near 3.9 Hz, unstable from 5 rpm on in both, {onset("torsion")}; the first edge mode {onset("edge")}
(bladefem's frequency with the spin softening added back). To 11 rpm the two agree mode by mode (frequencies within
0.4 %, damping ratios within 8 % plus 0.15 percentage point), but for the first edge mode's damping above rated
speed, which bladefem's model loses faster ({100 * first_ours["damping_ratio"]:.2f} % against
{100 * first_theirs["damping_ratio"]:.2f} % at {at:g} rpm).
The difference comes from the sections' mass centres, which lie off the reference axis: OpenFAST's BeamDyn
linearization of this turning blade is not conservative with them. Without aerodynamics and with its damping
off it damps its lowest modes ({100 * structural_edge["damping_ratio"]:.2f} % on the first edge mode at {at:g} rpm),
where an undamped rotating beam (bladefem's) has none: its eigenvalues come in pairs lambda, -conj(lambda). With
the mass centres moved onto the axis in both tools (the mass matrices' translation-rotation blocks set to 0) the
blade is conservative in OpenFAST too, and every compared mode agrees above rated speed, the first edge mode's
damping included: 0.13 % against 0.09 % at 11 rpm, -1.02 % against -1.06 % at 13.5 rpm, -1.758 % against -1.759 %
with every airfoil's Cm constant at -0.1 (tests/test_flutter_openfast_mass_offsets.py). On the stored blade
OpenFAST's extra damping is even in the pitching moment (with every Cm turned in sign, the part odd in the moment
agrees: -3.20 against -3.03 percentage points; OpenFAST's even part, +0.50 point, has no counterpart in
bladefem). OpenFAST/openfast#3394 reports BeamDyn's state Jacobians to be an inertial-frame snapshot; the transform
of its proposed fix (OpenFAST/openfast#3400) gives BeamDyn's edge modes bladefem's spin softening (0.7209 Hz in
both at 13.5 rpm) but leaves the blade with mass offsets non-conservative. From 16 rpm on, as
the torsion-carrying mode falls toward the flap modes, the modes between 2 and 3.5 Hz differ by up to 3 % in
frequency.

With Theodorsen's unsteady lift and the pitch-rate damping (`bladefem flutter` on the same straight blade) the
torsion-carrying mode stays damped and the edge mode is the first to lose its damping; on the prebent blade (the
IEA-15MW sweep above) the first onset is a flap mode with twist.

When OpenFAST linearizes matters: at 0.02 s, as the NREL 5MW comparison does, the blade is caught in the motion the
suddenly applied aerodynamic loads start (at {at:g} rpm its tip has twisted by
{math.degrees(late[at]["tip_twist_rad"]):.1f} deg, the airfoils' pitching
moment acting), and its edge modes' damping is then {", ".join(f"{100 * m['damping_ratio']:.2f} %" for m in late_edges)}
against {", ".join(f"{100 * m['damping_ratio']:.2f} %" for m in early_edges)} at 0 s (`lin_time_0.02_points`).
"""
