"""Chain checks: the Kane turbine model, linearized with only some DOFs free, against bladefem's modal solvers
and closed forms.

- One blade free at a constant rotor speed (gravity off): the blade frequencies of the Kane equations, fed with
  the FE (or Galerkin) modes as assumed shapes, equal the FE (Galerkin) frequencies. Without precone the Ritz
  space holds the exact FE eigenvectors and both integrate the same fields exactly, so they agree to rounding
  (1e-6 allows for the finite-difference Jacobian); with the NREL 5MW precone the Kane model keeps the Coriolis
  flap-edge coupling that the FE omits (THEORY.md), a shift of order sin^2(beta): within 1 %.
- Tower DOFs free with the rotor-nacelle as a rigid body: equal to bladefem's tower FE with that top body.
- Independent closed forms: a uniform cantilever fed with its exact non-rotating shapes gives the exact
  Southwell coefficient of the rotating beam (flap K1 = 1.193336; in-plane K1 - 1 from spin softening), and a
  uniform tower with a tip mass ratio mu = 1 the classic frequencies 1.557298 and 16.25009.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.elastodyn_blade import blade_from_elastodyn_main
from bladefem.builders.turbine_elastodyn import (
    blade_beam_from_modes,
    fe_tower_beam,
    read_elastodyn_tower,
    rotor_nacelle_body,
    tower_sections,
    turbine_from_elastodyn,
)
from bladefem.modal import modes
from bladefem.models.turbine import (
    TurbineModel,
    TurbineParameters,
    closed_form_cantilever,
    sample_beam,
    select_dofs,
)
from bladefem.models.turbine.linearize import linearize

CASE = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw"
MAIN = CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
BLADE_DOFS = ["blade1_flap1", "blade1_edge1", "blade1_flap2"]
CANTILEVER_BETA = np.array([1.87510407, 4.69409113])


@pytest.fixture(scope="module")
def nrel5mw() -> TurbineParameters:
    return turbine_from_elastodyn(MAIN, "polynomial", gauss_points=4)


def blade_frequencies(params: TurbineParameters, rpm: float) -> np.ndarray:
    model = TurbineModel(params.with_(gravity=0.0).without_damping())
    result = linearize(model, select_dofs(model.dofs, BLADE_DOFS), rpm)
    return np.sort([mode.frequency_hz for mode in result.modes])


def chosen(result) -> np.ndarray:
    return np.sort([result.first("flap", 1).frequency_hz, result.first("edge", 1).frequency_hz,
                    result.first("flap", 2).frequency_hz])


@pytest.mark.parametrize("rpm", [0.0, 12.1])
def test_one_blade_matches_the_rotating_fe(nrel5mw, rpm):
    blade = blade_from_elastodyn_main(MAIN).with_(precone=0.0)
    fe = modes(blade, rpm, 6)
    params = nrel5mw.with_(blade=blade_beam_from_modes(blade, fe), precone=0.0)
    np.testing.assert_allclose(blade_frequencies(params, rpm), chosen(fe), rtol=1e-6)


def test_one_blade_with_precone_within_one_percent(nrel5mw):
    blade = blade_from_elastodyn_main(MAIN)
    fe = modes(blade, 12.1, 6)
    params = nrel5mw.with_(blade=blade_beam_from_modes(blade, fe))
    kane = blade_frequencies(params, 12.1)
    np.testing.assert_allclose(kane, chosen(fe), rtol=1e-2)
    assert not np.allclose(kane, chosen(fe), rtol=1e-6)     # the Coriolis coupling is really there


def test_one_blade_matches_the_galerkin_model(nrel5mw):
    from bladefem.models.galerkin import galerkin_modes
    blade = blade_from_elastodyn_main(MAIN).with_(precone=0.0)
    galerkin = galerkin_modes(blade, 12.1, 6)
    params = nrel5mw.with_(blade=blade_beam_from_modes(blade, galerkin), precone=0.0)
    np.testing.assert_allclose(blade_frequencies(params, 12.1), chosen(galerkin), rtol=1e-6)


@pytest.mark.parametrize("gravity", [0.0, 9.80665])
def test_tower_with_rigid_rotor_nacelle_matches_the_tower_fe(nrel5mw, gravity):
    from bladefem.models.tower import tower_modes
    from bladefem.sections.tower import OPENFAST_AXES, TopMass, Tower

    params = nrel5mw.with_(gravity=gravity)
    sections = tower_sections(read_elastodyn_tower(CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"), 87.6)
    model = TurbineModel(params.with_(tower=fe_tower_beam(params, sections)).without_damping())
    kane = np.sort([m.frequency_hz for m in linearize(model, select_dofs(model.dofs, ["tower"]), 0.0).modes])
    mass, cm, inertia = rotor_nacelle_body(params)
    top = TopMass(mass, OPENFAST_AXES @ cm, OPENFAST_AXES @ inertia @ OPENFAST_AXES.T)
    fe = tower_modes(Tower(sections, top_mass=top, gravity=gravity), 8)
    expected = np.sort([fe.first(kind, k).frequency_hz for kind in ("fore-aft", "side-side") for k in (1, 2)])
    np.testing.assert_allclose(kane, expected, rtol=1e-6)


# -- closed forms ---------------------------------------------------------------------------------------------

def uniform_beam(length: float, mass: float, stiffness: float, beta: np.ndarray, directions) -> object:
    evaluate = closed_form_cantilever(length, beta, np.asarray(directions, dtype=float))
    return sample_beam(evaluate, np.linspace(0.0, length, 41), lambda x: np.full_like(x, mass),
                       lambda x: np.tile(np.eye(2) * stiffness, (len(x), 1, 1)))


def massless_tower(length: float = 80.0) -> object:
    return sample_beam(closed_form_cantilever(length, np.array([1.875, 4.694, 1.875, 4.694]),
                                              np.array([[1.0, 0], [1.0, 0], [0, 1.0], [0, 1.0]])),
                       np.linspace(0.0, length, 5), lambda x: np.zeros_like(x),
                       lambda x: np.tile(np.eye(2) * 1e12, (len(x), 1, 1)))


def test_southwell_coefficients_of_a_uniform_rotating_blade():
    L, m, EI = 30.0, 200.0, 4.0e8
    scale = np.sqrt(EI / (m * L**4))                  # omega = w * scale, Omega = lambda * scale
    blade = uniform_beam(L, m, EI, np.array([CANTILEVER_BETA[0], CANTILEVER_BETA[0], CANTILEVER_BETA[1]]),
                         [[0.0, 1.0], [1.0, 0.0], [0.0, 1.0]])
    params = TurbineParameters(tower=massless_tower(), blade=blade, n_blades=1, gravity=0.0)
    lam = 0.3
    rpm = lam * scale * 30 / np.pi
    w0 = blade_frequencies(params, 0.0) * 2 * np.pi / scale
    w = blade_frequencies(params, rpm) * 2 * np.pi / scale
    np.testing.assert_allclose(w0, [CANTILEVER_BETA[0] ** 2, CANTILEVER_BETA[0] ** 2, CANTILEVER_BETA[1] ** 2],
                               rtol=1e-7)             # exact shapes, Gauss-exact integrals
    southwell = (w**2 - w0**2) / lam**2
    # in-plane: K1 - 1 (spin softening), flap: K1 = 1.193336, K2 = 6.478225 (reference README, item 7); the
    # second flap shape couples in at order lambda^2 (relative ~1e-4 here): 1e-3
    np.testing.assert_allclose(southwell, [1.193336 - 1.0, 1.193336, 6.478225], rtol=1e-3)


def test_uniform_tower_with_tip_mass_ratio_one():
    L, m, EI = 80.0, 4000.0, 5.0e11
    mu_roots = np.sqrt([1.557298, 16.25009])          # reference README, item 3: w = beta^2 for mu = 1
    tower = sample_beam(closed_form_cantilever(L, np.repeat(mu_roots, 1).tolist() * 2,
                                               np.array([[1.0, 0], [1.0, 0], [0, 1.0], [0, 1.0]])),
                        np.linspace(0.0, L, 41), lambda x: np.full_like(x, m),
                        lambda x: np.tile(np.eye(2) * EI, (len(x), 1, 1)))
    blade = uniform_beam(10.0, 0.0, 1e6, np.array([1.875, 1.875, 4.694]), [[0, 1.0], [1.0, 0], [0, 1.0]])
    params = TurbineParameters(tower=tower, blade=blade, yaw_bearing_mass=m * L, gravity=0.0)
    model = TurbineModel(params)
    result = linearize(model, select_dofs(model.dofs, ["tower"]), 0.0)
    w = np.sort([mode.frequency_hz for mode in result.modes]) * 2 * np.pi / np.sqrt(EI / (m * L**4))
    # the reference is given to 7 digits
    np.testing.assert_allclose(w, [1.557298, 1.557298, 16.25009, 16.25009], rtol=2e-6)
