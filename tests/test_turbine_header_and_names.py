"""Issue 23, item 6: what the turbine commands print about the generator and the modes they cannot call
oscillations. The header says when the generator is locked (its torque law then unused); an overdamped pair (two
real roots of one coordinate) is named as such, once each, and listed with its decay time instead of a frequency;
a mode whose largest energy share belongs to a family that already names another mode says so."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import main
from bladefem.cli.aeroelastic import mode_lines
from bladefem.models.turbine.linearize import LinearMode
from bladefem.models.turbine.mode_names import name_modes

DECK = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"


@pytest.mark.parametrize("argv, expected, absent", [
    (["--rpm", "12.1"], "# generator: locked at 12.1 rpm (GenDOF off); ServoDyn's torque law is not used",
     "simple variable-speed torque law"),
    ([], "# generator: ServoDyn's simple variable-speed torque law (VSContrl 1)", "locked")])
def test_the_header_says_whether_the_generator_is_locked(tmp_path, capsys, argv, expected, absent):
    """--simulate with --rpm holds the generator at that speed: the header must not announce the torque law."""
    out = tmp_path / "out.csv"
    assert main(["turbine", str(DECK), "--simulate", "0.1", "--no-aero", "--quiet", "--elastodyn-compatible",
                 "--method", "RK45", "-o", str(out), *argv]) == 0
    text = capsys.readouterr().out
    assert expected in text and absent not in text


def test_an_overdamped_pair_is_named_once_each_and_not_as_an_oscillation():
    """Two real roots dominated by the collective flap (rates 2 and 10 1/s) and one oscillating edge mode: the
    roots are '(overdamped, slow root)' and '(overdamped, fast root)', not '1st blade collective flap (2)'."""
    coordinates = ["collective_flap1", "collective_edge1"]
    flap, edge = np.array([1.0, 0.05]), np.array([0.02, 1.0])
    shares = [v ** 2 / (v ** 2).sum() for v in (flap, flap, edge)]
    names = name_modes([flap, flap, edge], shares, coordinates, [False] * 3, True, [False, False, True])
    assert names == ["1st blade collective flap (overdamped, slow root)",
                     "1st blade collective flap (overdamped, fast root)", "1st blade collective edge"]
    single = name_modes([flap, edge], shares[1:], coordinates, [False] * 2, True, [False, True])
    assert single[0] == "1st blade collective flap (decaying)"


def test_a_non_oscillating_mode_has_no_frequency_in_the_table():
    """The table gives a real root's decay time (1 / |lambda|), not |lambda| / 2 pi as a frequency."""
    rate = 4.0                                                    # 1/s
    modes = [LinearMode("1st blade collective flap (overdamped, slow root)", rate / (2 * np.pi), 1.0, 0.0,
                        {"collective_flap1": 1.0}, oscillating=False),
             LinearMode("1st tower fore-aft", 0.25, 0.01, 0.25, {"tower_fa1": 1.0})]
    lines = mode_lines(modes)
    assert "no oscillation" in lines[1] and "decay time 0.25 s" in lines[1]
    assert f"{rate / (2 * np.pi):.4f}" not in lines[1]
    assert "0.2500" in lines[2] and "1.000" in lines[2]


def test_a_mode_dominated_by_a_full_family_says_so():
    """The drivetrain twist names the mode it dominates most; another mode it dominates too (0.66 against the
    collective edge's 0.30) is '1st blade collective edge / drivetrain', no longer plain collective edge."""
    coordinates = ["drivetrain", "collective_edge1"]
    torsion, edge = np.array([1.0, 0.2]), np.array([0.8, 0.55])
    shares = [np.array([0.96, 0.04]), np.array([0.66, 0.34])]
    names = name_modes([torsion, edge], shares, coordinates, [False, False], False)
    assert names == ["1st drivetrain torsion", "1st blade collective edge / drivetrain"]
