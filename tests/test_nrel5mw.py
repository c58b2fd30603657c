"""NREL 5MW blade against the seed paper's Table 1 (FAST 'Modes' column) and mesh convergence."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bladefem.io.case import read_case
from bladefem.modal import modes

CASES = Path(__file__).resolve().parent.parent / "cases"
# seed 002, Table 1, Modes (FAST): first flap, first edge, second flap, second edge (Hz)
MODES_FAST = {("flap", 1): 0.6830, ("edge", 1): 1.0968, ("flap", 2): 1.9909, ("edge", 2): 4.0714}


@pytest.fixture(scope="module")
def blade():
    return read_case(CASES / "nrel5mw_blade.yaml")


@pytest.mark.parametrize("mass_factor", [1.0, 1.04536], ids=["report-mass", "AdjBlMs"])
def test_table1_within_two_percent(blade, mass_factor):
    # Table 1's 'Modes' figures came from a polynomial-shape code with its own mass factor and mesh; the issue asks
    # for 2 %. Mass factor 1 (the report's distributed mass) gives +1.4/+1.3/+0.4/+0.7 %, AdjBlMs = 1.04536
    # (ElastoDyn's) gives -0.8/-1.0/-1.8/-1.5 %.
    scaled = blade.with_(sections=blade.sections.scaled(mass=mass_factor))
    result = modes(scaled, rpm=0.0, n_modes=6)
    for (kind, number), reference in MODES_FAST.items():
        assert result.first(kind, number).frequency_hz == pytest.approx(reference, rel=0.02), (kind, number)


def test_mesh_converged_and_stations_are_nodes(blade):
    # the automatic mesh is converged: a mesh four times finer moves the first six frequencies by < 1e-6
    automatic = modes(blade, rpm=12.1, n_modes=6)
    fine = modes(blade, rpm=12.1, n_modes=6, elements=400)
    np.testing.assert_allclose(automatic.frequencies_hz, fine.frequencies_hz, rtol=1e-6)
    assert np.all(np.isin(blade.sections.span, automatic.modes[0].shape.x))


def test_kinds_and_centrifugal_stiffening(blade):
    rest, rated = modes(blade, 0.0, 4), modes(blade, 12.1, 4)
    assert rest.kinds == rated.kinds == ["flap", "edge", "flap", "edge"]
    # spin softening offsets most of the centrifugal stiffening in plane: edge rises far less than flap
    flap_rise = rated.frequencies_hz[0] / rest.frequencies_hz[0] - 1
    edge_rise = rated.frequencies_hz[1] / rest.frequencies_hz[1] - 1
    assert flap_rise > 3 * edge_rise > 0
