"""The IEA reference turbines' monopile decks with ROSCO, brought to OpenFAST v5.0.0's layouts, run in steady wind as
bladefem runs them with ``--foundation rigid --quasi-steady``, and reduced to the means of the compared channels.

Shared by ``iea15_rosco/write_decks.py`` and ``iea22_rosco/write_decks.py``; each describes its deck with an
:class:`IEADeck` and lists, in its docstring, every line it adds or changes. The changes, the same for both decks
(both are written by WEIS/AeroElasticSE in the OpenFAST 3.x layouts):

- ``.fst``: the shipped NREL 5MW ROSCO deck's ``.fst`` (v4.2.1 layout, with the v5 additions of
  ``make_openfast_v5.py``; ``CompElast`` 1: ElastoDyn's blades) with the IEA deck's environment (``Gravity``,
  ``AirDens``, ``KinVisc``, ``SpdSound``), the step :attr:`IEADeck.dt` and the IEA module files; no HydroDyn or
  SubDyn (rigid foundation); text output every 0.05 s.
- ElastoDyn: every platform DOF off (the tower clamped at ``TowerBsHt``, bladefem's rigid foundation), the v4 lines
  ``HubIner_Teeter`` 0, ``PtfmXYIner``/``PtfmYZIner``/``PtfmXZIner`` 0 and the yaw-friction block (``YawFrctMod`` 0),
  the v5 lines ``PitchDOF`` False, ``PtfmRefxt``/``PtfmRefyt`` 0, ``PBrIner``/``BlPIner`` 0; the blade file without
  its ``PitchAxis`` column (removed in v4, unused by ElastoDyn); the case's initial ``RotSpeed`` and ``BlPitch``;
  output channels added.
- AeroDyn: the NREL 5MW deck's v4.2.1 primary file (v5 additions) carrying the IEA file's airfoils, blade files,
  tower table (with zero ``TwrCp``/``TwrCa``), ``UseBlCm``, ``TipLoss``, ``HubLoss``, ``TanInd``, ``AIDrag``,
  ``TIDrag``, ``MaxIter``; the airfoil files with ``NumCoords`` 0 (their coordinate files, used by aero-acoustics
  only, are not stored); the legacy ``WakeMod`` as AeroDyn v4 maps it (1: ``Wake_Mod`` 1, ``BEM_Mod`` 1; 11, v3.5's
  BEM with the polar projection: ``Wake_Mod`` 1, ``BEM_Mod`` 2; ``DBEMT_Mod`` 0) and ``SkewMod`` 2 as ``Skew_Mod`` 1
  (Pitt/Peters); quasi-steady: ``UA_Mod`` 0 and no tower potential flow, shadow or drag.
- InflowWind: the NREL 5MW deck's v4.2.1 file, steady wind ``HWindSpeed`` at the IEA file's ``RefHt`` with its
  power-law exponent.
- ServoDyn: v5's ``PitNeut``/``PitSpr``/``PitDamp`` 0 (used with PitchDOF only) and ``DLL_FileName`` the absolute
  path of ROSCO 2.10.6's library; the DISCON.IN stored beside the deck.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
sys.path.insert(0, str(HERE))
from make_aeroturbine import read_out  # noqa: E402  (one reader of OpenFAST's text outputs)
from make_openfast_v5 import OPENFAST, insert, set_value, to_v5  # noqa: E402

NREL = ROOT / "cases" / "nrel5mw"
CHANNELS = ("BldPitch1", "RotSpeed", "GenPwr", "RotThrust", "OoPDefl1", "IPDefl1", "TTDspFA", "TwrBsMyt")
ED_OUT = ("BldPitch1", "RotSpeed", "RotThrust", "OoPDefl1", "IPDefl1", "TTDspFA", "TwrBsMyt", "TwrBsMxt")
CONTROLLER = "ROSCO 2.10.6 (PyPI wheel rosco-2.10.6-cp311-manylinux_2_28_x86_64), rosco/lib/libdiscon.so"


@dataclass(frozen=True)
class IEADeck:
    """One IEA monopile deck and its runs: the stored deck ``tests/data/<tree>/<mono>/<fst>`` sharing the files of
    ``<shared>``; ``cases``: wind speed (m/s) -> initial rotor speed (rpm), pitch (deg); ``dt``: the runs' step (s;
    None: the deck's); ``tmax``, ``window``, ``late``: run length and the compared and late windows (s)."""

    name: str
    title: str
    tree: str
    mono: str
    shared: str
    ed: str
    ad: str
    sd: str
    iw: str
    blade: str
    cases: dict[float, tuple[float, float]]
    out: Path
    dt: str | None = None
    tmax: float = 200.0
    window: tuple[float, float] = (70.0, 120.0)
    late: tuple[float, float] = (150.0, 200.0)

    @property
    def data(self) -> Path:
        return ROOT / "tests" / "data" / self.tree

    @property
    def fst(self) -> str:
        return f"{self.mono}.fst"


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


def fst(deck: IEADeck, folder: Path, seconds: float) -> None:
    """The 5MW .fst (v5 additions) with the IEA deck's environment, step and files."""
    nrel = folder / "nrel"
    shutil.copytree(NREL, nrel)
    names = ("NRELOffshrBsline5MW_Onshore.fst", "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat",
             "NRELOffshrBsline5MW_Onshore_AeroDyn.dat", "NRELOffshrBsline5MW_Onshore_ServoDyn.dat")
    shutil.copyfile(nrel / "NRELOffshrBsline5MW_Onshore_ROSCO.fst", nrel / names[0])
    to_v5(nrel)
    source, target = folder / deck.mono / deck.fst, nrel / names[0]
    for label in ("Gravity", "AirDens", "KinVisc", "SpdSound", "DT"):
        edit(target, label, value(source, label))
    if deck.dt is not None:
        edit(target, "DT", deck.dt)
    files = {"EDFile": f'"{deck.ed}"', "InflowFile": f'"../{deck.shared}/{deck.iw}"', "AeroFile": f'"{deck.ad}"',
             "ServoFile": f'"{deck.sd}"'}
    for label, name in files.items():
        edit(target, label, name)
    edit(target, "TMax", f"{seconds:g}")
    edit(target, "DT_Out", "0.05")
    shutil.copyfile(target, source)
    shutil.copyfile(nrel / names[2], folder / deck.mono / (deck.ad + ".nrel"))
    shutil.copyfile(nrel / "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat",
                    folder / deck.shared / (deck.iw + ".nrel"))
    shutil.rmtree(nrel)


def elastodyn(deck: IEADeck, folder: Path, rpm: float, pitch: float) -> None:
    ed = folder / deck.mono / deck.ed
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
    blade = folder / deck.shared / deck.blade
    lines = text_of(blade).splitlines()
    k = next(i for i, line in enumerate(lines) if line.split()[:2] == ["BlFract", "PitchAxis"])
    count = int(value(blade, "NBlInpSt"))
    for i in range(k, k + 2 + count):
        words = lines[i].split()
        lines[i] = "  ".join(words[:1] + words[2:])
    blade.write_text("\n".join(lines) + "\n")


def bem_mod(source: Path) -> str:
    """AeroDyn v4's BEM_Mod of the legacy WakeMod: 1 the legacy projection, 11 (v3.5) the polar projection."""
    legacy = int(value(source, "WakeMod"))
    if legacy not in (1, 11):
        raise ValueError(f"{source.name}: WakeMod {legacy} (only 1 and 11 are mapped)")
    return "2" if legacy == 11 else "1"


def aerodyn(deck: IEADeck, folder: Path) -> None:
    """The 5MW v5 AeroDyn primary file carrying the IEA deck's inputs (module docstring)."""
    for polar in (folder / deck.shared / "Airfoils").glob("*Polar*.dat"):
        edit(polar, "NumCoords", "0")
    source, template = folder / deck.mono / deck.ad, folder / deck.mono / (deck.ad + ".nrel")
    lines = text_of(template).splitlines()
    old = text_of(source).splitlines()
    for label in ("UseBlCm", "TipLoss", "HubLoss", "TanInd", "AIDrag", "TIDrag", "MaxIter"):
        k = next(i for i, line in enumerate(lines) if line.split()[1:2] == [label])
        lines[k] = f"{value(source, label)}   {label}  - "
    settings = {"Wake_Mod": "1", "BEM_Mod": bem_mod(source), "DBEMT_Mod": "0", "UA_Mod": "0", "Skew_Mod": "1",
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


def inflow(deck: IEADeck, folder: Path, wind: float) -> None:
    source, template = folder / deck.shared / deck.iw, folder / deck.shared / (deck.iw + ".nrel")
    for label in ("RefHt", "PLExp"):
        edit(template, label, value(source, label))
    edit(template, "WindVziList", value(source, "RefHt"))
    edit(template, "WindType", "1")
    edit(template, "HWindSpeed", f"{wind:g}")
    shutil.move(template, source)


def servodyn(deck: IEADeck, folder: Path, library: str) -> None:
    sd = folder / deck.mono / deck.sd
    add_lines(sd, "TPCOn", [f"0   {n}({b})   - " for n in ("PitNeut", "PitSpr", "PitDamp") for b in (1, 2, 3)])
    edit(sd, "DLL_FileName", f'"{library}"')
    outputs(sd, ("GenPwr", "GenTq"))


def write_case(deck: IEADeck, folder: Path, wind: float, library: str, seconds: float | None = None) -> Path:
    """The v5 deck of one case in ``folder`` (replaced); its .fst."""
    if folder.exists():
        shutil.rmtree(folder)
    folder.mkdir(parents=True)
    for name in (deck.mono, deck.shared):
        shutil.copytree(deck.data / name, folder / name)
    rpm, pitch = deck.cases[wind]
    fst(deck, folder, deck.tmax if seconds is None else seconds)
    elastodyn(deck, folder, rpm, pitch)
    aerodyn(deck, folder)
    inflow(deck, folder, wind)
    servodyn(deck, folder, str(Path(library).resolve()))
    return folder / deck.mono / deck.fst


def reduce(deck: IEADeck, runs: Path, extra: dict | None = None) -> dict:
    """``steady.json`` of the runs in ``runs`` (written to :attr:`IEADeck.out`); ``extra``: more provenance."""
    results = {}
    window_s, late_s = deck.window, deck.late
    for wind in deck.cases:
        data, _ = read_out(runs / f"{deck.name}_{wind:g}" / deck.mono / deck.fst.replace(".fst", ".out"))
        t = data["Time"]
        window = (t >= window_s[0] - 1e-9) & (t <= window_s[1] + 1e-9)
        earlier = (t >= window_s[0] - 30 - 1e-9) & (t <= window_s[0] + 1e-9)
        late = (t >= late_s[0] - 1e-9) & (t <= late_s[1] + 1e-9)
        results[f"{wind:g}"] = {name: {"mean": float(f"{data[name][window].mean():.7g}"),
                                       "std": float(f"{data[name][window].std():.7g}"),
                                       "mean_30s_earlier": float(f"{data[name][earlier].mean():.7g}"),
                                       f"mean_{late_s[0]:g}_{late_s[1]:g}s": float(f"{data[name][late].mean():.7g}")}
                                for name in CHANNELS}
    out = {"case": f"{deck.title} monopile deck with ROSCO 2.10.6, rigid foundation, quasi-steady BEM, steady wind",
           "provenance": {"openfast": OPENFAST,
                          "controller": f"{CONTROLLER}, with the DISCON.IN of tests/data/{deck.tree}",
                          "deck": f"tests/data/{deck.tree}/{deck.mono}/{deck.fst}",
                          "script": f"tests/data/openfast/{deck.out.parent.name}/write_decks.py (the changes: its "
                                    "docstring)",
                          "initial": {f"{w:g}": {"RotSpeed_rpm": r, "BlPitch_deg": p}
                                      for w, (r, p) in deck.cases.items()},
                          "extraction": f"mean and population standard deviation over {window_s[0]:g} <= t <= "
                                        f"{window_s[1]:g} s of the text output (every 0.05 s), the mean over the 30 s "
                                        f"before and the mean over {late_s[0]:g}-{late_s[1]:g} s (settling checks); 7 "
                                        "significant digits; OpenFAST's units (deg, rpm, kW, kN, m, kN m)",
                          **(extra or {})},
           "tmax_s": deck.tmax, "compared_run_s": window_s[1], "window_s": list(window_s), "cases": results}
    deck.out.write_text(json.dumps(out, indent=1) + "\n")
    return out


def run_cases(deck: IEADeck, openfast: str, library: str, runs: Path) -> dict[str, float]:
    """Write and run every case; the wall-clock seconds of each."""
    seconds = {}
    for wind in deck.cases:
        fst_path = write_case(deck, runs / f"{deck.name}_{wind:g}", wind, library)
        start = time.perf_counter()
        subprocess.run([openfast, fst_path.name], cwd=fst_path.parent, check=True, stdout=subprocess.DEVNULL)
        seconds[f"{wind:g}"] = round(time.perf_counter() - start, 1)
    return seconds


def main(deck: IEADeck, argv: list[str]) -> None:
    """``OPENFAST LIBDISCON RUNS [--reduce]`` (``--reduce``: only extract ``steady.json`` from runs made in RUNS)."""
    if "--reduce" in argv:
        reduce(deck, Path(argv[2]))
    else:
        run_cases(deck, argv[0], argv[1], Path(argv[2]))
        reduce(deck, Path(argv[2]))
