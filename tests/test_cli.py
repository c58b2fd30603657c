"""The command line: JSON outputs, and bad input ending in one line naming file, line and field, exit code 2."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import main

ROOT = Path(__file__).resolve().parent.parent
CASE = ROOT / "cases" / "uniform_blade.yaml"
NREL = ROOT / "cases" / "nrel5mw_blade.yaml"
ELASTODYN_BLADE = ROOT / "tests" / "data" / "NRELOffshrBsline5MW_Blade.dat"


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_modes_json(capsys):
    code, out, _ = run(capsys, "modes", NREL, "--rpm", "12.1", "--n-modes", "4", "--json")
    data = json.loads(out)
    assert code == 0 and data["rotor_speed_rpm"] == 12.1
    assert [m["kind"] for m in data["modes"]] == ["flap", "edge", "flap", "edge"]
    assert data["frequencies_hz"] == [m["frequency_hz"] for m in data["modes"]]
    shape = data["modes"][0]["shape"]
    assert len(shape["x_m"]) == 49 and shape["flap"][0] == 0.0 and max(map(abs, shape["flap"])) == pytest.approx(1)
    assert any("torsion is rigid" in note for note in data["notes"])


def test_campbell_json_and_plot(capsys, tmp_path):
    plot = tmp_path / "campbell.png"
    code, out, _ = run(capsys, "campbell", CASE, "--rpm", "0:60:4", "--n-modes", "3", "--json", "--plot", plot)
    data = json.loads(out)
    assert code == 0 and data["rpm"] == [0.0, 20.0, 40.0, 60.0]
    assert [f["kind"] for f in data["families"]] == ["flap", "torsion", "edge"]
    assert all(len(f["frequencies_hz"]) == 4 for f in data["families"])
    assert plot.stat().st_size > 10_000 and not list(tmp_path.glob(".*tmp"))


def test_elastodyn_blade_with_geometry_options(capsys):
    # AdjBlMs applied; the same blade from the case file (mass factor 1) scaled by the factor gives the same answer
    code, out, _ = run(capsys, "modes", ELASTODYN_BLADE, "--tip-radius", "63", "--hub-radius", "1.5",
                       "--precone-deg", "-2.5", "--n-modes", "2", "--json")
    from bladefem.builders.case import read_case
    from bladefem.modal import modes
    blade = read_case(NREL)
    reference = modes(blade.with_(sections=blade.sections.scaled(mass=1.04536)), 0.0, 2)
    np.testing.assert_allclose(json.loads(out)["frequencies_hz"], reference.frequencies_hz, rtol=1e-6)
    assert any("AdjBlMs" in note for note in json.loads(out)["notes"])


def one_line_error(capsys, *argv: str) -> str:
    code = main([str(a) for a in argv])
    err = capsys.readouterr().err.strip()
    assert code == 2, err
    assert len(err.splitlines()) == 1, err
    return err


def edited_case(tmp_path: Path, old: str, new: str, source: Path = CASE) -> Path:
    text = source.read_text()
    assert old in text
    path = tmp_path / "case.yaml"
    path.write_text(text.replace(old, new, 1))
    return path


ROW = "    - [1.0, 1.0, 1.0, 4.0, 0.01, 1.0e-4, 1.0e-3]"


@pytest.mark.parametrize("old,new,field", [
    (ROW, "    - [1.0, 1.0, 1.0, 4.0, 0.01, 1.0e-4]", "rows"),                       # wrong column count
    (ROW, "    - [0.0, 1.0, 1.0, 4.0, 0.01, 1.0e-4, 1.0e-3]", "span"),               # stations not increasing
    (ROW, "    - [1.0, -1.0, 1.0, 4.0, 0.01, 1.0e-4, 1.0e-3]", "mass"),              # non-positive mass
    (ROW, "    - [1.0, 1.0, 0.0, 4.0, 0.01, 1.0e-4, 1.0e-3]", "flap_stiffness"),     # non-positive stiffness
    (ROW, "    - [1.0, 1.0, .nan, 4.0, 0.01, 1.0e-4, 1.0e-3]", "flap_stiffness_N_m2"),  # NaN
    (ROW, "    - [1.0, 1.0, abc, 4.0, 0.01, 1.0e-4, 1.0e-3]", "flap_stiffness_N_m2"),  # not a number
    ("root: cantilever", "root: wobbly", "root"),                                  # unknown value
])
def test_bad_case_file(capsys, tmp_path, old, new, field):
    path = edited_case(tmp_path, old, new)
    line = max(i for i, text in enumerate(path.read_text().splitlines(), 1) if text == new)   # the edited line
    err = one_line_error(capsys, "modes", path)
    assert f"{path}:{line}:" in err and f"'{field}'" in err


def test_bad_elastodyn_blade_file(capsys, tmp_path):
    lines = ELASTODYN_BLADE.read_text().splitlines()
    row = next(i for i, text in enumerate(lines) if text.startswith("3.5770000E-02"))
    lines[row] = lines[row].replace("7.4055000E+02", "-7.4055000E+02")
    path = tmp_path / "blade.dat"
    path.write_text("\n".join(lines) + "\n")
    err = one_line_error(capsys, "modes", path, "--tip-radius", "63")
    assert f"{path}:{row + 1}:" in err and "mass" in err.lower()
    lines[row] = " ".join(lines[row].split()[:4])                       # a row with too few columns
    path.write_text("\n".join(lines) + "\n")
    err = one_line_error(capsys, "modes", path, "--tip-radius", "63")
    assert f"{path}:{row + 1}:" in err


@pytest.mark.parametrize("argv,needle", [
    (["modes", "missing.yaml"], "missing.yaml: file not found"),
    (["modes", CASE, "--rpm", "fast"], "--rpm"),
    (["modes", CASE, "--rpm", "nan"], "--rpm"),
    (["modes", CASE, "--rpm", "-5"], "--rpm"),
    (["modes", CASE, "--n-modes", "0"], "--n-modes"),
    (["modes", CASE, "--root", "floppy"], "--root"),
    (["modes", CASE, "--method", "magic"], "--method"),
    (["modes", CASE, "--method", "galerkin", "--terms", "5,x,3"], "--terms"),
    (["campbell", CASE, "--rpm", "10:0:3"], "--rpm"),
    (["campbell", CASE, "--rpm", "0:15"], "--rpm"),
    (["modes", ELASTODYN_BLADE], "TipRad"),
])
def test_bad_options(capsys, argv, needle):
    assert needle in one_line_error(capsys, *argv)


def test_unwritable_output_is_one_line_and_leaves_nothing(capsys, tmp_path):
    # a plot into a path that cannot be created: one line, exit 2, and no partial file anywhere
    blocker = tmp_path / "file"
    blocker.write_text("")
    err = one_line_error(capsys, "campbell", CASE, "--rpm", "0:10:2", "--plot", blocker / "campbell.png")
    assert str(blocker) in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def test_warnings_are_one_line_on_stderr(capsys):
    """A model warning (a tower loaded to half its buckling load) reads 'bladefem: warning: ...', without Python's
    file name and source line."""
    deck = Path(__file__).resolve().parent / "data" / "bmodes_tower_platform.bmi"
    assert main(["modes", str(deck)]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert err and all(line.startswith("bladefem: warning: ") for line in err)
    assert "critical buckling load" in err[0] and ".py:" not in "".join(err)
