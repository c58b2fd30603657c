"""Write, run and reduce the OpenFAST v5.0.0 reference run of the NREL 5MW with ROSCO in a wind step.

The case is ``write_decks.py``'s (the shipped ``cases/nrel5mw/NRELOffshrBsline5MW_Onshore_ROSCO.fst`` in v5.0.0's
layout, ROSCO 2.10.6's library) with InflowWind ``WindType`` 2 and the uniform wind file ``wind_step.wnd`` (kept
beside this script): 10 m/s, rising linearly to 14 m/s between 40 and 40.5 s, no shear; 100 s from the steady
schedule's rotor speed and pitch at 10 m/s (11.43 rpm, 0 deg; Jonkman et al. 2009), ``RotThrust`` added to
ElastoDyn's outputs. ``step.json``: every 0.1 s of the text output (7 digits) of the channels the controller moves.
Not run by the tests (OpenFAST is not needed to use the JSON file); rerun with

    python tests/data/openfast/rosco/write_step.py OPENFAST LIBDISCON RUNS
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))
from make_aeroturbine import read_out  # noqa: E402  (one reader of OpenFAST's text outputs)
from make_openfast_v5 import OPENFAST  # noqa: E402
from write_decks import CASES, FST, set_value, write_case  # noqa: E402

WIND = "wind_step.wnd"
INFLOW = "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat"
TMAX, START = 100.0, (11.43, 0.0)
CHANNELS = ("BldPitch1", "RotSpeed", "GenPwr", "RotThrust", "OoPDefl1", "TTDspFA")


def write(folder: Path, library: str) -> Path:
    CASES[10.0] = START
    fst = write_case(folder, 10.0, library)
    set_value(fst, "TMax", f"{TMAX:g}")
    shutil.copyfile(HERE / WIND, folder / WIND)
    set_value(folder / INFLOW, "WindType", "2")
    set_value(folder / INFLOW, "FileName_Uni", f'"{WIND}"')
    return fst


def main(openfast: str, library: str, runs: str) -> None:
    fst = write(Path(runs) / "rosco_step", library)
    subprocess.run([openfast, fst.name], cwd=fst.parent, check=True, stdout=subprocess.DEVNULL)
    data, units = read_out(fst.with_suffix(".out"))
    time = data["Time"]
    keep = np.abs(time / 0.1 - np.round(time / 0.1)) < 1e-6
    out = {"case": "NREL 5MW land-based with ROSCO 2.10.6, wind step 10 -> 14 m/s at 40 s (0.5 s rise)",
           "provenance": {"openfast": OPENFAST,
                          "controller": "ROSCO 2.10.6 (PyPI wheel rosco-2.10.6-cp311-manylinux_2_28_x86_64), "
                                        "rosco/lib/libdiscon.so",
                          "deck": f"cases/nrel5mw/{FST}",
                          "wind": f"tests/data/openfast/rosco/{WIND} (InflowWind WindType 2)",
                          "script": "tests/data/openfast/rosco/write_step.py",
                          "initial": {"RotSpeed_rpm": START[0], "BlPitch_deg": START[1]},
                          "extraction": "every 0.1 s of the text output, 7 significant digits, OpenFAST's units"},
           "units": {name: units.get(name, "") for name in CHANNELS},
           "history": {name: [float(f"{v:.7g}") for v in data[name][keep]] for name in ("Time", *CHANNELS)}}
    (HERE / "step.json").write_text(json.dumps(out) + "\n")


if __name__ == "__main__":
    main(*sys.argv[1:4])
