"""docs/iea-blades.md holds what examples/iea_blades.py computes now: every row of its two frequency tables (full
and reduced sections, every format, parked and rated) within one unit of the last printed digit, and the claims
its prose makes of them."""

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
    assert len(written) == len(computed) == 32
    for row in computed:
        key = (f"{row.turbine} {row.source}", f"{row.rpm:.2f}", row.sections)
        np.testing.assert_allclose(written[key], row.hz, atol=1e-4 + 1e-12, err_msg=str(key))


def test_document_claims_hold(computed):
    by = {(r.turbine, r.source, r.sections, r.rpm > 0): np.array(r.hz) for r in computed}
    # the section model moves the IEA-15MW's first six by under 0.1 % (measured 0.09 %, edge 1), the IEA-22MW's
    # bending by up to 0.15 % (held to 0.25 %)
    for source in iea_blades.INPUTS["IEA-15MW"]:
        for rated in (False, True):
            full, reduced = by[("IEA-15MW", source, "full", rated)], by[("IEA-15MW", source, "reduced", rated)]
            assert np.max(np.abs(reduced / full - 1)) < 1e-3
    for source in iea_blades.INPUTS["IEA-22MW"]:
        full, reduced = by[("IEA-22MW", source, "full", False)], by[("IEA-22MW", source, "reduced", False)]
        assert np.max(np.abs(reduced[:5] / full[:5] - 1)) < 2.5e-3
    # rotation, parked to rated (on the deflected axis): IEA-15MW flap 1 +4.8 %, edge 1 +1.0 %; IEA-22MW +7.1 %,
    # +1.6 % (to 0.1 %)
    for turbine, flap, edge in (("IEA-15MW", 0.048, 0.010), ("IEA-22MW", 0.071, 0.016)):
        parked, rated = by[(turbine, "BeamDyn", "full", False)], by[(turbine, "BeamDyn", "full", True)]
        assert abs(rated[0] / parked[0] - 1 - flap) < 1e-3 and abs(rated[1] / parked[1] - 1 - edge) < 1e-3
    # the quoted values: flap 2.4 % and 4.9 % above bladefem's rated, edge 9.9 % below and 8.6 % above (to 0.1 %)
    for turbine, quoted, above in (("IEA-15MW", (0.555, 0.642), (0.024, -0.099)),
                                   ("IEA-22MW", (0.441, 0.581), (0.049, 0.086))):
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
