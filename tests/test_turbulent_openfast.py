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
way (over a shorter 230 s box it was +5.2 %).

Which choice makes the difference (switched one at a time on that 230 s box, TwrBsMxt standard deviation / DEL):
the ElastoDyn blade polynomials with bladefem's integration +6.1 % / +5.3 %; bladefem's FE blades with the
ElastoDyn-compatible tower -1.0 % / -0.7 %; the ElastoDyn-compatible model with only its tower side-side 1
generalized stiffness raised by 0.33 % to bladefem's +6.6 % / +5.7 %. So it is the tower's discretization alone:
ElastoDyn integrates the tower polynomial's curvature at the midpoints of TwrNodes = 20 elements, 0.33 % below the
exact integral of the same polynomial (which bladefem's default gives, within 1e-5), the mode 0.16 % lower in
frequency. Not the damping convention: both apply TwrSSDmp as ElastoDyn does (``CTSS = 0.01 TwrSSDmp KTSS / (pi
FreqTSS)``, FreqTSS of the tower without its top mass). A mode damped so lightly (0.61 % of critical with the
aerodynamics) answers one realization of the turbulence so narrowly that a 0.16 % frequency shift moves its standard
deviation by several per cent; the default keeps the exact integral.
:func:`test_tower_side_side_stiffness_is_the_exact_integral` checks the quadratures."""

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


def test_tower_side_side_stiffness_is_the_exact_integral():
    """The default tower's side-side 1 generalized stiffness is the exact integral of the polynomial (800 elements,
    4 Gauss points, within 1e-5); ElastoDyn's midpoint rule at TwrNodes = 20 gives 0.33 % less (the module
    docstring: the TwrBsMxt difference); both damp the mode as ElastoDyn does, c = 2 zeta sqrt(K m_tower)."""
    from bladefem.builders.turbine_elastodyn import turbine_from_elastodyn

    main = CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
    models = {name: turbine_from_elastodyn(main, blade_shapes="polynomial", **options) for name, options in
              (("default", {}), ("exact", {"tower_elements": 800, "gauss_points": 4}),
               ("elastodyn", {"elastodyn_compatible": True, "gauss_points": 1}))}
    stiffness = {name: model.tower.generalized_stiffness()[2, 2] for name, model in models.items()}
    assert stiffness["default"] == pytest.approx(stiffness["exact"], rel=1e-5)
    assert 0.0025 < 1.0 - stiffness["elastodyn"] / stiffness["exact"] < 0.0040
    for model in models.values():
        tower = model.tower
        zeta, own = tower.damping_ratio[2], tower.generalized_mass()[2, 2]
        damping = model.damping_matrices()[1][2, 2]
        assert damping == pytest.approx(2.0 * zeta * np.sqrt(tower.generalized_stiffness()[2, 2] * own), rel=1e-12)
