"""The seed paper's NREL 5MW tables (docs/seed-comparison.md): what bladefem reproduces and why Table 2 differs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bladefem.io.elastodyn_blade import blade_from_elastodyn_main
from bladefem.modal import modes
from bladefem.models.galerkin import PAPER_TERMS, galerkin_modes, galerkin_system, solve
from bladefem.models.galerkin_seed import (
    SEED_TABLE1,
    SEED_TABLE2,
    TABLE2_MODES,
    implied_southwell,
    inboard_tension,
    inboard_tension_matrices,
)
from bladefem.sections import Blade, uniform_sections

MAIN_FILE = Path(__file__).parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
#: positions of the seed's modes in bladefem's sorted list (flap 1, edge 1, flap 2, edge 2)
POSITION = {"1st flap": 0, "1st edge": 1, "2nd flap": 2, "2nd edge": 3}


@pytest.fixture(scope="module")
def blade() -> Blade:
    return blade_from_elastodyn_main(MAIN_FILE)


def seed_column(index: int, names=tuple(POSITION)) -> np.ndarray:
    return np.array([SEED_TABLE1[name][index] for name in names])


def test_paper_truncation_reproduces_the_seeds_table1(blade):
    result = galerkin_modes(blade, 0.0, 4, PAPER_TERMS)
    assert result.kinds == ["flap", "edge", "flap", "edge"]
    # same properties (AdjBlMs applied), same polynomial space: measured within 0.03%; the seed prints 4 decimals
    np.testing.assert_allclose(result.frequencies_hz, seed_column(2), rtol=1e-3)


def test_converged_fe_is_within_two_percent_of_table1(blade):
    fe = modes(blade, 0.0, 4).frequencies_hz
    # acceptance 2%: the seed's 5-term truncation is itself 1.9% stiff on the second flap mode (measured)
    np.testing.assert_allclose(fe, seed_column(2), rtol=0.02)
    np.testing.assert_allclose(fe, seed_column(0), rtol=0.02)            # FAST's Modes


def table2_array() -> np.ndarray:
    order = [TABLE2_MODES.index(name) for name in POSITION]                # seed columns in bladefem's order
    return np.array([[SEED_TABLE2[rpm][j] for j in order] for rpm in sorted(SEED_TABLE2)])


def test_root_integrated_tension_reproduces_table2(blade):
    matrices, notes = galerkin_system(blade, PAPER_TERMS)
    inboard = inboard_tension_matrices(blade, matrices)
    computed = np.array([solve(blade, inboard, rpm, 4, notes).frequencies_hz for rpm in sorted(SEED_TABLE2)])
    # measured 0.044% over all 24 numbers: the seed prints 4 decimals and its quadrature and precone handling
    # may differ in detail from bladefem's
    np.testing.assert_allclose(computed, table2_array(), rtol=1e-3)


def test_physical_model_stiffens_far_less_than_table2(blade):
    matrices, notes = galerkin_system(blade, PAPER_TERMS)
    physical = np.array([solve(blade, matrices, rpm, 4, notes).frequencies_hz for rpm in sorted(SEED_TABLE2)])
    seed = table2_array()
    rpm = np.array(sorted(SEED_TABLE2))[1:]
    K_physical = implied_southwell(physical[0, 0], physical[1:, 0], rpm)
    K_seed = implied_southwell(seed[0, 0], seed[1:, 0], rpm)
    # physics: an almost constant Southwell coefficient near 1.8 for the first flap mode; the seed's is 3-6 times
    # larger and falls with speed
    assert np.all(np.abs(K_physical - 1.8) < 0.05)
    assert np.all(K_seed > 3 * K_physical) and np.all(np.diff(K_seed) < 0)


def test_inboard_tension_of_a_uniform_blade_matches_closed_form():
    m, R, L, beta = 3.0, 2.0, 10.0, np.radians(-5)
    blade = Blade(uniform_sections(L, m, 1.0), hub_radius=R, precone=beta)
    x = np.linspace(0, L, 7)
    # int_0^x m (R + xi) cos^2(beta) dxi for the inboard pull; quadrature of a polynomial: round-off only
    np.testing.assert_allclose(inboard_tension(blade, x), m * (R * x + x**2 / 2) * np.cos(beta) ** 2,
                               rtol=1e-13, atol=1e-12)


def test_replacing_the_tension_by_itself_changes_nothing(blade):
    from bladefem.models.galerkin_seed import physical_tension, tension_variant_matrices
    matrices, _ = galerkin_system(blade, PAPER_TERMS)
    same = tension_variant_matrices(blade, matrices, physical_tension)
    # the diagnostic subtracts and re-adds the same integral: only round-off may differ
    assert abs(same.K2 - matrices.K2).max() <= 1e-12 * abs(matrices.K2).max()
