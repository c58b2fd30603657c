"""The automatic mesh choice (graded starting mesh, Richardson-chosen nested refinement) and the eigen-solver's
robustness: converged to tolerance against much finer meshes, round-off kept off fine meshes, fallbacks exercised."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.sparse.linalg as spla
from hypothesis import HealthCheck, given, settings
from test_closed_form import CANTILEVER_B
from test_properties import blades

from bladefem.assembly import (
    assemble_blade,
    blade_graded_nodes,
    graded_nodes,
    subdivide,
)
from bladefem.assembly.mesh import PROPERTY_RATIO, SHORTEST_ELEMENT, mesh_stations
from bladefem.builders.case import read_case
from bladefem.modal import MESH_RTOL, SolverError, converged_mesh, solve_modes
from bladefem.modal import solve as solve_module
from bladefem.modal.estimate import frequency_errors
from bladefem.modal.refinement import Solved, choose_mesh
from bladefem.modal.solve import cached_pairs
from bladefem.sections import Blade, uniform_sections

CASES = Path(__file__).resolve().parent.parent / "cases"


def reference_frequencies(blade, choice, rpm: float, n_modes: int) -> np.ndarray:
    """Frequencies on the chosen mesh's starting mesh refined four times further: its h^4 error is 1/256 of the
    chosen mesh's, so it serves as the converged answer."""
    start = blade_graded_nodes(blade, 24)
    fine = assemble_blade(blade, nodes=subdivide(start, 4 * choice.level))
    return solve_modes(fine, rpm, n_modes).frequencies_hz


@pytest.mark.parametrize("rpm", [0.0, 12.1])
def test_automatic_mesh_is_converged_on_nrel5mw(rpm):
    # the chosen mesh's frequencies (10 modes) are within the tolerance of the converged ones, and the error the
    # mesh choice estimates is honest: the true error is at most about it (the Richardson estimate is asymptotically
    # exact; 1.5x covers the rate not yet exactly 4)
    blade = read_case(CASES / "nrel5mw_blade.yaml")
    choice = converged_mesh(blade, 10, rpm=rpm)
    assert choice.note is None
    chosen = solve_modes(choice.matrices, rpm, 10).frequencies_hz
    error = np.max(np.abs(chosen / reference_frequencies(blade, choice, rpm, 10) - 1))
    assert error < MESH_RTOL
    assert error < 1.5 * choice.error


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(blades())
def test_automatic_mesh_is_converged_on_random_blades(blade):
    choice = converged_mesh(blade, 5, rpm=10.0)
    assert choice.note is None
    chosen = solve_modes(choice.matrices, 10.0, 5).frequencies_hz
    np.testing.assert_allclose(chosen, reference_frequencies(blade, choice, 10.0, 5), rtol=MESH_RTOL)


def test_refining_far_beyond_convergence_stays_put():
    # the frequencies are Rayleigh quotients with the strain energy summed at the quadrature points, so refining a
    # converged mesh to 1200 elements moves them by the h^4 remainder only (2e-9 here); eigenvalues taken from the
    # assembled matrices scatter by ~1e-6 at this size (Hermite round-off grows as (L / h)^4)
    blade = read_case(CASES / "nrel5mw_blade.yaml")
    coarse, fine = (solve_modes(assemble_blade(blade, n), 12.1, 6).frequencies_hz for n in (600, 1200))
    np.testing.assert_allclose(coarse, fine, rtol=1e-8)


def test_choose_mesh_follows_the_h4_rate_with_one_check():
    # a synthetic sequence e(s) = C s^-4: levels 1 and 2 give C, the chosen level is the first with e <= rtol / 2,
    # and it is solved once (the check) before being accepted
    exact, constant = np.array([1.0, 2.0]), np.array([3e-5, 1e-5])
    solved = []

    def solve(level: int) -> Solved:
        solved.append(level)
        return Solved(exact * (1 + constant * level**-4.0), np.zeros(2))

    choice = choose_mesh(lambda level: level, solve, 1e-6, 100)
    needed = int(np.ceil((3e-5 / 0.5e-6) ** 0.25))
    assert choice.level == needed and solved == [1, 2, needed] and choice.note is None


def test_choose_mesh_stops_where_round_off_wins():
    # error C s^-4 plus round-off R s^4 with a minimum above the tolerance: the level that minimises the estimate
    # is returned with a note instead of refining on
    def solve(level: int) -> Solved:
        return Solved(np.array([1.0 + 1e-4 * level**-4.0]), np.array([1e-8 * level**4.0]))

    choice = choose_mesh(lambda level: level, solve, 1e-7, 50)
    assert choice.note is not None and "round-off" in choice.note
    assert choice.level == 3      # (1e-4 / 1e-8)^(1/8) = 3.2


def test_graded_mesh_bounds_property_ratio_and_keeps_stations():
    # EI falls 100-fold over the last interval: its elements are graded so that none spans more than the ratio
    # (10 % slack: nodes are placed between samples of the density), none is longer than length / elements and
    # none shorter than the floor
    span = np.array([0.0, 10.0, 20.0, 40.0])
    stiffness = np.array([1e9, 5e8, 2e8, 2e6])
    nodes = graded_nodes(span, [stiffness], np.zeros(4), 8)
    assert np.all(np.isin(span, nodes))
    values = np.interp(nodes, span, stiffness)
    assert np.max(values[:-1] / values[1:]) < 1.1 * PROPERTY_RATIO
    assert np.max(np.diff(nodes)) <= 40.0 / 8 + 1e-12
    assert np.min(np.diff(nodes)) >= 0.99 * SHORTEST_ELEMENT * 40.0


def test_interpolated_sliver_stations_leave_the_mesh():
    # a station 1 mm from its neighbour whose values lie on the line between its neighbours (a BModes element node
    # merged into the table) is no node: its sliver element would ruin the conditioning; a real kink stays
    span = np.array([0.0, 10.0, 10.001, 20.0])
    linear = np.array([5.0, 3.0, 3.0 - 1e-4, 2.0])      # a kink at 10, straight on to 20
    assert list(mesh_stations(span, [linear])) == [0.0, 10.0, 20.0]
    kinked = linear.copy()
    kinked[2] = 2.5
    assert list(mesh_stations(span, [kinked])) == [0.0, 10.0, 20.0]     # within NEAR_STEP: a step at one node
    span[2] = 10.5                                                       # a real kink half a metre on stays
    assert list(mesh_stations(span, [kinked])) == list(span)
    assert list(mesh_stations(span, [np.interp(span, [0.0, 10.0, 20.0], [5.0, 3.0, 2.0])])) == [0.0, 10.0, 20.0]


def test_lanczos_failure_falls_back_to_dense(monkeypatch):
    # ARPACK forced to fail: the same eigenpairs come from the dense inverse problem
    blade = read_case(CASES / "nrel5mw_blade.yaml")
    matrices = assemble_blade(blade, 40)
    expected = solve_modes(matrices, 12.1, 6).frequencies_hz

    def failing(*args, **kwargs):
        raise spla.ArpackNoConvergence("forced failure", np.zeros(0), np.zeros((0, 0)))

    monkeypatch.setattr(solve_module.spla, "eigsh", failing)
    again = solve_modes(assemble_blade(blade, 40), 12.1, 6).frequencies_hz
    np.testing.assert_allclose(again, expected, rtol=1e-10)


def test_no_solver_converging_is_a_clear_error(monkeypatch):
    # both solvers fail: a SolverError (printed on one line by the CLI), never an ARPACK traceback
    blade = read_case(CASES / "nrel5mw_blade.yaml")

    def failing(*args, **kwargs):
        raise spla.ArpackNoConvergence("forced failure", np.zeros(0), np.zeros((0, 0)))

    monkeypatch.setattr(solve_module.spla, "eigsh", failing)
    monkeypatch.setattr(solve_module, "DENSE_FALLBACK_LIMIT", 10)
    with pytest.raises(SolverError, match="no eigen-solver converged"):
        solve_modes(assemble_blade(blade, 40), 12.1, 6)


def test_singular_stiffness_is_solved_with_a_shift():
    # a hinged blade at rest has two rigid rotations (K singular): they come out at zero frequency and the
    # elastic modes match those of a shifted solve
    blade = read_case(CASES / "nrel5mw_blade.yaml").with_(root="hinged")
    result = solve_modes(assemble_blade(blade, 60), 0.0, 6)
    assert np.all(np.abs(result.frequencies_hz[:2]) < 1e-6)
    assert result.frequencies_hz[2] > 1.0


def test_choose_mesh_with_a_prediction_solves_two_levels():
    # with an a-priori estimate the second level solved is the predicted one, and the Richardson check of the
    # pair (1, predicted) accepts it: two solves in all
    exact, constant = np.array([1.0, 2.0]), np.array([3e-5, 1e-5])
    solved = []

    def solve(level: int) -> Solved:
        solved.append(level)
        return Solved(exact * (1 + constant * level**-4.0), np.zeros(2))

    needed = int(np.ceil((3e-5 / 0.5e-6) ** 0.25))
    choice = choose_mesh(lambda level: level, solve, 1e-6, 100, predict=lambda level, result: constant)
    assert choice.level == needed and solved == [1, needed]


def test_a_priori_error_matches_the_uniform_cantilever():
    # the local-wavenumber estimate (kappa h)^4 / 1440 against the true error of a uniform cantilever's first
    # three bending frequencies on 8 elements (omega = b^2 for m = EI = L = 1): within a factor 1.5
    blade = Blade(uniform_sections(1.0, 1.0, 1.0, edge_stiffness=1e4))       # edge modes far above
    matrices = assemble_blade(blade, 8)
    values, vectors = cached_pairs(matrices, 0.0, 3)
    true = np.sqrt(values) / CANTILEVER_B[:3] ** 2 - 1
    ratio = frequency_errors(matrices, values, vectors) / true
    assert np.all((ratio > 1 / 1.5) & (ratio < 1.5)), ratio


def reference_blade_decks() -> list[Path]:
    pybmodes = pytest.importorskip("pybmodes")
    root = Path(pybmodes.__file__).parent / "_examples" / "sample_inputs" / "reference_turbines"
    return sorted(root.glob("*/*_blade.bmi"))


def test_reference_decks_converge_without_notes():
    # pybmodes' eleven reference blade decks (tip intervals where EI falls up to 6000-fold, BModes element nodes
    # 4 mm from section stations): the automatic mesh ends without a note, below 300 elements, and within the
    # tolerance of the 4x finer mesh
    from bladefem.builders.detect import read_model

    for deck in reference_blade_decks():
        blade = read_model(deck)
        choice = converged_mesh(blade, 6, rpm=12.0)
        assert choice.note is None, deck.name
        assert len(choice.matrices.dofs.nodes) - 1 < 300, deck.name
        chosen = solve_modes(choice.matrices, 12.0, 6).frequencies_hz
        np.testing.assert_allclose(chosen, reference_frequencies(blade, choice, 12.0, 6), rtol=MESH_RTOL,
                                   err_msg=deck.name)
