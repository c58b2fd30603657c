"""Ctrl-C during a simulation keeps the rows computed so far with every integrator, not only the compiled ones:
scipy's RK45 and DOP853 are stepped as solve_ivp steps them (the outputs equal solve_ivp's to round-off) so that
an interrupt leaves whole rows, and RK4 keeps its rows the same way."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from bladefem.builders.turbine_elastodyn import turbine_from_elastodyn
from bladefem.models.turbine import FreeSystem, TurbineModel
from bladefem.models.turbine.simulate import Interrupted, simulate

MAIN = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


def tower_system() -> FreeSystem:
    """The 5MW's first tower fore-aft mode, released from a 0.5 m top deflection (no aerodynamics)."""
    model = TurbineModel(turbine_from_elastodyn(MAIN, blade_shapes="polynomial"))
    free = np.zeros(model.n, dtype=bool)
    free[model.dofs.index("tower_fa1")] = True
    q0 = np.zeros(model.n)
    q0[model.dofs.index("tower_fa1")] = 0.5
    return FreeSystem(model, free, q0, np.zeros(model.n))


@pytest.mark.parametrize("method", ["RK45", "DOP853"])
def test_stepped_scipy_equals_solve_ivp(method):
    system = tower_system()
    result = simulate(system, 2.0, dt_output=0.1, method=method, rtol=1e-8, atol=1e-10)
    reference = solve_ivp(system, (0.0, 2.0), system.initial_state(), method=method, t_eval=result.time,
                          rtol=1e-8, atol=1e-10)
    index = system.model.dofs.index("tower_fa1")
    assert np.allclose(result.q[:, index], reference.y[0], rtol=0, atol=1e-12)


@pytest.mark.parametrize("method", ["RK45", "DOP853", "RK4"])
def test_ctrl_c_keeps_the_rows_done(method):
    system = tower_system()

    def interrupt_at_one_second(t: float) -> None:
        if t >= 1.0:
            raise KeyboardInterrupt

    with pytest.raises(Interrupted) as stop:
        simulate(system, 3.0, dt_output=0.1, method=method, progress=interrupt_at_one_second)
    rows = stop.value.result
    assert stop.value.exit_code == 130 and len(rows.time) == 11 and rows.time[-1] == pytest.approx(1.0)
    assert np.all(np.isfinite(rows.q)) and set(rows.outputs) and all(len(v) == 11 for v in rows.outputs.values())
