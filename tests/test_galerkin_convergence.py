"""Convergence of the Galerkin model with the number of assumed modes, and the conditioning of its basis."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.elastodyn_blade import blade_from_elastodyn_main
from bladefem.models.galerkin import galerkin_modes, galerkin_system
from bladefem.sections import Blade, SectionTable

MAIN_FILE = Path(__file__).parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
#: Relative round-off of the dense generalized eigen-solve on these systems: the lowest frequencies of the coupled
#: twisted blade move by up to 6e-10 when its section properties change only by round-off (1e-16); 16x margin.
ROUND_OFF = 1e-8


@pytest.fixture(scope="module")
def nrel5mw() -> Blade:
    return blade_from_elastodyn_main(MAIN_FILE)


def twisted_blade() -> Blade:
    """A tapered, twisted blade with torsion, section inertias and a centre-of-mass offset."""
    span = np.linspace(0.0, 20.0, 5)
    sections = SectionTable(span=span, mass=80 - 3 * span, flap_stiffness=4e6 - 1.5e5 * span,
                            edge_stiffness=1e7 - 4e5 * span, torsion_stiffness=1e6 - 4e4 * span,
                            twist=np.radians(12 - 0.6 * span), flap_inertia=0.4, edge_inertia=3.0 - 0.1 * span,
                            cm_offset=0.05)
    return Blade(sections, hub_radius=1.0, precone=np.radians(-3))


@pytest.mark.parametrize("rpm", [0.0, 12.1])
def test_nrel5mw_frequencies_decrease_monotonically_with_terms(nrel5mw, rpm):
    counts = [4, 8, 12, 16, 24, 32]
    frequencies = np.array([galerkin_modes(nrel5mw, rpm, 6, (n, n, 0)).frequencies_hz for n in counts])
    # nested trial spaces (Rayleigh-Ritz): every eigenvalue is non-increasing. The kinked 5MW properties keep every
    # step a real decrease (measured >= 2.9e-5 relative, 32 vs 24 terms), far above the eigen-solver's round-off
    # (ROUND_OFF): each step must fall by more than that
    assert np.all(np.diff(frequencies, axis=0) < -ROUND_OFF * frequencies[1:])


@pytest.mark.parametrize("rpm", [0.0, 30.0])
def test_coupled_twisted_blade_frequencies_decrease_with_terms(rpm):
    blade = twisted_blade()
    counts = [(4, 4, 2), (6, 6, 3), (8, 8, 5), (12, 12, 8), (16, 16, 12)]
    frequencies = np.array([galerkin_modes(blade, rpm, 8, terms).frequencies_hz for terms in counts])
    steps = np.diff(frequencies, axis=0) / frequencies[1:]
    # nested trial spaces: non-increasing up to the eigen-solver's round-off (the last step of the lowest modes is
    # at that level, measured |change| <= 3.5e-10); every mode that is not yet converged falls (first step: the
    # smallest drop is 1.6e-5, measured)
    assert np.all(steps <= ROUND_OFF)
    assert np.all(steps[0] < -1e-6)


def test_nrel5mw_error_falls_at_least_quadratically(nrel5mw):
    """The 5MW's stiffness and mass are only piecewise linear (kinks at stations): the polynomial Galerkin
    converges algebraically, not exponentially. The error against a 48-term solution falls like N^-2.1 to N^-2.5
    between 8 and 16 terms (measured, first four modes); require at least N^-1.8."""
    reference = galerkin_modes(nrel5mw, 0.0, 4, (48, 48, 0)).frequencies_hz
    error = {n: galerkin_modes(nrel5mw, 0.0, 4, (n, n, 0)).frequencies_hz / reference - 1 for n in (8, 16)}
    assert np.all(error[16] < error[8] / 2**1.8)


def test_uniform_blade_converges_exponentially():
    sections = SectionTable(span=np.array([0.0, 1.0]), mass=1.0, flap_stiffness=1.0, edge_stiffness=4.0)
    w = {n: galerkin_modes(Blade(sections), 0.0, 1, (n, n, 0)).frequencies_hz[0] * 2 * np.pi for n in (3, 5, 7)}
    exact = 1.87510407**2
    errors = [w[n] / exact - 1 for n in (3, 5, 7)]
    # smooth eigenfunction: each two extra polynomial terms gain orders of magnitude (limited by b's 9 digits)
    assert errors[0] > 0 and errors[1] < errors[0] / 1000 and errors[2] < 1e-8


@pytest.mark.parametrize("n", [3, 5, 8])
def test_monomial_and_jacobi_bases_span_the_same_space(nrel5mw, n):
    jacobi = galerkin_modes(nrel5mw, 12.1, 6, (n, n, 0), basis="jacobi").frequencies_hz
    monomial = galerkin_modes(nrel5mw, 12.1, 6, (n, n, 0), basis="monomial").frequencies_hz
    # identical spaces: differences are round-off amplified by the monomial mass-matrix condition (7e11 at n = 8)
    np.testing.assert_allclose(monomial, jacobi, rtol=1e-7)


def test_jacobi_basis_stays_well_conditioned(nrel5mw):
    def condition(n: int, basis: str) -> float:
        return float(np.linalg.cond(galerkin_system(nrel5mw, (n, n, 0), basis)[0].M))

    # the monomial Gram matrix grows like a Hilbert matrix (1e18 at n = 12, measured); the orthonormal basis
    # stays O(n) on the 5MW (72 at n = 40)
    assert condition(12, "monomial") > 1e15
    assert condition(40, "jacobi") < 1e3


def test_quadrature_is_converged(nrel5mw):
    from bladefem.models.galerkin_matrices import Terms, galerkin_matrices
    coarse = galerkin_matrices(nrel5mw, Terms(12, 12, 0))
    fine = galerkin_matrices(nrel5mw, Terms(12, 12, 0), order=30, min_cells=96)
    for name in ("M", "K0", "K2"):
        a, b = getattr(coarse, name), getattr(fine, name)
        # piecewise-polynomial integrands (linear properties times polynomials) are integrated exactly by the
        # default rule, except the cosines of the interpolated twist: measured differences are round-off (1e-15)
        assert np.abs(a - b).max() <= 1e-12 * np.abs(b).max()
