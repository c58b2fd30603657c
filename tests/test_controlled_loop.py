"""The compiled controlled loop (:mod:`bladefem.models.turbine.compiled_control`: the controller library called
from the kernel) against its Python twin (the loop of :mod:`bladefem.models.turbine.controlled` with the library in
a process of its own): the same deck, wind and controller give the same rows to rounding."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.controller import controller_setup
from bladefem.builders.turbine_deck import read_turbine_deck
from bladefem.models.turbine import FreeSystem, TurbineModel
from bladefem.models.turbine.controlled import simulate_controlled
from bladefem.models.turbine.discon import DisconController

DECK = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ROSCO.fst"

pytestmark = pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="controlled runs need numba")


def run(isolated: bool, wind: float, pitch_deg: float, rpm: float, shapes: str, method: str = "DP54",
        deck_path: Path = DECK):
    deck = read_turbine_deck(deck_path, wind_speed=wind, rpm=rpm, pitch=np.radians(pitch_deg), blade_shapes=shapes,
                             controller=True, dynamic_wake=deck_path != DECK)
    model = TurbineModel(deck.params, aero=deck.aero, generator=deck.generator)
    q, u = np.zeros(model.n), np.zeros(model.n)
    u[5] = rpm * np.pi / 30
    system = FreeSystem(model, np.ones(model.n, dtype=bool), q, u)
    with DisconController(controller_setup(deck, None), "twin", isolated=isolated) as controller:
        return simulate_controlled(system, controller, 0.6, dt_output=0.01, hub_wind=wind,
                                   efficiency=model.generator.efficiency, method=method, rk4_step=0.004)


@pytest.mark.parametrize("method", ["DP54", "RK4", "ABM4"])
@pytest.mark.parametrize("wind, pitch_deg, rpm, shapes", [(16.0, 10.0, 12.1, "fe"), (8.0, 0.0, 9.16, "polynomial")])
def test_compiled_loop_equals_the_python_loop(wind, pitch_deg, rpm, shapes, method):
    """Above rated (pitch and constant power) and below (torque law), each blade model, each integrator (RK4 at
    0.004 s: two steps per 0.00625 s interval, output rows every 0.01 s inside intervals and at their ends): every
    row, channel and right-hand side count alike; only the rounding of the end-of-interval loads differs (the
    compiled DP54 loop takes them from the step's last stage, the Python loop from the dense output at the
    interval's end)."""
    compiled = run(False, wind, pitch_deg, rpm, shapes, method)
    python = run(True, wind, pitch_deg, rpm, shapes, method)
    assert compiled.evaluations == python.evaluations
    np.testing.assert_array_equal(compiled.time, python.time)
    for name, values in python.outputs.items():
        scale = max(np.max(np.abs(values)), 1e-3)
        assert np.max(np.abs(compiled.outputs[name] - values)) <= 1e-9 * scale, name
    assert np.ptp(python.outputs["BldPitch1"]) > 0 or np.ptp(python.outputs["GenTq"]) > 0   # the controller acts


@pytest.mark.parametrize("method", ["RK4", "ABM4"])
def test_compiled_loop_equals_the_python_loop_with_the_dynamic_wake(tmp_path, method):
    """The same with the dynamic wake (DBEMT_Mod 2: its states carry the induction, the filters integrated with the
    structure) above rated: every row, channel and right-hand side count alike."""
    folder = tmp_path / "deck"
    shutil.copytree(DECK.parent, folder)
    aerodyn = folder / "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
    aerodyn.write_text("\n".join(f"{'2':>11s}   DBEMT_Mod" + line.split("DBEMT_Mod", 1)[1]
                                 if line.split()[1:2] == ["DBEMT_Mod"] else line
                                 for line in aerodyn.read_text().splitlines()) + "\n")
    deck = folder / DECK.name
    compiled = run(False, 16.0, 10.0, 12.1, "fe", method, deck)
    python = run(True, 16.0, 10.0, 12.1, "fe", method, deck)
    assert compiled.wake is not None and compiled.evaluations == python.evaluations
    for name, values in python.outputs.items():
        scale = max(np.max(np.abs(values)), 1e-3)
        assert np.max(np.abs(compiled.outputs[name] - values)) <= 1e-9 * scale, name
