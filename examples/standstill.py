"""Stall-induced vibration of the parked NREL 5MW and IEA-15MW blades against yaw: writes docs/standstill.md and,
beside it, its figures (standstill-nrel5mw.png, standstill-iea15mw.png).

    python examples/standstill.py [--output docs/standstill.md]

Runs ``bladefem standstill`` on each blade feathered (pitch 90 deg) in a 50 m/s wind (the order of the 50-year
extreme of IEC class I) over yaw misalignments of -180 to 180 deg every 5 deg, blade 1 pointing up, with the decks'
structural damping, and the IEA-15MW also at the three blades' azimuths (0, 120, 240 deg).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
from pathlib import Path

from bladefem.cli import main as bladefem

ROOT = Path(__file__).resolve().parent.parent
NREL5MW = ("cases/nrel5mw/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat", "--aero",
           "cases/nrel5mw/NRELOffshrBsline5MW_Onshore_AeroDyn.dat", "--tilt-deg", "-5",
           "--structural-damping-percent", "0.477465,0.477465")
IEA15 = ("tests/data/iea15/beamdyn/IEA-15-240-RWT_BeamDyn.dat", "--aero",
         "tests/data/iea15/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_AeroDyn15.dat", "--quasi-steady",
         "--damping-only", "--precone-deg", "-4", "--tilt-deg", "-6", "--structural-damping-percent", "0.48,0.48")
SWEEP = ("--wind-speed", "50", "--pitch-deg", "90", "--yaw-deg=-180:180:73", "--elements", "60", "--n-modes", "6")


def run(*argv: str) -> dict:
    """The JSON that ``bladefem standstill ARGV --json`` prints (notes on stderr are dropped)."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        code = bladefem(["standstill", *argv, "--json", "--quiet"])
    if code != 0:
        raise SystemExit(f"bladefem standstill {' '.join(argv)} failed with exit {code}")
    return json.loads(out.getvalue())


def command(args: tuple[str, ...], extra: tuple[str, ...] = ()) -> str:
    return "bladefem standstill " + " ".join((*args, *SWEEP, *extra))


def sector_table(data: dict) -> str:
    """Per mode: frequency at yaw 0, least total damping and where, the negative sectors at each azimuth."""
    lines = ["| mode | frequency at yaw 0, Hz | least total damping, % (yaw, azimuth) | negative total damping, yaw "
             "sectors in deg |", "|---|---|---|---|"]
    for name in data["modes"]:
        modes = [(p, m) for p in data["points"] for m in p["modes"] if m["name"] == name]
        aligned = next(m for p, m in modes if p["yaw_deg"] == 0 and p["azimuth_deg"] == data["points"][0][
            "azimuth_deg"])
        point, least = min(modes, key=lambda item: item[1]["total_damping_ratio"])
        sectors = "; ".join(f"azimuth {azimuth}: " + ", ".join(f"{a:.0f} to {b:.0f}" for a, b in spans)
                            for azimuth, spans in data["negative_sectors"][name].items() if spans) or "none"
        frequency = ("divergent" if aligned["divergent"] else "overdamped" if aligned["total_damping_ratio"] >= 1
                     else f"{aligned['frequency_hz']:.3f}")
        lines.append(f"| {name} | {frequency} | {100 * least['total_damping_ratio']:.2f} ({point['yaw_deg']:g}, "
                     f"{point['azimuth_deg']:g}) | {sectors} |")
    return "\n".join(lines)


def maps(folder: Path) -> tuple[dict, dict]:
    """The NREL 5MW and IEA-15MW yaw sweeps (``--json``); their figures are written into ``folder``."""
    nrel = run(*NREL5MW, *SWEEP, "--plot", str(folder / "standstill-nrel5mw.png"))
    iea = run(*IEA15, *SWEEP, "--azimuth-deg", "0,120,240", "--plot", str(folder / "standstill-iea15mw.png"))
    return nrel, iea


def document(folder: Path, sweeps: tuple[dict, dict] | None = None) -> str:
    """The page; its figures are written into ``folder`` (beside it) unless ``sweeps`` (from :func:`maps`) are
    given."""
    nrel, iea = sweeps or maps(folder)
    return f"""# Stall-induced vibration at standstill

This page is written by `python examples/flutter.py` (beside docs/flutter.md) or `python examples/standstill.py`
(do not edit by hand).

A parked or idling rotor in a storm meets the wind from any direction when the yaw system has failed or lost its
grid. A blade section then sees the wind at any angle of attack, often in deep stall, where the lift falls as the
angle grows: a section moving across the wind changes its angle of attack so that the load pushes it further, and
the mode loses its damping. `bladefem standstill` computes, for a parked blade in a steady wind, the quasi-steady
aerodynamic damping of each blade mode against the yaw misalignment (and the rotor azimuth), adds the structural
damping, and reports the yaw sectors where a mode's total damping is negative (derivation: [THEORY.md](THEORY.md),
"Parked blade").

## Command line

```text
bladefem standstill INPUT --aero AERODYN_PRIMARY --wind-speed U [--pitch-deg P] [--yaw-deg=START:STOP:COUNT]
                    [--azimuth-deg A|A1,A2,...] [--tilt-deg T] [--structural-damping-percent FLAP,EDGE[,TORSION]]
                    [--quasi-steady] [--damping-only] [--n-modes N] [--elements N] [--json] [--plot FILE.png]
                    [-o FILE]
```

`INPUT` is any blade bladefem reads (ElastoDyn, BeamDyn, HAWC2, windIO, BModes, case files; `--pitch-deg` pitches
its structure). The yaw misalignment is the nacelle yaw from the wind direction, positive anticlockwise seen from
above (ElastoDyn's `NacYaw`); write a range starting below zero with `=` (`--yaw-deg=-180:180:73`, the default).
The azimuth is blade 1's (0 up, positive with the rotation): `--azimuth-deg 0,120,240` covers the three blades of a
parked rotor. `--tilt-deg` is ElastoDyn's `ShftTilt`, the precone the blade's (`--precone-deg`). The rotor does not
turn and has no induction (AeroDyn's `WakeMod` 0 for a parked rotor): each AeroDyn node sees the wind resolved on the
coned blade's out-of-plane normal and its in-plane direction; the component along the blade is left out
(independence principle). `--quasi-steady` runs an AeroDyn file that asks for unsteady airfoil aerodynamics with its
static polars (the analysis is quasi-steady by construction). `--structural-damping-percent` defaults to an
ElastoDyn blade's `BldFlDmp(1)` and `BldEdDmp(1)` (0 for other inputs). `--damping-only` leaves out the aerodynamic
stiffness (the loads of the elastic twist), as the classical stall-induced vibration analysis does. Modes are named
after the undamped blade modes they continue; bending is named in the frame of the pitched chord, so the flapwise
mode of a feathered blade, which moves in the rotor plane, is `flap 1`.

Printed: the total damping ratio (per cent of critical) of each mode at each yaw and azimuth, then the negative
sectors (ends interpolated) and the least damped point. `--json` prints `{{"wind_speed_m_s", "pitch_deg", "modes",
"minimum": {{"total_damping_ratio", "mode", "yaw_deg", "azimuth_deg"}}, "negative_sectors": {{MODE: {{AZIMUTH:
[[start, stop], ...]}}}}, "points": [{{"yaw_deg", "azimuth_deg", "alpha_deg", "modes": [{{"name", "frequency_hz",
"divergent", "aerodynamic_damping_ratio", "structural_damping_ratio", "total_damping_ratio", "mac", "shares"}}]}}]}}`.
A damping ratio is a fraction of critical; a real eigenvalue above zero (a divergence, `"divergent": true`) has
damping ratio -1 and a negative frequency. `--plot` draws each mode's total damping against yaw (negative sectors
shaded) and, for several azimuths, the least total damping over yaw and azimuth. In `bladefem check` the requirement
`standstill_damping` holds a model's least total damping over a yaw range ([check.md](check.md)); in `bladefem batch`
the analysis `standstill` runs the sweep per case ([batch.md](batch.md)).

## NREL 5MW, feathered, 50 m/s

```bash
{command(NREL5MW)}
```

ElastoDyn blade (flap and edge bending, rigid torsion), the deck's AeroDyn polars, the deck's 0.477465 % structural
damping, shaft tilt -5 deg, blade 1 up:

{sector_table(nrel)}

![NREL 5MW parked at 50 m/s](standstill-nrel5mw.png)

The first edgewise mode loses its damping on both sides of the wind, at yaw misalignments of about 12 to 56 deg on
the negative side and 15 to 37 deg on the positive side, and near 160 to 173 deg; the flapwise modes (in the rotor
plane when feathered) lose theirs in a narrower sector near 20 to 33 deg. For this rotor, idling and feathered,
Jonkman and Buhl (2007, "Loads Analysis of a Floating Offshore Wind Turbine Using Fully Coupled Simulation",
NREL/CP-500-41714) report instabilities of the blade-edgewise mode at large yaw errors in the parked design load
case 6.2, and an answer on NREL's forum (forums.nrel.gov/t/designing-for-yaw-errors-using-fast/1051) notes that
several tools show it for many turbines, that part of it may come from how the tools model deep stall, and that
designs either avoid the yaw errors or raise the edgewise structural damping until it goes.

OpenFAST v5.0.0 linearized the same parked rotor (blade DOFs only, AeroDyn without induction, legacy projection,
no unsteady aerodynamics, no gravity; tests/data/openfast/standstill_linearization.json) at yaw -30, 0, 30 and
60 deg: blade 1's first flapwise, first edgewise and second flapwise modes match bladefem's within 2 % in frequency
(the FE's exact shapes against ElastoDyn's polynomials) and within 7 % plus 0.1 percentage point in total damping,
with the same sign everywhere: at 30 deg OpenFAST gives -7.92, -1.24 and -0.86 % where bladefem gives -8.29, -1.28
and -0.98 % (tests/test_standstill.py), both with the legacy projection (`BEM_Mod` 1 in a copy of the deck's AeroDyn
file). The map above runs the deck as shipped (`BEM_Mod` 2): in AeroDyn's polar projection each section, coned by
the precone and canted by any prebend in the pitched blade, sees the inflow in its own plane, as the BEM of the
turbine model and of `rotor` takes it (the second flap mode at 30 deg: -0.68 % against the legacy -0.98 %).

## IEA-15MW, feathered, 50 m/s

```bash
{command(IEA15, ("--azimuth-deg", "0,120,240"))}
```

BeamDyn six-by-six sections (torsion and the couplings kept), all 50 polars of the deck, precone -4 deg, shaft tilt
-6 deg, the deck's 0.48 % structural damping, aerodynamic damping alone:

{sector_table(iea)}

![IEA-15MW parked at 50 m/s](standstill-iea15mw.png)

With blade 1 up, the first edgewise mode's total damping is negative at yaw misalignments of about 15 to 70 deg on
either side of the wind (near 40 deg the sector has a short gap) and at about 120 to 148 deg, and with the other
blades' azimuths at 15 to 75 deg as well. OpenFAST users running the parked IEA-15MW (feathered, design load case
6.2, yaw errors -180 to 180 deg) find it unstable between about 20 and 60 deg on either side, an instability that a
20 deg pitch offset of one blade removes (github.com/IEAWindSystems/IEA-15-240-RWT/issues/218); Höning, Herráez and
Stoevesandt (2026, "Aeroelastic instabilities of the IEA 15 MW rotor during extreme yaw maneuvers", Wind Energy
Science 11, 1531) study the same rotor in extreme yaw. The flapwise mode (in the rotor plane when feathered) is
damped heavily by attached flow near the wind direction (87 % at yaw 0) and loses its damping in narrower sectors.
The first torsion mode's total damping is negative over most yaw misalignments, by less than 1 % but near the
wind's own direction and behind it (down to -4.7 %): this quasi-steady analysis has no pitch-rate
(three-quarter-chord) damping of the twisting sections (added as `bladefem flutter` adds it, broad negative
sectors remain), and the mode carries bending in stall; it marks where to look with unsteady aerodynamics.

The lift acts at the aerodynamic centres, with its arm measured from the prebent reference axis: the structure's
degrees of freedom are that axis's motion, and AeroDyn's `BlCrvAC` and BeamDyn's key points carry the same 4 m
prebend, so the arm is at most 0.065 m out of the plane of the chord (and AeroDyn's sweep, up to 0.44 m). Measured
from the pitch axis, as bladefem took it before, the prebend was a 4 m arm: it added 7 to 17 % to the torsion
mode's damping over most of the sweep and, with the aerodynamic stiffness kept (no `--damping-only`), made the
first flapwise mode diverge statically near yaw 0; with the arm from the axis no mode diverges anywhere in the sweep.

## Limits

Quasi-steady polars: no dynamic stall, whose hysteresis changes the damping in deep stall, so a negative sector
marks where to run time simulations with unsteady aerodynamics, not a predicted amplitude. The blade is
linearized about its undeflected shape without gravity, alone on a rigid hub (no tower, no coupling through the
other blades); the wind is steady and uniform. The claims and their tests are in [VALIDATION.md](VALIDATION.md).
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=str(ROOT / "docs" / "standstill.md"))
    args = parser.parse_args()
    Path(args.output).write_text(document(Path(args.output).parent))
    print(f"written {args.output}")


if __name__ == "__main__":
    main()
