"""docs/elastodyn-openfast.md holds what examples/elastodyn_openfast.py prints from the stored OpenFAST runs."""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "examples"))

import elastodyn_openfast  # noqa: E402


def test_the_page_holds_the_tables_the_example_prints():
    assert elastodyn_openfast.main() in (ROOT / "docs" / "elastodyn-openfast.md").read_text()


def test_the_coefficients_move_flap1_and_edge1_by_under_a_percent():
    """The page's first statement: between the three sets of coefficients flap 1 and edge 1 differ by < 0.6 %."""
    for turbine in ("iea15", "iea22"):
        for rpm in {r["rpm"] for r in elastodyn_openfast.CLIENT["runs"] if r["turbine"] == turbine}:
            runs = [r for r in elastodyn_openfast.CLIENT["runs"] if (r["turbine"], r["rpm"]) == (turbine, rpm)]
            for index in (0, 1):
                values = [r["frequencies_hz"][index] for r in runs]
                assert max(values) / min(values) - 1 < 0.006
