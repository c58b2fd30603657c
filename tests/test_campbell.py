"""Campbell sweeps: families followed by MAC through crossings, and the Ritz-basis sweep against full solves."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bladefem.assembly import assemble_blade
from bladefem.builders.case import read_case
from bladefem.modal import campbell_sweep, converged_matrices, solve_modes
from bladefem.sections import Blade, uniform_sections

CASES = Path(__file__).resolve().parent.parent / "cases"


def test_families_stay_continuous_through_a_crossing():
    # untwisted uniform blade with EI_edge = 1.2 EI_flap: at rest edge 1 (3.85) sits above flap 1 (3.52); the
    # centrifugal stiffening lifts flap 1 past it near lambda = 1.5 (a true crossing: the fields are uncoupled), so
    # sort order swaps while each family must keep its kind and its own frequency curve
    blade = Blade(uniform_sections(1.0, 1.0, 1.0, edge_stiffness=1.2))
    matrices = assemble_blade(blade, 30)
    rpm = np.linspace(0.0, 3.0, 13) * 30 / np.pi        # lambda = 0 .. 3
    sweep = campbell_sweep(matrices, rpm, n_modes=4)
    orders = [[mode.kind for mode in result.modes[:2]] for result in sweep.results]
    assert orders[0] == ["flap", "edge"] and orders[-1] == ["edge", "flap"]   # the sort order does swap
    for family in sweep.families:
        kinds = {sweep.results[k].modes[i].kind for k, i in enumerate(family.indices)}
        assert kinds == {family.kind}
        assert family.mac.min() > 0.99
    flap = next(f for f in sweep.families if f.kind == "flap")
    np.testing.assert_allclose(flap.frequencies_hz, [r.first("flap").frequency_hz for r in sweep.results])
    assert np.all(np.diff(flap.frequencies_hz) > 0)


@pytest.mark.parametrize("case,rpm_max", [("nrel5mw_blade.yaml", 15.0), ("uniform_blade.yaml", 120.0)])
def test_ritz_sweep_matches_full_solves(case, rpm_max):
    # the sweep solves most speeds in a Ritz basis of full solves; its frequencies must match a full solve at every
    # speed to 1e-8 (Ritz values err by ~ residual^2 and the residuals are held below 1e-4), even for the uniform
    # blade whose torsion and flap modes change strongly with speed (lambda up to 12.6)
    blade = read_case(CASES / case)
    matrices = converged_matrices(blade, 6)
    sweep = campbell_sweep(matrices, np.linspace(0.0, rpm_max, 16), 6)
    for speed, result in zip(sweep.rpm, sweep.results):
        full = solve_modes(matrices, speed, len(result.modes))
        np.testing.assert_allclose(result.frequencies_hz, full.frequencies_hz, rtol=1e-8)
        assert max(mode.residual for mode in result.modes) < 1e-4


def test_ritz_sweep_matches_full_solves_on_a_timoshenko_curved_blade():
    # the IEA-15MW BeamDyn blade (six-by-six sections, Timoshenko, prebent axis): its window of ten modes ends inside
    # a cluster (edge 7.54 Hz, torsion 7.65 Hz), which the highest speed's extra modes keep in the Ritz basis. The
    # Ritz residuals there (up to 3e-4) are the round-off of K x in the stiff shear and axial fields, not errors
    # of the pairs: the frequencies agree with full solves to 4e-11, held here to 1e-9
    from bladefem.builders.detect import read_model

    deck = Path(__file__).resolve().parent / "data" / "iea15" / "beamdyn" / "IEA-15-240-RWT_BeamDyn.dat"
    matrices = converged_matrices(read_model(deck, hub_radius=3.97), 6, rpm=7.56)
    sweep = campbell_sweep(matrices, np.linspace(0.0, 7.56, 16), 6)
    for speed, result in zip(sweep.rpm, sweep.results):
        full = solve_modes(matrices, speed, len(result.modes))
        np.testing.assert_allclose(result.frequencies_hz, full.frequencies_hz, rtol=1e-9)
