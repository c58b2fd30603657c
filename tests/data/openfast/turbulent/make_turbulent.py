"""The turbulent reference: one TurbSim box run through OpenFAST v5.0.0 and through bladefem, statistics of both
stored here. Not run by the tests (OpenFAST and TurbSim are not needed to use the JSON file).

1. TurbSim (OpenFAST v5.0.0's) writes ``box.bts`` from ``NAME.inp`` (beside this script): IEC Kaimal normal
   turbulence class B, 8 m/s at the 90 m hub, power-law exponent 0.2, over 140 m (periodic); ``turbulent_8mps``:
   15 x 15 points, 0.05 s, 330 s; ``turbulent_8mps_630s_small``: 7 x 7 points, 0.1 s, 630 s, whose box is kept here
   (``turbulent_8mps_630s_small.bts``, 1.9 MB) for the test that reruns bladefem.
2. OpenFAST v5.0.0 runs the shipped NREL 5MW deck (``cases/nrel5mw``) in that box: the deck turned into v5's layout
   by ``make_openfast_v5.py`` (``to_v5``, ``extend_outputs``: the sibling script of ``tests/data/openfast``),
   InflowWind ``WindType`` 3 with ``box.bts``, AeroDyn ``BEM_Mod`` 1, ``TMax`` the box's time, the torque law at
   fixed pitch (the deck's ServoDyn), every ElastoDyn DOF of the deck.
3. bladefem runs the same deck (v4.2.1 layout, the same two changes) as long:
   ``bladefem turbine DECK.fst --simulate SECONDS --output bladefem.csv``.

The JSON holds, for each tool, the mean, standard deviation and damage-equivalent load (bladefem.batch.loads: 1 Hz
equivalent cycles, m = 10 for the blade root, 4 otherwise) over 30 s to the end of the channels both write, in
``NAME.json``.

    python tests/data/openfast/turbulent/make_turbulent.py TURBSIM OPENFAST RUN_FOLDER NAME
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[3]
sys.path.insert(0, str(HERE.parent))
from make_openfast_v5 import AD, CASE, ED, FST, OPENFAST, extend_outputs, read_out, set_value, to_v5  # noqa: E402

INFLOW = "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat"
START = 30.0
#: OpenFAST channel -> bladefem channel compared
CHANNELS = {"RootMyc1": "RootMOoP1", "RootMxc1": "RootMIP1", "RotThrust": "RotThrust", "RotTorq": "RotTorq",
            "TTDspFA": "TTDspFA", "OoPDefl1": "OoPDefl1", "RotSpeed": "RotSpeed", "GenPwr": "GenPwr",
            "TwrBsMxt": "TwrBsMxt", "TwrBsMyt": "TwrBsMyt"}


def deck(folder: Path, v5: bool, seconds: float) -> Path:
    if folder.exists():
        shutil.rmtree(folder)
    shutil.copytree(CASE, folder)
    shutil.copyfile(folder.parent / "box.bts", folder / "box.bts")
    if v5:
        to_v5(folder)
        extend_outputs(folder)
    set_value(folder / INFLOW, "WindType", "3")
    set_value(folder / INFLOW, "FileName_BTS", '"box.bts"')
    set_value(folder / AD, "BEM_Mod", "1")
    set_value(folder / FST, "TMax", f"{seconds:g}")
    return folder / FST


def statistics(series: dict[str, np.ndarray], time: np.ndarray, seconds: float) -> dict:
    sys.path.insert(0, str(ROOT))
    from bladefem.batch.loads import damage_equivalent_load, wohler_slope
    window = time >= START - 1e-9
    out = {}
    for name, values in series.items():
        v = values[window]
        m = wohler_slope(name)
        out[name] = {"mean": float(f"{v.mean():.7g}"), "std": float(f"{v.std():.7g}"),
                     "del": float(f"{damage_equivalent_load(v, m, seconds - START):.7g}"), "wohler_m": m}
    return out


def main() -> None:
    turbsim, openfast, runs, name = sys.argv[1], sys.argv[2], Path(sys.argv[3]), sys.argv[4]
    runs.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(HERE / f"{name}.inp", runs / "box.inp")
    subprocess.run([turbsim, "box.inp"], cwd=runs, check=True, stdout=subprocess.DEVNULL)
    seconds = next(float(line.split()[0]) for line in (HERE / f"{name}.inp").read_text().splitlines()
                   if "AnalysisTime" in line)
    if name.endswith("_small"):
        shutil.copyfile(runs / "box.bts", HERE / f"{name}.bts")
    of_deck = deck(runs / "openfast", v5=True, seconds=seconds)
    subprocess.run([openfast, FST], cwd=of_deck.parent, check=True, stdout=subprocess.DEVNULL)
    data, _ = read_out(of_deck.with_suffix(".out"))
    bf_deck = deck(runs / "bladefem", v5=False, seconds=seconds)
    subprocess.run([sys.executable, "-m", "bladefem", "turbine", str(bf_deck), "--simulate", f"{seconds:g}",
                    "--output", str(runs / "bladefem.csv"), "--quiet"], check=True, stdout=subprocess.DEVNULL)
    table = np.genfromtxt(runs / "bladefem.csv", delimiter=",", names=True)
    ours = {b: table[[n for n in table.dtype.names if n.startswith(b + "_")][0]] for b in CHANNELS.values()}
    theirs = {b: data[o] for o, b in CHANNELS.items() if o in data}
    result = {"case": name,
              "description": "NREL 5MW, torque law at fixed pitch 0, BEM_Mod 1, quasi-steady, in one TurbSim box "
                             f"(IEC Kaimal class B, 8 m/s at the hub, shear 0.2), {seconds:g} s; statistics from "
                             f"{START:g} s.",
              "provenance": {"openfast": OPENFAST, "turbsim": "TurbSim of the same OpenFAST build",
                             "turbsim_input": f"tests/data/openfast/turbulent/{name}.inp",
                             "script": "tests/data/openfast/turbulent/make_turbulent.py"},
              "window_s": [START, seconds], "openfast": statistics(theirs, data["Time"], seconds),
              "bladefem": statistics(ours, table[table.dtype.names[0]], seconds)}
    (HERE / f"{name}.json").write_text(json.dumps(result, indent=1) + "\n")


if __name__ == "__main__":
    main()
