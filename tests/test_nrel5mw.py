"""NREL 5MW blade against the seed paper's Table 1 (FAST 'Modes' column) and mesh convergence."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.case import read_case
from bladefem.modal import modes
from bladefem.models.galerkin import galerkin_modes

CASES = Path(__file__).resolve().parent.parent / "cases"
# seed 002, Table 1, Modes (FAST): first flap, first edge, second flap, second edge (Hz)
MODES_FAST = {("flap", 1): 0.6830, ("edge", 1): 1.0968, ("flap", 2): 1.9909, ("edge", 2): 4.0714}
#: ElastoDyn's blade mass factor in NRELOffshrBsline5MW_Blade.dat (the case file uses mass factor 1)
ADJ_BL_MS = 1.04536


@pytest.fixture(scope="module")
def blade():
    return read_case(CASES / "nrel5mw_blade.yaml")


def table1_values(result) -> np.ndarray:
    return np.array([result.first(kind, number).frequency_hz for kind, number in MODES_FAST])


@pytest.mark.parametrize("mass_factor", [1.0, ADJ_BL_MS], ids=["report-mass", "AdjBlMs"])
def test_fe_reproduces_the_modes_column_once_its_model_choices_are_applied(blade, mass_factor):
    """The converged FE differs from Table 1's 'Modes (FAST)' column by up to 1.5 % (mass factor 1) or 1.8 %
    (AdjBlMs); every part of that difference has a named cause, applied here one by one:

    1. mass: the Modes run used ElastoDyn's AdjBlMs = 1.04536 (mass factor 1 is sqrt(AdjBlMs) = 2.2 % higher);
    2. twist coupling: NREL's Modes program computes uncoupled flap and edge modes, and the column is reproduced
       with the structural twist zero (the usual input for ElastoDyn, which couples the modes itself through the
       pretwist; with the 5MW twist Modes' turned stiffnesses would give +1.5 % on the first flap mode): removing
       the twist moves the FE frequencies by -0.1, +0.3, -0.3, +0.9 %;
    3. truncation: Modes is a Rayleigh-Ritz model with the 5 polynomials x^2..x^6, stiff by +0.7, +0.5, +1.9, +0.5 %
       on this blade (bladefem's Galerkin model with the same 5-polynomial space against its converged 40 terms).

    What remains is 0.10-0.26 % (measured), the same for both mass factors: the Modes run's own input table, which
    the seed does not give (Modes' 100-interval trapezoid rule accounts for 0.03 % only); bound 0.3 %."""
    scaled = blade.with_(sections=blade.sections.scaled(mass=mass_factor))
    untwisted = scaled.with_(sections=replace(scaled.sections, twist=np.zeros_like(scaled.sections.span)))
    fe = table1_values(modes(untwisted, rpm=0.0, n_modes=6))
    truncation = (table1_values(galerkin_modes(untwisted, 0.0, 6, (5, 5, 0)))
                  / table1_values(galerkin_modes(untwisted, 0.0, 6, (40, 40, 0))))
    modes_program = np.array(list(MODES_FAST.values())) * np.sqrt(ADJ_BL_MS / mass_factor)
    np.testing.assert_allclose(fe * truncation, modes_program, rtol=3e-3)


def test_mesh_converged_and_stations_are_nodes(blade):
    # the automatic mesh is converged: a mesh four times finer moves the first six frequencies by < 1e-6
    # (measured 1.7e-7)
    automatic = modes(blade, rpm=12.1, n_modes=6)
    elements = len(automatic.modes[0].shape.x) - 1
    fine = modes(blade, rpm=12.1, n_modes=6, elements=4 * elements)
    assert len(fine.modes[0].shape.x) - 1 >= 4 * elements
    np.testing.assert_allclose(automatic.frequencies_hz, fine.frequencies_hz, rtol=1e-6)
    assert np.all(np.isin(blade.sections.span, automatic.modes[0].shape.x))


def test_kinds_and_centrifugal_stiffening(blade):
    rest, rated = modes(blade, 0.0, 4), modes(blade, 12.1, 4)
    assert rest.kinds == rated.kinds == ["flap", "edge", "flap", "edge"]
    # spin softening offsets most of the centrifugal stiffening in plane: edge rises far less than flap
    flap_rise = rated.frequencies_hz[0] / rest.frequencies_hz[0] - 1
    edge_rise = rated.frequencies_hz[1] / rest.frequencies_hz[1] - 1
    assert flap_rise > 3 * edge_rise > 0
