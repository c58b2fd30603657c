"""Adams-Bashforth-Moulton between controller calls (ElastoDyn's default ``Method`` 3, bladefem's ``--method auto``
with the controller library where it is stable): its amplification against the recurrence stepped, its order, and
the controlled NREL 5MW run against Dormand-Prince 5(4) at rtol 1e-9. The compiled loop and its Python twin agree
on it in tests/test_controlled_loop.py."""

from __future__ import annotations

import contextlib
import io
import os
import re
from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import main
from bladefem.models.turbine.compiled_control import ABM4_CORRECTOR, ABM4_PREDICTOR
from bladefem.models.turbine.interval_steps import abm4_growth, abm4_stable
from simulation_table import table

CASE = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw"
DECK = CASE / "NRELOffshrBsline5MW_Onshore_ROSCO.fst"


def stepped(z: complex, steps: int = 4000) -> float:
    """The growth per step of ABM4 on y' = lambda y (z = h lambda) measured by stepping it from exact starting
    values: the geometric mean of |y_(n+1) / y_n| over the second half (the values rescaled every step)."""
    y = [np.exp(z * k) for k in range(4)]
    logs = []
    for _ in range(steps):
        f = [z * value for value in y[-4:]]                     # h times the derivatives
        predicted = y[-1] + ABM4_PREDICTOR @ np.array(f[::-1])
        corrected = y[-1] + ABM4_CORRECTOR[0] * z * predicted + ABM4_CORRECTOR[1:] @ np.array(f[:0:-1])
        scale = abs(corrected)
        logs.append(np.log(scale / abs(y[-1])))
        y = [value / scale for value in y[-3:]] + [corrected / scale]
    return float(np.exp(np.mean(logs[steps // 2:])))


@pytest.mark.parametrize("z", [0.3j, 0.7j, 0.5 * np.exp(1j * np.radians(100)), -0.5 + 0.0j, -1.0 + 0.2j])
def test_growth_is_the_recurrence_stepped(z):
    """The characteristic root of :func:`abm4_growth` is the growth of the stepped recurrence (to 1e-6: the other
    roots' share after 2000 steps)."""
    assert abm4_growth(z) == pytest.approx(stepped(z), rel=1e-6)


def test_the_method_is_fourth_order():
    """Per step the dominant root differs from exp(z) by O(z^5): the slope of log|rho - e^z| against log|z| on the
    imaginary axis is 5 (fitted 0.02 to 0.08)."""
    from numpy.polynomial import polynomial
    P, C = ABM4_PREDICTOR, ABM4_CORRECTOR
    sizes = np.geomspace(0.02, 0.08, 6)
    errors = []
    for r in sizes:
        z = 1j * r
        predicted = np.array([1.0, 0, 0, 0]) + z * P
        corrected = np.array([1.0, 0, 0, 0]) + z * np.append(C[1:], 0.0) + z * C[0] * predicted
        roots = np.roots(np.concatenate([[1.0], -corrected]))
        principal = roots[np.argmin(np.abs(roots - np.exp(z)))]
        errors.append(abs(principal - np.exp(z)))
    slope = polynomial.polyfit(np.log(sizes), np.log(errors), 1)[1]
    assert slope == pytest.approx(5.0, abs=0.05)


def test_stability_check():
    """An undamped mode grows under ABM4 (and is refused), a mode damped 1 % is stable to about 0.92 of w h (so at
    0.3, with the factor 2 margin, accepted; at 0.6 refused), a growing mode is not asked about."""
    omega = 10.0
    assert not abm4_stable(np.array([1j * omega, -1j * omega]), 0.03)
    damped = omega * np.array([-0.01 + 1j * np.sqrt(1 - 1e-4), -0.01 - 1j * np.sqrt(1 - 1e-4)])
    assert abm4_stable(damped, 0.03)
    assert not abm4_stable(damped, 0.06)
    assert abm4_stable(np.concatenate([damped, [0.5]]), 0.03)


def run(tmp_path: Path, name: str, *options: str) -> tuple[dict, int, str]:
    out = tmp_path / f"{name}.csv"
    messages = io.StringIO()
    with contextlib.redirect_stderr(messages):
        code = main(["turbine", str(DECK), "--simulate", "10", "--wind-speed", "16", "--pitch-deg", "10", "-o",
                     str(out), "--quiet", *options])
    assert code == 0, messages.getvalue()
    found = re.search(r"(\d+) right-hand sides \((\w+) between controller calls\)", messages.getvalue())
    return table(out), int(found.group(1)), found.group(2)


@pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="controlled runs need numba")
def test_controlled_run_against_the_reference(tmp_path):
    """10 s from 10 deg of pitch at 16 m/s with ROSCO (the start transient): the default ABM4 against DP54 at rtol
    1e-9 within 5 mm of tip deflection (measured 3.0 mm over 30 s; RK4 per interval 4.8 mm), 0.5 kW of power
    (0.28), 0.005 deg of pitch (0.0025), with fewer than half of RK4's right-hand sides (340 against 800 per
    simulated second)."""
    reference, _, _ = run(tmp_path, "reference", "--method", "DP54", "--rtol", "1e-9")
    abm4, abm4_count, chosen = run(tmp_path, "abm4")
    _, rk4_count, _ = run(tmp_path, "rk4", "--method", "RK4", "--step", "0.00625")
    assert chosen == "ABM4"                                      # what auto chose, said with the count
    for channel, bound in (("OoPDefl1", 5e-3), ("GenPwr", 0.5), ("BldPitch1", 5e-3)):
        assert np.max(np.abs(abm4[channel] - reference[channel])) <= bound, channel
    assert np.ptp(reference["BldPitch1"]) > 0.1                  # the controller moved the pitch
    assert abm4_count < 0.5 * rk4_count


def test_abm4_needs_the_controller(capsys):
    """Without the controller library (the rotor held) --method ABM4 is refused, naming the option."""
    code = main(["turbine", str(CASE / "NRELOffshrBsline5MW_Onshore.fst"), "--simulate", "1", "--rpm", "12.1",
                 "--method", "ABM4", "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and "--method" in err and "controller" in err and "Traceback" not in err


@pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="controlled runs need numba")
def test_abm4_refused_where_a_mode_would_grow(capsys):
    """With the controller called every 0.05 s, a step of 0.05 s lets the 6 Hz mode (w h = 1.9) grow: --method
    ABM4 is refused naming --method (auto falls back to RK4 or DP54 there)."""
    code = main(["turbine", str(DECK), "--simulate", "0.2", "--wind-speed", "16", "--pitch-deg", "10",
                 "--method", "ABM4", "--controller-dt", "0.05", "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and "--method" in err and "ABM4" in err and "Traceback" not in err


@pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="the compiled forcing needs numba")
def test_initial_modes_from_the_compiled_forcing_equal_the_numpy_ones():
    """The eigenvalues that choose ABM4 and RK4's step (``initial_modes``: central differences of the compiled
    forcing, each BEM solve from scratch) equal those of the numpy forcing, also after the model ran elsewhere (its
    nodes' roots then at another state): within 1e-6 of the largest eigenvalue (measured 6e-10; the solves started
    from the last perturbation's roots, which agree only to the BEM's tolerance, left 2.8e-4)."""
    from bladefem.builders.turbine_deck import read_turbine_deck
    from bladefem.models.turbine import FreeSystem, TurbineModel
    from bladefem.models.turbine.linearize import state_matrix
    from bladefem.models.turbine.simulate import initial_modes
    deck = read_turbine_deck(CASE / "NRELOffshrBsline5MW_Onshore.fst", wind_speed=11.4, rpm=12.1, pitch=0.0)
    model = TurbineModel(deck.params, aero=deck.aero, generator=deck.generator)
    q, u = np.zeros(model.n), np.zeros(model.n)
    u[model.dofs.index("generator_azimuth")] = 12.1 * np.pi / 30
    system = FreeSystem(model, np.ones(model.n, dtype=bool), q, u)
    model.fast_equations()(q + 0.01, u)
    compiled = np.sort_complex(initial_modes(system)[0])
    numpy = np.sort_complex(np.linalg.eigvals(state_matrix(system, q, u)))
    np.testing.assert_allclose(compiled, numpy, rtol=0, atol=1e-6 * np.abs(numpy).max())
