"""Coriolis (gyroscopic) coupling of the rotating blade and the quadratic eigenproblem.

- The gyroscopic matrix G of a rigid blade with tip body (section centre-of-mass offset, rotary inertia, pitch,
  precone, hub radius) equals the one from the exact Lagrangian of that rigid body in the rotating frame, derived
  with sympy from Euler-angle rotations (an independent parameterisation; G does not depend on it at first order).
- The solver against the closed form of a point mass on two springs in a rotating plane.
- The Kane turbine model of one blade at constant speed (it keeps Coriolis through its exact kinematics) fed with the
  FE modes, against the FE reduced to the same modes (exact comparison) and against the converged FE.
- No damping without aerodynamics; equal to the symmetric solve at rest; Arnoldi equal to dense LAPACK.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
import sympy

from bladefem.assembly import assemble_blade
from bladefem.modal import campbell_sweep, solve_modes
from bladefem.modal.quadratic import (
    QuadraticProblem,
    dense_state_pairs,
    full_pairs,
    quadratic_problem,
    ritz_pairs,
    solve_quadratic_modes,
)
from bladefem.modal.quadratic_campbell import quadratic_campbell_sweep
from bladefem.modal.solve import rpm_to_rad_s
from bladefem.sections import Blade, SectionTable, TipMass, uniform_sections

ROOT = Path(__file__).resolve().parents[1]
MAIN = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


# -- the gyroscopic matrix of a rigid blade against its exact Lagrangian -----------------------------------------

L, MASS, OFFSET, I_FLAP, I_EDGE, PITCH = 8.0, 40.0, 0.15, 0.6, 2.5, 0.3
HUB, PRECONE = 1.5, 0.1
TIP = TipMass(25.0, offset=[0.1, 0.2, -0.05], inertia=np.diag([1.0, 2.0, 3.0]))


def rigid_test_blade() -> Blade:
    sections = SectionTable(span=np.array([0.0, L]), mass=MASS, flap_stiffness=1e7, edge_stiffness=3e7,
                            torsion_stiffness=1e6, axial_stiffness=1e9, cm_offset=OFFSET, flap_inertia=I_FLAP,
                            edge_inertia=I_EDGE)
    return Blade(sections, hub_radius=HUB, precone=PRECONE, pitch=PITCH, tip_mass=TIP)


def rigid_body_moments() -> tuple[float, np.ndarray, np.ndarray]:
    """Mass, first and second moment (int rho p, int rho p p^T) of the rigid blade and tip body about the root,
    from the section description (chord along (cos, -sin) of the pitch angle, thickness along (sin, cos))."""
    c, s = np.cos(PITCH), np.sin(PITCH)
    chord, thickness = np.array([0.0, c, -s]), np.array([0.0, s, c])
    x = np.array([1.0, 0.0, 0.0])
    mass = MASS * L + TIP.mass
    first = MASS * (L**2 / 2 * x + L * OFFSET * chord)
    second = MASS * (L**3 / 3 * np.outer(x, x) + L**2 / 2 * OFFSET * (np.outer(x, chord) + np.outer(chord, x)))
    second += L * ((I_EDGE + MASS * OFFSET**2) * np.outer(chord, chord) + I_FLAP * np.outer(thickness, thickness))
    position = L * x + TIP.offset
    first = first + TIP.mass * position
    second = second + TIP.mass * np.outer(position, position) + 0.5 * np.trace(TIP.inertia) * np.eye(3) - TIP.inertia
    return mass, first, second


def exact_rigid_matrices(omega: float) -> tuple[np.ndarray, np.ndarray]:
    """Mass matrix and gyroscopic matrix (G in M q'' + Omega G q' + ...) of the rigid blade turning at ``omega``
    about ``a`` (blade frame), coordinates (translation of the root, rotation about it), from
    ``T = 1/2 int rho |r' + omega a x r|^2``, ``r = R e_x + t + Rz Ry Rx p``."""
    mass, first, second = rigid_body_moments()
    q = sympy.symbols("t0:3 th0:3")
    qd = sympy.symbols("td0:3 thd0:3")
    t, theta = sympy.Matrix(q[:3]), q[3:]
    # second-order Taylor polynomials of sin and cos: T's second derivatives at rest need no more, and the
    # polynomial Lagrangian differentiates fast
    c = [1 - angle**2 / 2 for angle in theta]
    s = list(theta)
    Rx = sympy.Matrix([[1, 0, 0], [0, c[0], -s[0]], [0, s[0], c[0]]])
    Ry = sympy.Matrix([[c[1], 0, s[1]], [0, 1, 0], [-s[1], 0, c[1]]])
    Rz = sympy.Matrix([[c[2], -s[2], 0], [s[2], c[2], 0], [0, 0, 1]])
    rotation = Rz * Ry * Rx
    rate = sum((rotation.diff(theta[i]) * qd[3 + i] for i in range(3)), sympy.zeros(3, 3))
    a = sympy.Matrix([np.sin(PRECONE), 0, np.cos(PRECONE)])
    cross = sympy.Matrix([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    # velocity of a body point p: A0 + B p
    A0 = sympy.Matrix(qd[:3]) + omega * cross * (sympy.Matrix([HUB, 0, 0]) + t)
    B = rate + omega * cross * rotation
    gens = q + qd
    a0 = [sympy.Poly(e, *gens) for e in A0]
    b = [[sympy.Poly(B[i, k], *gens) for k in range(3)] for i in range(3)]
    bS = [sum((b[i][k] * float(first[k]) for k in range(3)), sympy.Poly(0, *gens)) for i in range(3)]
    bJb = sum((b[i][k] * b[i][l] * float(second[k, l]) for i in range(3) for k in range(3) for l in range(3)),
              sympy.Poly(0, *gens))
    T = (sum((x * x for x in a0), sympy.Poly(0, *gens)) * mass
         + sum((x * y for x, y in zip(a0, bS)), sympy.Poly(0, *gens)) * 2 + bJb) * 0.5

    def second_derivative(x: sympy.Symbol, y: sympy.Symbol) -> float:
        return float(T.diff(x).diff(y).eval(dict.fromkeys(gens, 0)))

    M = np.array([[second_derivative(i, j) for j in qd] for i in qd])
    C = np.array([[second_derivative(i, j) for j in q] for i in qd])     # d2T / dqd_i dq_j
    return M, (C - C.T) / omega


def rigid_body_vectors(matrices) -> np.ndarray:
    """The six rigid motions (root translation t, rotation theta) as FE DOF vectors: u = t_x, phi = theta_x,
    v = t_y + x theta_z (slope theta_z), w = t_z - x theta_y (slope -theta_y)."""
    dofs = matrices.dofs
    x = dofs.nodes
    V = np.zeros((dofs.size, 6))
    V[dofs.field_dofs["u"], 0] = 1.0
    V[dofs.field_dofs["phi"], 3] = 1.0
    V[dofs.value["v"], 1] = 1.0
    V[dofs.value["v"], 5] = x
    V[dofs.slope["v"], 5] = 1.0
    V[dofs.value["w"], 2] = 1.0
    V[dofs.value["w"], 4] = -x
    V[dofs.slope["w"], 4] = -1.0
    return V


def test_gyroscopic_matrix_of_a_rigid_blade_equals_the_exact_lagrangian():
    matrices = assemble_blade(rigid_test_blade(), elements=3)
    V = rigid_body_vectors(matrices)
    M_exact, G_exact = exact_rigid_matrices(omega=1.3)
    scale = np.abs(M_exact).max()
    # both sides are exact integrals of polynomials (Gauss rule of degree 9, sympy): round-off only
    np.testing.assert_allclose(V.T @ matrices.M @ V, M_exact, atol=1e-12 * scale)
    np.testing.assert_allclose(V.T @ matrices.G @ V, G_exact, atol=1e-12 * scale)
    assert np.abs(G_exact).max() > 0.1 * scale           # every block is exercised: a real check
    G = matrices.G.toarray()
    np.testing.assert_array_equal(G, -G.T)                # skew by construction


# -- the solver against a rotating spring-mass system --------------------------------------------------------------

def spring_mass_problem(stiffness: np.ndarray, mass: float, omega: float) -> QuadraticProblem:
    """Point masses in a plane turning at omega, each on springs k_x, k_y (rows of ``stiffness``), rotating frame:
    m q'' + 2 m omega J q' + (k - m omega^2) q = 0, J = [[0, -1], [1, 0]]."""
    n = len(stiffness)
    M = sp.identity(2 * n, format="csc") * mass
    C = sp.block_diag([2 * mass * omega * np.array([[0.0, -1.0], [1.0, 0.0]])] * n, format="csc")
    K = sp.diags(stiffness.ravel() - mass * omega**2, format="csc")
    return QuadraticProblem(M=M, C=C, K=K, symmetric=K, conservative=True)


def spring_mass_frequencies(kx: float, ky: float, mass: float, omega: float) -> np.ndarray:
    """Closed form: (kx' - m w^2)(ky' - m w^2) = 4 m^2 Omega^2 w^2 with k' = k - m Omega^2, a quadratic in w^2."""
    a, b = kx / mass - omega**2, ky / mass - omega**2
    p = a + b + 4 * omega**2
    return np.sqrt((p + np.array([-1.0, 1.0]) * np.sqrt(p**2 - 4 * a * b)) / 2)


@pytest.mark.parametrize("copies", [1, 40], ids=["dense", "arnoldi"])
def test_rotating_spring_mass_closed_form(copies):
    rng = np.random.default_rng(3)
    stiffness = rng.uniform(1.5, 30.0, size=(copies, 2))
    mass, omega = 2.0, 0.8
    expected = np.sort(np.concatenate([spring_mass_frequencies(kx, ky, mass, omega) for kx, ky in stiffness]))
    problem = spring_mass_problem(stiffness, mass, omega)
    count = min(2 * copies, 12)
    values, vectors = full_pairs(problem, count)
    np.testing.assert_allclose(np.abs(values), expected[:count], rtol=1e-12)   # round-off of well-separated roots
    assert np.all(values.real == 0.0)
    assert problem.residuals(values, vectors).max() < 1e-12


@pytest.mark.parametrize("precone_deg", [-5.0, 10.0])
def test_hinged_coned_blade_rigid_flap_lag_closed_form(precone_deg):
    """A hinged coned blade (R = 0) moves rigidly: every load of a rigid flap angle b and lag angle z (inertia,
    centrifugal, Coriolis) is proportional to m x, so w = -b x, v = z x solve the equations for any EI. With
    I = int m x^2: I b'' - 2 I Omega s z' + I Omega^2 cos(2 beta) b = 0, I z'' + 2 I Omega s b' - I Omega^2 s^2 z = 0
    (s = sin beta): nu = lambda / Omega solves nu^4 + (1 + s^2) nu^2 - s^2 cos(2 beta) = 0, one real pair (the lag
    divergence about the undeflected position, now slowed) and one imaginary pair (the coupled flap)."""
    beta, omega = np.radians(precone_deg), 1.0
    s = np.sin(beta)
    roots = np.roots([1.0, 1.0 + s**2, -(s**2) * np.cos(2 * beta)])          # nu^2
    divergence, flap = np.sqrt(roots.max()), np.sqrt(-roots.min())
    # EI = 1e5 keeps the elastic modes well above 1P while the eigenvalue round-off stays near 1e-10
    blade = Blade(uniform_sections(10.0, 5.0, 1e5), root="hinged", precone=beta)
    result = solve_quadratic_modes(assemble_blade(blade, 10), omega * 30 / np.pi, 3)
    lag, coupled = result.modes[0], result.modes[1]
    assert lag.kind == "edge" and lag.damping_ratio == -1.0
    assert -2 * np.pi * lag.frequency_hz == pytest.approx(divergence, rel=1e-8)
    assert coupled.kind == "flap" and coupled.damping_ratio == 0.0
    assert 2 * np.pi * coupled.frequency_hz == pytest.approx(flap, rel=1e-8)
    # without Coriolis: omega^2 = cos(2 beta) and -sin^2(beta) (tests/test_rotating.py); the coupling is visible
    assert abs(flap**2 - np.cos(2 * beta)) > 1e-3


def test_hinged_blade_at_rest_reports_its_rigid_modes_once():
    blade = Blade(uniform_sections(10.0, 50.0, 1e7, edge_stiffness=3e7), root="hinged", precone=0.1)
    for elements in (8, 20):                             # dense and Arnoldi paths
        matrices = assemble_blade(blade, elements)
        quadratic, symmetric = solve_quadratic_modes(matrices, 0.0, 4), solve_modes(matrices, 0.0, 4)
        assert sorted(quadratic.kinds[:2]) == ["edge", "flap"]
        assert quadratic.frequencies_hz[0] == quadratic.frequencies_hz[1] == 0.0
        np.testing.assert_allclose(quadratic.frequencies_hz[2:], symmetric.frequencies_hz[2:], rtol=1e-9)


# -- the NREL 5MW blade: Kane model of one blade, damping, special cases ----------------------------------------

@pytest.fixture(scope="module")
def nrel5mw_blade():
    from bladefem.builders.elastodyn_blade import blade_from_elastodyn_main
    return blade_from_elastodyn_main(MAIN)


@pytest.fixture(scope="module")
def kane_case(nrel5mw_blade):
    """The ElastoDyn 5MW blade (precone -2.5 deg) at 12.1 rpm: the FE (converged mesh), its flap 1, edge 1, flap 2
    modes as the Kane model's assumed modes, and the Kane model's frequencies and damping ratios with only that
    blade free (gravity and structural damping off)."""
    from bladefem.builders.turbine_elastodyn import (
        blade_beam_from_modes,
        turbine_from_elastodyn,
    )
    from bladefem.modal import blade_matrices
    from bladefem.models.turbine import TurbineModel, select_dofs
    from bladefem.models.turbine.linearize import linearize

    rpm = 12.1
    matrices = blade_matrices(nrel5mw_blade, None, 6, rpm)
    fe = solve_modes(matrices, rpm, 6)
    params = turbine_from_elastodyn(MAIN, "polynomial", gauss_points=4)
    params = params.with_(blade=blade_beam_from_modes(nrel5mw_blade, fe), gravity=0.0).without_damping()
    model = TurbineModel(params)
    linear = linearize(model, select_dofs(model.dofs, ["blade1_flap1", "blade1_edge1", "blade1_flap2"]), rpm)
    kane = sorted((mode.frequency_hz, mode.damping_ratio) for mode in linear.modes)
    chosen = [fe.modes.index(fe.first(kind, k)) for kind, k in (("flap", 1), ("edge", 1), ("flap", 2))]
    return matrices, fe.vectors[:, chosen], np.array(kane), rpm


def test_kane_one_blade_equals_the_fe_reduced_to_the_same_modes(kane_case):
    matrices, basis, kane, rpm = kane_case
    values, _ = ritz_pairs(quadratic_problem(matrices, rpm), basis, 3)
    # same shapes, same integrals: equal up to the Kane model's finite-difference Jacobian (measured 8e-11)
    np.testing.assert_allclose(np.abs(values) / (2 * np.pi), kane[:, 0], rtol=1e-6)
    np.testing.assert_allclose(kane[:, 1], 0.0, atol=1e-6)
    symmetric = np.sort(solve_modes(matrices, rpm, 6).frequencies_hz[[0, 1, 2]])
    assert np.abs(kane[:, 0] / symmetric - 1).max() > 1e-4     # the Coriolis shift (2.2e-4) is really there


def test_kane_one_blade_against_the_converged_fe_with_coriolis(kane_case):
    matrices, _, kane, rpm = kane_case
    fe = solve_quadratic_modes(matrices, rpm, 6)
    full = np.array([fe.first(kind, k).frequency_hz for kind, k in (("flap", 1), ("edge", 1), ("flap", 2))])
    # first flap and edge: within 1e-6 (measured 3.0e-7 and 2.5e-8). The second flap mode carries the truncation
    # of Kane's three modes: its Coriolis coupling to the second edge mode (4.1 Hz), absent there, shifts it by
    # 1.1e-5 (the FE reduced to those three modes shows the same, test above): 2e-5.
    np.testing.assert_allclose(kane[:2, 0], full[:2], rtol=1e-6)
    assert kane[2, 0] == pytest.approx(full[2], rel=2e-5)


def test_no_damping_without_aerodynamics(kane_case):
    matrices, _, _, rpm = kane_case
    problem = quadratic_problem(matrices, rpm)
    result = solve_quadratic_modes(matrices, rpm, 10)
    assert all(mode.damping_ratio == 0.0 for mode in result.modes)
    # the solver's own eigenvalues, before their Rayleigh-functional refinement, are undamped to round-off
    values, _ = full_pairs(replace(problem, conservative=False), 10)
    assert np.abs(values.real / np.abs(values)).max() < 1e-9
    # those raw values carry the round-off of the factorisation, which grows as (L / h)^4 on the graded mesh
    # (measured 3e-8); the refined ones take the strain energy summed at the quadrature points
    np.testing.assert_allclose(np.abs(values) / (2 * np.pi), result.frequencies_hz, rtol=1e-7)


def test_equal_to_the_symmetric_solve_at_rest(nrel5mw_blade):
    matrices = assemble_blade(nrel5mw_blade, 48)
    symmetric = solve_modes(matrices, 0.0, 8)
    quadratic = solve_quadratic_modes(matrices, 0.0, 8)
    # the same eigenproblem solved two ways, both frequencies from Rayleigh quotients with the strain energy summed
    # at the quadrature points: round-off (measured 3e-15)
    np.testing.assert_allclose(quadratic.frequencies_hz, symmetric.frequencies_hz, rtol=1e-12)
    assert quadratic.kinds == symmetric.kinds


def test_arnoldi_equals_dense():
    matrices = assemble_blade(rigid_test_blade(), 12)          # all four fields, offsets, precone, tip body
    problem = quadratic_problem(matrices, 200.0)
    values, vectors = full_pairs(problem, 8)
    scale = sp.diags(1.0 / np.sqrt(problem.symmetric.diagonal()))
    all_values, _ = dense_state_pairs(*(scale @ A @ scale for A in (problem.M, problem.C, problem.K)))
    dense = np.sort(np.abs(all_values[all_values.imag > 0]))[:8]
    # the dense QZ of the state-space form errs by about eps ||A|| relative to the lowest eigenvalues (the stiffest
    # element modes set ||A||); measured 1.9e-9 against the Rayleigh-refined Arnoldi values
    np.testing.assert_allclose(np.abs(values), dense, rtol=1e-8)
    assert problem.residuals(values, vectors).max() < 1e-8


def test_without_precone_coriolis_couples_edge_with_axial_only():
    """a = e_z: [a]x couples u with v only. Flap frequencies keep their symmetric values. The edge mode's Coriolis
    force drives the axial field, whose quasi-static response (the fixed-free rod's flexibility min(x, xi) / EA)
    acts back as added mass m_a = Omega^2 G^T K_u^-1 G: to first order
    d omega / omega = -2 Omega^2 m int_0^L (int_s^L phi)^2 ds / (EA int_0^L phi^2) (uniform m, phi the edge mode)."""
    from scipy.integrate import cumulative_trapezoid, trapezoid

    L, m, EA = 10.0, 50.0, 2e8
    sections = SectionTable(span=np.array([0.0, L]), mass=m, flap_stiffness=2e6, edge_stiffness=8e6,
                            axial_stiffness=EA)
    matrices = assemble_blade(Blade(sections, hub_radius=1.0), 16)
    rpm = 60.0
    symmetric, quadratic = solve_modes(matrices, rpm, 4), solve_quadratic_modes(matrices, rpm, 4)
    assert quadratic.kinds == symmetric.kinds
    flap = symmetric.first("flap").frequency_hz
    assert quadratic.first("flap").frequency_hz == pytest.approx(flap, rel=1e-10)    # two solvers: round-off
    edge = symmetric.first("edge")
    x = np.linspace(0.0, L, 4001)
    phi = edge.shape.at(x)["edge"]
    outboard = trapezoid(phi, x) - cumulative_trapezoid(phi, x, initial=0.0)
    omega = rpm_to_rad_s(rpm)
    expected = -2 * omega**2 * m * trapezoid(outboard**2, x) / (EA * trapezoid(phi**2, x))
    shift = quadratic.first("edge").frequency_hz / edge.frequency_hz - 1
    # the estimate neglects the axial inertia ((omega_edge / omega_axial)^2 = 2e-3) and terms of second order in
    # the coupling: measured 1.4e-3, falling as 1 / EA (5.6e-3 at EA / 4, 3.5e-4 at 4 EA)
    assert shift == pytest.approx(expected, rel=5e-3)


def test_campbell_with_coriolis_tracks_complex_shapes(nrel5mw_blade):
    matrices = assemble_blade(nrel5mw_blade, 24)
    rpm = np.linspace(0.0, 15.0, 4)
    result = quadratic_campbell_sweep(matrices, rpm, 4)
    plain = campbell_sweep(matrices, rpm, 4)
    assert [f.kind for f in result.families] == [f.kind for f in plain.families]
    for family in result.families:
        assert family.mac.min() > 0.99 and np.all(family.damping_ratios == 0.0)
        for k, i in enumerate(family.indices):
            assert result.results[k].modes[i].frequency_hz == family.frequencies_hz[k]
    # speeds solved in the Ritz basis equal full solves: the error is about the square of the residual (< 1e-4)
    for speed, solved in zip(rpm, result.results):
        full = solve_quadratic_modes(matrices, speed, 8)
        np.testing.assert_allclose(solved.frequencies_hz, full.frequencies_hz, rtol=1e-8)
    # at rest the two agree (round-off); at 15 rpm they differ by the Coriolis shift (about 3e-4 for flap 1)
    np.testing.assert_allclose([f.frequencies_hz[0] for f in result.families],
                               [f.frequencies_hz[0] for f in plain.families], rtol=1e-10)
    shift = np.abs(result.families[0].frequencies_hz[-1] / plain.families[0].frequencies_hz[-1] - 1)
    assert shift > 1e-4
