"""Tower modal analysis against closed forms and an independent power-series solution.

Uniform tower, nondimensional: m = EI = L = 1, so omega = beta^2 and the gravity load parameter q L^3 / EI = g.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from bladefem.assembly.tower import assemble_tower
from bladefem.models.tower import critical_load_factor, tower_modes, with_blade_kinds
from bladefem.sections import uniform_sections
from bladefem.sections.tower import TopMass, Tower

# FE frequencies converge as h^4; the default mesh is refined to 1e-6, 40+ elements give ~1e-8 on these cases.
# Tolerance 1e-5 on beta (the acceptance criterion) leaves two orders of margin.
BETA_TOL = 1e-5


def uniform_tower(**changes: object) -> Tower:
    return Tower(uniform_sections(1.0, 1.0, 1.0), gravity=0.0).with_(**changes)


def roots(f, start: float, stop: float, count: int) -> list[float]:
    """The first ``count`` sign changes of ``f`` on a fine grid, refined by Brent's method."""
    grid = np.linspace(start, stop, 600)
    values = np.array([f(b) for b in grid])
    found = [brentq(f, grid[i], grid[i + 1], xtol=1e-14) for i in np.flatnonzero(np.sign(values[:-1])
                                                                                   != np.sign(values[1:]))]
    return found[:count]


def tip_mass_equation(b: float, mu: float, j: float = 0.0) -> float:
    """Frequency equation of a clamped-free uniform beam with a tip mass mu = M/(mL) and tip rotary inertia
    j = J/(mL^3) about the tip (derived in docs/tower.md; j = 0 is the equation of the reference README)."""
    c, s, ch, sh = np.cos(b), np.sin(b), np.cosh(b), np.sinh(b)
    return (1 + c * ch + mu * b * (c * sh - s * ch) - j * b**3 * (sh * c + s * ch)
            + mu * j * b**4 * (1 - c * ch))


def test_tip_mass_mu_one_matches_the_frequency_equation():
    expected = roots(lambda b: tip_mass_equation(b, 1.0), 0.5, 6.0, 2)
    assert expected == pytest.approx([1.247917, 4.031139], abs=1e-6)     # the values (7 digits)
    result = tower_modes(uniform_tower(top_mass=TopMass(1.0)), 4)
    fore_aft = [np.sqrt(2 * np.pi * result.first("fore-aft", n).frequency_hz) for n in (1, 2)]
    side_side = [np.sqrt(2 * np.pi * result.first("side-side", n).frequency_hz) for n in (1, 2)]
    assert fore_aft == pytest.approx(expected, abs=BETA_TOL)
    assert side_side == pytest.approx(expected, abs=BETA_TOL)


def test_tip_rotary_inertia_matches_the_frequency_equation():
    mu, j = 1.0, 0.05
    expected = roots(lambda b: tip_mass_equation(b, mu, j), 0.5, 6.0, 2)
    # the expanded equation agrees with the boundary determinant it was derived from (the series reference below
    # with g = 0 and c = 0 is that determinant evaluated numerically): guards the algebra
    assert np.sqrt(series_frequencies(0.0, 2, mu=mu, j=j)) == pytest.approx(expected, rel=1e-9)
    inertia = np.diag([0.0, j, 0.0])             # about y: resists fore-aft section rotation only
    result = tower_modes(uniform_tower(top_mass=TopMass(mu, inertia=inertia)), 6)
    fore_aft = [np.sqrt(2 * np.pi * result.first("fore-aft", n).frequency_hz) for n in (1, 2)]
    assert fore_aft == pytest.approx(expected, abs=BETA_TOL)
    side_side = [np.sqrt(2 * np.pi * result.first("side-side", n).frequency_hz) for n in (1, 2)]
    assert side_side == pytest.approx(roots(lambda b: tip_mass_equation(b, mu), 0.5, 6.0, 2), abs=BETA_TOL)


# -- gravity: an independent power-series solution -----------------------------------------------------------

def series_determinant(omega2: float, g: float, mu: float = 0.0, c: float = 0.0, j: float = 0.0,
                       terms: int = 90) -> float:
    """Boundary determinant of w'''' + ((g (1 - x) + mu g) w')' = omega^2 w on [0, 1] (m = EI = L = 1), clamped at
    0; at 1 a body of mass mu, centre of mass c above the top, rotary inertia j about it:
    w'' - mu g c w' - omega^2 (mu c (w + c w') + j w') = 0 and -w''' - mu g w' - omega^2 mu (w + c w') = 0.
    The solution is an entire power series sum a_k x^k, a_0 = a_1 = 0 (the ODE has polynomial coefficients)."""
    P = g + mu * g
    columns = []
    for start in (2, 3):
        a = np.zeros(terms + 4)
        a[start] = 1.0
        for k in range(terms):
            a[k + 4] = (omega2 * a[k] - P * (k + 2) * (k + 1) * a[k + 2] + g * (k + 1) ** 2 * a[k + 1]) / (
                (k + 4) * (k + 3) * (k + 2) * (k + 1))
        n = np.arange(len(a))
        w, w1 = a.sum(), (n * a).sum()
        w2, w3 = (n * (n - 1) * a).sum(), (n * (n - 1) * (n - 2) * a).sum()
        tip = w + c * w1
        columns.append([w2 - mu * g * c * w1 - omega2 * (mu * c * tip + j * w1), -w3 - mu * g * w1 - omega2 * mu * tip])
    return columns[0][0] * columns[1][1] - columns[0][1] * columns[1][0]


def series_frequencies(g: float, count: int, **body: float) -> list[float]:
    """Lowest ``count`` omega from the series determinant (roots in omega^2, scanned on a grid)."""
    def f(omega: float) -> float:
        return series_determinant(omega**2, g, **body)
    return roots(f, 1e-3, 40.0, count)


def test_series_reference_reproduces_the_classic_values():
    # self-check of the independent reference: bare cantilever and Greenhill's critical self-weight 7.837
    # the b_n are given to 9 digits (relative 3e-9), so omega = b^2 is known to ~6e-9
    assert series_frequencies(0.0, 2) == pytest.approx([1.87510407**2, 4.69409113**2], rel=1e-8)
    critical = brentq(lambda g: series_determinant(0.0, g), 7.0, 8.5, xtol=1e-13)
    assert critical == pytest.approx(7.837, abs=5e-4)


def test_self_weight_buckling_load():
    critical = brentq(lambda g: series_determinant(0.0, g), 7.0, 8.5, xtol=1e-13)
    factor = critical_load_factor(assemble_tower(uniform_tower(gravity=1.0), 40))
    # h^4 convergence: 40 elements give ~1e-8 relative
    assert factor == pytest.approx(critical, rel=1e-6)


@pytest.mark.parametrize("deck", ["Test03_tower", "Test04_wires_supported_tower"])
def test_buckling_factor_is_the_dense_generalised_eigenvalue(deck):
    # the sparse Lanczos value against the dense solve of every eigenvalue of G x = mu K x on BModes' CertTest
    # towers (tapered, top mass with offsets, wires): the same largest mu to round-off
    from pathlib import Path

    import scipy.linalg as la

    from bladefem.builders.detect import read_model
    matrices = assemble_tower(read_model(Path(__file__).parent / "data" / "bmodes_certtest" / f"{deck}.bmi"), 40)
    K, _ = matrices.reduced(0.0)
    K_g = (matrices.Z.T @ matrices.K_gravity @ matrices.Z).toarray()
    largest = la.eigh(-0.5 * (K_g + K_g.T), K.toarray(), eigvals_only=True).max()
    assert critical_load_factor(matrices) == pytest.approx(1.0 / largest, rel=1e-9)


@pytest.mark.filterwarnings("ignore:the gravity load is")
@pytest.mark.parametrize("g", [0.0, 2.0, 4.0, 6.0, 7.5, 7.8])
def test_frequency_falls_with_self_weight_as_the_series_solution(g):
    expected = series_frequencies(g, 2)
    result = tower_modes(uniform_tower(gravity=g), 4, elements=80)
    found = [2 * np.pi * result.first("fore-aft", n).frequency_hz for n in (1, 2)]
    # near the critical load omega_1 -> 0 and the relative error grows; compare omega^2 absolutely (the FE error
    # on omega^2 is ~1e-8 absolute on this mesh) and omega_2 relatively
    assert found[0] ** 2 == pytest.approx(expected[0] ** 2, abs=1e-6)
    assert found[1] == pytest.approx(expected[1], rel=1e-7)


@pytest.mark.filterwarnings("ignore:the gravity load is")
def test_top_mass_pendulum_and_compression():
    body = {"mu": 0.5, "c": 0.2, "j": 0.01}
    g = 1.5
    expected = series_frequencies(g, 2, **body)
    offset = np.array([body["c"], 0.0, 0.0])                       # centre of mass above the top
    top = TopMass(body["mu"], offset=offset, inertia=np.diag([0.0, body["j"], 0.0]))
    result = tower_modes(uniform_tower(top_mass=top, gravity=g), 6, elements=80)
    found = [2 * np.pi * result.first("fore-aft", n).frequency_hz for n in (1, 2)]
    assert found == pytest.approx(expected, rel=1e-7)
    # the pendulum effect matters: without it (c = 0 in the reference) the first frequency is clearly higher
    assert series_frequencies(g, 1, mu=0.5, j=0.01 + 0.5 * 0.04)[0] > expected[0] * 1.001


def test_buckling_warning_near_the_critical_load():
    with pytest.warns(UserWarning, match="critical buckling load"):
        result = tower_modes(uniform_tower(gravity=7.0), 2, elements=40)
    assert any(note.startswith("warning:") for note in result.notes)


def test_buckled_tower_reports_negative_frequency():
    with pytest.warns(UserWarning, match="buckles"):
        result = tower_modes(uniform_tower(gravity=8.0), 2, elements=40)
    assert result.frequencies_hz[0] < 0


def test_degenerate_pair_is_rotated_into_clean_directions():
    result = tower_modes(uniform_tower(top_mass=TopMass(1.0)), 4, elements=40)
    for mode in result.modes:
        assert max(mode.energy_fractions.values()) > 1 - 1e-9
    assert result.kinds == ["fore-aft", "side-side", "fore-aft", "side-side"]
    assert result.modes[0].shape.flap[-1] == pytest.approx(1.0)
    assert np.abs(result.modes[0].shape.edge).max() < 1e-9
    assert max(mode.residual for mode in result.modes) < 1e-12


def test_torsion_and_axial_closed_forms():
    sections = uniform_sections(2.0, 3.0, 5.0, torsion_stiffness=7.0, axial_stiffness=11.0, flap_inertia=0.2,
                                edge_inertia=0.3)
    result = tower_modes(Tower(sections, gravity=0.0), 12, elements=60)
    torsion = 2 * np.pi * result.first("torsion").frequency_hz
    axial = 2 * np.pi * result.first("axial").frequency_hz
    # clamped-free rods: omega = (pi / 2) sqrt(GJ / (I_p L^2)), (pi / 2) sqrt(EA / (m L^2)); quadratic elements
    # converge as h^2... h^4 for frequencies: 60 elements give ~1e-6
    assert torsion == pytest.approx(np.pi / 2 * np.sqrt(7.0 / (0.5 * 4.0)), rel=1e-5)
    assert axial == pytest.approx(np.pi / 2 * np.sqrt(11.0 / (3.0 * 4.0)), rel=1e-5)


def test_blade_kinds_view_for_the_elastodyn_fit():
    result = with_blade_kinds(tower_modes(uniform_tower(top_mass=TopMass(1.0)), 2, elements=30))
    assert result.kinds == ["flap", "edge"]
    assert result.modes[0].energy_fractions["flap"] == pytest.approx(1.0)
