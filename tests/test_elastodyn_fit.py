"""ElastoDyn mode-shape polynomials: constrained fit, independence of node spacing, mode selection by kind,
ElastoDyn-derived frequencies against closed forms and FE, and the NREL 5MW blade and tower."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.elastodyn_blade import blade_from_elastodyn_main, read_elastodyn_blade
from bladefem.builders.elastodyn_tower import read_elastodyn_tower, tower_from_elastodyn_main
from bladefem.modal.elastodyn_fit import (
    blade_coefficients,
    centrifugal_load,
    composite_gauss,
    elastodyn_frequency,
    fit_sextic,
    fitting_target,
    modes_of_kind,
    polynomial,
)
from bladefem.modal.results import ModalResult, Mode, ModeShape
from bladefem.models.tower_fit import tower_coefficients
from bladefem.sections import Blade, uniform_sections

DATA = Path(__file__).parent / "data"
MAIN = DATA / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
BETA1 = 1.87510407                              # first root of 1 + cos b cosh b = 0


def cantilever_mode(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exact first mode of a uniform clamped-free beam of unit length, and its slope."""
    b = BETA1
    sigma = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))
    value = np.cosh(b * x) - np.cos(b * x) - sigma * (np.sinh(b * x) - np.sin(b * x))
    slope = b * (np.sinh(b * x) + np.sin(b * x) - sigma * (np.cosh(b * x) - np.cos(b * x)))
    return value, slope


def analytic_mode(nodes: np.ndarray, rigid: tuple[float, float] = (0.0, 0.0)) -> Mode:
    """A Mode carrying the exact cantilever shape (plus an optional rigid translation and rotation) at ``nodes``."""
    value, slope = cantilever_mode(nodes)
    value = value + rigid[0] + rigid[1] * nodes
    slope = slope + rigid[1]
    zero = np.zeros_like(nodes)
    shape = ModeShape(x=nodes, flap=value, flap_slope=slope, edge=zero, edge_slope=zero, twist=zero, axial=zero)
    return Mode(1.0, "flap", {"flap": 1.0, "edge": 0.0, "torsion": 0.0, "axial": 0.0}, 0.0, shape)


# -- the constrained least-squares fit ---------------------------------------------------------------------------

def test_exact_sextic_is_recovered_and_the_constraint_holds():
    known = np.array([0.3, 2.1, -4.0, 3.5, -0.9])                      # adds up to 1
    points, weights = composite_gauss(np.linspace(0, 1, 7))
    fit = fit_sextic(points, weights, polynomial(known, points), float(polynomial(known, np.array([1.0]), 1)[0]))
    assert np.allclose(fit.coefficients, known, rtol=0, atol=1e-9)     # conditioning ~1e3 times 1e-16 rounding
    assert abs(fit.coefficients.sum() - 1) < 1e-12
    assert fit.rms_error < 1e-12 and abs(fit.tip_slope_error) < 1e-9


def test_tip_constraint_is_imposed_on_a_target_that_violates_it():
    # a sextic whose coefficients add up to 1.1: an unconstrained fit would return it exactly (RMS 0); the
    # constrained one must keep sum c = 1 and so cannot reach it
    known = 1.1 * np.array([0.3, 2.1, -4.0, 3.5, -0.9])
    points, weights = composite_gauss(np.linspace(0, 1, 7))
    fit = fit_sextic(points, weights, polynomial(known, points), 0.0)
    assert abs(fit.coefficients.sum() - 1) < 1e-12
    assert fit.rms_error > 1e-3
    free, *_ = np.linalg.lstsq(np.sqrt(weights)[:, None] * points[:, None] ** np.arange(2, 7),
                               np.sqrt(weights) * polynomial(known, points), rcond=None)
    assert np.allclose(free, known, atol=1e-9)                         # the control: unconstrained recovers it


def test_frequency_preserving_fit_has_the_target_rayleigh_quotient():
    """The exact first cantilever mode with a target frequency 2 % above its own: the constrained fit's Rayleigh
    quotient (with the given stiffness and mass forms) hits the target to rounding, keeps sum c = 1, and stays
    close to the shape; the plain displacement fit has the cantilever's frequency (the control)."""
    from bladefem.modal.elastodyn_fit import elastodyn_forms, fit_sextic_at_frequency
    beam = uniform_sections(1.0, 1.0, 1.0)
    target = fitting_target(analytic_mode(np.linspace(0, 1, 41)), "flap", 1.0)
    K, M = elastodyn_forms(beam, "flap_stiffness", 400)
    plain = fit_sextic(target.points, target.weights, target.values, target.tip_slope)
    omega = 1.02 * BETA1**2
    fit = fit_sextic_at_frequency(target.points, target.weights, target.values, target.tip_slope, K, M, omega)
    c = fit.coefficients
    assert fit.frequency_preserved
    assert math.sqrt(c @ K @ c / (c @ M @ c)) == pytest.approx(omega, rel=1e-9)      # root finder's tolerance
    assert abs(c.sum() - 1) < 1e-12
    assert math.sqrt(plain.coefficients @ K @ plain.coefficients / (plain.coefficients @ M @ plain.coefficients)) \
        == pytest.approx(BETA1**2, rel=1e-4)
    assert plain.rms_error < fit.rms_error < 0.05
    # below the lowest Rayleigh quotient of any sextic (the exact eigenvalue bounds it) no fit exists: the plain
    # displacement fit is returned, flagged
    low = fit_sextic_at_frequency(target.points, target.weights, target.values, target.tip_slope, K, M,
                                  0.98 * BETA1**2)
    assert not low.frequency_preserved and np.allclose(low.coefficients, plain.coefficients)


def test_fit_does_not_depend_on_node_spacing():
    uniform = np.linspace(0, 1, 41)
    graded = np.unique(np.concatenate([np.linspace(0, 1, 26), np.linspace(0.9, 1, 61)]))   # 3 of 4 nodes at the tip
    fits = [fitting_target(analytic_mode(nodes), "flap", 1.0) for nodes in (uniform, graded)]
    results = [fit_sextic(t.points, t.weights, t.values, t.tip_slope) for t in fits]
    # reference: the continuous least-squares problem on the exact shape with a very fine quadrature
    points, weights = composite_gauss(np.linspace(0, 1, 401))
    value, slope = cantilever_mode(np.append(points, 1.0))
    reference = fit_sextic(points, weights, value[:-1] / value[-1], slope[-1] / value[-1])
    for result in results:
        # the Hermite interpolation of the exact shape between nodes (h <= 0.04) errs by ~h^4 beta^4 / 384 ~ 2e-7,
        # amplified by at most 1 / sigma_min(design) ~ 3e3 in the coefficients
        assert np.allclose(result.coefficients, reference.coefficients, rtol=0, atol=5e-5)
        assert result.rms_error == pytest.approx(reference.rms_error, rel=0.05)
    # the test can fail: an unweighted least-squares fit at the graded nodes is pulled toward the tip
    v, _ = cantilever_mode(graded)
    naive = fit_sextic(graded, np.full(len(graded), 1 / len(graded)), v / v[-1], 0.0)
    assert np.max(np.abs(naive.coefficients - reference.coefficients)) > 1e-3
    # a sextic cannot reproduce cosh/cos exactly but comes within 1e-3 of the tip deflection (acceptance)
    assert 1e-7 < reference.rms_error < 1e-3
    assert abs(reference.coefficients.sum() - 1) < 1e-12


def test_rigid_base_motion_is_removed_for_towers():
    nodes = np.linspace(0, 1, 21)
    plain = fitting_target(analytic_mode(nodes), "flap", 1.0, remove_base_motion=True)
    moved = fitting_target(analytic_mode(nodes, rigid=(0.4, -0.7)), "flap", 1.0, remove_base_motion=True)
    assert np.allclose(moved.values, plain.values, rtol=0, atol=1e-12)
    kept = fitting_target(analytic_mode(nodes, rigid=(0.4, -0.7)), "flap", 1.0, remove_base_motion=False)
    assert not np.allclose(kept.values, plain.values, atol=1e-3)


# -- ElastoDyn's generalized mass and stiffness ------------------------------------------------------------------

def test_centrifugal_load_of_a_uniform_blade():
    sections = uniform_sections(10.0, 3.0, 1e6)
    nodes = (np.arange(400) + 0.5) * 10.0 / 400
    load = centrifugal_load(sections, nodes, 10.0 / 400, hub_radius=2.0, tip_mass=5.0, omega=1.5, precone=0.0)
    exact = 1.5**2 * (3.0 * ((12.0**2 - (2.0 + nodes) ** 2) / 2) + 5.0 * 12.0)
    # the lumping misplaces the node's outer half-element by at most dr^2 m: relative error ~ (dr/L)^2
    assert np.allclose(load, exact, rtol=1e-4)


def test_derived_frequency_of_a_uniform_cantilever():
    beam = uniform_sections(1.0, 1.0, 1.0)
    nodes = np.linspace(0, 1, 41)
    target = fitting_target(analytic_mode(nodes), "flap", 1.0)
    fit = fit_sextic(target.points, target.weights, target.values, target.tip_slope)
    frequency = elastodyn_frequency(fit.coefficients, beam, "flap_stiffness", 400)
    exact = BETA1**2 / (2 * math.pi)
    # Rayleigh quotient of a near-exact shape: error second order in the shape error (~1e-6), midpoint rule on 400
    # nodes ~1e-5 relative
    assert frequency == pytest.approx(exact, rel=1e-4)


@pytest.mark.parametrize(("speed", "w1"), [(4, 5.58500), (8, 9.25684), (12, 13.17015)])
def test_derived_rotating_flap_frequency_matches_the_published_table(speed, w1):
    # reference README table 4 (Wright et al. 1982): uniform blade, R = 0, lambda = Omega sqrt(m L^4 / EI)
    blade = Blade(uniform_sections(1.0, 1.0, 1.0))
    result = blade_coefficients(blade, speed * 30 / math.pi, nodes=400, n_modes=6, elements=40)
    flap = result.fits["flap1"]
    # FE is converged to < 1e-6; the polynomial (Rayleigh-Ritz) is an upper bound within 0.1 % of the exact
    assert flap.fe_frequency_hz * 2 * math.pi == pytest.approx(w1, rel=1e-5)
    assert flap.elastodyn_frequency_hz * 2 * math.pi == pytest.approx(w1, rel=1e-3)
    assert flap.fit.rms_error < 1e-3


def test_edge_spin_softening_follows_the_flap_frequency():
    # equal stiffnesses, no twist or precone: omega_edge^2 = omega_flap^2 - Omega^2 (reference README item 5),
    # both in the FE and in the derived frequencies (same polynomial, same integrals)
    blade = Blade(uniform_sections(1.0, 1.0, 1.0))
    omega = 6.0
    result = blade_coefficients(blade, omega * 30 / math.pi, nodes=200, n_modes=6, elements=40)
    flap, edge = result.fits["flap1"], result.fits["edge1"]
    for name in ("fe_frequency_hz", "elastodyn_frequency_hz"):
        f, e = (2 * math.pi * getattr(fit, name) for fit in (flap, edge))
        assert e**2 == pytest.approx(f**2 - omega**2, rel=1e-6)


# -- mode selection ----------------------------------------------------------------------------------------------

def test_modes_are_chosen_by_kind_not_position():
    # edgewise much softer than flapwise: the first two modes are edge modes
    blade = Blade(uniform_sections(1.0, 1.0, 100.0, edge_stiffness=1.0))
    result = blade_coefficients(blade, 0.0, nodes=100, n_modes=8, elements=30)
    assert result.fits["edge1"].fe_frequency_hz == pytest.approx(BETA1**2 / (2 * math.pi), rel=1e-6)
    assert result.fits["flap1"].fe_frequency_hz == pytest.approx(10 * BETA1**2 / (2 * math.pi), rel=1e-6)


def test_degenerate_tower_pairs_split_into_fore_aft_and_side_side():
    shape = analytic_mode(np.linspace(0, 1, 5)).shape
    mixed = [Mode(1.0, "flap", {"flap": 0.6, "edge": 0.4}, 0.0, shape),
             Mode(1.0, "edge", {"flap": 0.4, "edge": 0.6}, 0.0, shape),
             Mode(3.0, "edge", {"flap": 0.3, "edge": 0.7}, 0.0, shape),
             Mode(3.0, "flap", {"flap": 0.7, "edge": 0.3}, 0.0, shape)]
    result = ModalResult(0.0, mixed, np.zeros(2), np.zeros((1, 4)))
    assert [m.frequency_hz for m in modes_of_kind(result, "flap")] == [1.0, 3.0]
    assert [m.frequency_hz for m in modes_of_kind(result, "edge")] == [1.0, 3.0]
    assert modes_of_kind(result, "flap")[1] is mixed[3]


# -- NREL 5MW acceptance -----------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def blade_5mw():
    blade = blade_from_elastodyn_main(MAIN)
    shipped = read_elastodyn_blade(DATA / "NRELOffshrBsline5MW_Blade.dat").modes
    return blade_coefficients(blade, 12.1, nodes=17, shipped=shipped)


def test_5mw_blade_first_modes(blade_5mw):
    for name in ("flap1", "edge1"):
        fit = blade_5mw.fits[name]
        # acceptance criterion 1e-3 of the tip deflection for the displacement fit (measured 8.3e-4 and 1.7e-4);
        # holding the frequency costs 2.5e-4 and 6.2e-4 of it (measured 1.08e-3, 7.9e-4)
        assert fit.fit.rms_error < 1.5e-3
        assert abs(fit.fit.coefficients.sum() - 1) < 1e-12
        # ElastoDyn's own 17-node integrals of the fitted polynomial (twisted shapes of its equations of motion)
        # give the FE frequency
        assert fit.fit.frequency_preserved
        assert fit.elastodyn_frequency_hz == pytest.approx(fit.fe_frequency_hz, rel=1e-9)
    # the reference README quotes about 0.73 Hz for ElastoDyn's rotating first flap frequency at 12.1 rpm
    assert blade_5mw.fits["flap1"].fe_frequency_hz == pytest.approx(0.73, abs=0.01)
    # the shipped polynomials are rougher fits of the same shapes than the fresh ones (they were fitted to another
    # model of the blade), so the fresh first-mode fits have the smaller RMS error
    for name in ("flap1", "edge1"):
        assert blade_5mw.fits[name].fit.rms_error < blade_5mw.shipped[name].fit.rms_error


def test_5mw_second_flap_fit_keeps_the_fe_frequency(blade_5mw):
    """The second flap mode: a displacement fit (RMS 4.0e-3) is a stiffer Rayleigh-Ritz shape, +5.5 % in
    ElastoDyn's own 17-node equations at 12.1 rpm (issue 10, defect 9); the frequency-preserving fit gives the FE
    frequency to rounding, its displacement error (6.5e-3) below the shipped coefficients' (1.1e-2, -0.5 %). The
    plain fits are flagged as further from the FE frequency than the file's."""
    fit = blade_5mw.fits["flap2"]
    assert fit.fit.frequency_preserved
    assert fit.elastodyn_frequency_hz == pytest.approx(fit.fe_frequency_hz, rel=1e-9)
    assert fit.fit.rms_error < blade_5mw.shipped["flap2"].fit.rms_error
    assert blade_5mw.warnings == ()
    plain = blade_coefficients(blade_from_elastodyn_main(MAIN), 12.1, nodes=17, preserve_frequency=False,
                               shipped=read_elastodyn_blade(DATA / "NRELOffshrBsline5MW_Blade.dat").modes)
    assert plain.fits["flap2"].elastodyn_frequency_hz > 1.05 * fit.fe_frequency_hz          # the defect it fixes
    assert any("flap 2" in w and "file's coefficients" in w for w in plain.warnings)


def test_5mw_tower_first_modes():
    tower = tower_from_elastodyn_main(MAIN)
    assert tower.top_mass is not None
    # NREL/TP-500-38060: rotor 110,000 kg + nacelle 240,000 kg = 350,000 kg; our blade mass integral is 0.7 % below
    # the report's (exact linear integral versus ElastoDyn's 17 nodes), which moves the total by 0.2 %
    assert tower.top_mass.mass == pytest.approx(350000, rel=0.003)
    shipped = read_elastodyn_tower(DATA / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat").modes
    # the tower model (standard gravity, top point mass as ElastoDyn's TwrTpMass) and the non-rotating beam view
    # (no gravity): the ElastoDyn integrals carry the same gravity term as the FE model in each case
    for model in (tower, tower.as_beam()):
        result = tower_coefficients(model, nodes=20, shipped=shipped)
        for name in ("fa1", "ss1"):
            fit = result.fits[name]
            assert fit.fit.rms_error < 1e-3
            assert abs(fit.fit.coefficients.sum() - 1) < 1e-12
            assert fit.elastodyn_frequency_hz == pytest.approx(fit.fe_frequency_hz, rel=0.01)
    # gravity (350 t on top of 87.6 m) softens the first mode by about 2 %: 0.3309 Hz against 0.3366 Hz
    assert result.fits["fa1"].fe_frequency_hz > tower_coefficients(tower, nodes=20).fits["fa1"].fe_frequency_hz
    # equal FA and SS stiffness: the degenerate pairs give the same fore-aft and side-side polynomials; their FE
    # frequencies differ by rounding (~1e-8), and the frequency-preserving fit moves the coefficients by the
    # square root of that (the Rayleigh quotient is stationary at the mode): 1e-3
    assert np.allclose(result.fits["fa1"].fit.coefficients, result.fits["ss1"].fit.coefficients, atol=1e-3)
    # the second modes barely move the heavy tower top: the tip-normalised polynomial is flagged
    assert any("fore-aft 2" in w for w in result.warnings)


def test_gravity_load_of_a_uniform_tower():
    from bladefem.modal.elastodyn_fit import gravity_load
    sections = uniform_sections(80.0, 5000.0, 5e10)
    nodes = (np.arange(20) + 0.5) * 4.0
    # uniform mass: the weight above a node's midpoint is exactly m g (L - r) plus the top mass
    expected = 9.81 * (5000.0 * (80.0 - nodes) + 3.5e5)
    assert np.allclose(gravity_load(sections, nodes, 4.0, 3.5e5, 9.81), expected, rtol=1e-14)


def test_elastodyn_frequency_is_that_of_elastodyns_equations_of_motion():
    """The frequency reported for a blade polynomial is the one the mode has alone in ElastoDyn's equations (the
    twisted shapes carry the mass): equal to the ElastoDyn-compatible Kane model (checked against OpenFAST) with
    that one mode free, at rest without gravity, to 1e-6; the untwisted estimate ElastoDyn prints (FreqBF) is
    0.5 % higher for the 5MW's first flap mode."""
    from bladefem.builders.turbine_elastodyn import turbine_from_elastodyn
    from bladefem.modal.elastodyn_fit import BeamIntegrals
    from bladefem.models.turbine import TurbineModel, select_dofs
    from bladefem.models.turbine.linearize import linearize

    main = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
    blade = blade_from_elastodyn_main(main).with_(precone=0.0)
    shipped = read_elastodyn_blade(DATA / "NRELOffshrBsline5MW_Blade.dat").modes
    model = TurbineModel(turbine_from_elastodyn(main, "polynomial", elastodyn_compatible=True).with_(
        gravity=0.0, precone=0.0))
    beam = BeamIntegrals(blade.sections, 0.0, blade.hub_radius, 0.0, 0.0, pitch=blade.pitch)
    for name, kind in (("flap1", "flap"), ("edge1", "edge"), ("flap2", "flap")):
        kane = linearize(model, select_dofs(model.dofs, [f"blade1_{name}"]), 0.0).modes[0].frequency_hz
        assert beam.frequency(shipped[name], kind, 17) == pytest.approx(kane, rel=1e-6), name
    untwisted = elastodyn_frequency(shipped["flap1"], blade.sections, "flap_stiffness", 17)
    assert untwisted / beam.frequency(shipped["flap1"], "flap", 17) - 1 == pytest.approx(0.0048, abs=0.0005)


def test_a_frequency_the_integrals_cannot_hold_keeps_the_displacement_fit():
    """Holding a frequency far above the shape's own (what a tower top's rotary inertia does to the FE mode, which
    ElastoDyn's point-mass integrals cannot see) would distort the polynomial: the displacement fit is kept with a
    note; a frequency below every sextic's is reported only when the displacement fit misses it by more than 0.1 %."""
    from bladefem.modal.elastodyn_fit import BeamIntegrals, _frequency_preserving
    beam = BeamIntegrals(uniform_sections(1.0, 1.0, 1.0), tower=True)
    target = fitting_target(analytic_mode(np.linspace(0, 1, 41)), "flap", 1.0)
    plain = fit_sextic(target.points, target.weights, target.values, target.tip_slope)
    exact = BETA1**2 / (2 * math.pi)
    kept, note = _frequency_preserving(plain, target, beam, "flap", 400, 3.0 * exact)
    assert kept is plain and "distort" in note
    held, note = _frequency_preserving(plain, target, beam, "flap", 400, 1.01 * exact)
    assert held.frequency_preserved and note is None
    assert _frequency_preserving(plain, target, beam, "flap", 400, 0.9995 * exact) == (plain, None)
    kept, note = _frequency_preserving(plain, target, beam, "flap", 400, 0.95 * exact)
    assert kept is plain and "no sextic" in note
