"""The IEA-15MW monopile deck simulated in wind (rigid foundation, quasi-steady aerodynamics, the rotor held at
7.56 rpm in place of its DISCON controller), from the deck's undeflected start at 10 m/s.

The start-up transient throws the 117 m blades downwind at up to about 12 m/s within 0.1 s, and the adaptive
integrator's step collapses there: the right-hand side is not smooth (the structure alone runs, and the fixed step
ElastoDyn uses runs through it). The run stops with exit 1, the rows so far and one line that names the way
forward, instead of running on or returning nonsense; with ``--method RK4 --step 0.005`` it settles to physical
values. (The test copy of the deck holds all 50 airfoil polars, tests/data/iea15/README.md; a run of 20-30 s
gives 14.8 m tip deflection, 2565 kN thrust and Cp 0.467.)
"""

from __future__ import annotations

import numpy as np
from deck_copies import deck_copy

from bladefem.cli import main

DECK = "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile.fst"
WAYS = ["--wind-speed", "10", "--rpm", "7.56", "--foundation", "rigid", "--quasi-steady", "--quiet"]


def test_the_adaptive_start_up_stops_with_the_way_forward_and_rk4_runs(tmp_path, capsys):
    fst = str(deck_copy("iea15", tmp_path) / DECK)
    rows = tmp_path / "run.csv"
    assert main(["turbine", fst, "--simulate", "2", *WAYS, "--output", str(rows)]) == 1
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert "right-hand sides" in err and "--method RK4 --step 0.005" in err
    assert rows.is_file()                                  # the rows up to the stop, written whole
    fixed = tmp_path / "rk4.csv"
    assert main(["turbine", fst, "--simulate", "5", *WAYS, "--method", "RK4", "--step", "0.005",
                 "--output", str(fixed)]) == 0
    table = np.genfromtxt(fixed, delimiter=",", names=True)
    assert len(table) == 101
    assert 5.0 < table["OoPDefl1_m"][-1] < 30.0            # tens of metres on a 117 m blade: bent, not broken
    assert 0.0 < table["RtAeroCp_"][-1] < 16 / 27 and table["RotThrust_kN"][-1] > 1000.0
