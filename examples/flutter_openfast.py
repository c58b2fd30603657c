"""The section of docs/flutter.md that sets bladefem's quasi-steady modes of the NREL 5MW BeamDyn blade turning in
still air beside OpenFAST v5.0.0's BeamDyn + AeroDyn linearization (tests/data/openfast/
blade_aeroelastic_linearization.json); imported by examples/flutter.py."""

from __future__ import annotations

import contextlib
import io
import json
import math
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
REFERENCE = ROOT / "tests/data/openfast/blade_aeroelastic_linearization.json"
BLADE = "tests/data/nrel5mw_beamdyn/bd_primary_nrel_5mw.inp"
AERODYN = "cases/nrel5mw/NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
COMMAND = f"bladefem modes {BLADE} --hub-radius 1.5 --aero {AERODYN} --wind-speed 0 --rpm RPM --n-modes 12"


def modes(rpm: float) -> list[dict]:
    """``bladefem modes ... --aero --wind-speed 0 --json`` at ``rpm``: its modes."""
    from bladefem.cli import main

    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        code = main(COMMAND.replace("RPM", f"{rpm:g}").split()[1:] + ["--json"])
    if code != 0:
        raise SystemExit(f"bladefem modes at {rpm:g} rpm failed with exit {code}")
    return json.loads(out.getvalue())["modes"]


def pairs(rpm: float, theirs: list[dict]) -> list[tuple[dict, dict, float]]:
    """OpenFAST's modes with bladefem's (the pairing of tests/test_flutter_openfast.py: least total relative
    frequency and damping difference, an edge mode's frequency with the spin softening added back)."""
    import numpy as np
    from scipy.optimize import linear_sum_assignment

    spin = rpm / 60
    ours = [m for m in modes(rpm) if m["damping_ratio"] < 1]
    shifted = [math.hypot(m["frequency_hz"], spin) if m["kind"] == "edge" else m["frequency_hz"] for m in ours]
    cost = np.array([[abs(f / t["natural_frequency_hz"] - 1) + abs(m["damping_ratio"] - t["damping_ratio"])
                      for m, f in zip(ours, shifted)] for t in theirs])
    rows, columns = linear_sum_assignment(cost)
    return [(theirs[i], ours[j], shifted[j]) for i, j in zip(rows, columns)]


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
than OpenFAST's (the same sign), a difference not explained here. With the deck's precone of -2.5 deg, OpenFAST
linearizes about the blade bent by its centrifugal load, and at 20 rpm both edge modes then lose their damping
({coned}): the steady flapwise bending couples the edgewise motion with twist (Kallesøe 2011, above); the
comparison sets the precone to 0, as bladefem's blade has it (tests/test_flutter_openfast.py).
"""
