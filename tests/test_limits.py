"""Arguments the models cannot answer are refused before any computation (API: ValueError; CLI: one line, exit 2,
the limit named), and an answer that is not a result (a mode whose residual is not small) is never printed as a
frequency (API: SolveError; CLI: one line, exit 1)."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import numpy as np
import pytest
from cpu_watchdog import cpu_limit

import bladefem

from bladefem.cli import main
from bladefem.errors import SolveError
from bladefem.builders.case import read_case
from bladefem.limits import MAX_ELEMENTS, MAX_MODES, MAX_RPM, MAX_SPEEDS, sweep_bytes
from bladefem.modal import campbell, modes
from bladefem.modal.results import MAX_RESIDUAL, ModalResult, Mode, check_modes
from bladefem.sections import Blade, uniform_sections

ROOT = Path(__file__).parent.parent
NREL = ROOT / "cases" / "nrel5mw_blade.yaml"
BLADE = Blade(uniform_sections(1.0, 1.0, 1.0))
#: what a hang in these tests means
UNCHECKED = "the limit was not checked before computing"
TOWER = bladefem.read(ROOT / "cases" / "uniform_tower.yaml")


@pytest.mark.parametrize("call,message", [
    (lambda: modes(BLADE, rpm=float("nan")), "finite"),
    (lambda: modes(BLADE, rpm=1e160), f"{MAX_RPM:g} rpm"),
    (lambda: modes(BLADE, rpm=-1.0), f"{MAX_RPM:g} rpm"),
    (lambda: modes(BLADE, n_modes=300), f"{MAX_MODES} modes"),
    (lambda: modes(BLADE, n_modes=2.5), "whole number"),
    (lambda: modes(BLADE, elements=100000), f"{MAX_ELEMENTS} elements"),
    (lambda: campbell(BLADE, np.linspace(0, 15, 100000)), f"{MAX_SPEEDS} rotor speeds"),
    (lambda: campbell(BLADE, [0.0, float("inf")]), "finite"),
    (lambda: campbell(BLADE, np.linspace(0, 15, 1000), n_modes=100, elements=2000), "GB of mode shapes"),
    (lambda: bladefem.modes(TOWER, n_modes=300), f"{MAX_MODES} modes"),
    (lambda: bladefem.campbell(TOWER, [0.0, float("nan")]), "finite"),
])
def test_api_arguments_are_clear_value_errors(call, message):
    with cpu_limit(2, UNCHECKED), pytest.raises(ValueError, match=re.escape(message)):
        call()


def test_sweep_estimate_counts_every_shape():
    # 1000 speeds x (100 + 4) modes x 2001 nodes x 6 DOFs, vectors and shapes, 8 bytes each
    assert sweep_bytes(1000, 100, 2000) == 8.0 * 1000 * 104 * 2001 * 6 * 2


def cli(*argv: object) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), cpu_limit(5, UNCHECKED):
        code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


@pytest.mark.parametrize("argv,limit", [
    (["modes", NREL, "--n-modes", "10000"], f"{MAX_MODES} modes"),
    (["modes", NREL, "--rpm", "1e160"], f"{MAX_RPM:g} rpm"),
    (["modes", NREL, "--rpm", "nan"], "finite"),
    (["modes", NREL, "--elements", "100000"], f"{MAX_ELEMENTS} elements"),
    (["campbell", NREL, "--rpm", "0:15:100000"], f"COUNT <= {MAX_SPEEDS}"),
    (["campbell", NREL, "--rpm", "0:15:1000", "--n-modes", "100", "--elements", "2000"], "GB of mode shapes"),
    (["export", NREL, "--rpm", "1e160", "-o", "out"], f"{MAX_RPM:g} rpm"),
    (["report", NREL, "--sweep", "0:15:100000", "-o", "out"], f"COUNT <= {MAX_SPEEDS}"),
    (["elastodyn", NREL, "--rpm", "1e160"], f"{MAX_RPM:g} rpm"),
    (["elastodyn", NREL, "--rpm", "10", "--n-modes", "10000"], f"{MAX_MODES} modes"),
    (["elastodyn", NREL, "--rpm", "10", "--nodes", "100000"], "1000 nodes"),
])
def test_cli_options_are_bounded_before_computing(argv, limit):
    code, out, err = cli(*argv)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1, err
    assert limit in err, err


# -- a mode whose residual is not small is not a result -------------------------------------------------------------

def test_check_modes_refuses_large_residuals_and_non_finite_frequencies():
    result = modes(BLADE, n_modes=3, elements=10)
    shape = result.modes[0].shape

    def mode(frequency: float, residual: float) -> Mode:
        return Mode(frequency, "flap", {"flap": 1.0}, residual, shape)

    check_modes([mode(1.0, MAX_RESIDUAL), mode(1e-5, 1.0)], 0.0)       # at the limit; a rigid mode at round-off
    assert modes(read_case(NREL), n_modes=6, elements=1600).modes[0].residual < MAX_RESIDUAL / 100
    for bad in ([mode(0.77, 1.0)], [mode(1.0, 1e-9), mode(float("nan"), 1e-9)], [mode(1.0, float("nan"))]):
        with pytest.raises(SolveError, match="is not a result"):
            check_modes(bad, 12.0)
    with pytest.raises(SolveError):
        ModalResult(0.0, [mode(-3273.0, 1.0)], np.zeros(2), np.zeros((1, 1)))


def test_an_answer_that_is_not_a_result_exits_1_naming_the_input(monkeypatch):
    from bladefem.cli import blade

    def unreliable(*args, **kwargs):
        check_modes([Mode(0.771, "edge", {"edge": 1.0}, 1.0, None)], 0.0)   # type: ignore[arg-type]

    monkeypatch.setattr(blade, "compute_modes", unreliable)
    code, out, err = cli("modes", NREL)
    assert code == 1 and out == "" and len(err.strip().splitlines()) == 1
    assert str(NREL) in err and "is not a result" in err and "0.771" in err


def test_a_stiffness_spike_below_the_slip_limit_is_not_printed_as_a_frequency(tmp_path):
    # a 1e6 spike passes the unit-slip check (6 decades); on 1600 elements round-off swamps the lowest modes
    # (eigen-residual 1.0, first frequency 5e-3 off, measured): not a table of plausible-looking numbers
    blade = read_case(NREL)
    stiffness = blade.sections.flap_stiffness.copy()
    stiffness[25] *= 0.99e6
    from dataclasses import replace
    spiky = blade.with_(sections=replace(blade.sections, flap_stiffness=stiffness))
    with pytest.raises(SolveError, match="is not a result"):
        modes(spiky, n_modes=6, elements=1600)
