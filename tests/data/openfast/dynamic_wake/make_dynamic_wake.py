"""Run OpenFAST v5.0.0 on copies of the shipped NREL 5MW deck with a wind step and AeroDyn's dynamic wake
(``DBEMT_Mod`` 0, 1 and 2), and write ``wind_step.json`` (time histories). Not run by the tests (OpenFAST is not
needed to use the JSON file).

Every case: the deck brought to v5's layout (``make_openfast_v5.to_v5``, inputs of features the runs leave off),
quasi-steady airfoils (UA_Mod 0), no tower influence, the rotor speed held at 12.1 rpm (ElastoDyn GenDOF False),
pitch 0, every other ElastoDyn DOF of the deck on, 60 s from the undeflected state; uniform wind (InflowWind
WindType 2, no shear) of 8 m/s up to t = 25 s, rising linearly to 11 m/s at t = 25.5 s and steady after. The
cases differ only in AeroDyn's ``DBEMT_Mod`` (0: quasi-steady; 1: ``tau1_const`` the deck's 4 s, finite-difference
formulation; 2: tau1 from the disk-averaged induction and wind, finite-difference formulation; 3: ``tau1_const`` 4 s,
continuous formulation). Outputs every 0.05 s (AeroDyn's ``DBEMTau1`` added); the JSON keeps every second row
(0.1 s).

    python tests/data/openfast/dynamic_wake/make_dynamic_wake.py OPENFAST_EXECUTABLE RUN_FOLDER
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from make_aeroturbine import read_out  # noqa: E402  (one reader of OpenFAST's text outputs)
from make_openfast_v5 import AD, CASE, ED, FST, OPENFAST, set_value, to_v5  # noqa: E402

INFLOW = "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat"
WIND = "wind_step.uni"
#: the uniform wind file: time, speed (the other columns zero)
STEP = ((0.0, 8.0), (25.0, 8.0), (25.5, 11.0), (1000.0, 11.0))
TMAX = 60.0
CASES = {"dbemt0": "0", "dbemt1": "1", "dbemt2": "2", "dbemt3": "3"}
CHANNELS = ("RtAeroFxh", "RtAeroMxh", "OoPDefl1", "RotThrust", "RotTorq", "DBEMTau1")


def uniform_wind() -> str:
    rows = "\n".join(f"{t:8.3f} {v:7.3f} 0 0 0 0 0 0 0" for t, v in STEP)
    return ("! wind step for the dynamic-wake reference (bladefem tests/data/openfast/dynamic_wake)\n"
            "! Time Wind Wind Vert. Horiz. Pwr.Law Lin.Vert. Gust Upflow\n"
            "! (s) Speed Dir Speed Shear Vert.Shr Shear Speed (deg)\n" + rows + "\n")


def write_case(folder: Path, dbemt: str) -> None:
    if folder.exists():
        shutil.rmtree(folder)
    shutil.copytree(CASE, folder)
    to_v5(folder)
    set_value(folder / FST, "TMax", f"{TMAX:g}")
    for label, value in (("GenDOF", "False"), ("RotSpeed", "12.1"), ("BlPitch(1)", "0"), ("BlPitch(2)", "0"),
                         ("BlPitch(3)", "0")):
        set_value(folder / ED, label, value)
    set_value(folder / AD, "DBEMT_Mod", dbemt)
    (folder / WIND).write_text(uniform_wind())
    set_value(folder / INFLOW, "WindType", "2")
    set_value(folder / INFLOW, "FileName_Uni", f'"{WIND}"')
    lines = (folder / ED).read_text().splitlines()
    start = next(k for k, line in enumerate(lines) if line.split()[:1] == ["OutList"])
    end = next(k for k in range(start + 1, len(lines)) if lines[k].startswith("END"))
    lines[end:end] = ['"RotThrust"', '"RootMOoP1"']
    (folder / ED).write_text("\n".join(lines) + "\n")
    lines = (folder / AD).read_text().splitlines()
    start = next(k for k, line in enumerate(lines) if line.split()[:1] == ["OutList"])
    end = next(k for k in range(start + 1, len(lines)) if lines[k].startswith("END"))
    lines[end:end] = ['"DBEMTau1"']
    (folder / AD).write_text("\n".join(lines) + "\n")


def run(executable: str, runs: Path) -> None:
    for case, dbemt in CASES.items():
        write_case(runs / case, dbemt)
        subprocess.run([executable, FST], cwd=runs / case, check=True, stdout=subprocess.DEVNULL)


def histories(runs: Path) -> dict:
    cases = {}
    for case, dbemt in CASES.items():
        data, units = read_out(runs / case / FST.replace(".fst", ".out"))
        rows = slice(None, None, 2)
        cases[f"DBEMT_Mod {dbemt}"] = {"Time": [round(float(t), 4) for t in data["Time"][rows]],
                                      **{name: {"unit": units[name],
                                                "values": [float(f"{v:.6g}") for v in data[name][rows]]}
                                         for name in CHANNELS}}
    return {"case": "wind_step_dynamic_wake",
            "description": "NREL 5MW, 12.1 rpm held, pitch 0, uniform wind 8 m/s stepping to 11 m/s over "
                           "25-25.5 s, 60 s from the undeflected state, AeroDyn DBEMT_Mod 0, 1 (tau1_const 4 s), "
                           "2 and 3 (tau1_const 4 s).",
            "provenance": {"openfast": OPENFAST, "deck": "cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst",
                           "changes_from_deck": ["v5 layout additions (make_openfast_v5.py)",
                                                 "ElastoDyn GenDOF False, RotSpeed 12.1, BlPitch 0",
                                                 "InflowWind WindType 2 with the wind step (STEP)",
                                                 "AeroDyn DBEMT_Mod per case, output DBEMTau1", "TMax 60 s"],
                           "script": "tests/data/openfast/dynamic_wake/make_dynamic_wake.py",
                           "extraction": "every second output row (0.1 s), 6 significant digits"},
            "wind_step": [list(row) for row in STEP], "cases": cases}


if __name__ == "__main__":
    executable, runs = sys.argv[1], Path(sys.argv[2])
    run(executable, runs)
    (HERE / "wind_step.json").write_text(json.dumps(histories(runs)) + "\n")
