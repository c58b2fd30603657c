"""Write, run and reduce the OpenFAST v5.0.0 reference runs of the IEA-15MW monopile deck with ROSCO in steady wind,
rigid foundation, quasi-steady aerodynamics: the deck bladefem runs with ``--foundation rigid --quasi-steady``.

The stored deck (``tests/data/iea15``, OpenFAST 3.x layouts written by WEIS) is brought to v5.0.0's layouts with
only these changes, each one what bladefem's two options mean:

- ``.fst``: the shipped NREL 5MW ROSCO deck's ``.fst`` (v4.2.1 layout, with the v5 additions of
  ``../make_openfast_v5.py``) with the IEA deck's environment (``Gravity``, ``AirDens``, ``KinVisc``,
  ``SpdSound``), its ``DT`` 0.005 s and its module files; ``CompHydro`` and ``CompSub`` 0 (rigid foundation);
  text output every 0.05 s.
- ElastoDyn: the IEA file with every platform DOF off (the tower clamped at ``TowerBsHt`` 15 m, as bladefem's
  rigid foundation), the v4 lines ``HubIner_Teeter`` 0 (two-bladed rotors only), ``PtfmXYIner``/``PtfmYZIner``/
  ``PtfmXZIner`` 0 and the yaw-friction block (``YawFrctMod`` 0), the v5 lines ``PitchDOF`` False, ``PtfmRefxt``/``PtfmRefyt`` 0, ``PBrIner``/``BlPIner`` 0;
  the blade file without its ``PitchAxis`` column (removed in v4, unused by ElastoDyn); initial ``RotSpeed`` and
  ``BlPitch`` of the case; output channels added.
- AeroDyn: the NREL 5MW deck's v4.2.1 primary file (v5 additions) carrying the IEA file's airfoils, blade file,
  tower table (with zero ``TwrCp``/``TwrCa``), ``UseBlCm``, ``TipLoss``, ``HubLoss``, ``TanInd``, ``AIDrag``,
  ``TIDrag``, ``MaxIter``; the airfoil files with ``NumCoords`` 0 (their coordinate files, used by
  aero-acoustics only, are not stored); the legacy ``WakeMod`` 1 as AeroDyn maps it (``Wake_Mod`` 1, ``BEM_Mod`` 1,
  ``DBEMT_Mod`` 0) and ``SkewMod`` 2 as ``Skew_Mod`` 1 (Pitt/Peters); quasi-steady: ``UA_Mod`` 0 and no tower
  potential flow, shadow or drag (``TwrPotent`` 0, ``TwrShadow`` 0, ``TwrAero`` False).
- InflowWind: the NREL 5MW deck's v4.2.1 file, steady wind ``HWindSpeed`` at the IEA file's ``RefHt`` 150 m with
  its power-law exponent 0.12.
- ServoDyn: the IEA file with v5's ``PitNeut``/``PitSpr``/``PitDamp`` 0 (used with PitchDOF only) and
  ``DLL_FileName`` the absolute path of ROSCO 2.10.6's library; the DISCON.IN stored beside the deck.

Not run by the tests (OpenFAST is not needed to use ``steady.json``); rerun with

    python tests/data/openfast/iea15_rosco/write_decks.py OPENFAST LIBDISCON RUNS [--reduce]

(``--reduce``: only extract ``steady.json`` from runs made in RUNS).
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[3]
sys.path.insert(0, str(HERE.parent))
from make_aeroturbine import read_out  # noqa: E402  (one reader of OpenFAST's text outputs)
from make_openfast_v5 import OPENFAST, insert, set_value, to_v5  # noqa: E402

IEA = ROOT / "tests" / "data" / "iea15"
NREL = ROOT / "cases" / "nrel5mw"
MONO, SHARED = "IEA-15-240-RWT-Monopile", "IEA-15-240-RWT"
FST = f"{MONO}.fst"
ED, AD, SD = f"{MONO}_ElastoDyn.dat", f"{MONO}_AeroDyn15.dat", f"{MONO}_ServoDyn.dat"
IW = f"{SHARED}_InflowFile.dat"
#: wind speed (m/s) -> initial rotor speed (rpm), pitch (deg), near the operating point (ROSCO's steady schedule)
CASES = {8.0: (5.68, 0.0), 11.0: (7.55, 4.0), 16.0: (7.55, 12.0)}
TMAX, WINDOW, LATE = 200.0, (70.0, 120.0), (150.0, 200.0)
CHANNELS = ("BldPitch1", "RotSpeed", "GenPwr", "RotThrust", "OoPDefl1", "IPDefl1", "TTDspFA", "TwrBsMyt")
ED_OUT = ("BldPitch1", "RotSpeed", "RotThrust", "OoPDefl1", "IPDefl1", "TTDspFA", "TwrBsMyt", "TwrBsMxt")


def text_of(path: Path) -> str:
    return path.read_text(errors="replace")


def value(path: Path, label: str) -> str:
    match = re.search(rf"^\s*(\S+)\s+{re.escape(label)}\s", text_of(path), flags=re.M | re.I)
    if match is None:
        raise KeyError(f"{path.name}: {label}")
    return match.group(1)


def edit(path: Path, label: str, new: str) -> None:
    set_value(path, label, new)


def add_lines(path: Path, label: str, lines: list[str], after: bool = True) -> None:
    path.write_text(insert(text_of(path), label, lines, after))


def outputs(path: Path, names: tuple[str, ...]) -> None:
    """Append the ``names`` not yet listed to the first OutList of ``path``."""
    lines = text_of(path).splitlines()
    start = next(k for k, line in enumerate(lines) if line.split()[:1] == ["OutList"]
                 or line.split()[1:2] == ["OutList"])
    end = next(k for k in range(start + 1, len(lines)) if lines[k].startswith("END"))
    listed = {w.strip('"').lower() for line in lines[start + 1:end] for w in re.split(r"[\s,]+", line) if w}
    lines[end:end] = [f'"{name}"' for name in names if name.lower() not in listed]
    path.write_text("\n".join(lines) + "\n")


def fst(folder: Path, seconds: float) -> None:
    """The 5MW .fst (v5 additions) with the IEA deck's environment, step and files."""
    nrel = folder / "nrel"
    shutil.copytree(NREL, nrel)
    names = ("NRELOffshrBsline5MW_Onshore.fst", "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat",
             "NRELOffshrBsline5MW_Onshore_AeroDyn.dat", "NRELOffshrBsline5MW_Onshore_ServoDyn.dat")
    shutil.copyfile(nrel / "NRELOffshrBsline5MW_Onshore_ROSCO.fst", nrel / names[0])
    to_v5(nrel)
    source, target = folder / MONO / FST, nrel / names[0]
    for label in ("Gravity", "AirDens", "KinVisc", "SpdSound", "DT"):
        edit(target, label, value(source, label))
    files = {"EDFile": f'"{ED}"', "InflowFile": f'"../{SHARED}/{IW}"', "AeroFile": f'"{AD}"',
             "ServoFile": f'"{SD}"'}
    for label, name in files.items():
        edit(target, label, name)
    edit(target, "TMax", f"{seconds:g}")
    edit(target, "DT_Out", "0.05")
    shutil.copyfile(target, source)
    shutil.copyfile(nrel / names[2], folder / MONO / (AD + ".nrel"))
    shutil.copyfile(nrel / "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat", folder / SHARED / (IW + ".nrel"))
    shutil.rmtree(nrel)


def elastodyn(folder: Path, rpm: float, pitch: float) -> None:
    ed = folder / MONO / ED
    for dof in ("PtfmSgDOF", "PtfmSwDOF", "PtfmHvDOF", "PtfmRDOF", "PtfmPDOF", "PtfmYDOF"):
        edit(ed, dof, "False")
    add_lines(ed, "EdgeDOF", ["False                  PitchDOF    - "])
    add_lines(ed, "PtfmRefzt", ["0.0                    PtfmRefxt   - ", "0.0                    PtfmRefyt   - "],
              after=False)
    add_lines(ed, "TipMass(3)", [f"0.0                    {n}({b})  - " for n in ("PBrIner", "BlPIner")
                                 for b in (1, 2, 3)])
    add_lines(ed, "HubIner", ["0.0                    HubIner_Teeter  - "])
    add_lines(ed, "PtfmYIner", [f"0.0                    {n}  - " for n in ("PtfmXYIner", "PtfmYZIner",
                                                                               "PtfmXZIner")])
    friction = ["---------------------- YAW-FRICTION --------------------------------------------",
                "0                      YawFrctMod  - "] + [f"0                      {n}  - " for n in (
                    "M_CSmax", "M_FCSmax", "M_MCSmax", "M_CD", "M_FCD", "M_MCD", "sig_v", "sig_v2", "OmgCut")]
    lines = text_of(ed).splitlines()
    k = next(i for i, line in enumerate(lines) if "DRIVETRAIN" in line and line.startswith("-"))
    lines[k:k] = friction
    ed.write_text("\n".join(lines) + "\n")
    edit(ed, "RotSpeed", f"{rpm:g}")
    for b in (1, 2, 3):
        edit(ed, f"BlPitch({b})", f"{pitch:g}")
    outputs(ed, ED_OUT)
    blade = folder / SHARED / f"{SHARED}_ElastoDyn_blade.dat"
    lines = text_of(blade).splitlines()
    k = next(i for i, line in enumerate(lines) if line.split()[:2] == ["BlFract", "PitchAxis"])
    count = int(value(blade, "NBlInpSt"))
    for i in range(k, k + 2 + count):
        words = lines[i].split()
        lines[i] = "  ".join(words[:1] + words[2:])
    blade.write_text("\n".join(lines) + "\n")


def aerodyn(folder: Path) -> None:
    """The 5MW v5 AeroDyn primary file carrying the IEA deck's inputs (module docstring)."""
    for polar in (folder / SHARED / "Airfoils").glob("*Polar*.dat"):
        edit(polar, "NumCoords", "0")
    source, template = folder / MONO / AD, folder / MONO / (AD + ".nrel")
    lines = text_of(template).splitlines()
    old = text_of(source).splitlines()
    for label in ("UseBlCm", "TipLoss", "HubLoss", "TanInd", "AIDrag", "TIDrag", "MaxIter"):
        k = next(i for i, line in enumerate(lines) if line.split()[1:2] == [label])
        lines[k] = f"{value(source, label)}   {label}  - "
    settings = {"Wake_Mod": "1", "BEM_Mod": "1", "DBEMT_Mod": "0", "UA_Mod": "0", "Skew_Mod": "1",
                "TwrPotent": "0", "TwrShadow": "0", "TwrAero": "False"}
    for label, new in settings.items():
        k = next(i for i, line in enumerate(lines) if line.split()[1:2] == [label])
        lines[k] = f"{new}   {label}  - "
    # airfoils: NumAFfiles and the list
    count = int(value(source, "NumAFfiles"))
    j = next(i for i, line in enumerate(old) if line.split()[1:2] == ["AFNames"])
    names = [line.split()[0] for line in old[j:j + count]]
    k = next(i for i, line in enumerate(lines) if line.split()[1:2] == ["NumAFfiles"])
    n_old = int(lines[k].split()[0])
    lines[k] = f"{count}   NumAFfiles  - "
    lines[k + 1:k + 1 + n_old] = [f"{names[0]}   AFNames  - "] + names[1:]
    for b in (1, 2, 3):
        k = next(i for i, line in enumerate(lines) if line.split()[1:2] == [f"ADBlFile({b})"])
        lines[k] = f"{value(source, f'ADBlFile({b})')}   ADBlFile({b})  - "
    # tower table: the IEA rows with zero TwrCp, TwrCa
    nodes = int(value(source, "NumTwrNds"))
    j = next(i for i, line in enumerate(old) if line.split()[1:2] == ["NumTwrNds"])
    rows = [line + "  0.0  0.0" for line in old[j + 3:j + 3 + nodes]]
    k = next(i for i, line in enumerate(lines) if line.split()[1:2] == ["NumTwrNds"])
    n_old = int(lines[k].split()[0])
    lines[k] = f"{nodes}   NumTwrNds  - "
    lines[k + 3:k + 3 + n_old] = rows
    source.write_text("\n".join(lines) + "\n")
    template.unlink()
    outputs(source, ("RtAeroCp", "RtTSR", "RtAeroFxh"))


def inflow(folder: Path, wind: float) -> None:
    source, template = folder / SHARED / IW, folder / SHARED / (IW + ".nrel")
    for label in ("RefHt", "PLExp"):
        edit(template, label, value(source, label))
    edit(template, "WindVziList", value(source, "RefHt"))
    edit(template, "WindType", "1")
    edit(template, "HWindSpeed", f"{wind:g}")
    shutil.move(template, source)


def servodyn(folder: Path, library: str) -> None:
    sd = folder / MONO / SD
    add_lines(sd, "TPCOn", [f"0   {n}({b})   - " for n in ("PitNeut", "PitSpr", "PitDamp") for b in (1, 2, 3)])
    edit(sd, "DLL_FileName", f'"{library}"')
    outputs(sd, ("GenPwr", "GenTq"))


def write_case(folder: Path, wind: float, library: str, seconds: float = TMAX) -> Path:
    if folder.exists():
        shutil.rmtree(folder)
    folder.mkdir(parents=True)
    for name in (MONO, SHARED):
        shutil.copytree(IEA / name, folder / name)
    rpm, pitch = CASES.get(wind, (7.56, 0.0))
    fst(folder, seconds)
    elastodyn(folder, rpm, pitch)
    aerodyn(folder)
    inflow(folder, wind)
    servodyn(folder, str(Path(library).resolve()))
    return folder / MONO / FST


def reduce(runs: Path) -> None:
    results = {}
    for wind in CASES:
        data, _ = read_out(runs / f"iea15_{wind:g}" / MONO / FST.replace(".fst", ".out"))
        time = data["Time"]
        window = (time >= WINDOW[0] - 1e-9) & (time <= WINDOW[1] + 1e-9)
        earlier = (time >= WINDOW[0] - 30 - 1e-9) & (time <= WINDOW[0] + 1e-9)
        late = (time >= LATE[0] - 1e-9) & (time <= LATE[1] + 1e-9)
        results[f"{wind:g}"] = {name: {"mean": float(f"{data[name][window].mean():.7g}"),
                                       "std": float(f"{data[name][window].std():.7g}"),
                                       "mean_30s_earlier": float(f"{data[name][earlier].mean():.7g}"),
                                       "mean_150_200s": float(f"{data[name][late].mean():.7g}")}
                                for name in CHANNELS}
    out = {"case": "IEA-15MW monopile deck with ROSCO 2.10.6, rigid foundation, quasi-steady BEM, steady wind",
           "provenance": {"openfast": OPENFAST,
                          "controller": "ROSCO 2.10.6 (PyPI wheel rosco-2.10.6-cp311-manylinux_2_28_x86_64), "
                                        "rosco/lib/libdiscon.so, with the DISCON.IN of tests/data/iea15",
                          "deck": f"tests/data/iea15/{MONO}/{FST}",
                          "script": "tests/data/openfast/iea15_rosco/write_decks.py (the changes: its docstring)",
                          "initial": {f"{w:g}": {"RotSpeed_rpm": r, "BlPitch_deg": p}
                                      for w, (r, p) in CASES.items()},
                          "extraction": f"mean and population standard deviation over {WINDOW[0]:g} <= t <= "
                                        f"{WINDOW[1]:g} s of the text output (every 0.05 s), the mean over the 30 s "
                                        f"before and the mean over {LATE[0]:g}-{LATE[1]:g} s (settling checks); 7 "
                                        "significant digits; OpenFAST's units (deg, rpm, kW, kN, m, kN m)"},
           "tmax_s": TMAX, "compared_run_s": WINDOW[1], "window_s": list(WINDOW), "cases": results}
    (HERE / "steady.json").write_text(json.dumps(out, indent=1) + "\n")


def main(openfast: str, library: str, runs: str) -> None:
    for wind in CASES:
        deck = write_case(Path(runs) / f"iea15_{wind:g}", wind, library)
        subprocess.run([openfast, deck.name], cwd=deck.parent, check=True, stdout=subprocess.DEVNULL)
    reduce(Path(runs))


if __name__ == "__main__":
    if "--reduce" in sys.argv:
        reduce(Path(sys.argv[3]))
    else:
        main(*sys.argv[1:4])
