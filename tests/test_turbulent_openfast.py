"""The NREL 5MW in a TurbSim box against OpenFAST v5.0.0 in the same box (tests/data/openfast/turbulent/README.md):
the torque law at fixed pitch, BEM_Mod 1, quasi-steady, class B turbulence at 8 m/s, 230 s; the mean, standard
deviation and damage-equivalent load of the blade root moments, tower-base moments, shaft thrust and torque,
tower-top fore-aft displacement, tip deflection, rotor speed and power over 30-230 s within 2.5 % of OpenFAST's (the
goal of the comparison is 5 %).

With bladefem's default structure (FE blade shapes, its span integration) every statistic is within 1.4 % (the tip
deflection's standard deviation, the thrust's DEL) but the side-to-side tower-base moment's standard deviation and
DEL, +5.2 % and +4.6 % (the tower-top side-to-side displacement too, +4.4 %; all of it in the 0.25-0.4 Hz band of
the first side-to-side tower mode). With ElastoDyn's own choices (``--elastodyn-compatible``) every statistic,
TwrBsMxt's included, is within 1.7 % (TwrBsMxt: mean -0.37 %, standard deviation -0.01 %, DEL +0.18 %).

Which choice makes the difference (switched one at a time, same box, TwrBsMxt standard deviation / DEL): the
ElastoDyn blade polynomials with bladefem's integration +6.1 % / +5.3 %; bladefem's FE blades with the
ElastoDyn-compatible tower -1.0 % / -0.7 %; the ElastoDyn-compatible model with only its tower side-side 1
generalized stiffness raised by 0.33 % to bladefem's +6.6 % / +5.7 %. So it is the tower's discretization alone:
ElastoDyn integrates the tower polynomial's curvature at the midpoints of TwrNodes = 20 elements, 0.33 % below the
exact integral of the same polynomial (which bladefem's default gives, within 1e-5), the mode 0.16 % lower in
frequency. Not the damping convention: both apply TwrSSDmp as ElastoDyn does (``CTSS = 0.01 TwrSSDmp KTSS / (pi
FreqTSS)``, FreqTSS of the tower without its top mass): 1 % of the tower alone, about 0.37 % of critical with the
rotor-nacelle mass (350 t) at its top, 0.61 % with the aerodynamics (linearized at 8 m/s, 9.2 rpm: 0.3143 Hz default,
0.3138 Hz ElastoDyn-compatible; bladefem's tower FE with the rigid rotor-nacelle 0.3141 Hz). A mode damped so
lightly answers one 200 s realization of the turbulence so narrowly that a 0.16 % frequency shift moves its
standard deviation by 6 %: the default is the better integral, and its TwrBsMxt standard deviation and DEL are left
out of the comparison (:data:`STRUCTURAL`), and the default blades on the ElastoDyn-compatible tower are held to every
statistic; :func:`test_tower_side_side_stiffness_is_the_exact_integral` checks the quadratures."""

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


#: the statistics the default structure leaves out (the module docstring: ElastoDyn's tower quadrature)
STRUCTURAL = {"TwrBsMxt": ("std", "del")}
#: the default structure with the ElastoDyn-compatible tower (its quadrature) in place of bladefem's
ELASTODYN_TOWER = "elastodyn-tower"


def use_elastodyn_tower(monkeypatch) -> None:
    """Build every deck's turbine with the default blades on the ElastoDyn-compatible tower."""
    import bladefem.builders.turbine_deck as turbine_deck

    build = turbine_deck.turbine_from_elastodyn

    def hybrid(main, **options):
        theirs = build(main, **{**options, "blade_shapes": "polynomial", "elastodyn_compatible": True,
                                "gauss_points": 1})
        return build(main, **options).with_(tower=theirs.tower)

    monkeypatch.setattr(turbine_deck, "turbine_from_elastodyn", hybrid)


@pytest.mark.slow
@pytest.mark.parametrize("structure", [(), ("--elastodyn-compatible",), (ELASTODYN_TOWER,)],
                         ids=["default", "elastodyn-compatible", "default-on-elastodyn-tower"])
def test_turbulent_run_against_openfast(tmp_path, monkeypatch, structure):
    """Default structure: every statistic but TwrBsMxt's standard deviation and DEL within 2.5 %; the
    ElastoDyn-compatible one, and the default blades on the ElastoDyn-compatible tower (the only difference being
    the tower's quadrature), every statistic."""
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        pytest.skip("230 s runs need the kernels")
    if structure == (ELASTODYN_TOWER,):
        use_elastodyn_tower(monkeypatch)
        structure = ("--tower-shapes", "polynomial")
    from bladefem.batch.loads import damage_equivalent_load, wohler_slope
    from bladefem.cli import main

    default = not structure
    reference = json.loads((DATA / "turbulent_8mps_small.json").read_text())
    start, seconds = reference["window_s"]
    folder = tmp_path / "deck"
    shutil.copytree(CASE, folder)
    shutil.copyfile(DATA / "turbulent_8mps_small.bts", folder / "box.bts")
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
            if default and statistic in STRUCTURAL.get(channel, ()):
                continue
            assert ours[statistic] == pytest.approx(theirs[statistic], rel=0.025), (channel, statistic)


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
