"""Twins agree: the compiled right-hand side and load channels (numba: ``compiled_kernels``, ``compiled_loads``,
``compiled_outputs``) against the numpy reference (``TurbineModel.equations`` with ``aero.py`` and ``control.py``,
``outputs.load_row``), on every option of the deck and the command line that reaches them, one at a time from the
shipped NREL 5MW deck: AeroDyn's BEM_Mod (the legacy and the polar projection: cant, toe, dr/dz), Wake_Mod,
TipLoss, HubLoss, TanInd, AIDrag, TIDrag, Skew_Mod, SkewRedistr_Mod, SkewRedistrFactor, UseBlCm, the air density,
InflowWind's shear, direction and upflow, its uniform wind files and TurbSim full fields (at times inside the table,
before it and at the box's wrap), ServoDyn's torque law (or none: CompServo 0), the blade shapes and
--elastodyn-compatible, --pitch-deg, --no-aero, --no-gravity, --no-damping, a locked generator, a yawed nacelle.

Each compiled model is called first at another state, then at the state compared, once with its nodes' roots at
the other state as where each solve starts (a run's right-hand sides) and once from scratch: a solution that
depended on the previous call beyond the BEM's tolerance (the warm start that took the NREL 5MW's blade tips into
the propeller-brake root with BEM_Mod 1, 14-29 % low loads) shows as a difference of the first (:data:`WARM_START`).
From scratch both paths solve the same BEM equations by the same kernel from the same inputs (which differ by
rounding only), so the tolerance is rounding: 1e-10 of the largest entry.
"""

from __future__ import annotations

import math
import os
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.turbine_deck import read_turbine_deck
from bladefem.models.turbine import FreeSystem, TurbineModel

pytest.importorskip("numba")
CASE = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw"
FST = "NRELOffshrBsline5MW_Onshore.fst"
AERODYN = "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
INFLOW = "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat"
RATED = 12.1 * math.pi / 30
#: a uniform wind table with every column moving (speed, direction, vertical speed, the three shears, gust, upflow)
UNIFORM = """! time speed dir vert hshear vshear_exp vlinshear gust upflow
0.0  10.0  0.0  0.0  0.0  0.10  0.0  0.0  0.0
2.0  11.0  5.0  0.3  0.2  0.15  0.1  0.5  2.0
9.0  12.5 -8.0 -0.2  0.4  0.20  0.3  1.5 -3.0
"""
#: a TurbSim box made here for the 5MW rotor (tests/data/turbsim/README.md)
BOX = Path(__file__).resolve().parent / "data" / "turbsim" / "nrel5mw_11p4_short.bts"
#: relative tolerance: the same sums in another order
ROUNDING = 1e-10
#: a solve started from the roots at another state finds each root again only to the BEM's tolerance (|R| < 5e-10;
#: measured 1.5e-9 of the largest entry): 1e-7, five orders below the propeller-brake root's 14-29 %
WARM_START = 1e-7

#: name -> (file edits {file: {label: value}}, read_turbine_deck keywords, model/state changes)
VARIANTS = {
    "deck as shipped (BEM_Mod 2)": ({}, {}, {}),
    "BEM_Mod 1": ({AERODYN: {"BEM_Mod": "1"}}, {}, {}),
    "BEM_Mod 1 yawed, sheared": ({AERODYN: {"BEM_Mod": "1"}}, {"shear_exponent": 0.2}, {"yaw": 0.3}),
    "BEM_Mod 2 yawed, sheared": ({}, {"shear_exponent": 0.2}, {"yaw": 0.3}),
    "AIDrag alone (BEM_Mod 2 polar coefficients)": ({AERODYN: {"AIDrag": "True"}}, {}, {}),
    "Wake_Mod 0 (no induction)": ({AERODYN: {"Wake_Mod": "0"}}, {}, {}),
    "TipLoss False": ({AERODYN: {"TipLoss": "False"}}, {}, {}),
    "HubLoss False": ({AERODYN: {"HubLoss": "False"}}, {}, {}),
    "TanInd False": ({AERODYN: {"TanInd": "False"}}, {}, {}),
    "AIDrag and TIDrag": ({AERODYN: {"AIDrag": "True", "TIDrag": "True"}}, {}, {}),
    "AIDrag and TIDrag, BEM_Mod 1": ({AERODYN: {"AIDrag": "True", "TIDrag": "True", "BEM_Mod": "1"}}, {}, {}),
    "Skew_Mod 0, yawed": ({AERODYN: {"Skew_Mod": "0"}}, {}, {"yaw": 0.3}),
    "SkewRedistr_Mod 0, yawed": ({AERODYN: {"SkewRedistr_Mod": "0"}}, {}, {"yaw": 0.3}),
    "SkewRedistrFactor 1, yawed": ({AERODYN: {"SkewRedistrFactor": "1.0"}}, {}, {"yaw": 0.3}),
    "UseBlCm False": ({AERODYN: {"UseBlCm": "False"}}, {}, {}),
    "AirDens 1.0": ({FST: {"AirDens": "1.0"}}, {}, {}),
    "PropagationDir and VFlowAng": ({INFLOW: {"PropagationDir": "20", "VFlowAng": "8"}}, {}, {}),
    "wind speed 20 m/s, pitch 15 deg": ({}, {"wind_speed": 20.0, "pitch": math.radians(15)}, {}),
    "wind speed 4 m/s, BEM_Mod 1": ({AERODYN: {"BEM_Mod": "1"}}, {"wind_speed": 4.0}, {}),
    "CompServo 0 (no torque law)": ({FST: {"CompServo": "0"}}, {}, {}),
    "locked generator": ({}, {}, {"locked": True}),
    "no aerodynamics": ({}, {"aero": False}, {}),
    "elastodyn-compatible": ({}, {"elastodyn_compatible": True, "gauss_points": 1}, {}),
    "FE blade shapes at 12.1 rpm": ({}, {"blade_shapes": "fe", "rpm": 12.1}, {}),
    "no gravity, no damping": ({}, {}, {"no_gravity": True, "no_damping": True}),
    "uniform wind file (WindType 2) at t = 7.3 s": (
        {INFLOW: {"WindType": "2", "FileName_Uni": '"gusty.uni"', "RefLength": "120"}}, {},
        {"time": 7.3, "files": {"gusty.uni": UNIFORM}}),
    "uniform wind file before its first time": (
        {INFLOW: {"WindType": "2", "FileName_Uni": '"gusty.uni"'}}, {}, {"time": 0.5, "files": {"gusty.uni": UNIFORM}}),
    "TurbSim full field (WindType 3) at t = 12.34 s": (
        {INFLOW: {"WindType": "3", "FileName_BTS": '"box.bts"'}}, {}, {"time": 12.34, "files": {"box.bts": BOX}}),
    "TurbSim full field, yawed, at its wrap-around": (
        {INFLOW: {"WindType": "3", "FileName_BTS": '"box.bts"'}}, {}, {"time": 29.95, "yaw": 0.3,
                                                                         "files": {"box.bts": BOX}}),
}


def edit(path: Path, label: str, value: str) -> None:
    """Set the value of the line labelled ``label`` of an OpenFAST input file."""
    text = path.read_text()
    new, count = re.subn(rf"^(\s*)\S+(\s+{re.escape(label)}\s)", rf"\g<1>{value}\g<2>", text, count=1,
                         flags=re.MULTILINE)
    assert count == 1, (path.name, label)
    path.write_text(new)


def variant_model(tmp_path: Path, name: str) -> tuple[TurbineModel, dict]:
    edits, options, changes = VARIANTS[name]
    folder = tmp_path / "deck"
    shutil.copytree(CASE, folder)
    for name, content in changes.get("files", {}).items():
        (folder / name).write_bytes(content.read_bytes() if isinstance(content, Path) else content.encode())
    for file, labels in edits.items():
        for label, value in labels.items():
            edit(folder / file, label, value)
    options = {"blade_shapes": "polynomial", **options}
    deck = read_turbine_deck(folder / FST, **options)
    params = deck.params
    if changes.get("no_gravity"):
        params = params.with_(gravity=0.0)
    if changes.get("no_damping"):
        params = params.without_damping()
    return TurbineModel(params, aero=deck.aero, generator=deck.generator), changes


def states(model: TurbineModel, changes: dict, seed: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """Two states near the operating point: deflected, moving, spinning near rated (yawed if asked); the first
    with the blades flapping fast downwind (blade tips in the propeller brake)."""
    rng = np.random.default_rng(seed)
    yaw = model.dofs.index("yaw")
    out = []
    for flap_rate in (4.0, 0.0):
        q, u = rng.normal(scale=0.05, size=model.n), rng.normal(scale=0.05, size=model.n)
        q[model.blade_columns] = rng.normal(scale=0.3, size=model.blade_columns.shape)
        u[model.blade_columns[:, 0]] += flap_rate
        q[model.dofs.index("generator_azimuth")] = rng.uniform(0, 2 * np.pi)
        u[model.dofs.index("generator_azimuth")] = RATED * (1 + rng.normal(scale=0.05))
        q[yaw] = changes.get("yaw", q[yaw])
        out.append((q, u))
    return out


@pytest.mark.parametrize("name", list(VARIANTS))
def test_compiled_equals_numpy_for_every_option(tmp_path, name):
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        pytest.skip("compiled kernels switched off")
    from bladefem.models.turbine.compiled import compiled_equations
    from bladefem.models.turbine.outputs import load_row
    model, changes = variant_model(tmp_path, name)
    compiled = compiled_equations(model)
    (q_before, u_before), (q, u) = states(model, changes, seed=len(name))
    free = np.ones(model.n, dtype=bool)
    free[model.dofs.index("generator_azimuth")] = not changes.get("locked", False)
    system = FreeSystem(model, free, q, u)
    t = changes.get("time", 0.0)
    compiled(q_before, u_before)
    compiled.derivative(0.0, FreeSystem(model, free, q_before, u_before).initial_state(), q_before, u_before,
                        system.index)
    _, f_warm = compiled(q, u, t=t)                  # each solve starting from the roots at the other state
    compiled.forget_solutions()
    M, f = model.equations(q, u, t=t)
    Mc, fc = compiled(q, u, t=t)
    np.testing.assert_allclose(Mc, M, rtol=0, atol=ROUNDING * np.abs(M).max())
    np.testing.assert_allclose(fc, f, rtol=0, atol=ROUNDING * np.abs(f).max())
    np.testing.assert_allclose(f_warm, f, rtol=0, atol=WARM_START * np.abs(f).max())
    ix = system.index
    du = np.zeros(model.n)
    du[ix] = np.linalg.solve(M[system.block], f[ix])
    x = system.initial_state()
    np.testing.assert_allclose(compiled.derivative(t, x, q - u * t, u, ix), np.concatenate([x[system.size:], du[ix]]),
                               rtol=0, atol=ROUNDING * np.abs(du).max())
    np.testing.assert_allclose(compiled.rate(t, x, q - u * t, u, ix), np.concatenate([x[system.size:], du[ix]]),
                               rtol=0, atol=ROUNDING * np.abs(du).max())
    compiled(q_before, u_before)
    compiled.forget_solutions()
    row = compiled.outputs(np.full(1, t), x[None], q - u * t, u, ix)[0]
    expected = load_row(model, q, u, du, t=t)
    np.testing.assert_allclose(row, expected, rtol=10 * ROUNDING, atol=1e-6)


@pytest.mark.slow
def test_bem_mod1_deck_against_openfast(tmp_path):
    """The shipped deck with ``BEM_Mod 1``, 100 s at 11.4 m/s, 12.1 rpm (generator locked), pitch 0, from the
    undeflected state, through the default (compiled) integrator: means over 80-100 s against OpenFAST v4.2.1 run
    with BEM_Mod 1 (tests/data/openfast/rated_fixed_speed_bem_mod1.json), within the tolerances of the deck's own
    comparison (tests/test_turbine_aeroelastic.py): thrust and torque 0.6 % (measured -0.12 %, -0.11 %), the tip
    deflection 2.5 % (measured +0.86 %); the tip's 1P out-of-plane swing (std) within 3 % of OpenFAST v5's with
    BEM_Mod 1 (rated_fixed_speed_v5.json; measured +0.98 %, +12 % with the sections turned by the out-of-plane
    slope alone). Before the BEM fix: -15.9 %, -23.6 % and -29.5 %."""
    import json

    from bladefem.models.turbine import select_dofs
    from bladefem.models.turbine.initial import free_from_switches, initial_state
    from bladefem.models.turbine.simulate import simulate
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        pytest.skip("100 s runs need the kernels")
    folder = tmp_path / "deck"
    shutil.copytree(CASE, folder)
    edit(folder / AERODYN, "BEM_Mod", "1")
    deck = read_turbine_deck(folder / FST, wind_speed=11.4, rpm=12.1, pitch=0.0)
    model = TurbineModel(deck.params, aero=deck.aero, generator=deck.generator)
    free = select_dofs(model.dofs, [], base=free_from_switches(model.dofs, {**deck.switches, "GenDOF": False}))
    q0, u0, _ = initial_state(model, free, deck.conditions.with_(rotor_speed=RATED))
    result = simulate(FreeSystem(model, free, q0, u0), 100.0, dt_output=0.05)
    window = result.time >= 80.0 - 1e-9
    reference = json.loads((CASE.parents[1] / "tests" / "data" / "openfast" / "rated_fixed_speed_bem_mod1.json")
                           .read_text())["channels"]
    for name, tolerance in (("RtAeroFxh", 0.006), ("RtAeroMxh", 0.006), ("RotThrust", 0.006), ("RotTorq", 0.006),
                            ("OoPDefl1", 0.025)):
        mean = float(np.mean(result.outputs[name][window]))
        assert mean == pytest.approx(reference[name]["mean"], rel=tolerance), name
    v5 = json.loads((CASE.parents[1] / "tests" / "data" / "openfast" / "rated_fixed_speed_v5.json").read_text())
    swing = float(np.std(result.outputs["OoPDefl1"][window]))
    assert swing == pytest.approx(v5["channels"]["BEM_Mod 1"]["OoPDefl1"]["std"], rel=0.03)


@pytest.mark.parametrize("name", [name for name, (_, options, changes) in VARIANTS.items()
                                  if options.get("aero", True) and not changes.get("time")])
def test_held_induction_equals_the_numpy_frozen_wake(tmp_path, name):
    """The compiled loads with the induction held (the flag RK4's inner stages of a controlled run set): each node
    takes the induced velocities (vx a, vy a') of the last solve, here at another state, against the numpy frozen
    wake (:meth:`bladefem.models.turbine.frozen_wake.SectionAero.generalized` with :func:`held_induction` of that
    state) as the difference from the loads solved afresh, on every option of the steady-wind variants; the hold
    at the solved state itself gives the solved loads. Rounding: 1e-10 of the largest entry."""
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        pytest.skip("compiled kernels switched off")
    from bladefem.models.turbine.aero import aero_loads
    from bladefem.models.turbine.compiled import compiled_equations
    from bladefem.models.turbine.frozen_wake import SectionAero, held_induction
    model, changes = variant_model(tmp_path, name)
    compiled = compiled_equations(model)
    (q_before, u_before), (q, u) = states(model, changes, seed=len(name))
    hold = compiled.state[13]
    _, solved = compiled(q, u)
    _, solved_before = compiled(q_before, u_before)
    hold[2] = 1.0
    _, held = compiled(q, u)
    _, again = compiled(q_before, u_before)
    hold[2] = 0.0
    frozen = SectionAero.of(model.aero).generalized(model, held_induction(model, model.aero, q_before, u_before), q,
                                                    u).sum(axis=0)
    fresh = aero_loads(model, model.aero, q, u).generalized
    change = frozen - fresh
    np.testing.assert_allclose(held - solved, change, rtol=0, atol=ROUNDING * np.abs(solved).max())
    np.testing.assert_allclose(again, solved_before, rtol=0, atol=ROUNDING * np.abs(solved).max())
    if model.aero.rotor.options.induction:
        assert np.abs(change).max() > 1e-2 * np.abs(fresh).max()            # the held induction is not the new one
