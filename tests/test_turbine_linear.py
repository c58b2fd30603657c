"""Linearization, multi-blade coordinates and the full-system modes of the Kane turbine model.

- An isotropic 3-blade rotor on a fixed hub (tower, yaw, drivetrain locked, constant speed, no gravity, no
  precone) seen in multi-blade coordinates: the collective mode keeps the blade's own frequency w, the
  asymmetric pair splits into whirls at exactly w - Omega and w + Omega (the Coleman transform's frequency
  shift), each equal to a single blade's frequency from the same equations.
- The NREL 5MW full system at 0 rpm against the published FAST/ElastoDyn full-system frequencies (Jonkman et al.
  2009, NREL/TP-500-38060, Table 9-1): tower 1st FA 0.3240, SS 0.3120 Hz; blade 1st asymmetric flap 0.6664 /
  0.6675, collective flap 0.6993, 1st asymmetric edge 1.0793 / 1.0898, 2nd asymmetric flap 1.9223 / 1.9220,
  2nd collective flap 2.0205 Hz. Same polynomial shapes as FAST but a different (exact-kinematics) assembly and
  the rotor-nacelle's rotary inertia, which ElastoDyn's tower modes leave to the coupling: within 4 %.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bladefem.io.turbine_elastodyn import turbine_from_elastodyn
from bladefem.models.turbine import TurbineModel, select_dofs
from bladefem.models.turbine.linearize import linearize

MAIN = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


@pytest.fixture(scope="module")
def params():
    return turbine_from_elastodyn(MAIN, "polynomial", gauss_points=1)


def frequency(result, name: str) -> float:
    return next(mode.frequency_hz for mode in result.modes if mode.name == name)


def test_multiblade_whirl_splits_by_the_rotor_speed(params):
    rotor = params.with_(gravity=0.0, precone=0.0).without_damping()
    model = TurbineModel(rotor)
    rpm = 12.1
    omega_hz = rpm / 60.0
    single = linearize(model, select_dofs(model.dofs, ["blade1_flap1"]), rpm)
    w = single.modes[0].frequency_hz
    rotor_modes = linearize(model, select_dofs(model.dofs, ["flap1"]), rpm)
    # exact in theory; the finite-difference Jacobian and the azimuth average leave ~1e-8
    assert frequency(rotor_modes, "1st blade collective flap") == pytest.approx(w, rel=1e-6)
    assert frequency(rotor_modes, "1st blade asymmetric flap (backward whirl)") == pytest.approx(w - omega_hz,
                                                                                                 rel=1e-6)
    assert frequency(rotor_modes, "1st blade asymmetric flap (forward whirl)") == pytest.approx(w + omega_hz,
                                                                                                rel=1e-6)


def test_nrel5mw_full_system_modes_at_rest(params):
    model = TurbineModel(params.without_damping())
    result = linearize(model, np.ones(model.n, dtype=bool), 0.0)
    names = [mode.name for mode in result.modes]
    found = {name: frequency(result, name) for name in names}
    published = {"1st tower fore-aft": 0.3240, "1st tower side-side": 0.3120,
                 "1st blade collective flap": 0.6993, "2nd blade collective flap": 2.0205}
    for name, value in published.items():
        assert found[name] == pytest.approx(value, rel=0.04), name
    asymmetric = sorted(v for k, v in found.items() if k.startswith("1st blade asymmetric flap"))
    np.testing.assert_allclose(asymmetric, [0.6664, 0.6675], rtol=0.04)
    edge = sorted(v for k, v in found.items() if k.startswith("1st blade asymmetric edge"))
    np.testing.assert_allclose(edge, [1.0793, 1.0898], rtol=0.04)
    assert len(result.modes) == 15            # 16 DOFs less the rigid rotor rotation


def test_damping_ratios_follow_the_inputs(params):
    model = TurbineModel(params.with_(gravity=0.0))
    result = linearize(model, select_dofs(model.dofs, ["blade1_flap1"]), 0.0)
    # a single mode with its own damping ratio, no gravity stiffness: zeta = 0.477465 % of the blade file
    assert result.modes[0].damping_ratio == pytest.approx(0.00477465, rel=1e-6)


def test_fe_shapes_and_their_polynomial_fits_give_close_system_modes():
    """The same turbine with bladefem's FE shapes and with ElastoDyn polynomials fitted to them (the effect of the
    polynomial representation): tower, first blade modes, drivetrain and yaw agree within 2 % (measured <= 1.4 %).
    The second flap family does not: the constrained sextic fitted to the second flap displacement is a stiffer
    Ritz shape (measured +7.5 to +9.5 %; the single blade shows the same, 2.20 against 2.01 Hz), so it is held to
    12 % only."""
    fe = TurbineModel(turbine_from_elastodyn(MAIN, "fe", tower_shapes="fe", gauss_points=1))
    fitted = TurbineModel(turbine_from_elastodyn(MAIN, "fe-polynomial", tower_shapes="fe-polynomial",
                                                 gauss_points=1))
    a = {m.name: m.frequency_hz for m in linearize(fe, np.ones(fe.n, dtype=bool), 12.1).modes}
    b = {m.name: m.frequency_hz for m in linearize(fitted, np.ones(fitted.n, dtype=bool), 12.1).modes}
    assert set(a) == set(b)
    for name in a:
        assert b[name] == pytest.approx(a[name], rel=0.12 if name.startswith("2nd blade") else 0.02), name
