"""The Galerkin blade model against closed forms and published tables (no finite elements involved)."""

from __future__ import annotations

import numpy as np
import pytest

from bladefem.errors import InputError
from bladefem.models.galerkin import galerkin_modes, galerkin_system, parse_terms
from bladefem.sections import Blade, SectionTable, TipMass, uniform_sections

L, MASS, EI = 10.0, 5.0, 2.0e4
#: frequency scale: w = omega * sqrt(m L^4 / EI), lambda = Omega * sqrt(m L^4 / EI)
SCALE = np.sqrt(MASS * L**4 / EI)
TERMS = (14, 14, 0)


def nondimensional(frequencies_hz):
    return np.asarray(frequencies_hz) * 2 * np.pi * SCALE


def rpm_of(lam: float) -> float:
    return lam / SCALE * 30 / np.pi


def flap_frequencies(result):
    return nondimensional([mode.frequency_hz for mode in result.modes if mode.kind == "flap"])


def uniform_blade(**options) -> Blade:
    """Uniform blade whose edge stiffness (3 EI) separates edge from flap modes."""
    return Blade(uniform_sections(L, MASS, EI, edge_stiffness=3 * EI), **options)


def test_nonrotating_cantilever_matches_characteristic_roots():
    b = np.array([1.87510407, 4.69409113, 7.85475744, 10.99554073])
    flap = flap_frequencies(galerkin_modes(uniform_blade(), 0.0, 8, TERMS))
    # the roots are given to 9 digits: omega ~ b^2 carries about 1e-8 relative rounding
    np.testing.assert_allclose(flap[:4], b**2, rtol=2e-8)


ROTATING_TABLE = {  # lambda: (w1, w2, w3), reference README item 4 (R = 0)
    0: (3.51602, 22.03449, 61.69721), 1: (3.68165, 22.18101, 61.84176), 2: (4.13732, 22.61492, 62.27318),
    3: (4.79728, 23.32026, 62.98497), 4: (5.58500, 24.27335, 63.96676), 5: (6.44954, 25.44608, 65.20504),
    6: (7.36037, 26.80908, 66.68391), 7: (8.29964, 28.33408, 68.38595), 8: (9.25684, 29.99538, 70.29296),
    9: (10.22569, 31.77051, 72.38668), 10: (11.20233, 33.64037, 74.64929), 11: (12.18434, 35.58897, 77.06384),
    12: (13.17015, 37.60311, 79.61448)}


@pytest.mark.parametrize("lam", sorted(ROTATING_TABLE))
def test_rotating_flap_matches_published_table(lam):
    flap = flap_frequencies(galerkin_modes(uniform_blade(), rpm_of(lam), 8, TERMS))
    # the table has 5 decimals: agreement to one unit in the last digit (acceptance asks 1e-4 relative)
    np.testing.assert_allclose(flap[:3], ROTATING_TABLE[lam], rtol=0, atol=1e-5)


def test_southwell_coefficients_are_the_small_speed_slope():
    matrices, _ = galerkin_system(uniform_blade(), TERMS)
    result = galerkin_modes(uniform_blade(), 0.0, 8, TERMS)
    flap = [j for j, mode in enumerate(result.modes) if mode.kind == "flap"][:3]
    phi = result.vectors[:, flap]
    # omega^2 = omega_0^2 + K Omega^2: first-order perturbation of the M-normalised modes, dlambda/dOmega^2
    slope = np.einsum("ij,ik,kj->j", phi, matrices.K2, phi)
    # published to 7 significant digits
    np.testing.assert_allclose(slope, [1.193336, 6.478225, 17.85952], rtol=1e-6)


def tapered_sections(flap: float, edge: float) -> SectionTable:
    span = np.linspace(0.0, L, 6)
    return SectionTable(span=span, mass=MASS * (1.5 - 0.1 * span), flap_stiffness=flap * (2 - 0.15 * span),
                        edge_stiffness=edge * (2 - 0.15 * span))


@pytest.mark.parametrize("rpm", [10.0, 40.0])
def test_lag_frequencies_follow_flap_minus_rotor_speed_squared(rpm):
    """omega_lag^2 = omega_flap^2(EI_lag) - Omega^2 for any m(x), EI(x), hub radius and tip mass (no precone)."""
    options = dict(hub_radius=1.3, tip_mass=TipMass(4.0))
    edge_blade = Blade(tapered_sections(EI, 4 * EI), **options)
    swapped = Blade(tapered_sections(4 * EI, EI), **options)
    lag = [m.frequency_hz for m in galerkin_modes(edge_blade, rpm, 8, (10, 10, 0)).modes if m.kind == "edge"]
    flap = [m.frequency_hz for m in galerkin_modes(swapped, rpm, 8, (10, 10, 0)).modes if m.kind == "flap"]
    omega = rpm * np.pi / 30
    lag, flap = (2 * np.pi * np.array(values[:3]) for values in (lag, flap))
    # same shape functions for v and w: the relation holds in the discrete model up to eigen-solver round-off
    np.testing.assert_allclose(lag**2, flap**2 - omega**2, rtol=1e-9)


@pytest.mark.parametrize("rpm", [0.0, 25.0, 60.0])
def test_rotating_torsion_follows_propeller_moment(rpm):
    i_flap, i_edge, GJ = 0.01, 0.3, 3.0e3
    sections = uniform_sections(L, MASS, EI, edge_stiffness=5 * EI, torsion_stiffness=GJ, flap_inertia=i_flap,
                                edge_inertia=i_edge)
    result = galerkin_modes(Blade(sections), rpm, 14, (8, 8, 3))
    torsion = 2 * np.pi * np.array([mode.frequency_hz for mode in result.modes if mode.kind == "torsion"][:2])
    polar = i_flap + i_edge
    omega = rpm * np.pi / 30
    n = np.array([1, 2])
    expected = np.sqrt(((2 * n - 1) * np.pi / 2) ** 2 * GJ / (polar * L**2)
                       + omega**2 * (i_edge - i_flap) / polar)
    # the sine functions are the exact uncoupled torsion modes: only quadrature round-off remains
    np.testing.assert_allclose(torsion, expected, rtol=1e-10)


def test_tip_mass_cantilever_matches_frequency_equation():
    blade = uniform_blade(tip_mass=TipMass(MASS * L))            # mu = 1
    flap = flap_frequencies(galerkin_modes(blade, 0.0, 8, TERMS))
    # published to 7 significant digits
    np.testing.assert_allclose(flap[:3], [1.557298, 16.25009, 50.89584], rtol=1e-6)


def test_first_mode_shape_matches_cantilever_eigenfunction():
    sections = SectionTable(span=np.linspace(0, L, 11), mass=MASS, flap_stiffness=EI, edge_stiffness=3 * EI)
    shape = galerkin_modes(Blade(sections), 0.0, 1, TERMS).modes[0].shape
    b = 1.87510407 / L
    sigma = (np.cosh(b * L) + np.cos(b * L)) / (np.sinh(b * L) + np.sin(b * L))
    x = shape.x
    exact = np.cosh(b * x) - np.cos(b * x) - sigma * (np.sinh(b * x) - np.sin(b * x))
    slope = b * (np.sinh(b * x) + np.sin(b * x) - sigma * (np.cosh(b * x) - np.cos(b * x)))
    # b is given to 9 digits; the converged polynomial shape is accurate far below this
    np.testing.assert_allclose(shape.flap, exact / exact[-1], atol=1e-7)
    np.testing.assert_allclose(shape.flap_slope, slope / exact[-1], atol=1e-7 / L)
    assert np.all(shape.edge == 0) and np.all(shape.twist == 0)


def test_no_torsion_stiffness_means_rigid_torsion():
    result = galerkin_modes(uniform_blade(), 0.0, 6, (5, 5, 3))
    assert "torsion" not in result.kinds
    assert result.n_dofs == 10
    assert any("rigid" in note for note in result.notes)


def test_hinged_root_is_refused():
    with pytest.raises(InputError, match="cantilever"):
        galerkin_modes(uniform_blade(root="hinged"))


@pytest.mark.parametrize("text", ["5,5", "a,b,c", "0,5,3", "5,5,-1", ""])
def test_bad_terms_are_input_errors(text):
    with pytest.raises(InputError) as error:
        parse_terms(text)
    assert error.value.field == "--terms"


def test_terms_parse():
    assert parse_terms(" 8, 6,2") == (8, 6, 2)


def test_centrifugal_tension_matches_closed_form():
    from bladefem.models.galerkin_matrices import cell_edges, centrifugal_tension
    R, beta, tip_mass, p_x = 1.5, np.radians(-5), 4.0, 0.3
    blade = uniform_blade(hub_radius=R, precone=beta, tip_mass=TipMass(tip_mass, offset=[p_x, 0.0, 0.0]))
    x = np.linspace(0, L, 9)
    # N / Omega^2 = cos^2(beta) [m (R (L - x) + (L^2 - x^2) / 2) + M_t (R + L + p_x)]: a polynomial integrand
    expected = np.cos(beta) ** 2 * (MASS * (R * (L - x) + (L**2 - x**2) / 2) + tip_mass * (R + L + p_x))
    computed = centrifugal_tension(blade, cell_edges(blade.sections.span), x, 8)
    np.testing.assert_allclose(computed, expected, rtol=1e-13)


def coupled_blade() -> Blade:
    sections = SectionTable(span=np.array([0.0, 4.0, L]), mass=[6.0, 5.0, 3.0], flap_stiffness=[3e4, 2e4, 1e4],
                            edge_stiffness=[8e4, 6e4, 3e4], torsion_stiffness=[5e3, 4e3, 2e3],
                            twist=[0.3, 0.15, 0.0], flap_inertia=0.02, edge_inertia=0.25, cm_offset=0.08)
    return Blade(sections, hub_radius=1.0, precone=np.radians(-3), pitch=0.05)


def test_result_reports_fractions_and_small_residuals():
    result = galerkin_modes(coupled_blade(), 20.0, 8, (8, 8, 4))
    for mode in result.modes:
        assert abs(sum(mode.energy_fractions.values()) - 1) < 1e-12
        assert mode.energy_fractions[mode.kind] == max(mode.energy_fractions.values())
        # dense generalized eigen-solver on a 20x20 system: residuals at round-off level
        assert mode.residual < 1e-10
    assert {"flap", "edge", "torsion"} <= set(result.kinds)
    assert np.all(np.diff(result.frequencies_hz) >= 0)


def test_campbell_families_follow_the_single_speed_solutions():
    from bladefem.models.galerkin import galerkin_campbell
    rpm = [0.0, 10.0, 20.0, 30.0]
    sweep = galerkin_campbell(coupled_blade(), rpm, n_modes=4, terms=(8, 8, 4))
    for k, speed in enumerate(rpm):
        single = galerkin_modes(coupled_blade(), speed, 12, (8, 8, 4)).frequencies_hz
        for family in sweep.families:
            # the same matrices; the eigen-solver computes a subset or all pairs (LAPACK round-off, 1e-11 measured)
            assert family.frequencies_hz[k] == pytest.approx(single[family.indices[k]], rel=1e-9)
    # twist couples flap and edge more as the speed grows: MAC between neighbouring speeds measured >= 0.945
    assert all(family.mac.min() > 0.9 for family in sweep.families)
    assert [family.kind for family in sweep.families] == ["flap", "edge", "flap", "torsion"]
