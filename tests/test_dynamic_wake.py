"""The dynamic wake (AeroDyn's DBEMT, Oye's two filters, bladefem.aero.dynamic_wake): the filter against its closed-
form step response, the time constants and disk weights against AeroDyn's definitions (DBEMT.f90, BEMT.f90), the
rest state, and the twins: the compiled right-hand side, load channels and a short simulation against the numpy
reference for DBEMT_Mod 0, 1, 2, 3 on the shipped NREL 5MW deck (with the deck's BEM_Mod 2 and with BEM_Mod 1)."""

from __future__ import annotations

import math
import os
import shutil
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from bladefem.aero.dynamic_wake import (
    OYE_K,
    DynamicWake,
    disk_weights,
    initial_wake,
    step_response,
    time_constant,
    wake_rates,
)
from bladefem.builders.turbine_deck import read_turbine_deck
from bladefem.errors import InputError
from bladefem.models.turbine import FreeSystem, TurbineModel

CASE = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw"
FST = "NRELOffshrBsline5MW_Onshore.fst"
AERODYN = "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
RATED = 12.1 * math.pi / 30
#: the same sums in another order (the twins test of every option: tests/test_turbine_twins.py)
ROUNDING = 1e-10


@pytest.mark.parametrize("tau1, ratio", [(4.0, 0.0), (4.0, 0.7), (10.0, 0.95)])
def test_filter_step_response_is_the_closed_form(tau1, ratio):
    """A unit step of the quasi-steady induced velocity from rest: the integrated filter equals the closed form of
    two first-order stages with Oye's k = 0.6 term (v_int jumps by k, then v = 1 - c e^(-t/tau1) - (1 - c)
    e^(-t/tau2), c = (1 - k) tau1 / (tau1 - tau2), tau2 = (0.39 - 0.26 (r/R)^2) tau1); tolerance: the integrator's
    (rtol 1e-10)."""
    tau2 = (0.39 - 0.26 * ratio**2) * tau1

    def rates(t, y):
        return wake_rates(y[0], y[1], 1.0, tau1, ratio, OYE_K)

    t = np.linspace(0.0, 6 * tau1, 61)
    solution = solve_ivp(rates, (0.0, t[-1]), [0.0, 0.0], t_eval=t, rtol=1e-10, atol=1e-12, method="DOP853")
    np.testing.assert_allclose(solution.y[1], step_response(t, tau1, tau2), atol=1e-8)
    np.testing.assert_allclose(solution.y[0] + OYE_K, 1.0 - (1.0 - OYE_K) * np.exp(-t / tau1), atol=1e-8)
    half = t[np.argmax(solution.y[1] >= 0.5)]
    assert 0.0 < half < tau1                         # k = 0.6 of the step passes at once: faster than one stage


def test_rest_state_has_no_rate():
    """At rest on the quasi-steady velocities (z = (1 - k) v_qs, v = v_qs: AeroDyn's DBEMT_InitStates) nothing
    moves."""
    quasi = np.array([2.5, -0.3])
    z_a, z_t, v_a, v_t = initial_wake(quasi)
    for z, v, q in ((z_a, v_a, quasi[0]), (z_t, v_t, quasi[1])):
        assert wake_rates(z, v, q, 7.0, 0.5, OYE_K) == pytest.approx((0.0, 0.0), abs=1e-15)


def test_time_constants_as_aerodyn():
    """tau1 of DBEMT_Mod 2 = 1.1 R / ((1 - 1.3 a) U) with a at most 0.5, U at least 0.1 m/s and tau1 at most
    100 s (DBEMT.f90, ComputeTau1); DBEMT_Mod 1 and 3 keep tau1_const."""
    two = DynamicWake(2).vector()
    assert time_constant(two, 0.3, 11.0, 63.0) == pytest.approx(1.1 * 63.0 / (0.61 * 11.0))
    assert time_constant(two, 0.7, 11.0, 63.0) == pytest.approx(1.1 * 63.0 / (0.35 * 11.0))
    assert time_constant(two, -0.2, 11.0, 63.0) == pytest.approx(1.1 * 63.0 / (1.26 * 11.0))
    assert time_constant(two, 0.3, 0.01, 63.0) == 100.0
    for model in (1, 3):
        assert time_constant(DynamicWake(model, 4.0).vector(), 0.3, 11.0, 63.0) == 4.0
    with pytest.raises(ValueError, match="tau1_const"):
        DynamicWake(1, 0.0)


def test_disk_weights_as_aerodyn():
    """AeroDyn's averaging weights: one in all, nothing outside 0.6 R to 0.8 R, largest at 0.7 R (BEMT.f90)."""
    r = np.broadcast_to(np.linspace(1.5, 63.0, 40), (3, 40))
    w = disk_weights(r)
    ratio = r / r.max()
    assert w.sum() == pytest.approx(1.0)
    assert np.all(w[(ratio <= 0.6) | (ratio >= 0.8)] == 0.0)
    assert ratio[0, np.argmax(w[0])] == pytest.approx(0.7, abs=0.02)


def deck_model(tmp_path: Path, dbemt: str, bem_mod: str = "2") -> TurbineModel:
    folder = tmp_path / f"deck{dbemt}_{bem_mod}"
    shutil.copytree(CASE, folder)
    text = (folder / AERODYN).read_text()
    for label, value in (("DBEMT_Mod", dbemt), ("BEM_Mod", bem_mod)):
        lines = [f"{value:>11s}   {label}" + line.split(label, 1)[1] if line.split()[1:2] == [label] else line
                 for line in text.splitlines()]
        text = "\n".join(lines) + "\n"
    (folder / AERODYN).write_text(text)
    deck = read_turbine_deck(folder / FST, blade_shapes="polynomial", dynamic_wake=True)
    return TurbineModel(deck.params, aero=deck.aero, generator=deck.generator)


def test_dynamic_wake_decks_are_read(tmp_path):
    """DBEMT_Mod 1-3 give the rotor a dynamic wake for a time simulation (tau1_const for 1 and 3); the steady and
    linear analyses refuse it naming DBEMT_Mod and --quasi-steady, which leaves it out."""
    for dbemt, expected in (("0", None), ("1", DynamicWake(1, 4.0)), ("3", DynamicWake(3, 4.0))):
        assert deck_model(tmp_path, dbemt).aero.rotor.dynamic_wake == expected
    wake = deck_model(tmp_path, "2").aero.rotor.dynamic_wake
    assert wake.model == 2
    path = next(tmp_path.glob("deck2_2")) / FST
    with pytest.raises(InputError) as error:
        read_turbine_deck(path)
    assert error.value.field == "DBEMT_Mod" and "--quasi-steady" in str(error.value)
    deck = read_turbine_deck(path, leave_out={"--quasi-steady"})
    assert deck.aero.rotor.dynamic_wake is None and any("DBEMT_Mod 2" in note for note in deck.notes)


def states(model: TurbineModel, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    q, u = rng.normal(scale=0.05, size=model.n), rng.normal(scale=0.05, size=model.n)
    q[model.blade_columns] = rng.normal(scale=0.3, size=model.blade_columns.shape)
    q[model.dofs.index("generator_azimuth")] = rng.uniform(0, 2 * np.pi)
    u[model.dofs.index("generator_azimuth")] = RATED
    return q, u


@pytest.mark.parametrize("dbemt, bem_mod", [("0", "2"), ("1", "2"), ("2", "2"), ("3", "2"), ("2", "1")])
def test_compiled_equals_numpy_with_the_dynamic_wake(tmp_path, monkeypatch, dbemt, bem_mod):
    """Twins: dx/dt (coordinates, rates and the wake's states, away from rest) and the load channels of the compiled
    kernels equal the numpy reference (FreeSystem without numba: model.equations with aero.py) to rounding, for
    every DBEMT_Mod and both projections; the compiled model is first called at another state, so that nothing of
    a previous call leaks. Then 0.1 s simulated in both paths from this state (the wake's states move) with the
    same adaptive integrator (rtol 1e-9) agree within 1e-5 of each channel's largest magnitude over the run: the
    compiled path's solves start next to the previous roots and agree with the reference's from scratch only to
    the BEM's tolerance (5e-10 rad at a node of the BEM_Mod 1 deck after two 2 ms steps), once rounding differs the
    two runs take other steps, and this violent start amplifies both (measured at 0.1 s: 3.8e-7 of RtAeroMxh and
    5.8e-7 of OoPDefl1 for DBEMT_Mod 2 with BEM_Mod 1; by 0.2 s 1.8e-5 of RtAeroMxh, 1.5e-4 with fixed RK4 steps
    of 2 ms, so the runs stop at 0.1 s); a path that left the wake's states out differs by 0.4 to 16 % at 0.05 and
    0.1 s (BEM_Mod 1)."""
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        pytest.skip("compiled kernels switched off")
    from bladefem.models.turbine import compiled as compiled_module
    from bladefem.models.turbine.outputs import load_row
    from bladefem.models.turbine.simulate import simulate
    model = deck_model(tmp_path, dbemt, bem_mod)
    reference = deck_model(tmp_path / "numpy", dbemt, bem_mod)
    q, u = states(model, 7)
    q_before, u_before = states(model, 8)
    free = np.ones(model.n, dtype=bool)
    system = FreeSystem(model, free, q, u)
    x = system.initial_state()
    assert len(x) == 2 * system.size + (0 if dbemt == "0" else 3 * 4 * model.aero.n_nodes)
    x[2 * system.size:] *= 1.0 + 0.3 * np.random.default_rng(3).normal(size=system.wake_size)
    compiled = model.fast_equations()
    compiled.derivative(0.3, FreeSystem(model, free, q_before, u_before).initial_state(), q_before, u_before,
                        system.index)
    monkeypatch.setattr(compiled_module, "compiled_equations", lambda model: None)
    numpy_system = FreeSystem(reference, free, q, u)
    assert not hasattr(reference.fast_equations(), "derivative")
    expected = numpy_system(0.0, x)
    np.testing.assert_allclose(system(0.0, x), expected, rtol=0, atol=ROUNDING * np.abs(expected).max())
    if dbemt != "0":
        wake = expected[2 * system.size:]
        assert np.abs(wake).max() > 1e-3                  # the states away from rest do move
    wake = system.wake(x)
    du = numpy_system.accelerations(q, u, 0.0, wake)
    row = compiled.outputs(np.zeros(1), x[None], q, u, system.index)[0]
    np.testing.assert_allclose(row, load_row(reference, q, u, du, wake=wake), rtol=10 * ROUNDING, atol=1e-6)
    compiled_run = simulate(system, 0.1, dt_output=0.05, method="RK45", rtol=1e-9, atol=1e-9)
    numpy_run = simulate(numpy_system, 0.1, dt_output=0.05, method="RK45", rtol=1e-9, atol=1e-9)
    for name in ("RtAeroFxh", "RtAeroMxh", "OoPDefl1"):
        expected = numpy_run.outputs[name]
        np.testing.assert_allclose(compiled_run.outputs[name], expected, rtol=0, atol=1e-5 * np.abs(expected).max())


def test_the_command_line_runs_the_dynamic_wake(tmp_path, capsys):
    """`turbine DECK.fst --simulate` with DBEMT_Mod 2: exit 0, the header names the dynamic wake; with
    --quasi-steady it is left out, said in the header; --linearize refuses it naming DBEMT_Mod (exit 2, one
    line)."""
    from bladefem.cli import main
    deck_model(tmp_path, "2")
    fst = str(tmp_path / "deck2_2" / FST)
    common = ("--simulate", "0.2", "--rpm", "12.1", "--dt", "0.1", "--quiet", "-o", str(tmp_path / "out.csv"))
    assert main(["turbine", fst, *common]) == 0
    assert "BEM with the dynamic wake (DBEMT_Mod 2)" in capsys.readouterr().out
    assert main(["turbine", fst, *common, "--quasi-steady"]) == 0
    out = capsys.readouterr().out
    assert "quasi-steady BEM" in out and "DBEMT_Mod 2" in out
    assert main(["turbine", fst, "--linearize", "--rpm", "12.1", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "DBEMT_Mod" in err and "--quasi-steady" in err and "\n" not in err.strip()


def test_batch_simulation_runs_the_dynamic_wake(tmp_path):
    """A batch plan's turbine_simulate case of a DBEMT_Mod 2 deck runs with the dynamic wake: its thrust equals
    `bladefem turbine --simulate`'s (the same model and integrator), and differs from the quasi-steady deck's where
    the blades' first swing changes the inflow: the lagging induction lets the thrust's first dip (0.25 s) go 1.1 %
    deeper (measured; the 2 s means differ by only 3e-5, the wake returning what it took)."""
    pytest.importorskip("pyarrow")
    from bladefem.batch import read_plan, run_case
    from bladefem.cli import main
    deck_model(tmp_path, "2")
    fst = tmp_path / "deck2_2" / FST
    means, lowest = {}, {}
    for name, path in (("dynamic", fst), ("quasi-steady", CASE / FST)):
        plan_file = tmp_path / f"plan_{name}.yaml"
        plan_file.write_text(f"model: {path}\nanalysis: {{type: turbine_simulate, seconds: 2, dt: 0.05, "
                             "statistics_from_s: 0, rpm: 12.1, pitch_deg: 0}\ngrid: {wind_speed_m_s: [11.4]}\n")
        rows = run_case(read_plan(plan_file).cases[0])
        assert all(row["status"] == "ok" for row in rows)
        means[name] = {row["channel"]: row["mean"] for row in rows}["RtAeroFxh"]
        lowest[name] = {row["channel"]: row["min"] for row in rows}["RtAeroFxh"]
    output = tmp_path / "run.csv"
    assert main(["turbine", str(fst), "--simulate", "2", "--dt", "0.05", "--rpm", "12.1", "--pitch-deg", "0",
                 "--wind-speed", "11.4", "--output", str(output), "--quiet"]) == 0
    lines = output.read_text().splitlines()
    column = lines[0].split(",").index(next(c for c in lines[0].split(",") if c.startswith("RtAeroFxh")))
    thrust = np.array([float(line.split(",")[column]) for line in lines[1:]])
    assert means["dynamic"] == pytest.approx(thrust.mean(), rel=1e-8)
    assert lowest["dynamic"] == pytest.approx(thrust.min(), rel=1e-8)
    assert lowest["dynamic"] / lowest["quasi-steady"] - 1 < -5e-3
