"""Blade flutter with unsteady section aerodynamics: writes docs/flutter.md (and its two diagrams).

    python examples/flutter.py [--output docs/flutter.md]

Runs ``bladefem flutter`` on the Goland wing (the first command of cases/goland_wing/README.md) and on the NREL
5MW blade with its BeamDyn sections turning in still air, and tabulates the damping of each tracked mode.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import os
import shlex
import sys
import tempfile
from pathlib import Path

import numpy as np

from bladefem.cli import main as bladefem

ROOT = Path(__file__).resolve().parent.parent
GOLAND = next(line for line in (ROOT / "cases/goland_wing/README.md").read_text().splitlines()
              if line.startswith("bladefem flutter"))
NREL5MW = ("bladefem flutter tests/data/nrel5mw_beamdyn/bd_primary_nrel_5mw.inp --hub-radius 1.5 "
           "--aero cases/nrel5mw/NRELOffshrBsline5MW_Onshore_AeroDyn.dat --rpm 8:32:13 --n-modes 6")
RATED_RPM = 12.1
IEA15 = ("bladefem flutter tests/data/iea15/beamdyn/IEA-15-240-RWT_BeamDyn.dat --hub-radius 3.97 --aero "
         "{deck}/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_AeroDyn15.dat --rpm 4:22:19 --n-modes 6")
IEA15_RATED_RPM = 7.56


def run(command: str, plot: Path | None = None) -> dict:
    """The JSON that ``COMMAND --json`` prints, run from the repository root (notes on stderr dropped)."""
    argv = shlex.split(command)[1:] + ["--json", "--quiet"] + (["--plot", str(plot)] if plot else [])
    out, here = io.StringIO(), os.getcwd()
    os.chdir(ROOT)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
            code = bladefem(argv)
    finally:
        os.chdir(here)
    if code != 0:
        raise SystemExit(f"{command} failed with exit {code}")
    return json.loads(out.getvalue())


def sweep_table(result: dict, swept: str) -> str:
    count = len(result["sweep"][0]["modes"])
    header = [swept] + [f"mode {j + 1} Hz" for j in range(count)] + [f"mode {j + 1} damping %" for j in range(count)]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for point in result["sweep"]:
        value = point["rpm"] if swept == "rpm" else point["wind_speed_m_s"]
        cells = [f"{value:.2f}"] + [f"{m['frequency_hz']:.3f}" for m in point["modes"]]
        cells += [f"{100 * m['damping_ratio']:.2f}" for m in point["modes"]]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def crossing(result: dict, mode: int) -> float:
    """The rotor speed (rpm) where tracked ``mode`` (1-based) first turns unstable, interpolated; nan if never."""
    points = result["sweep"]
    for a, b in zip(points, points[1:]):
        za, zb = a["modes"][mode - 1]["damping_ratio"], b["modes"][mode - 1]["damping_ratio"]
        if za >= 0 > zb:
            return a["rpm"] + za / (za - zb) * (b["rpm"] - a["rpm"])
    return float("nan")


def classical(result: dict) -> tuple[float, int]:
    """(rpm, mode) of the earliest crossing among the modes other than the onset's."""
    count = len(result["sweep"][0]["modes"])
    return min((crossing(result, j), j) for j in range(1, count + 1)
               if j != result["onset"]["mode"] and not math.isnan(crossing(result, j)))


EDGE_RPM = 28.0


def edge_terms() -> str:
    """The first edgewise mode's damping ratio (%) at EDGE_RPM in still air with all section loads and with the
    pitching moment, the lift or the drag taken out (the 5MW sweep's model: BeamDyn sections, no induction)."""
    from dataclasses import replace

    from bladefem.builders.aerodyn_rotor import aerodyn_rotor
    from bladefem.builders.detect import Geometry, read_model
    from bladefem.modal import blade_matrices
    from bladefem.models.blade_aero import operating_point
    from bladefem.models.flutter_aero import flutter_sections
    from bladefem.models.flutter_basis import ReducedAero, SweepBasis
    from bladefem.models.flutter_pk import pk_root

    blade = read_model(ROOT / "tests/data/nrel5mw_beamdyn/bd_primary_nrel_5mw.inp", None, Geometry(hub_radius=1.5))
    rotor = aerodyn_rotor(ROOT / "cases/nrel5mw/NRELOffshrBsline5MW_Onshore_AeroDyn.dat", blade, 3)
    rotor = replace(rotor, options=replace(rotor.options, induction=False))
    speed = EDGE_RPM * math.pi / 30
    matrices = blade_matrices(blade, None, 6, EDGE_RPM)
    basis = SweepBasis(matrices, [speed], 18)
    K = basis.stiffness(speed)
    values, vectors = np.linalg.eigh(K)
    op = operating_point(rotor, 0.0, speed, 0.0)
    cases = {"all": op, "no pitching moment": replace(op, cm=0 * op.cm, dcm=0 * op.dcm),
             "no lift": replace(op, cl=0 * op.cl), "no drag": replace(op, cd=0 * op.cd)}
    edge = 1                                    # the second undamped mode: the first edgewise
    out = []
    for name, point in cases.items():
        aero = ReducedAero(basis, flutter_sections(point))
        root = pk_root(np.eye(basis.size), speed * basis.G, K, aero, math.sqrt(values[edge]),
                       vectors[:, edge].astype(complex))
        out.append(f"{name} {100 * root.damping_ratio:.2f} %")
    return ", ".join(out)


def path_of(result: dict, mode: int) -> str:
    """Tracked ``mode`` (1-based): its frequency at the sweep's first and last points and its shares at both."""
    first, last = (result["sweep"][i]["modes"][mode - 1] for i in (0, -1))

    def shares(m: dict) -> str:
        return ", ".join(f"{name} {share:.2f}" for name, share in m["shares"].items())
    return (f"{first['frequency_hz']:.2f} Hz with {shares(first)} at the first point, {last['frequency_hz']:.2f} Hz "
            f"with {shares(last)} at the last")


def onset_line(onset: dict | None) -> str:
    if onset is None:
        return "no onset in the sweep"
    shares = ", ".join(f"{name} {share:.2f}" for name, share in onset["shares"].items())
    return (f"mode {onset['mode']} at {onset['rpm']:.2f} rpm, {onset['wind_speed_m_s']:.2f} m/s, "
            f"{onset['frequency_hz']:.3f} Hz ({2 * math.pi * onset['frequency_hz']:.2f} rad/s); shares {shares}")


def iea15(folder: Path) -> dict:
    """The IEA-15MW sweep on a complete copy of the stored deck (tests/deck_copies.py)."""
    sys.path.insert(0, str(ROOT / "tests"))
    from deck_copies import deck_copy

    with tempfile.TemporaryDirectory() as temporary:
        deck = deck_copy("iea15", Path(temporary))
        return run(IEA15.format(deck=deck), folder / "flutter-iea15.png")


def document(folder: Path) -> str:
    goland = run(GOLAND, folder / "flutter-goland.png")
    five = run(NREL5MW, folder / "flutter-nrel5mw.png")
    fifteen = iea15(folder)
    g, f, i = goland["onset"], five["onset"], fifteen["onset"]
    return f"""# Blade flutter: damping of each mode with unsteady aerodynamics

This page is written by `python examples/flutter.py` (do not edit by hand). The model (Theodorsen's function in a
p-k iteration, pitch rate, apparent mass, on the blade's modal reduction at each operating point) is derived in
[THEORY.md](THEORY.md#flutter-unsteady-section-aerodynamics-bladefem-flutter).

## The Goland wing

```bash
{GOLAND}
```

Onset: {onset_line(g)}. Goland (1945): 137 m/s, 70.7 rad/s; the exact continuous-wing solution with Theodorsen
strip aerodynamics (ContourRoots): 136.984 m/s, 70.033 rad/s. bladefem's speed differs from the exact one by
{100 * (g['wind_speed_m_s'] / 136.984 - 1):+.2f} %, its frequency by {100 * (2 * math.pi * g['frequency_hz'] / 70.033 - 1):+.2f} %
(cases/goland_wing/README.md).

{sweep_table(goland, "wind m/s")}

![Goland wing](flutter-goland.png)

## NREL 5MW blade turning in still air

```bash
{NREL5MW}
```

The BeamDyn sections (torsion, centre-of-mass and shear-centre offsets; the ElastoDyn blade has no torsion and
cannot flutter), the AeroDyn blade and polars of the 5MW deck, the rotor turning in still air (no induction: the
relative velocity is the rotation alone), pitch 0, no structural damping.

First onset: {onset_line(f)}: {f['rpm'] / RATED_RPM:.2f} times the rated {RATED_RPM} rpm.

{sweep_table(five, "rpm")}

![NREL 5MW](flutter-nrel5mw.png)

What the figures say: in still air the first edgewise mode loses its small aerodynamic damping first. The sections
meet the air at minus their twist (-13 to 0 deg), where they carry negative lift and a pitching moment; their lift
slopes stay positive. Taking parts out of the section loads at {EDGE_RPM:g} rpm tells which ones drive it (first
edgewise damping ratio: {edge_terms()}): without the airfoils' pitching moment or without their lift the mode stays
damped, without drag it is less damped still. The steady pitching moment and lift of the negatively loaded
sections couple the edgewise motion with twist: an instability of the blade turning in still air, not the
classical coupling. The coupled flutter follows higher: mode {classical(five)[1]}
({path_of(five, classical(five)[1])}) crosses zero at {classical(five)[0]:.1f} rpm
({classical(five)[0] / RATED_RPM:.2f} times rated, interpolated): a torsion-dominated mode whose frequency falls
toward the flap modes as the rotor speeds up and which takes on flapwise motion, the classical coalescence (the
kinetic-energy shares understate the twist, whose inertia is small). Multi-megawatt blades are reported to flutter at about twice their operating speed: Lobitz (2004, Wind
Energy 7) found about twice for a 1.5 MW blade (as summarised by Shakya, Sunny and Maiti 2020, Mech. Based Des.
Struct. Mach.). Published flutter speeds of the 5MW and IEA-15MW blades differ with the section data and
aerodynamics used and were not available to check here: the tests hold the onset to 1.5-3 times rated.

## IEA-15MW blade turning in still air

```bash
{IEA15.format(deck="DECK")}
```

`DECK` is a copy of the stored IEA-15-240-RWT deck (tests/data/iea15, all 50 airfoil polars; tests/deck_copies.py).
The BeamDyn sections are the IEA-15MW's own (six-by-six, with every coupling, transverse shear kept, on the
prebent reference axis). No published flutter speed of this blade was found to compare with. AeroDyn's unsteady airfoil model (`AFAeroMod` 2) and tower
settings are named and replaced (Theodorsen's theory, the blade alone).

First onset: {onset_line(i)}: {i['rpm'] / IEA15_RATED_RPM:.2f} times the rated {IEA15_RATED_RPM} rpm. The
strongly unstable mode that follows is mode {classical(fifteen)[1]} ({path_of(fifteen, classical(fifteen)[1])}),
from {classical(fifteen)[0]:.1f} rpm ({classical(fifteen)[0] / IEA15_RATED_RPM:.2f} times rated).

{sweep_table(fifteen, "rpm")}

![IEA-15MW](flutter-iea15.png)

## Stall-induced vibration at standstill

A parked or idling blade is not safe from negative damping either: in stall, the polars' negative lift slopes feed
energy into the flap and edge modes at large yaw misalignments. That analysis (`bladefem standstill`, the damping of
each mode against yaw and azimuth, the NREL 5MW and IEA-15MW maps, the comparison with OpenFAST's linearization)
has its own page: [standstill.md](standstill.md).

## Command line

```text
bladefem flutter BLADE --aero AERODYN_PRIMARY --rpm START:STOP:COUNT [--wind-speed U] [--pitch-deg P]
bladefem flutter BLADE --aero AERODYN_PRIMARY --wind-speed START:STOP:COUNT [--rpm R] [--pitch-deg P]
                 [--n-modes N] [--blades N] [--plot FILE.png] [--vtk DIR] [--json]
```

`--json` prints `{{"onset": {{"rpm", "wind_speed_m_s", "frequency_hz", "mode", "shares"}} or null, "sweep":
[{{"rpm", "wind_speed_m_s", "pitch_deg", "modes": [{{"mode", "frequency_hz", "damping_ratio", "shares",
"converged"}}]}}], "notes": [...]}}`. The frequency is the damped frequency `Im(p) / 2 pi`, the damping ratio
`-Re(p) / |p|`. `--vtk DIR` writes the unstable mode's shape at the first unstable point. AeroDyn's unsteady airfoil
model, dynamic wake and tower settings are accepted and named: the flutter analysis replaces them (Theodorsen's
theory, frozen induction, the blade alone).
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=str(ROOT / "docs" / "flutter.md"))
    args = parser.parse_args()
    output = Path(args.output)
    output.write_text(document(output.parent))


if __name__ == "__main__":
    main()
