"""``--coriolis`` on the command line: damping ratios with the quadratic solve, nothing changed without the
option, refused where it does not apply."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

from bladefem.assembly import assemble_blade
from bladefem.modal.quadratic import solve_quadratic_modes
from bladefem.sections import Blade

ROOT = Path(__file__).resolve().parents[1]
NREL = ROOT / "cases" / "nrel5mw_blade.yaml"


def run(capsys, *argv: str) -> tuple[int, str, str]:
    from bladefem.cli import main
    code = main([str(a) for a in argv])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_modes_with_coriolis_report_damping(capsys):
    code, out, _ = run(capsys, "modes", NREL, "--rpm", "12.1", "--n-modes", "4", "--elements", "24", "--coriolis",
                       "--json")
    data = json.loads(out)
    assert code == 0
    expected = solve_quadratic_modes(assemble_blade(blade_of(NREL), 24), 12.1, 4)
    assert [m["frequency_hz"] for m in data["modes"]] == list(expected.frequencies_hz)
    assert all(m["damping_ratio"] == 0.0 and m["damped_frequency_hz"] == m["frequency_hz"] for m in data["modes"])
    code, out, _ = run(capsys, "modes", NREL, "--rpm", "12.1", "--n-modes", "4", "--elements", "24", "--coriolis")
    assert code == 0 and "damping" in out.splitlines()[4] and "quadratic eigenproblem" in out


def test_without_the_option_nothing_changes(capsys):
    """No --coriolis: the same keys and columns as before (the outputs were compared byte for byte with the
    previous version on the 5MW and uniform blades, table and JSON, modes and campbell)."""
    code, out, _ = run(capsys, "modes", NREL, "--rpm", "12.1", "--n-modes", "2", "--elements", "24", "--json")
    assert code == 0
    assert [set(m) for m in json.loads(out)["modes"]] == [{"frequency_hz", "kind", "energy_fractions", "residual",
                                                          "shape"}] * 2
    code, out, _ = run(capsys, "modes", NREL, "--rpm", "12.1", "--n-modes", "2", "--elements", "24")
    assert out.splitlines()[3] == "# method fe, rotor speed 12.1 rpm, 192 DOFs"
    assert out.splitlines()[4] == "mode  frequency_hz  kind      flap  edge  tors axial   residual"
    code, out, _ = run(capsys, "campbell", NREL, "--rpm", "0:12:3", "--n-modes", "2", "--elements", "24", "--json")
    assert [set(f) for f in json.loads(out)["families"]] == [{"kind", "frequencies_hz", "min_mac"}] * 2


def test_real_mac_unchanged_by_the_complex_form():
    from bladefem.modal.campbell import mac_matrix
    rng = np.random.default_rng(0)
    A, B = rng.standard_normal((30, 4)), rng.standard_normal((30, 5))
    M = sp.diags(rng.uniform(1, 2, 30))
    old = (A.T @ (M @ B)) ** 2 / (np.einsum("ij,ij->j", A, M @ A)[:, None] * np.einsum("ij,ij->j", B, M @ B))
    np.testing.assert_array_equal(mac_matrix(A, B, M), old)


def test_campbell_with_coriolis_json(capsys):
    code, out, _ = run(capsys, "campbell", NREL, "--rpm", "0:12:3", "--n-modes", "3", "--elements", "24",
                       "--coriolis", "--json")
    data = json.loads(out)
    assert code == 0 and [f["kind"] for f in data["families"]] == ["flap", "edge", "flap"]
    assert all(f["damping_ratios"] == [0.0, 0.0, 0.0] for f in data["families"])


@pytest.mark.parametrize("argv", [["modes", NREL, "--coriolis", "--method", "galerkin"],
                                  ["modes", ROOT / "cases" / "nrel5mw_tower.yaml", "--coriolis"]],
                         ids=["galerkin", "tower"])
def test_coriolis_refused_where_it_does_not_apply(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and "--coriolis" in err


def blade_of(path: Path) -> Blade:
    from bladefem.builders.detect import read_model
    return read_model(str(path))
