"""Write, run and extract the OpenFAST linearizations of the parked NREL 5MW in yaw (standstill_linearization.json).

Not run by the tests (OpenFAST is not needed to use the JSON file). Each case is ``cases/nrel5mw`` written in
OpenFAST v5.0.0's layout (:func:`write_case`) with: the blade DOFs only (FlapDOF1, FlapDOF2, EdgeDOF; drivetrain,
generator, yaw and tower DOFs off), RotSpeed 0, BlPitch 90 deg (feathered), Azimuth 0 (blade 1 up), NacYaw the yaw
misalignment, Gravity 0, no ServoDyn (CompServo 0), AeroDyn without induction (Wake_Mod 0, the parked rotor's
geometric inflow), legacy projection (BEM_Mod 1, bladefem's), no unsteady aerodynamics (UA_Mod 0) and no tower
influence, steady uniform wind of 50 m/s (HWindSpeed, PLExp 0), the deck's shaft tilt (-5 deg), precone (-2.5 deg)
and blade structural damping (0.477465 %), linearized once about the undeflected initial state (Linearize True,
CalcSteady False, LinTimes 0). The three blades do not couple (no rotor, tower or yaw DOF): blade 1's three modes
are the eigenvalues whose eigenvectors live on its states.

    python tests/data/openfast/make_standstill.py OPENFAST_EXECUTABLE RUNS_FOLDER
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
DECK = HERE.parents[2] / "cases" / "nrel5mw"
FST = "NRELOffshrBsline5MW_Onshore.fst"
YAWS = (-30.0, 0.0, 30.0, 60.0)
WIND = 50.0
AERODYN = "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
INFLOW = "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat"


def labelled(text: str, label: str, value: str) -> str:
    """``text`` with the value (first word) of the line labelled ``label`` replaced."""
    new, count = re.subn(rf"^\s*\S+(\s+{re.escape(label)}\s)", value + r"\1", text, flags=re.M)
    if count != 1:
        raise SystemExit(f"{label} found {count} times")
    return new


def write_case(folder: Path, yaw: float) -> Path:
    """The case's files in OpenFAST v5.0.0's layout: the .fst and ElastoDyn primary written by the BeamDyn
    reference's writers (beamdyn/make_decks.py, from FAST_Subs.f90's and ElastoDyn_IO.f90's reading order), the
    deck's AeroDyn file without the Buoyancy flag and with the v5 tower table (TwrCp, TwrCa zero), its blade,
    tower, airfoil and InflowWind files."""
    sys.path.insert(0, str(HERE / "beamdyn"))
    import make_decks

    if folder.exists():
        shutil.rmtree(folder)
    shutil.copytree(DECK, folder)
    main = make_decks.fst("NREL 5MW parked in yaw", "0", "0.00625", "0", "unused", "ed.dat")
    main = main.replace('"unused"                       InflowFile', f'"{INFLOW}" InflowFile')
    main = main.replace('"unused"                       AeroFile', f'"{AERODYN}" AeroFile')
    for label, value in (("CompElast", "1"), ("CompInflow", "1"), ("CompAero", "2"), ("LinInputs", "0"),
                         ("LinOutputs", "0")):
        main = labelled(main, label, value)
    (folder / FST).write_text(main)
    ed = make_decks.elastodyn((folder / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat").read_text(), 0.0,
                              "NRELOffshrBsline5MW_Blade.dat", "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat")
    for label in ("FlapDOF1", "FlapDOF2", "EdgeDOF"):
        ed = labelled(ed, label, "True")
    for label in ("BlPitch(1)", "BlPitch(2)", "BlPitch(3)"):
        ed = labelled(ed, label, "90")
    (folder / "ed.dat").write_text(labelled(ed, "NacYaw", f"{yaw:g}"))
    aero = (folder / AERODYN).read_text()
    for label, value in (("Wake_Mod", "0"), ("BEM_Mod", "1"), ("UA_Mod", "0"), ("TwrPotent", "0"),
                         ("TwrShadow", "0"), ("TwrAero", "False")):
        aero = labelled(aero, label, value)
    lines = [line for line in aero.splitlines() if not re.match(r"^\s*\S+\s+Buoyancy\s", line)]
    k = next(i for i, line in enumerate(lines) if re.match(r"^\s*\S+\s+NumTwrNds\s", line))
    lines[k + 1], lines[k + 2] = "TwrElev TwrDiam TwrCd TwrTI TwrCb TwrCp TwrCa", "(m) (m) (-) (-) (-) (-) (-)"
    for j in range(k + 3, k + 3 + int(lines[k].split()[0])):
        lines[j] = "  ".join(lines[j].split()[:5] + ["0", "0"])
    (folder / AERODYN).write_text("\n".join(lines) + "\n")
    inflow = labelled((folder / INFLOW).read_text(), "HWindSpeed", f"{WIND:g}")
    (folder / INFLOW).write_text(labelled(inflow, "PLExp", "0"))
    return folder / FST


def read_lin(path: Path) -> tuple[list[str], np.ndarray]:
    """The state names and the state matrix A of an OpenFAST .lin file."""
    lines = path.read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if "Order of continuous states" in line)
    names = []
    for line in lines[start + 3:]:
        if not line.strip():
            break
        names.append(line.split(maxsplit=3)[-1].strip())
    a = next(i for i, line in enumerate(lines) if line.startswith("A:"))
    A = np.array([[float(v) for v in lines[a + 1 + k].split()] for k in range(len(names))])
    return names, A


def blade1_modes(names: list[str], A: np.ndarray) -> list[dict]:
    values, vectors = np.linalg.eig(A)
    n = len(names) // 2
    modes = []
    for k in np.flatnonzero(values.imag >= 0):
        share = np.abs(vectors[:n, k])
        blade1 = [i for i in range(n) if "blade 1" in names[i]]
        if share[blade1].sum() < 0.99 * share.sum():
            continue
        top = max(blade1, key=lambda i: share[i])
        modes.append({"dof": names[top], "natural_frequency_hz": float(abs(values[k]) / (2 * np.pi)),
                      "damped_frequency_hz": float(values[k].imag / (2 * np.pi)),
                      "damping_ratio": float(-values[k].real / abs(values[k]))})
    return sorted(modes, key=lambda mode: mode["natural_frequency_hz"])


def main() -> None:
    openfast, runs = sys.argv[1], Path(sys.argv[2])
    points = []
    for yaw in YAWS:
        fst = write_case(runs / f"yaw{yaw:+g}", yaw)
        subprocess.run([openfast, fst.name], cwd=fst.parent, check=True, capture_output=True)
        names, A = read_lin(fst.with_suffix(".1.lin"))
        points.append({"yaw_deg": yaw, "modes": blade1_modes(names, A)})
    out = {"case": "standstill_linearization",
           "description": "NREL 5MW parked (0 rpm, blades feathered at 90 deg, blade 1 up), blade DOFs only, no "
                          "gravity, AeroDyn without induction (Wake_Mod 0), BEM_Mod 1, UA off, steady 50 m/s, "
                          "linearized about the undeflected state at each yaw misalignment (NacYaw); blade 1's "
                          "modes (ElastoDyn's 0.477465 % structural damping included).",
           "provenance": {"openfast": {"version": "v5.0.0", "commit": "2895884d2",
                                       "build": "the build of /work/build/openfast-src (Release, double precision)"},
                          "deck": "cases/nrel5mw/" + FST,
                          "changes_from_deck": "tests/data/openfast/make_standstill.py write_case",
                          "script": "tests/data/openfast/make_standstill.py"},
           "wind_speed_m_s": WIND, "points": points}
    (HERE / "standstill_linearization.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
