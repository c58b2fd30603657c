"""Aerodynamic loads on the Kane turbine model (numpy reference, ``bladefem.models.turbine.aero``): the rigid
rotor's loads equal the rigid-rotor BEM (``bladefem.aero.rotor_performance``, itself checked against OpenFAST),
the nodes' partial velocities are the derivatives of their positions, the generalized forces do the loads' work,
and moving blades feel aerodynamic damping."""

from __future__ import annotations

import os
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bladefem.aero.performance import performance_at
from bladefem.builders.openfast_fst import read_openfast_deck
from bladefem.builders.turbine_elastodyn import turbine_from_elastodyn
from bladefem.models.turbine import TurbineModel
from bladefem.models.turbine.aero import (
    TurbineAero,
    aero_forcing,
    aero_loads,
    aero_nodes,
    turbine_aero,
)

DECK = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"
RATED = 12.1 * np.pi / 30


@pytest.fixture(scope="module")
def deck():
    return read_openfast_deck(DECK)


@pytest.fixture(scope="module")
def model(deck) -> TurbineModel:
    params = turbine_from_elastodyn(deck.elastodyn.path, "polynomial", gauss_points=2, blade_elements=20,
                                    tower_elements=10)
    return TurbineModel(params)


def spinning(model, azimuth: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    q, u = np.zeros(model.n), np.zeros(model.n)
    q[5], u[5] = azimuth, RATED
    return q, u


@pytest.mark.parametrize("shear, formulation, cant, pitch", [(0.0, 2, False, 0.0), (0.2, 2, False, 0.0),
                                                            (0.2, 1, True, 0.0), (0.2, 2, True, 0.0),
                                                            (0.2, 1, True, 0.25), (0.2, 2, True, 0.25)])
def test_rigid_rotor_loads_equal_the_rigid_rotor_bem(deck, model, shear, formulation, cant, pitch):
    """Undeflected turbine at 12.1 rpm, the deck's tilt, precone and aerodynamic-centre offsets (and a prebent,
    swept blade's offsets and sections canted by ``BlCrvAng``, pitched by ``pitch`` rad: offsets and cant turn
    with the blade): the same node inputs as the rigid-rotor kinematics, so loads, thrust, torque, Cp and the
    tip-speed ratio agree to rounding; the torque is the generalized force on the generator azimuth and on the
    drivetrain twist. Pitched, the turbine model once kept the offsets and the cant in the unpitched blade (the
    pitch a twist only): 3.2 % less thrust and torque at 0.25 rad with the legacy projection, 1.2 % with the
    polar one."""
    aero = canted(TurbineAero.from_deck(deck, model.params, wind_speed=11.4, shear_exponent=shear), model.params,
                  formulation, cant, pitch)
    for azimuth in (0.0, 0.7, 2.0):
        loads = aero_loads(model, aero, *spinning(model, azimuth))
        rigid = performance_at(aero.rotor, aero.inflow, RATED, pitch, 0.0, np.array([azimuth]))
        np.testing.assert_allclose(loads.column("fn"), rigid.fn[0], rtol=0, atol=1e-10 * np.abs(rigid.fn).max())
        np.testing.assert_allclose(loads.column("ft"), rigid.ft[0], rtol=0, atol=1e-10 * np.abs(rigid.ft).max())
        for ours, theirs in ((loads.thrust, rigid.thrust), (loads.torque, rigid.torque), (loads.cp, rigid.cp),
                             (loads.tsr, rigid.tsr)):
            assert ours == pytest.approx(theirs, rel=1e-12)
        generalized = loads.generalized[[model.dofs.index("generator_azimuth"), model.dofs.index("drivetrain")]]
        np.testing.assert_allclose(generalized, rigid.torque, rtol=1e-12)


@pytest.mark.parametrize("prebent", [False, True])
def test_node_partial_velocities_are_position_derivatives(deck, model, prebent):
    """J of every aerodynamic node (with its aerodynamic-centre offset, swept and prebent) equals the central
    difference of its position over each coordinate, at a deflected, yawed, spinning state."""
    aero = canted(TurbineAero.from_deck(deck, model.params, wind_speed=11.4), model.params, 2, prebent)
    rng = np.random.default_rng(3)
    q = rng.normal(scale=0.3, size=model.n)
    u = rng.normal(scale=0.3, size=model.n)
    nodes = aero_nodes(model, aero, q, u)
    J = nodes.J
    h = 1e-6
    for i in range(model.n):
        dq = np.zeros(model.n)
        dq[i] = h
        derivative = (aero_nodes(model, aero, q + dq, u).r - aero_nodes(model, aero, q - dq, u).r) / (2 * h)
        np.testing.assert_allclose(J[..., i], derivative, rtol=0, atol=1e-7)
    np.testing.assert_allclose(nodes.velocity(u), np.einsum("bpkn,n->bpk", J, u), atol=1e-12)


@pytest.mark.parametrize("amplitudes, order", [([0.2, -0.05, 0.03], 2), ([2.0, -0.5, 0.3], 3)])
def test_offset_nodes_turn_with_the_bent_section(deck, model, amplitudes, order):
    """A node off the blade axis (a prebent blade's aerodynamic centre, 3 m upwind at the tip, and the 5MW's sweep)
    rides on a rigid arm turned with its section, as OpenFAST carries AeroDyn's nodes on ElastoDyn's: its place
    relative to the node without the offset is the offset turned by the bent section's rotation
    (:func:`bladefem.aero.polar.bent_axes` of the two slopes), to second order in the slopes: the error is of the
    third (within |o| s^3 with slopes s up to 0.11 rad; the arm turned to first order only missed by 2.3 |o| s^3,
    the thrust's work through it 3.9 % of the IEA-22MW's tip deflection, tests/test_iea22_rosco_openfast.py)."""
    from bladefem.aero.polar import bent_axes
    aero = canted(TurbineAero.from_deck(deck, model.params), model.params, 2, True)
    bare = replace(aero, offset=0 * aero.offset)
    q, u = spinning(model, 0.4)
    q[model.blade_columns[1]] = amplitudes
    R = model.motion(q, u).blade_frames.R[1]                   # columns i3, e_t, i1
    v_slope, w_slope = np.einsum("k,kpa->ap", q[model.blade_columns[1]], aero.slope)
    arm = aero_nodes(model, aero, q, u).r[1] - aero_nodes(model, bare, q, u).r[1]
    for p in range(aero.n_nodes):
        c = np.array(bent_axes(v_slope[p], w_slope[p]))
        turned = aero.offset[p, 1] * c[3:6] + aero.offset[p, 2] * c[0:3]      # (i3, e_t, i1) components
        slope2 = v_slope[p] ** 2 + w_slope[p] ** 2
        np.testing.assert_allclose(arm[p], R @ turned, rtol=0,
                                   atol=np.abs(aero.offset[p]).max() * slope2 ** (order / 2) + 1e-12)
    assert np.abs(arm[-1] - R @ aero.offset[-1][[0, 1, 2]]).max() > 1e-3           # the turn is seen


def test_nodes_move_with_the_structural_blade(deck, model):
    """An aerodynamic node without offsets is the linear interpolation of the structural span nodes (root and tip
    included) at any deflection, as OpenFAST maps ElastoDyn's blade onto AeroDyn's nodes."""
    aero = TurbineAero.from_deck(deck, model.params)
    bare = TurbineAero(**{**{f: getattr(aero, f) for f in aero.__dataclass_fields__}, "offset": 0 * aero.offset})
    q, u = spinning(model, 0.4)
    q[model.blade_columns[1]] = [2.0, -0.5, 0.3]
    q[:4] = [0.3, 0.05, -0.1, 0.02]
    blades = model.motion(q, u).blades.r[1]
    root = model.motion(q, u).apex.r + model.motion(q, u).blade_frames.R[1][:, 0] * model.params.hub_radius
    structural = np.vstack([root, blades])
    x = np.concatenate([[0.0], model.params.blade.x, [model.params.blade.length]])
    span = np.clip(aero.axial - model.params.hub_radius, 0, x[-1])
    expected = np.column_stack([np.interp(span, x, structural[:, k]) for k in range(3)])
    np.testing.assert_allclose(aero_nodes(model, bare, q, u).r[1], expected, atol=1e-12)


def test_generalized_forces_do_the_work_of_the_loads(deck, model):
    """u . Q = sum F . v + (sum M) . omega_rotor at a random state: the generalized forces are the projection
    of the nodal loads on the partial velocities."""
    aero = TurbineAero.from_deck(deck, model.params, wind_speed=11.4, shear_exponent=0.14)
    rng = np.random.default_rng(8)
    q, u = spinning(model, 1.1)
    q += rng.normal(scale=0.2, size=model.n)
    u += rng.normal(scale=0.2, size=model.n)
    loads = aero_loads(model, aero, q, u)
    omega = model.motion(q, u).rotor.omega
    work = np.sum(loads.forces * loads.velocities) + np.sum(loads.moments.sum(axis=(0, 1)) * omega)
    assert u @ loads.generalized == pytest.approx(work, rel=1e-12)


def test_flapping_blade_feels_aerodynamic_damping(deck, model):
    """A blade moving downwind sees less relative wind: its flap generalized force drops (positive aerodynamic
    damping), and the model with aerodynamics includes the same loads in its forcing."""
    aero = TurbineAero.from_deck(deck, model.params, wind_speed=11.4)
    q, u = spinning(model, 0.0)
    flap = model.blade_columns[0, 0]
    base = aero_loads(model, aero, q, u).generalized[flap]
    u[flap] = 0.5
    moving = aero_loads(model, aero, q, u).generalized[flap]
    assert moving < base - 1e3
    with_aero = TurbineModel(model.params, aero=aero)
    np.testing.assert_allclose(with_aero.equations(q, u)[1], model.equations(q, u)[1]
                               + aero_loads(model, aero, q, u).generalized, rtol=1e-13, atol=1e-6)
    np.testing.assert_allclose(aero_forcing(model, aero)(q, u), with_aero.equations(q, u)[1], rtol=1e-13,
                               atol=1e-6)


def canted(aero: TurbineAero, params, formulation: int, cant: bool, pitch: float | None = None) -> TurbineAero:
    """``aero`` with the projection of ``BEM_Mod`` ``formulation`` and, with ``cant``, a prebent, swept blade's
    aerodynamic centres and sections (``BlCrvAC`` to -3 m, ``BlSwpAC`` to 1 m and ``BlCrvAng`` to -6 deg at the
    tip; the 5MW's are 0), at ``pitch`` (rad; None: ``aero``'s)."""
    rotor = replace(aero.rotor, options=replace(aero.rotor.options, formulation=formulation))
    if cant:                                     # the prebend whose slope the cant is: 3 m upwind at the tip
        shape = (rotor.span / rotor.span[-1]) ** 2
        rotor = replace(rotor, curve=-3.0 * shape, sweep=1.0 * shape, curve_angle=-np.radians(6.0) * shape)
    return turbine_aero(rotor, aero.inflow, params, aero.pitch if pitch is None else pitch)


@pytest.mark.parametrize("generator_free, formulation, cant, pitch",
                         [(True, 2, False, 0.0), (False, 2, False, 0.0), (True, 1, True, 0.0), (True, 2, True, 0.0),
                          (True, 1, True, 0.25), (True, 2, True, 0.25)])
def test_compiled_loads_equal_the_numpy_reference(deck, model, generator_free, formulation, cant, pitch):
    """The compiled right-hand side with aerodynamics (sheared wind) and the generator's torque law equals the
    numpy assembly to rounding at a random deflected, yawed, spinning state (both solve the BEM from scratch
    there), and so do the load channels (root moments, shaft loads, generator torque, rotor summary, powers): both
    projections (BEM_Mod 1 and 2), with the sections canted by a prebent, swept blade's ``BlCrvAng`` and without,
    unpitched and pitched (offsets and cant turned with the blade)."""
    pytest.importorskip("numba")
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        pytest.skip("compiled kernels switched off")
    from bladefem.models.turbine import FreeSystem
    from bladefem.models.turbine.compiled import compiled_equations
    from bladefem.models.turbine.control import Generator
    from bladefem.models.turbine.outputs import load_row
    aero = canted(TurbineAero.from_deck(deck, model.params, wind_speed=11.4, shear_exponent=0.1), model.params,
                  formulation, cant, pitch)
    loaded = TurbineModel(model.params, aero=aero, generator=Generator.from_servodyn(deck.servodyn))
    compiled = compiled_equations(loaded)
    rng = np.random.default_rng(2)
    q, u = rng.normal(scale=0.3, size=loaded.n), rng.normal(scale=0.3, size=loaded.n)
    u[5] += 1.2
    M, f = loaded.equations(q, u)
    Mc, fc = compiled(q, u)
    # the same sums in another order, and the same Brent iterations from the same start: rounding only
    np.testing.assert_allclose(Mc, M, rtol=0, atol=1e-13 * np.abs(M).max())
    np.testing.assert_allclose(fc, f, rtol=0, atol=1e-13 * np.abs(f).max())
    free = np.ones(loaded.n, dtype=bool)
    free[5] = generator_free
    system = FreeSystem(loaded, free, q, u)
    row = compiled.outputs(np.zeros(1), system.initial_state()[None], q, u, system.index)[0]
    expected = load_row(loaded, q, u, system.accelerations(q, u))
    np.testing.assert_allclose(row, expected, rtol=1e-11, atol=1e-9)


@pytest.mark.parametrize("formulation", [1, 2])
def test_pitch_on_the_kernels_turns_the_prebent_blade(formulation):
    """A prebent, swept blade built at pitch 0 and pitched to 0.25 rad on the compiled arrays (as the controller
    pitches it) gives the mass matrix and forcing of the model built at 0.25 rad, to rounding (ElastoDyn's
    polynomial shapes, whose turn is exact): the aerodynamic-centre offsets and the sections' cant turn with the
    blade, both projections (1e-20 measured). With the offsets left unturned on the arrays the forcing differs by
    3.1e-5 of its largest entry (a structural one), with the kernels' pitch left at the base 1.3e-5."""
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        pytest.skip("compiled kernels switched off")
    from bladefem.builders.turbine_deck import read_turbine_deck
    from bladefem.models.turbine.pitching import CompiledPitch
    options = {"blade_shapes": "polynomial", "elastodyn_compatible": True, "gauss_points": 1, "wind_speed": 16.0}
    base, pitched = (read_turbine_deck(DECK, pitch=pitch, **options) for pitch in (0.0, 0.25))
    model, other = (TurbineModel(deck.params, aero=canted(deck.aero, deck.params, formulation, True),
                                 generator=deck.generator) for deck in (base, pitched))
    compiled, reference = model.fast_equations(), other.fast_equations()
    CompiledPitch(model, compiled).set(0.25)
    rng = np.random.default_rng(3)
    q, u = 0.05 * rng.standard_normal(model.n), 0.1 * rng.standard_normal(model.n)
    u[5] = RATED
    M, f = compiled(q, u)
    M_ref, f_ref = reference(q, u)
    assert np.max(np.abs(f - f_ref)) < 1e-9 * np.max(np.abs(f_ref))
    assert np.max(np.abs(M - M_ref)) < 1e-9 * np.max(np.abs(M_ref))
