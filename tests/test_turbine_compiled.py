"""The numba-compiled right-hand side equals the numpy Kane assembly (mass matrix, forcing, free-coordinate
derivative, the external-force hook on the blade nodes) to rounding, at random states of the full 16-DOF NREL 5MW
model and of a model with locked DOFs; the compiled integrators' dense output and divergence checks."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.turbine_elastodyn import turbine_from_elastodyn
from bladefem.models.turbine import FreeSystem, TurbineModel, select_dofs
from bladefem.models.turbine.compiled import compiled_equations

pytest.importorskip("numba")
MAIN = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


@pytest.fixture(scope="module")
def model() -> TurbineModel:
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        pytest.skip("compiled kernels switched off")
    return TurbineModel(turbine_from_elastodyn(MAIN, "polynomial", gauss_points=1, blade_elements=12,
                                               tower_elements=8))


def test_compiled_equations_equal_the_numpy_assembly(model):
    compiled = compiled_equations(model)
    rng = np.random.default_rng(11)
    for _ in range(5):
        q, u = rng.normal(scale=0.5, size=model.n), rng.normal(scale=0.5, size=model.n)
        M, f = model.equations(q, u)
        Mc, fc = compiled(q, u)
        # the same sums in another order: rounding only
        np.testing.assert_allclose(Mc, M, rtol=0, atol=1e-13 * np.abs(M).max())
        np.testing.assert_allclose(fc, f, rtol=0, atol=1e-13 * np.abs(f).max())


def test_kernel_leaves_the_frames_and_the_apex_of_the_numpy_motion(model):
    """The kernel leaves the blade frames, the apex position and each blade's shared partials ``Z = [J_apex;
    W_rotor; E_blade]`` in ``work`` (what the aerodynamic loads and the output rows take) as the numpy kinematics
    has them."""
    compiled = compiled_equations(model)
    rng = np.random.default_rng(7)
    q, u = rng.normal(scale=0.5, size=model.n), rng.normal(scale=0.5, size=model.n)
    compiled(q, u)
    Z, frames, apex = compiled.work[:3]
    motion = model.motion(q, u)
    np.testing.assert_allclose(apex, motion.apex.r, atol=1e-12)
    np.testing.assert_allclose(frames, motion.blade_frames.R, atol=1e-12)
    np.testing.assert_allclose(Z[:, :3], np.broadcast_to(motion.apex.J, Z[:, :3].shape), atol=1e-12)
    np.testing.assert_allclose(Z[:, 3:6], np.broadcast_to(motion.rotor.W, Z[:, 3:6].shape), atol=1e-12)


def test_compiled_derivative_of_a_locked_system(model):
    rng = np.random.default_rng(5)
    q0, u0 = rng.normal(scale=0.3, size=model.n), rng.normal(scale=0.3, size=model.n)
    system = FreeSystem(model, select_dofs(model.dofs, ["tower1", "flap1", "yaw"]), q0, u0)
    x = system.initial_state() + rng.normal(scale=0.1, size=2 * system.size)
    q, u = system.full(1.3, x)
    M, f = model.equations(q, u)
    expected = np.concatenate([x[system.size:], np.linalg.solve(M[system.block], f[system.index])])
    np.testing.assert_allclose(system(1.3, x), expected, rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("method", ["DP54", "DP853"])
def test_compiled_dormand_prince_matches_a_tight_reference_and_conserves_energy(model, method):
    """The compiled Dormand-Prince 5(4) and 8(5,3) against scipy's DOP853 at rtol 1e-10 (5 s), and the energy of
    the undamped, spinning, generator-free turbine over 60 s: both to the tolerance (a few times rtol)."""
    from bladefem.models.turbine.simulate import simulate
    conservative = TurbineModel(model.params.without_damping())
    q, u = np.zeros(conservative.n), np.zeros(conservative.n)
    u[5] = 12.1 * np.pi / 30
    q[[0, 2, 4]] = [0.3, 0.2, 0.01]
    q[conservative.blade_columns[:, 0]] = [1.0, 0.5, -0.5]
    system = FreeSystem(conservative, np.ones(conservative.n, dtype=bool), q, u)
    rtol = 1e-7
    reference = simulate(system, 5.0, dt_output=0.5, method="DOP853", rtol=1e-10, atol=1e-12)
    result = simulate(system, 5.0, dt_output=0.5, method=method, rtol=rtol, atol=1e-9)
    # global error of a 5th-order scheme with local control at rtol: bounded by ~100 rtol over 5 s here
    np.testing.assert_allclose(result.q, reference.q, rtol=0, atol=100 * rtol * np.abs(reference.q).max())
    long = simulate(system, 60.0, dt_output=1.0, method=method, rtol=rtol, atol=1e-9)
    energy = np.array([sum(conservative.energy(qi, ui)) for qi, ui in zip(long.q, long.u)])
    assert np.abs(energy - energy[0]).max() < 10 * rtol * conservative.energy(q, u)[0]


@pytest.mark.parametrize("method", ["DP54", "DP853"])
def test_dense_output_between_steps(model, method):
    """Outputs every 6.25 ms come from the continuous extension, not from steps forced onto them: as accurate as
    the steps (against DOP853 at rtol 1e-10), and the steps are those of a run with outputs every 0.5 s (DOP853's
    interpolant costs 3 more right-hand sides on a step with outputs, 15 instead of 12; DP54's none)."""
    from bladefem.models.turbine.simulate import simulate
    q, u = np.zeros(model.n), np.zeros(model.n)
    u[5] = 12.1 * np.pi / 30
    q[[0, 2]] = [0.3, 0.2]
    q[model.blade_columns[:, 0]] = 1.0
    system = FreeSystem(model, np.ones(model.n, dtype=bool), q, u)
    reference = simulate(system, 2.0, dt_output=0.00625, method="DOP853", rtol=1e-10, atol=1e-12)
    result = simulate(system, 2.0, dt_output=0.00625, method=method, rtol=1e-7, atol=1e-9)
    assert len(result.time) == 321
    # interpolant of order 7 (DOP853) or 4 (DP54) on steps held to rtol 1e-7
    np.testing.assert_allclose(result.q, reference.q, rtol=0, atol=(1e-5 if method == "DP853" else 1e-4)
                               * np.abs(reference.q).max())
    coarse = simulate(system, 2.0, dt_output=0.5, method=method, rtol=1e-7, atol=1e-9)
    assert result.evaluations <= coarse.evaluations * (15 / 12 if method == "DP853" else 1.0) + 20


def test_divergence_stops_the_run(model):
    """A state beyond its limit (here an artificially small one) or not finite stops the compiled integrator with
    its status, the time and the offending state; simulate turns it into a DivergenceError naming the coordinate."""
    from bladefem.models.turbine.simulate import (
        DivergenceError,
        divergence_limits,
        simulate,
    )
    q, u = np.zeros(model.n), np.zeros(model.n)
    q[0] = 0.3
    system = FreeSystem(model, np.ones(model.n, dtype=bool), q, u)
    compiled = compiled_equations(model)
    limit = divergence_limits(system)
    assert limit[0] == pytest.approx(model.params.tower.length / abs(model.params.tower.tip_value[0, 0]))
    limit[0] = 0.31                                           # tower_fa1 may not exceed 0.31 m
    times = np.linspace(0.0, 3.0, 61)
    run = compiled.integrate(times, system.initial_state(), 1e-6, 1e-8, system.q0, system.u0, system.index,
                             limit=limit)
    assert run.status == 2 and run.offending == 0 and 0 < run.time < 3.0
    nan = system.initial_state()
    nan[system.size + 3] = np.nan
    run = compiled.integrate(times, nan, 1e-6, 1e-8, system.q0, system.u0, system.index)
    assert run.status in (1, 3) and run.time < 0.1
    q[model.blade_columns[0, 0]] = 1e3                        # a 1 km tip deflection of blade 1
    with pytest.raises(DivergenceError) as error:
        simulate(FreeSystem(model, np.ones(model.n, dtype=bool), q, u), 1.0)
    assert error.value.coordinate == "blade1_flap1" and "diverged" in str(error.value)


def test_dormand_prince_tableau_is_scipys():
    """The Dormand-Prince 5(4) coefficients written in bladefem (to spare the run scipy.integrate's import) are
    scipy's RK45 ones, to the bit."""
    from scipy.integrate._ivp.rk import RK45
    from bladefem.models.turbine.compiled import _dp54_tableau
    for ours, theirs in zip(_dp54_tableau(), (RK45.A, RK45.B, RK45.C, RK45.E, RK45.P)):
        np.testing.assert_array_equal(ours, theirs)


def test_modal_integrals_equal_the_sums_over_the_nodes():
    """A blade's inertia from its modal integrals (:mod:`.compiled_invariants`) equals the sums over its nodes of
    ``m G^T G`` and ``G^T m (g - a)`` (random shapes, an unsymmetric shortening, random motion), to rounding; and
    with the shapes turned by a pitch, the integrals of the unturned shapes in the turned frame
    (:func:`pitched_frame`) equal the turned shapes' sums."""
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        pytest.skip("compiled kernels switched off")
    from bladefem.models.turbine.compiled_invariants import (blade_inertia, blade_invariants, pitched_frame,
                                                             scratch_size)
    rng = np.random.default_rng(2)
    k, P = 3, 9
    across, S = rng.normal(size=(k, P, 3)), rng.normal(size=(k, k, P))
    axial, m = np.linspace(1.5, 60.0, P), rng.uniform(100.0, 500.0, P)
    q, u, g, w, al = (rng.normal(size=size) for size in (k, k, 3, 3, 3))

    def skew(v):
        return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])

    def node_sums(across):
        A, F = np.zeros((6 + k, 6 + k)), np.zeros(6 + k)
        for p in range(P):
            d = across[:, p].T @ q
            d[0] += axial[p] - 0.5 * q @ S[:, :, p] @ q
            D = across[:, p].T.copy()
            D[0] -= S[:, :, p] @ q
            a = np.cross(al, d) + np.cross(w, np.cross(w, d)) + 2.0 * np.cross(w, D @ u)
            a[0] -= u @ S[:, :, p] @ u
            G = np.hstack([np.eye(3), -skew(d), D])
            A += m[p] * G.T @ G
            F += G.T @ (m[p] * (g - a))
        return A, F

    A, F = np.zeros((6 + k, 6 + k)), np.zeros(6 + k)
    scratch = np.empty(scratch_size(k))
    blade_inertia(blade_invariants(across, S, axial, m), q, u, g, w, al, A, F, scratch)
    A_ref, F_ref = node_sums(across)
    np.testing.assert_allclose(A, A_ref, rtol=0, atol=1e-13 * np.abs(A_ref).max())
    np.testing.assert_allclose(F, F_ref, rtol=0, atol=1e-13 * np.abs(F_ref).max())
    c, s = np.cos(0.3), np.sin(0.3)
    turned = across.copy()
    turned[..., 1], turned[..., 2] = across[..., 1] * c + across[..., 2] * s, -across[..., 1] * s + across[..., 2] * c
    Q = pitched_frame(np.eye(3), np.array([c, s]))
    T = np.eye(6 + k)
    T[:3, :3] = T[3:6, 3:6] = Q
    blade_inertia(blade_invariants(across, S, axial, m), q, u, Q.T @ g, Q.T @ w, Q.T @ al, A, F, scratch)
    A_ref, F_ref = node_sums(turned)
    np.testing.assert_allclose(T @ A @ T.T, A_ref, rtol=0, atol=1e-13 * np.abs(A_ref).max())
    np.testing.assert_allclose(T @ F, F_ref, rtol=0, atol=1e-13 * np.abs(F_ref).max())
