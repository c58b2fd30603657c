"""Write, run and reduce the OpenFAST reference runs of the NREL 5MW with ROSCO in steady wind.

Each case is a copy of ``cases/nrel5mw/NRELOffshrBsline5MW_Onshore_ROSCO.fst`` and its files (OpenFAST v4.2.1's
layout) brought to v5.0.0's layout by :func:`to_v5` (inputs of features the runs leave off, at v5's "off" values:
the .fst's ``ModCoupling`` 1, ``RhoInf``, ``ConvTol``, ``MaxConvIter``, ``NRotors`` 1, ``CompSoil`` 0,
``MirrorRotor`` F, ``SoilFile``; ElastoDyn's ``PitchDOF`` False, ``PtfmRefxt``/``PtfmRefyt`` 0, ``PBrIner``/
``BlPIner`` 0; AeroDyn without its ``Buoyancy`` line and with zero ``TwrCp``/``TwrCa`` columns; ServoDyn's
``PitNeut``/``PitSpr``/``PitDamp`` 0, used with PitchDOF only), with only these changes: InflowWind ``HWindSpeed`` (steady, no shear), ``TMax``, ElastoDyn's initial ``RotSpeed`` and ``BlPitch``
(near the operating point, as bladefem's run is started), ServoDyn's ``DLL_FileName`` the absolute path of ROSCO's
library, and ``RotThrust`` added to ElastoDyn's outputs. Not run by the tests (OpenFAST is not needed to use the
JSON file); rerun with

    python tests/data/openfast/rosco/write_decks.py OPENFAST LIBDISCON RUNS

(OPENFAST: the executable; LIBDISCON: ROSCO 2.10.6's ``rosco/lib/libdiscon.so``; RUNS: a scratch folder), which
writes ``steady.json`` and ``transient.json`` here (``--histories RUNS`` writes the latter from runs made).
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
DECK = HERE.parents[3] / "cases" / "nrel5mw"
FST = "NRELOffshrBsline5MW_Onshore_ROSCO.fst"
#: wind speed (m/s) -> initial rotor speed (rpm), pitch (deg): Jonkman et al. 2009's steady schedule
CASES = {8.0: (9.16, 0.0), 11.4: (12.1, 0.0), 16.0: (12.1, 10.45), 20.0: (12.1, 17.47)}
TMAX, WINDOW = 150.0, (100.0, 150.0)
HISTORY_S, HISTORY_CHANNELS = 60.0, ("BldPitch1", "RotSpeed", "GenPwr", "RotThrust", "OoPDefl1")
CHANNELS = ("BldPitch1", "RotSpeed", "GenPwr", "GenTq", "RotThrust", "OoPDefl1", "IPDefl1", "TTDspFA", "RtAeroCp")


def set_value(path: Path, label: str, value: str) -> None:
    """Replace the value in front of ``label`` on its line (the first line naming it)."""
    text = path.read_text()
    pattern = re.compile(rf"^(\s*)(\S+)(\s+{re.escape(label)}(?=\s|$))", re.M)
    new, count = pattern.subn(lambda m: f"{m.group(1)}{value}{m.group(3)}", text, count=1)
    if count != 1:
        raise SystemExit(f"{label} not found in {path}")
    path.write_text(new)


def insert(path: Path, label: str, lines: list[str], after: bool = True) -> None:
    """Insert ``lines`` after (or before) the line naming ``label``."""
    text = path.read_text()
    match = re.search(rf"^.*\s{re.escape(label)}(\s.*)?$", text, flags=re.M)
    if match is None:
        raise SystemExit(f"{label} not found in {path}")
    block = "\n".join(lines)
    at = match.end() if after else match.start()
    path.write_text(text[:at] + ("\n" + block if after else block + "\n") + text[at:])


def to_v5(folder: Path) -> None:
    """The v5.0.0 layout additions listed in the module docstring (all for features left off)."""
    fst = folder / FST
    insert(fst, "DT", ["          1   ModCoupling     - Module coupling method (switch) {1=loose}"])
    insert(fst, "NumCrctn", ["        0.0   RhoInf          - ", "       1e-4   ConvTol         - ",
                             "          6   MaxConvIter     - "])
    insert(fst, "CompElast", ["          1   NRotors         - "], after=False)
    insert(fst, "CompIce", ["          0   CompSoil        - "])
    insert(fst, "MHK", ["          F   MirrorRotor     - "])
    insert(fst, "IceFile", ['"unused"      SoilFile        - '])
    elasto = folder / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
    insert(elasto, "EdgeDOF", ["False         PitchDOF    - "])
    insert(elasto, "PtfmRefzt", ["          0   PtfmRefxt   - ", "          0   PtfmRefyt   - "], after=False)
    insert(elasto, "TipMass(3)", [f"          0   {name}({b})  - " for name in ("PBrIner", "BlPIner")
                                  for b in (1, 2, 3)])
    aero = folder / "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
    lines = [line for line in aero.read_text().splitlines() if line.split()[1:2] != ["Buoyancy"]]
    i = next(k for k, line in enumerate(lines) if line.split()[1:2] == ["NumTwrNds"])
    lines[i + 1] += "  TwrCp  TwrCa"
    lines[i + 2] += "  (-)  (-)"
    for k in range(i + 3, i + 3 + int(lines[i].split()[0])):
        lines[k] += "  0.0000000E+00  0.0000000E+00"
    aero.write_text("\n".join(lines) + "\n")
    insert(folder / "NRELOffshrBsline5MW_Onshore_ROSCO_ServoDyn.dat", "TPCOn",
           [f"          0   {name}({b})   - " for name in ("PitNeut", "PitSpr", "PitDamp") for b in (1, 2, 3)])


def write_case(folder: Path, wind: float, library: str) -> Path:
    if folder.exists():
        shutil.rmtree(folder)
    shutil.copytree(DECK, folder)
    to_v5(folder)
    rpm, pitch = CASES[wind]
    set_value(folder / FST, "TMax", f"{TMAX:g}")
    set_value(folder / "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat", "HWindSpeed", f"{wind:g}")
    elasto = folder / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
    set_value(elasto, "RotSpeed", f"{rpm:g}")
    for blade in (1, 2, 3):
        set_value(elasto, f"BlPitch({blade})", f"{pitch:g}")
    text = elasto.read_text()
    elasto.write_text(text.replace('"OoPDefl1"', '"RotThrust"\n"OoPDefl1"', 1))
    set_value(folder / "NRELOffshrBsline5MW_Onshore_ROSCO_ServoDyn.dat", "DLL_FileName", f'"{library}"')
    return folder / FST


def read_out(path: Path) -> dict[str, np.ndarray]:
    lines = path.read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("Time"))
    names = lines[start].split()
    data = np.loadtxt(lines[start + 2:])
    return {name: data[:, j] for j, name in enumerate(names)}


def histories(runs: Path) -> None:
    """``transient.json``: the first 60 s of every case (from the start at the schedule's rotor speed and pitch),
    every 0.1 s, of the channels the controller moves."""
    cases = {}
    for wind in CASES:
        data = read_out(runs / f"rosco_{wind:g}" / FST.replace(".fst", ".out"))
        keep = (data["Time"] <= HISTORY_S + 1e-9) & (np.abs(data["Time"] / 0.1 - np.round(data["Time"] / 0.1))
                                                     < 1e-6)
        cases[f"{wind:g}"] = {name: [float(f"{v:.7g}") for v in data[name][keep]]
                              for name in ("Time", *HISTORY_CHANNELS)}
    out = {"case": "NREL 5MW land-based with ROSCO 2.10.6, steady wind: the first 60 s",
           "provenance": "as steady.json (same runs, write_decks.py); every 0.1 s of the text output, 7 digits",
           "cases": cases}
    (HERE / "transient.json").write_text(json.dumps(out) + "\n")


def main(openfast: str, library: str, runs: str) -> None:
    results = {}
    for wind in CASES:
        fst = write_case(Path(runs) / f"rosco_{wind:g}", wind, library)
        subprocess.run([openfast, fst.name], cwd=fst.parent, check=True, stdout=subprocess.DEVNULL)
        data = read_out(fst.with_suffix(".out"))
        window = (data["Time"] >= WINDOW[0] - 1e-9) & (data["Time"] <= WINDOW[1] + 1e-9)
        earlier = (data["Time"] >= WINDOW[0] - 30 - 1e-9) & (data["Time"] <= WINDOW[0] + 1e-9)
        results[f"{wind:g}"] = {name: {"mean": float(f"{data[name][window].mean():.7g}"),
                                       "std": float(f"{data[name][window].std():.7g}"),
                                       "mean_30s_earlier": float(f"{data[name][earlier].mean():.7g}")}
                                for name in CHANNELS}
    version = subprocess.run([openfast, "-v"], capture_output=True, text=True).stdout
    match = re.search(r"OpenFAST-(\S+)", version)
    out = {"case": "NREL 5MW land-based with ROSCO 2.10.6, steady wind",
           "provenance": {"openfast": {"version": match.group(1) if match else "unknown",
                                       "commit": "2895884d2", "executable": openfast},
                          "controller": "ROSCO 2.10.6 (PyPI wheel rosco-2.10.6-cp311-manylinux_2_28_x86_64), "
                                        "rosco/lib/libdiscon.so",
                          "deck": f"cases/nrel5mw/{FST}",
                          "changes_from_deck": ["v5.0.0 layout additions (write_decks.py's to_v5)",
                                                "InflowWind HWindSpeed = the case's wind speed",
                                                f"TMax {TMAX:g} s",
                                                "ElastoDyn RotSpeed and BlPitch(1..3) = the case's initial values",
                                                "ServoDyn DLL_FileName = absolute path of libdiscon.so",
                                                "ElastoDyn OutList: RotThrust added"],
                          "initial": {f"{wind:g}": {"RotSpeed_rpm": rpm, "BlPitch_deg": pitch}
                                      for wind, (rpm, pitch) in CASES.items()},
                          "extraction": f"mean and population standard deviation over {WINDOW[0]:g} <= t <= "
                                        f"{WINDOW[1]:g} s of the text output (every 0.05 s), and the mean over the "
                                        "30 s before (settling check); 7 significant digits; OpenFAST's units "
                                        "(deg, rpm, kW, kN m, kN, m)"},
           "window_s": list(WINDOW), "cases": results}
    (HERE / "steady.json").write_text(json.dumps(out, indent=1) + "\n")
    histories(Path(runs))


if __name__ == "__main__":
    if sys.argv[1] == "--histories":                 # reduce runs already made: write_decks.py --histories RUNS
        histories(Path(sys.argv[2]))
    else:
        main(*sys.argv[1:4])
