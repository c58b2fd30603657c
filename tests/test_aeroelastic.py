"""Aeroelastic linearization of the whole turbine about its operating point (models/turbine/operating_point.py,
frozen_wake.py, aeroelastic.py).

- Without aerodynamics at rest the linearization is today's (``linearize``), to the finite differences.
- One blade free in the turbine model equals the blade FE with Coriolis and quasi-steady aerodynamics
  (``models/blade_aero.py``, the quadratic eigenproblem) reduced to the same mode shapes.
- The frozen-wake loads and their Jacobians against the BEM they freeze and against plain differences.
- The operating point (thrust, torque, static deflections, the torque law's rotor speed) against OpenFAST v4.2.1.
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from bladefem.aero.rotor import Inflow
from bladefem.builders.aerodyn_rotor import aerodyn_rotor
from bladefem.builders.elastodyn_blade import blade_from_elastodyn_main
from bladefem.builders.openfast_fst import read_openfast_deck
from bladefem.builders.turbine_elastodyn import blade_beam_from_modes, turbine_from_elastodyn
from bladefem.modal import blade_matrices, solve_modes
from bladefem.modal.quadratic import quadratic_problem, ritz_pairs
from bladefem.models.blade_aero import aero_matrices, operating_point
from bladefem.models.turbine import TurbineModel, select_dofs
from bladefem.models.turbine.aero import TurbineAero, aero_loads, turbine_aero
from bladefem.models.turbine.aeroelastic import linearize_at
from bladefem.models.turbine.control import Generator
from bladefem.models.turbine.frozen_wake import SectionAero, aero_jacobians, held_induction
from bladefem.models.turbine.linearize import linearize
from bladefem.models.turbine.operating_point import OperatingPoint, steady_state

ROOT = Path(__file__).resolve().parents[1]
CASE = ROOT / "cases" / "nrel5mw"
DECK = CASE / "NRELOffshrBsline5MW_Onshore.fst"
MAIN = CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
AERODYN = CASE / "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
OPENFAST = ROOT / "tests" / "data" / "openfast"
RPM = math.pi / 30


@pytest.fixture(scope="module")
def deck():
    return read_openfast_deck(DECK)


def elastodyn_turbine(deck, pitch_deg: float = 0.0) -> TurbineModel:
    """The ElastoDyn-compatible 5MW (OpenFAST's structure to 0.05 %) with the deck's yaw spring and damper."""
    return TurbineModel(turbine_from_elastodyn(
        deck.elastodyn.path, "polynomial", elastodyn_compatible=True, gauss_points=1, pitch=math.radians(pitch_deg),
        yaw_stiffness=deck.servodyn.yaw_spring, yaw_damping=deck.servodyn.yaw_damper))


@pytest.fixture(scope="module")
def model(deck) -> TurbineModel:
    return elastodyn_turbine(deck)


def fixed_speed(model: TurbineModel) -> np.ndarray:
    return select_dofs(model.dofs, ["all", "GenDOF=off"])


# -- without aerodynamics at rest: today's linearization ----------------------------------------------------------

def test_without_aerodynamics_at_rest_the_linearization_is_todays(model):
    """Parked at azimuth 0, no aerodynamics: the equilibrium without gravity is the undeflected state and the linear
    model is ``linearize``'s (same state matrix, modes, names); with gravity, about the undeflected state, too."""
    free = fixed_speed(model)
    for structure in (TurbineModel(model.params.with_(gravity=0.0)), model):
        today = linearize(structure, free, 0.0, 0.0)
        if structure.params.gravity == 0.0:
            point = steady_state(structure, None, free, 0.0)
            assert np.abs(point.q).max() == 0.0
        else:
            point = OperatingPoint(0.0, 0.0, 0.0, np.zeros(model.n), np.zeros(1), True)
        ours = linearize_at(structure, None, point, free)
        # the same central differences, on the compiled kernel instead of the numpy equations: round-off
        np.testing.assert_allclose(ours.A, today.A, rtol=0, atol=1e-7 * np.abs(today.A).max())
        assert [m.name for m in ours.modes] == [m.name for m in today.modes]
        np.testing.assert_allclose([m.frequency_hz for m in ours.modes], [m.frequency_hz for m in today.modes],
                                   rtol=1e-9)
        np.testing.assert_allclose([m.damping_ratio for m in ours.modes], [m.damping_ratio for m in today.modes],
                                   rtol=0, atol=1e-9)


def test_a_parked_rotor_stands_at_its_azimuth(model):
    """Parked at 0.5 rad without gravity or aerodynamics: the equilibrium is the undeflected state there and the
    modes are ``linearize``'s at that azimuth (names in multi-blade coordinates of that azimuth)."""
    structure = TurbineModel(model.params.with_(gravity=0.0))
    free = fixed_speed(model)
    point = steady_state(structure, None, free, 0.0, azimuth=0.5)
    assert point.azimuths[0] == 0.5 and np.abs(point.q).max() == 0.0
    ours, today = linearize_at(structure, None, point, free), linearize(structure, free, 0.0, 0.5)
    assert [m.name for m in ours.modes] == [m.name for m in today.modes]
    # the same central differences on the compiled kernel instead of the numpy equations: round-off
    np.testing.assert_allclose([m.frequency_hz for m in ours.modes], [m.frequency_hz for m in today.modes],
                               rtol=1e-9)


# -- one blade through the turbine model against the blade FE with Coriolis and aerodynamics ----------------------

def refined_rotor(blade, nodes: int):
    """The 5MW AeroDyn planform at ``nodes`` equally spaced stations (chord and twist interpolated, each station's
    airfoil the one of the AeroDyn node at or below it), aerodynamic centres on the pitch axis, no shaft tilt, and
    AeroDyn's legacy projection (BEM_Mod 1: the plane section of the blade FE's aerodynamics)."""
    base = aerodyn_rotor(AERODYN, blade)
    span = np.linspace(base.span[0], base.span[-1], nodes)
    airfoil = base.airfoil[np.clip(np.searchsorted(base.span, span, side="right") - 1, 0, len(base.span) - 1)]
    return dataclasses.replace(base, span=span, chord=np.interp(span, base.span, base.chord),
                               twist=np.interp(span, base.span, base.twist), airfoil=airfoil,
                               curve=np.zeros(nodes), sweep=np.zeros(nodes), curve_angle=np.zeros(nodes), shaft_tilt=0.0,
                               hub_height=90.0,
                               options=dataclasses.replace(base.options, formulation=1))


def one_blade_case(wind_speed: float, rpm: float, pitch_deg: float, precone_deg: float, slope_projection: bool):
    """(FE, Kane) natural frequencies (Hz) and damping ratios of the 5MW blade's flap 1, edge 1, flap 2 modes at an
    operating point, frozen wake, no gravity or structural damping: the FE reduced to its own three modes
    (Rayleigh-Ritz on the quadratic problem with Coriolis and the aerodynamic damping and stiffness), and the
    turbine model with only blade 1 free, fed with those modes, linearized about the undeflected state as the FE
    is. The AeroDyn planform is refined to 300 stations and the Kane blade to 200 elements: both models then
    integrate the same section matrices (the FE between the AeroDyn nodes on its own mesh, the turbine model by
    lumping the loads at the nodes), whose discretizations differ by O(h^2)."""
    pitch = math.radians(pitch_deg)
    blade = blade_from_elastodyn_main(MAIN).with_(precone=math.radians(precone_deg), pitch=pitch)
    rotor = refined_rotor(blade, 300)
    speed = rpm * RPM
    matrices = blade_matrices(blade, None, 6, rpm)
    fe = solve_modes(matrices, rpm, 6)
    basis = fe.vectors[:, [fe.modes.index(fe.first(kind, k)) for kind, k in (("flap", 1), ("edge", 1), ("flap", 2))]]
    damping, stiffness = aero_matrices(matrices, operating_point(rotor, wind_speed, speed, pitch))
    values, _ = ritz_pairs(quadratic_problem(matrices, rpm, damping=damping, stiffness=stiffness), basis, 3)
    values = values[np.argsort(np.abs(values))]
    params = turbine_from_elastodyn(MAIN, "polynomial")
    beam = blade_beam_from_modes(blade, fe, edges=np.linspace(0.0, blade.length, 201), gauss_points=2)
    params = params.with_(blade=beam, gravity=0.0, precone=blade.precone, shaft_tilt=0.0, pitch=pitch)
    model = TurbineModel(params.without_damping())
    aero = turbine_aero(rotor, Inflow(wind_speed, 90.0), model.params, pitch)
    if not slope_projection:
        aero = dataclasses.replace(aero, slope=0.0 * aero.slope)
    free = select_dofs(model.dofs, ["blade1_flap1", "blade1_edge1", "blade1_flap2"])
    point = OperatingPoint(wind_speed, speed, pitch, np.zeros(model.n), np.zeros(1), False)
    kane = linearize_at(model, aero, point, free)
    fe_pairs = np.column_stack([np.abs(values) / (2 * np.pi), -values.real / np.abs(values)])
    kane_pairs = np.array([[m.frequency_hz, m.damping_ratio] for m in kane.modes])
    return fe_pairs, kane_pairs


@pytest.mark.parametrize("wind_speed, rpm, pitch_deg, precone_deg, slope_projection",
                         [(11.4, 12.1, 0.0, 0.0, True), (16.0, 12.1, 12.06, 0.0, True),
                          (11.4, 12.1, 0.0, -2.5, False)])
def test_one_blade_in_the_turbine_equals_the_blade_fe_with_coriolis_and_aerodynamics(
        wind_speed, rpm, pitch_deg, precone_deg, slope_projection):
    fe, kane = one_blade_case(wind_speed, rpm, pitch_deg, precone_deg, slope_projection)
    # measured: frequencies within 5.3e-5 (the Kane blade's 200 elements; 1.3e-5 with 400 and 600 stations),
    # damping ratios within 4.6e-5
    np.testing.assert_allclose(kane[:, 0], fe[:, 0], rtol=1e-4)
    np.testing.assert_allclose(kane[:, 1], fe[:, 1], rtol=0, atol=1e-3)
    assert fe[0, 1] > 0.5 and fe[1, 1] > 0.005             # the flap and edge modes are damped by the air


def test_the_coned_blade_differs_by_the_slope_projection_the_fe_leaves_out():
    """With precone the turbine's aerodynamics see the wind's span component turned into the normal by the flap
    slope (AeroDyn's projection, ``vx = V . n(w')``); the blade FE leaves it out (``models/blade_aero.py``). That
    term alone moves the first flap frequency by 3.5e-3 at 2.5 deg precone (the test above shows the rest agree
    to 1e-4 with it switched off)."""
    fe, kane = one_blade_case(11.4, 12.1, 0.0, -2.5, True)
    assert kane[0, 0] / fe[0, 0] - 1 == pytest.approx(-3.5e-3, abs=0.5e-3)


# -- the frozen wake --------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def rated(deck, model):
    aero = TurbineAero.from_deck(deck, model.params, wind_speed=11.4)
    point = steady_state(model, aero, fixed_speed(model), 12.1 * RPM)
    return aero, point


def test_frozen_loads_at_the_operating_point_are_the_bem_loads(model, rated):
    """Holding the induced velocities of a state reproduces the BEM's loads there (deflected, spinning, 0.7 rad)."""
    aero, point = rated
    q, u = point.state(model, 0.7)
    held = held_induction(model, aero, q, u)
    frozen = SectionAero.of(aero).generalized(model, held, q, u).sum(axis=0)
    reference = aero_loads(model, aero, q, u).generalized
    np.testing.assert_allclose(frozen, reference, rtol=0, atol=1e-12 * np.abs(reference).max())


@pytest.mark.parametrize("frozen", [True, False])
def test_aero_jacobians_are_the_differences_of_the_loads(model, rated, frozen):
    """The Jacobians over q (the same mode of every blade perturbed at once with a frozen wake) and over u (the
    node velocities moved by J_i at fixed kinematics) against plain central differences of the generalized
    forces, one coordinate at a time, with a step ten times larger."""
    aero, point = rated
    q, u = point.state(model, 0.4)
    u = u + 0.05 * np.random.default_rng(2).normal(size=model.n)
    columns = np.flatnonzero(fixed_speed(model))
    held = held_induction(model, aero, q, u) if frozen else None
    sections = SectionAero.of(aero)
    dq, du = aero_jacobians(model, aero, q, u, columns, held, sections)

    def forces(qq, uu):
        if held is None:
            return aero_loads(model, aero, qq, uu).generalized
        return sections.generalized(model, held, qq, uu).sum(axis=0)
    for target, vector in ((dq, q), (du, u)):
        numeric = np.zeros_like(target)
        for j, i in enumerate(columns):
            h = 1e-5 * max(1.0, abs(vector[i]))
            step = np.zeros(model.n)
            step[i] = h
            args = ((q + step, u), (q - step, u)) if vector is q else ((q, u + step), (q, u - step))
            numeric[:, j] = (forces(*args[0]) - forces(*args[1])) / (2 * h)
        # truncation of the coarser step and the polars' kinks: measured 2e-7 of the largest entry
        np.testing.assert_allclose(target, numeric, rtol=0, atol=1e-5 * np.abs(numeric).max())


def test_quasi_steady_induction_lowers_the_flap_damping_less_than_it_changes_the_frequency(model, rated):
    """Re-solving the induction for every perturbation (quasi-steady) instead of holding it: OpenFAST's two
    treatments at 11.4 m/s differ by -0.4 to +0.7 % on the first flap family's damping and -1.9 to +0.2 % on its
    frequencies; bladefem's two treatments differ alike (within 1 % and 2.5 %)."""
    aero, point = rated
    free = fixed_speed(model)
    frozen = {m.name: m for m in linearize_at(model, aero, point, free).modes}
    steady = {m.name: m for m in linearize_at(model, aero, point, free, induction="quasi-steady").modes}
    for name in ("1st blade collective flap", "1st blade asymmetric flap (backward whirl)",
                 "1st blade asymmetric flap (forward whirl)"):
        assert steady[name].damping_ratio == pytest.approx(frozen[name].damping_ratio, rel=0.025)
        assert steady[name].frequency_hz == pytest.approx(frozen[name].frequency_hz, rel=0.025)
        assert steady[name].frequency_hz != frozen[name].frequency_hz


def test_the_free_rotor_speed_mode_is_the_torque_balance(deck, model):
    """Rigid turbine, only the generator azimuth free, the deck's torque law at 11.4 m/s (its steep slip line,
    region 2.5): the rotor-speed mode is the real root of the one-DOF balance J dOmega/dt = Q(Omega) -
    N T_g(N Omega), lambda = (dQ/dOmega - N^2 dT_g/domega) / J, with J the model's inertia about the shaft and
    dQ/dOmega the frozen-wake aerodynamic torque differenced by hand; named 'rotor speed', damping ratio 1. (In
    region 2 the pole is slower than 0.02 Hz and listed with the rigid-body motions.)"""
    generator = Generator.from_servodyn(deck.servodyn)
    aero = TurbineAero.from_deck(deck, model.params, wind_speed=11.4)
    free = select_dofs(model.dofs, ["generator_azimuth"])
    point = steady_state(model, aero, free, None, generator)
    mode = next(m for m in linearize_at(model, aero, point, free, generator).modes if m.name == "rotor speed")
    gen, ratio, h = model.dofs.index("generator_azimuth"), model.params.gearbox_ratio, 1e-4
    q, u = point.state(model, point.azimuths[0])              # one coordinate: linearized at the first azimuth
    held = held_induction(model, aero, q, u)
    step = h * np.eye(model.n)[gen]
    sections = SectionAero.of(aero)
    dQ = (sections.generalized(model, held, q, u + step) - sections.generalized(model, held, q, u - step)
          ).sum(axis=0)[gen] / (2 * h)
    speed = ratio * u[gen]
    dT = (generator.torque(speed + ratio * h) - generator.torque(speed - ratio * h)) / (2 * h)
    rate = (dQ - ratio * dT) / model.equations(q, u)[0][gen, gen]
    assert mode.damping_ratio == 1.0 and rate < 0
    # central differences of smooth loads; the azimuth's gravity and tilt stiffness moves the root by 1e-5
    assert 2 * math.pi * mode.frequency_hz == pytest.approx(-rate, rel=1e-4)


# -- the operating point against OpenFAST -------------------------------------------------------------------------

def openfast_points(variant: str = "frozen_wake") -> list[dict]:
    return json.loads((OPENFAST / "aero_linearization.json").read_text())["variants"][variant]["points"]


@pytest.mark.parametrize("point", openfast_points(), ids=lambda p: f"{p['wind_speed_m_s']:g} m/s")
def test_operating_point_against_openfast(deck, point):
    """Thrust, torque and the static blade-tip and tower-top deflections of the azimuth-averaged equilibrium
    against OpenFAST's periodic steady state (CalcSteady, means over the last revolution) at the Table 7-1 points,
    generator locked. Measured with the deck's polar projection (BEM_Mod 2): thrust -0.38 to +0.04 %, torque -0.43
    to -0.01 %, tip out-of-plane +0.6 to +1.0 % (8 mm at 25 m/s, where it is 2 cm), tower top -0.9 to +0.7 %, tip
    in-plane within 1.4 % (20 % of 1 cm at 25 m/s). Thrust and torque within 0.8 %: with the legacy projection in
    its place they were 1.0 % and 1.5 % low at 11.4 m/s, where the blades deflect most (5.6 m)."""
    model = elastodyn_turbine(deck, point["pitch_deg"])
    aero = TurbineAero.from_deck(deck, model.params, wind_speed=point["wind_speed_m_s"])
    ours = steady_state(model, aero, fixed_speed(model), point["rotor_speed_rpm"] * RPM)
    theirs = point["operating_point_last_revolution"]
    d = ours.deflections(model)
    assert ours.thrust == pytest.approx(theirs["RtAeroFxh_N"], rel=0.008)
    assert ours.torque == pytest.approx(theirs["RtAeroMxh_N-m"], rel=0.008)
    assert d["OoPDefl"] == pytest.approx(theirs["OoPDefl1_m"], rel=0.015, abs=0.01)
    assert d["TTDspFA"] == pytest.approx(theirs["TTDspFA_m"], rel=0.015)
    assert d["IPDefl"] == pytest.approx(theirs["IPDefl1_m"], rel=0.05, abs=0.01)


def test_torque_law_rotor_speed_against_openfast(deck):
    """With the generator free, the rotor speed where the torque law holds the mean aerodynamic torque against
    OpenFAST's 200 s runs with the same law (tests/data/openfast/torque_law.json): measured -0.16 % at 8 m/s
    (region 2) and -0.12 % at 11.4 m/s (region 2.5)."""
    model = elastodyn_turbine(deck)
    generator = Generator.from_servodyn(deck.servodyn)
    free = select_dofs(model.dofs, ["all"])
    for point in json.loads((OPENFAST / "torque_law.json").read_text())["points"]:
        aero = TurbineAero.from_deck(deck, model.params, wind_speed=point["wind_speed_m_s"])
        ours = steady_state(model, aero, free, None, generator)
        assert ours.trimmed
        assert ours.rpm == pytest.approx(point["channels"]["RotSpeed"]["mean"], rel=0.004)
        ratio = model.params.gearbox_ratio
        assert ours.torque == pytest.approx(ratio * generator.torque(ratio * ours.rotor_speed), rel=1e-6)
