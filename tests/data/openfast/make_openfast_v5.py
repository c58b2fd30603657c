"""Run OpenFAST v5.0.0 on copies of the shipped NREL 5MW deck and extract the reference JSON file of the BEM_Mod 2
projection. Not run by the tests (OpenFAST is not needed to use the JSON file).

The shipped deck (``cases/nrel5mw/``) is in OpenFAST v4.2.1's layout; v5.0.0 reads it after these additions, all
of them inputs for features the runs leave off (the values are v5's "off" settings): the .fst's ``ModCoupling`` 1
(loose, as v4), ``RhoInf``, ``ConvTol``, ``MaxConvIter`` (tight coupling only), ``NRotors`` 1, ``CompSoil`` 0,
``MirrorRotor`` F, ``SoilFile`` "unused"; ElastoDyn's ``PitchDOF`` False, ``PtfmRefxt``/``PtfmRefyt`` 0,
``PBrIner``/``BlPIner`` 0; AeroDyn without the ``Buoyancy`` line (v5 has none) and with zero ``TwrCp``/``TwrCa``
tower columns (MHK only); ServoDyn's ``PitNeut``/``PitSpr``/``PitDamp`` 0 (used with PitchDOF only). The output
lists are extended (:data:`EXTRA`; outputs only).

Cases (every one: the deck's quasi-steady settings, UA_Mod 0, no tower influence, steady 11.4 m/s without shear,
pitch 0, the rotor speed held at 12.1 rpm, GenDOF False):

- ``rated_bem2``, ``rated_bem1``: 100 s from the undeflected state, BEM_Mod 2 (the deck's) and 1, DT_Out 0.0125 s
  -> ``rated_fixed_speed_v5.json`` (mean, std, min, max over 80-100 s of every channel).

    python tests/data/openfast/make_openfast_v5.py OPENFAST_EXECUTABLE RUN_FOLDER
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path


sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_aeroturbine import read_out  # noqa: E402  (one reader of OpenFAST's text outputs)

HERE = Path(__file__).resolve().parent
CASE = HERE.parents[2] / "cases" / "nrel5mw"
FST, ED, AD, SD = ("NRELOffshrBsline5MW_Onshore.fst", "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat",
                   "NRELOffshrBsline5MW_Onshore_AeroDyn.dat", "NRELOffshrBsline5MW_Onshore_ServoDyn.dat")
OPENFAST = {"version": "v5.0.0", "commit": "2895884d2be01862173c88d70f86b358d2f1a50a",
            "build": "gfortran, CMake Release, double precision, built from source on the development machine",
            "executable": "/work/build/openfast-src/build/glue-codes/openfast/openfast (outside the repository)"}
COMMON = {ED: {"GenDOF": "False", "RotSpeed": "12.1", "BlPitch(1)": "0", "BlPitch(2)": "0", "BlPitch(3)": "0"}}
CASES = {
    "rated_bem2": {FST: {"DT_Out": "0.0125"}, AD: {"BldNd_BladesOut": "1"}},
    "rated_bem1": {FST: {"DT_Out": "0.0125"}, AD: {"BEM_Mod": "1"}},
}
#: channels added to the deck's output lists (outputs only)
EXTRA = {ED: ("RotThrust", "RotPwr", "TipDxc1", "TipDyc1", "RootMxc1", "RootMyc1", "RootMOoP1", "RootMIP1",
              "LSShftFxa"),
         AD: ("RtAeroPwr", "RtTSR", "RtAeroCp", "RtSkew")}
#: blade-node channels added to AeroDyn's nodal output list (written for blade 1 in ``rated_bem2``): the section's
#: cant ("Curve", deg) and toe (deg) in the polar projection, and its inflow
NODAL = ("Curve", "Toe", "Theta", "Alpha", "Phi", "AxInd", "Vx", "Vy", "Vrel", "Cl", "Fx", "Fy")


def line_of(text: str, label: str) -> re.Match:
    match = re.search(rf"^.*\s{re.escape(label)}(\s.*)?$", text, flags=re.MULTILINE)
    if match is None:
        raise KeyError(label)
    return match


def insert(text: str, label: str, lines: list[str], after: bool = True) -> str:
    match = line_of(text, label)
    at = match.end() if after else match.start()
    block = "\n".join(lines)
    return text[:at] + ("\n" + block if after else block + "\n") + text[at:]


def set_value(path: Path, label: str, value: str) -> None:
    text = path.read_text()
    new, count = re.subn(rf"^(\s*)\S+(\s+{re.escape(label)}\s)", rf"\g<1>{value}\g<2>", text, count=1,
                         flags=re.MULTILINE)
    if count != 1:
        raise KeyError(f"{path.name}: {label}")
    path.write_text(new)


def to_v5(folder: Path) -> None:
    """The additions listed in the module docstring."""
    fst = folder / FST
    t = fst.read_text()
    t = insert(t, "DT", ["          1   ModCoupling     - Module coupling method (switch) {1=loose}"])
    t = insert(t, "NumCrctn", ["        0.0   RhoInf          - ", "       1e-4   ConvTol         - ",
                               "          6   MaxConvIter     - "])
    t = insert(t, "CompElast", ["          1   NRotors         - "], after=False)
    t = insert(t, "CompIce", ["          0   CompSoil        - "])
    t = insert(t, "MHK", ["          F   MirrorRotor     - "])
    t = insert(t, "IceFile", ['"unused"      SoilFile        - '])
    fst.write_text(t)
    ed = folder / ED
    t = ed.read_text()
    t = insert(t, "EdgeDOF", ["False         PitchDOF    - "])
    t = insert(t, "PtfmRefzt", ["          0   PtfmRefxt   - ", "          0   PtfmRefyt   - "], after=False)
    t = insert(t, "TipMass(3)", [f"          0   {name}({b})  - " for name in ("PBrIner", "BlPIner")
                                 for b in (1, 2, 3)])
    ed.write_text(t)
    ad = folder / AD
    lines = [line for line in ad.read_text().splitlines() if line.split()[1:2] != ["Buoyancy"]]
    i = next(k for k, line in enumerate(lines) if line.split()[1:2] == ["NumTwrNds"])
    lines[i + 1] += "  TwrCp  TwrCa"
    lines[i + 2] += "  (-)  (-)"
    for k in range(i + 3, i + 3 + int(lines[i].split()[0])):
        lines[k] += "  0.0000000E+00  0.0000000E+00"
    ad.write_text("\n".join(lines) + "\n")
    sd = folder / SD
    sd.write_text(insert(sd.read_text(), "TPCOn", [f"          0   {name}({b})   - "
                                                   for name in ("PitNeut", "PitSpr", "PitDamp") for b in (1, 2, 3)]))


def extend_outputs(folder: Path) -> None:
    """:data:`EXTRA` appended to the first OutList of ElastoDyn and AeroDyn."""
    for file, names in EXTRA.items():
        lines = (folder / file).read_text().splitlines()
        start = next(k for k, line in enumerate(lines) if line.split()[:1] == ["OutList"])
        end = next(k for k in range(start + 1, len(lines)) if lines[k].startswith("END"))
        lines[end:end] = [f'"{name}"' for name in names]
        (folder / file).write_text("\n".join(lines) + "\n")
    lines = (folder / AD).read_text().splitlines()
    start = next(k for k, line in enumerate(lines) if line.split()[:1] == ["OutList_Nodal"])
    end = next(k for k in range(start + 1, len(lines)) if lines[k].startswith("END"))
    lines[end:end] = [f'"{name}"' for name in NODAL]
    (folder / AD).write_text("\n".join(lines) + "\n")


def apply_edits(folder: Path, common: dict, edits: dict, special: dict | None = None) -> None:
    """Each file's labels set in the deck in ``folder``: ``common`` updated by the case's ``edits`` ({file: {label:
    value}}); a file named in ``special`` is changed by its function of the file's path instead of label by label."""
    special = special or {}
    for file in {*common, *edits}:
        if file in special:
            special[file](folder / file)
            continue
        for label, value in {**common.get(file, {}), **edits.get(file, {})}.items():
            set_value(folder / file, label, value)


def prepare(folder: Path, common: dict, edits: dict, special: dict | None = None) -> Path:
    """A fresh copy of the shipped deck in ``folder``, brought to the v5 layout, its outputs extended, and
    :func:`apply_edits`."""
    if folder.exists():
        shutil.rmtree(folder)
    shutil.copytree(CASE, folder)
    to_v5(folder)
    extend_outputs(folder)
    apply_edits(folder, common, edits, special)
    return folder


def run(executable: str, runs: Path) -> None:
    for case, edits in CASES.items():
        folder = prepare(runs / case, COMMON, edits)
        subprocess.run([executable, FST], cwd=folder, check=True, stdout=subprocess.DEVNULL)


def statistics(runs: Path) -> dict:
    variants = {}
    for case, bem_mod in (("rated_bem2", 2), ("rated_bem1", 1)):
        data, units = read_out(runs / case / FST.replace(".fst", ".out"))
        window = data["Time"] >= 80.0 - 1e-9
        variants[f"BEM_Mod {bem_mod}"] = {
            name: {"unit": units[name], "mean": float(f"{v[window].mean():.7g}"),
                   "std": float(f"{v[window].std():.7g}"), "min": float(f"{v[window].min():.7g}"),
                   "max": float(f"{v[window].max():.7g}")}
            for name, v in data.items() if name != "Time" and not re.match(r"A?B\dN\d{3}", name)}
        nodal = {quantity: [name for name in data if re.fullmatch(rf"A?B1N\d{{3}}{quantity}", name)]
                 for quantity in NODAL}
        if all(nodal.values()):
            variants[f"BEM_Mod {bem_mod}"]["blade1_nodes"] = {
                quantity: {"unit": units[names[0]], "mean": [float(f"{data[n][window].mean():.7g}") for n in names],
                           "std": [float(f"{data[n][window].std():.7g}") for n in names]}
                for quantity, names in nodal.items()}
    return {"case": "rated_fixed_speed_v5",
            "description": "NREL 5MW, 11.4 m/s, 12.1 rpm held, pitch 0, quasi-steady BEM, 100 s from the "
                           "undeflected state, with AeroDyn's BEM_Mod 2 (polar projection, the deck's) and BEM_Mod 1.",
            "provenance": {"openfast": OPENFAST, "deck": "cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst",
                           "changes_from_deck": ["v5 layout additions (make_openfast_v5.py)", "ElastoDyn GenDOF False",
                                                 "DT_Out 0.0125 s", "BEM_Mod 1 in the second variant",
                                                 "BEM_Mod 2: blade 1's nodal outputs Curve (the cant), Toe, Vx, Vy"],
                           "script": "tests/data/openfast/make_openfast_v5.py",
                           "extraction": "mean, population standard deviation, min and max over 80 <= t <= 100 s"},
            "window_s": [80.0, 100.0], "channels": variants}


if __name__ == "__main__":
    executable, runs = sys.argv[1], Path(sys.argv[2])
    run(executable, runs)
    (HERE / "rated_fixed_speed_v5.json").write_text(json.dumps(statistics(runs), indent=1) + "\n")
