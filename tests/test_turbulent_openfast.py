"""The NREL 5MW in a TurbSim box against OpenFAST v5.0.0 in the same box (tests/data/openfast/turbulent/README.md):
the torque law at fixed pitch, BEM_Mod 1, quasi-steady, class B turbulence at 8 m/s, 630 s; the mean, standard
deviation and damage-equivalent load of the blade root moments, tower-base moments, shaft thrust and torque,
tower-top fore-aft displacement, tip deflection, rotor speed and power over the 600 s from 30 s within 2.5 % of
OpenFAST's (the goal of the comparison is 5 %).

With ``--elastodyn-compatible`` (ElastoDyn's polynomial shapes, discretization and damping convention) every
statistic is within 1.27 % (the side-to-side tower-base moment's standard deviation -1.27 %, the tip deflection
+1.1 to +1.2 %). With bladefem's default structure every statistic is within 0.93 % but the side-to-side
tower-base moment's standard deviation and DEL, -4.2 % and -3.8 %, held to the comparison's goal of 5 %: the first
side-to-side tower mode (0.31 Hz) is lightly damped, its response to the turbulence depends on the structural
model's small differences of frequency and damping, and over one realization its standard deviation moves either
way (over a shorter 230 s box it was +5.2 %)."""

from __future__ import annotations

import json
import os
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "openfast" / "turbulent"
CASE = ROOT / "cases" / "nrel5mw"
FST = "NRELOffshrBsline5MW_Onshore.fst"
EDITS = {"NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat": {"WindType": "3", "FileName_BTS": '"box.bts"'},
         "NRELOffshrBsline5MW_Onshore_AeroDyn.dat": {"BEM_Mod": "1"}}


def edit(path: Path, label: str, value: str) -> None:
    text, count = re.subn(rf"^(\s*)\S+(\s+{re.escape(label)}\s)", rf"\g<1>{value}\g<2>", path.read_text(), count=1,
                          flags=re.MULTILINE)
    assert count == 1, label
    path.write_text(text)


#: the box: 630 s, the comparison's 600 s window from 30 s (tests/data/openfast/turbulent/README.md)
BOX = "turbulent_8mps_630s_small"
#: the statistics the default structure holds to the comparison's goal of 5 % rather than 2.5 % (the module
#: docstring: the first side-to-side tower mode of its FE tower)
STRUCTURAL = {"TwrBsMxt": ("std", "del")}


@pytest.mark.slow
@pytest.mark.parametrize("structure", [(), ("--elastodyn-compatible",)], ids=["default", "elastodyn-compatible"])
def test_turbulent_run_against_openfast(tmp_path, structure):
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        pytest.skip("230 s runs need the kernels")
    from bladefem.batch.loads import damage_equivalent_load, wohler_slope
    from bladefem.cli import main

    reference = json.loads((DATA / f"{BOX}.json").read_text())
    start, seconds = reference["window_s"]
    folder = tmp_path / "deck"
    shutil.copytree(CASE, folder)
    shutil.copyfile(DATA / f"{BOX}.bts", folder / "box.bts")
    for file, labels in EDITS.items():
        for label, value in labels.items():
            edit(folder / file, label, value)
    out = tmp_path / "run.csv"
    assert main(["turbine", str(folder / FST), "--simulate", f"{seconds:g}", "--output", str(out), "--quiet",
                 *structure]) == 0
    table = np.genfromtxt(out, delimiter=",", names=True)
    window = table[table.dtype.names[0]] >= start - 1e-9
    for channel, theirs in reference["openfast"].items():
        column = next(n for n in table.dtype.names if n.startswith(channel + "_"))
        values = table[column][window]
        ours = {"mean": values.mean(), "std": values.std(),
                "del": damage_equivalent_load(values, wohler_slope(channel), seconds - start)}
        for statistic in ("mean", "std", "del"):
            tolerance = 0.05 if not structure and statistic in STRUCTURAL.get(channel, ()) else 0.025
            assert ours[statistic] == pytest.approx(theirs[statistic], rel=tolerance), (channel, statistic)
