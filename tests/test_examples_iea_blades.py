"""docs/iea-blades.md holds what examples/iea_blades.py computes now: every row of its three frequency tables
(full, condensed and reduced sections, every format, parked and rated) and of its comparison with OpenFAST/BeamDyn
within one unit of the last printed digit, and the claims its prose makes of them."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCUMENT = ROOT / "docs" / "iea-blades.md"
sys.path.insert(0, str(ROOT / "examples"))

import iea_blades  # noqa: E402

pytestmark = pytest.mark.slow


def document_rows() -> dict[tuple[str, str, str], np.ndarray]:
    """(turbine and source, rpm, section model) -> the six frequencies, from the document's two tables."""
    text = DOCUMENT.read_text()
    rows = {}
    model = None
    for line in text.splitlines():
        if line.startswith("**Full six-by-six sections**"):
            model = "full"
        elif line.startswith("**Condensed**"):
            model = "condensed"
        elif line.startswith("**Reduced**"):
            model = "reduced"
        elif model and line.startswith("| IEA-"):
            cells = [c.strip() for c in line.strip("|").split("|")]
            rows[(cells[0], cells[1], model)] = np.array([float(c) for c in cells[2:]])
        elif line.startswith("Other sources"):
            model = None
    return rows


@pytest.fixture(scope="module")
def computed() -> list:
    return iea_blades.rows()


def test_document_tables_are_current(computed):
    written = document_rows()
    assert len(written) == len(computed) == 48
    for row in computed:
        key = (f"{row.turbine} {row.source}", f"{row.rpm:.2f}", row.sections)
        np.testing.assert_allclose(written[key], row.hz, atol=1e-4 + 1e-12, err_msg=str(key))


def test_document_claims_hold(computed):
    by = {(r.turbine, r.source, r.sections, r.rpm > 0): np.array(r.hz) for r in computed}
    # the section couplings (condensed against reduced, both Euler-Bernoulli) move the IEA-15MW's first six by under
    # 0.1 % (measured 0.08 %, HAWC2 torsion), the IEA-22MW's bending by up to 0.21 % (held to 0.25 %)
    for source in iea_blades.INPUTS["IEA-15MW"]:
        for rated in (False, True):
            full, reduced = by[("IEA-15MW", source, "condensed", rated)], by[("IEA-15MW", source, "reduced", rated)]
            assert np.max(np.abs(reduced / full - 1)) < 1e-3
    for source in iea_blades.INPUTS["IEA-22MW"]:
        full, reduced = by[("IEA-22MW", source, "condensed", False)], by[("IEA-22MW", source, "reduced", False)]
        assert np.max(np.abs(reduced[:5] / full[:5] - 1)) < 2.5e-3
    # the shear, full against condensed from BeamDyn parked: IEA-15MW flap 1 -2.2 %, edge 1 -1.7 %; IEA-22MW
    # -1.5 %, -1.3 % (to 0.1 %)
    for turbine, flap, edge in (("IEA-15MW", -0.022, -0.017), ("IEA-22MW", -0.015, -0.013)):
        full, condensed = by[(turbine, "BeamDyn", "full", False)], by[(turbine, "BeamDyn", "condensed", False)]
        assert abs(full[0] / condensed[0] - 1 - flap) < 1e-3 and abs(full[1] / condensed[1] - 1 - edge) < 1e-3
    # rotation, parked to rated: IEA-15MW flap 1 +4.9 %, edge 1 +0.9 %; IEA-22MW +7.3 %, +1.3 % (to 0.1 %)
    for turbine, flap, edge in (("IEA-15MW", 0.049, 0.009), ("IEA-22MW", 0.073, 0.013)):
        parked, rated = by[(turbine, "BeamDyn", "full", False)], by[(turbine, "BeamDyn", "full", True)]
        assert abs(rated[0] / parked[0] - 1 - flap) < 1e-3 and abs(rated[1] / parked[1] - 1 - edge) < 1e-3
    # the quoted values: flap 4.5 % and 6.4 % above bladefem's rated, edge 9.1 % below and 9.0 % above (to 0.1 %)
    for turbine, quoted, above in (("IEA-15MW", (0.555, 0.642), (0.045, -0.091)),
                                   ("IEA-22MW", (0.441, 0.581), (0.064, 0.090))):
        rated = by[(turbine, "BeamDyn", "full", True)]
        for k in range(2):
            assert abs(quoted[k] / rated[k] - 1 - above[k]) < 1e-3, (turbine, k)


def test_beamdyn_comparison_table_is_current():
    """The mode-by-mode comparison with OpenFAST/BeamDyn: the document's table is what the example computes."""
    text = DOCUMENT.read_text()
    start = text.index("| straightened blade | rpm |")
    written = text[start:].split("\n\n", 1)[0].strip()
    assert written == iea_blades.beamdyn_table(iea_blades.beamdyn_rows())
