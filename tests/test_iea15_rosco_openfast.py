"""The IEA-15MW monopile deck with its own ROSCO settings (rigid foundation, quasi-steady BEM) in steady wind against
OpenFAST v5.0.0 with the same library, deck and start (tests/data/openfast/iea15_rosco/steady.json, written by
write_decks.py there): below rated (8 m/s), just above (11 m/s) and well above (16 m/s).

bladefem runs ElastoDyn's structure (``--elastodyn-compatible``: the blade file's polynomial shapes, ElastoDyn's
discretization and damping convention), as OpenFAST does, so that the comparison is of the loads, the Kane model and
the controller's loop. With bladefem's default FE blade shapes the tip deflection is within 1.3 % of OpenFAST's
(+1.25 %, +1.09 %, +0.77 %; docs/turbine-aero.md)."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import main
from simulation_table import table

ROOT = Path(__file__).resolve().parents[1]
DECK = ROOT / "tests" / "data" / "iea15" / "IEA-15-240-RWT-Monopile" / "IEA-15-240-RWT-Monopile.fst"
REFERENCE = ROOT / "tests" / "data" / "openfast" / "iea15_rosco" / "steady.json"

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="controlled runs need numba")]


@pytest.fixture(scope="module")
def reference():
    return json.loads(REFERENCE.read_text())


@pytest.fixture(scope="module", params=["8", "11", "16"])
def case(request, reference, tmp_path_factory):
    """bladefem's run of one OpenFAST case, 120 s (OpenFAST's 200 s runs show the means over 70-120 s settled: the
    means over 150-200 s differ by at most 0.031 %, the tip deflection's by 0.29 %) from the same rotor speed and
    pitch, with ElastoDyn's fixed step (the adaptive step collapses in the IEA-15MW's start-up transient:
    tests/test_iea15_simulation.py) and ElastoDyn's structure."""
    wind = request.param
    initial = reference["provenance"]["initial"][wind]
    out = tmp_path_factory.mktemp("iea15_rosco") / f"bf_{wind}.csv"
    code = main(["turbine", str(DECK), "--simulate", f"{reference['compared_run_s']:g}", "--foundation", "rigid",
                 "--quasi-steady", "--wind-speed", wind, "--initial", f"RotSpeed={initial['RotSpeed_rpm']}",
                 "--pitch-deg", str(initial["BlPitch_deg"]), "--method", "RK4", "--step", "0.005",
                 "--elastodyn-compatible", "--quiet",
                 "-o", str(out)])
    assert code == 0
    return wind, table(out)


@pytest.mark.parametrize("channel", ["BldPitch1", "GenPwr", "RotSpeed", "RotThrust", "OoPDefl1"])
def test_iea15_rosco_steady_operation_against_openfast(reference, case, channel):
    """Means over 70-120 s of generator power, rotor speed, rotor thrust and blade-tip out-of-plane deflection
    within 2 %, blade pitch within 0.5 deg (the acceptance of the NREL 5MW's ROSCO comparison; measured figures in
    docs/turbine-aero.md: the tip deflection +0.18 %, +0.15 %, +0.16 %, the others within 0.04 % and 0.011 deg;
    with the nodes' arms turned to first order only the tip deflection was -1.14 %, -1.82 %, -0.42 %).
    With the sections not canted by the prebent blade's ``BlCrvAng`` and the nodes' arms not turned with them, the
    rotor drew 1.2 % less power below rated and the tip deflection at 8 m/s was 2.04 % low
    (tests/test_iea15_rigid_rotor_openfast.py)."""
    wind, ours = case
    theirs = reference["cases"][wind][channel]["mean"]
    mean = np.mean(ours[channel][ours["Time"] >= reference["window_s"][0] - 1e-9])
    if channel == "BldPitch1":
        assert mean == pytest.approx(theirs, abs=0.5)
    else:
        assert mean == pytest.approx(theirs, rel=0.02)
