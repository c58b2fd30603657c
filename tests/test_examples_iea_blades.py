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
    # the section couplings (condensed against reduced, both Euler-Bernoulli, on the curved axis) move the IEA-15MW's
    # first six by under 0.1 % (measured 0.09 %, edge 1), the IEA-22MW's bending by up to 0.15 % (held to 0.25 %)
    for source in iea_blades.INPUTS["IEA-15MW"]:
        for rated in (False, True):
            full, reduced = by[("IEA-15MW", source, "condensed", rated)], by[("IEA-15MW", source, "reduced", rated)]
            assert np.max(np.abs(reduced / full - 1)) < 1e-3
    for source in iea_blades.INPUTS["IEA-22MW"]:
        full, reduced = by[("IEA-22MW", source, "condensed", False)], by[("IEA-22MW", source, "reduced", False)]
        assert np.max(np.abs(reduced[:5] / full[:5] - 1)) < 2.5e-3
    # the shear, full against condensed from BeamDyn parked (prebent): IEA-15MW flap 1 -2.1 %, edge 1 -1.8 %;
    # IEA-22MW -1.5 %, -1.4 % (to 0.1 %)
    for turbine, flap, edge in (("IEA-15MW", -0.021, -0.018), ("IEA-22MW", -0.015, -0.014)):
        full, condensed = by[(turbine, "BeamDyn", "full", False)], by[(turbine, "BeamDyn", "condensed", False)]
        assert abs(full[0] / condensed[0] - 1 - flap) < 1e-3 and abs(full[1] / condensed[1] - 1 - edge) < 1e-3
    # rotation, parked to rated (on the deflected axis): IEA-15MW flap 1 +4.9 %, edge 1 +1.0 %; IEA-22MW +7.3 %,
    # +1.6 % (to 0.1 %)
    for turbine, flap, edge in (("IEA-15MW", 0.049, 0.010), ("IEA-22MW", 0.073, 0.016)):
        parked, rated = by[(turbine, "BeamDyn", "full", False)], by[(turbine, "BeamDyn", "full", True)]
        assert abs(rated[0] / parked[0] - 1 - flap) < 1e-3 and abs(rated[1] / parked[1] - 1 - edge) < 1e-3
    # the quoted values: flap 4.4 % and 6.4 % above bladefem's rated, edge 8.2 % below and 10.1 % above (to 0.1 %)
    for turbine, quoted, above in (("IEA-15MW", (0.555, 0.642), (0.044, -0.082)),
                                   ("IEA-22MW", (0.441, 0.581), (0.064, 0.101))):
        rated = by[(turbine, "BeamDyn", "full", True)]
        for k in range(2):
            assert abs(quoted[k] / rated[k] - 1 - above[k]) < 1e-3, (turbine, k)


def test_the_prebend_table_is_current():
    """docs/iea-blades.md's prebend table is what examples/iea_blades.py computes, to the printed digit."""
    text = DOCUMENT.read_text()
    for (turbine, rpm), change in iea_blades.prebend_effects().items():
        line = next(line for line in text.splitlines() if line.startswith(f"| {turbine} bladefem | {rpm:.2f} |"))
        written = [float(c.strip().rstrip(" %")) for c in line.strip("|").split("|")[2:]]
        np.testing.assert_allclose(written, change, atol=0.005 + 1e-12, err_msg=line)


@pytest.mark.parametrize("axis, label", [("straight", "straightened"), ("prebent", "prebent")])
def test_beamdyn_comparison_table_is_current(axis, label):
    """The mode-by-mode comparisons with OpenFAST/BeamDyn, straightened and prebent: the document's tables are what
    the example computes."""
    text = DOCUMENT.read_text()
    start = text.index(f"| {label} blade | rpm |")
    written = text[start:].split("\n\n", 1)[0].strip()
    assert written == iea_blades.beamdyn_table(iea_blades.beamdyn_rows(axis), label)
