"""Energy and structure of the Kane equations of the full 16-DOF NREL 5MW model (ElastoDyn polynomial shapes,
coarse span nodes to keep the test fast; the energy balance holds for any quadrature).

- With damping off, gravity on, the rotor spinning at 12.1 rpm and the generator free, the total energy
  ``1/2 u^T M u + gravity + strain + springs`` is conserved to the integrator's tolerance, by the numba kernel
  (60 s) and by the numpy equations (10 s): the equations are those of a conservative Lagrangian system only if
  M, the bias accelerations and the partial velocities all come from the same kinematics.
- With damping on, the energy only falls (a control that the check can fail).
- M is symmetric positive definite and equals the Hessian of the kinetic energy in the rates.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.turbine_elastodyn import turbine_from_elastodyn
from bladefem.models.turbine import FreeSystem, TurbineModel
from bladefem.models.turbine.simulate import simulate

MAIN = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


@pytest.fixture(scope="module")
def model() -> TurbineModel:
    params = turbine_from_elastodyn(MAIN, "polynomial", gauss_points=1, blade_elements=12, tower_elements=8)
    return TurbineModel(params)


def spinning_state(model: TurbineModel) -> tuple[np.ndarray, np.ndarray]:
    """12.1 rpm with every flexible DOF displaced (tower, yaw, drivetrain, all blades)."""
    q, u = np.zeros(model.n), np.zeros(model.n)
    u[5] = 12.1 * np.pi / 30
    q[:5] = [0.3, 0.02, 0.2, -0.02, 0.01]
    q[6] = 2e-3
    q[7:] = np.tile([1.0, 0.3, -0.1], 3) * [1.0, 1.0, 1.0, 0.5, 0.5, 0.5, -0.5, 0.2, 0.2]
    return q, u


def total_energy(model: TurbineModel, q: np.ndarray, u: np.ndarray) -> np.ndarray:
    return np.array([sum(model.energy(qi, ui)) for qi, ui in zip(q, u)])


@pytest.mark.parametrize("backend, seconds", [("numba", 60.0), ("numpy", 10.0)])
def test_energy_is_conserved_without_damping(model, backend, seconds):
    conservative = TurbineModel(model.params.without_damping())
    if backend == "numpy":
        conservative._fast = conservative.equations          # the reference numpy assembly
    elif not hasattr(conservative.fast_equations(), "integrate"):
        pytest.skip("numba not installed")
    q, u = spinning_state(conservative)
    system = FreeSystem(conservative, np.ones(conservative.n, dtype=bool), q, u)
    rtol = 1e-6
    result = simulate(system, seconds, dt_output=0.5, rtol=rtol, atol=1e-8, method="DOP853")
    energy = total_energy(conservative, result.q, result.u)
    kinetic = conservative.energy(q, u)[0]
    drift = np.abs(energy - energy[0]).max() / kinetic
    # the local error per step is held below rtol; the energy error accumulates over the steps but is bounded
    # well below 10 rtol for a conservative system (measured ~1e-7)
    assert drift < 10 * rtol
    assert np.ptp(result.outputs["RotSpeed"]) > 0.1           # the generator is really free (rotor speed varies)
    assert np.ptp(result.outputs["TTDspSS"]) > 0.05


def test_damping_only_removes_energy(model):
    q, u = spinning_state(model)
    result = simulate(FreeSystem(model, np.ones(model.n, dtype=bool), q, u), 4.0, dt_output=0.25, rtol=1e-7,
                      atol=1e-9, method="DOP853")
    energy = total_energy(model, result.q, result.u)
    assert np.all(np.diff(energy) < 1e-6 * energy[0])
    assert energy[-1] < energy[0] - 1e-3 * model.energy(q, u)[0]


def test_mass_matrix_is_the_kinetic_energy_hessian(model):
    q, u = spinning_state(model)
    M, _ = model.equations(q, u)
    assert np.allclose(M, M.T, rtol=0, atol=1e-9 * np.abs(M).max())
    assert np.linalg.eigvalsh(M).min() > 0
    rng = np.random.default_rng(3)
    for _ in range(3):
        v = rng.normal(size=model.n)
        # T is exactly quadratic in u, so 2 T(v) = v^T M v (rounding only)
        assert np.isclose(2 * model.energy(q, v)[0], v @ M @ v, rtol=1e-10)


def test_locked_generator_keeps_the_rotor_speed(model):
    q, u = spinning_state(model)
    free = np.ones(model.n, dtype=bool)
    free[5] = False
    result = simulate(FreeSystem(model, free, q, u), 2.0, dt_output=0.5, rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(result.outputs["LSSGagVxa"], 12.1, rtol=1e-12)
    np.testing.assert_allclose(np.degrees(result.q[:, 5]), np.degrees(12.1 * np.pi / 30 * result.time), atol=1e-9)


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_root_moment_of_a_resting_horizontal_blade_is_its_weight_moment(model, backend):
    """Blade 1 horizontal (azimuth 90 deg: it points to the right looking downwind, leading edge down; shaft tilt
    off so that the rotor plane is vertical), everything locked at rest: the in-plane root moment is g times the
    blade's first mass moment about the root (tip mass included), the out-of-plane moment is zero; the compiled
    outputs and the numpy ones alike."""
    model = TurbineModel(model.params.with_(shaft_tilt=0.0))
    if backend == "numpy":
        model._fast = model.equations
    q, u = np.zeros(model.n), np.zeros(model.n)
    q[5] = np.pi / 2
    result = simulate(FreeSystem(model, np.eye(model.n, dtype=bool)[4], q, u), 0.1, dt_output=0.05)
    p = model.params
    first_moment = np.sum(p.blade.point_mass * p.blade.x) + p.blade_tip_mass * p.blade.length
    np.testing.assert_allclose(result.outputs["RootMIP1"] * 1e3, p.gravity * first_moment, rtol=1e-12)
    assert np.abs(result.outputs["RootMOoP1"]).max() < 1e-9 * abs(result.outputs["RootMIP1"][0])
    np.testing.assert_allclose(result.outputs["Azimuth"], 90.0)


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_tower_base_moment_of_the_resting_turbine_is_its_weight_moment(model, backend):
    """Everything at rest (blade 1 at 30 deg azimuth, the nacelle yawed 20 deg so that the masses sit off both
    axes; only the balanced rotor free): the tower-base moments are the weight's moment about the base, ``TwrBsMyt = g sum m x`` (downwind mass
    positive) and ``TwrBsMxt = -g sum m y`` (mass to the left looking downwind negative), summed over every point
    mass at its place; the compiled outputs and the numpy ones alike."""
    if backend == "numpy":
        model = TurbineModel(model.params)
        model._fast = model.equations
    q, u = np.zeros(model.n), np.zeros(model.n)
    q[4], q[5] = np.radians(20.0), np.radians(30.0)
    result = simulate(FreeSystem(model, np.eye(model.n, dtype=bool)[5], q, u), 0.1, dt_output=0.05)
    r = model.positions(model.motion(q, u))
    g = model.params.gravity
    np.testing.assert_allclose(result.outputs["TwrBsMyt"] * 1e3, g * model.masses @ r[:, 0], rtol=1e-9)
    np.testing.assert_allclose(result.outputs["TwrBsMxt"] * 1e3, -g * model.masses @ r[:, 1], rtol=1e-9)
    assert g * model.masses @ r[:, 0] < 0 < -g * model.masses @ r[:, 1]      # rotor upwind, yawed to the right


def test_tip_deflection_channels_follow_openfast_signs(model):
    """OoPDefl1 positive downwind, IPDefl1 positive toward the trailing edge (OpenFAST's xc1, yc1): blade 1 up
    (azimuth 0) moves toward -y as the rotor turns, so its trailing edge faces +y and a tip moved toward +y reads
    IPDefl1 > 0."""
    q = np.zeros(model.n)
    q[model.blade_columns[0, :2]] = [1.0, 0.5]                # flap 1 and edge 1 of blade 1
    motion = model.motion(q, np.zeros(model.n))
    rest = model.motion(np.zeros(model.n), np.zeros(model.n))
    tip_motion = motion.blades.r[0, -1] - rest.blades.r[0, -1]
    from bladefem.models.turbine.outputs import LOAD_COLUMNS, channels
    out = channels(model, q[None], np.zeros((1, model.n)), np.zeros((1, len(LOAD_COLUMNS))))
    # the rotor plane is tilted by 5 deg and coned by 2.5 deg: compare in the blade's own axes
    R = rest.blade_frames.R[0]
    assert out["OoPDefl1"][0] == pytest.approx(tip_motion @ R[:, 2], rel=1e-3)
    assert out["IPDefl1"][0] == pytest.approx(-(tip_motion @ R[:, 1]), rel=1e-3)
    assert np.sign(out["IPDefl1"][0]) == np.sign(tip_motion[1]) != 0
