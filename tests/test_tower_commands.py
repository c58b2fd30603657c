"""Towers through every command that makes sense for them, and one ``modes`` API for blades and towers.

The uniform tower case is the clamped beam with a tip mass equal to its own mass (closed form: the first root
b1 = 1.247917 of 1 + cos b cosh b + b (cos b sinh b - sin b cosh b) = 0, f1 = b1^2 / (2 pi) = 0.247852 Hz), so
the rotor-speed chart's classification can be put on each side of every band edge by the choice of the operating
range alone.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import bladefem
from bladefem.cli import main
from bladefem.builders.tower_case import read_tower_case
from bladefem.models.tower_campbell import MARGIN, tower_campbell

ROOT = Path(__file__).resolve().parents[1]
UNIFORM = ROOT / "cases" / "uniform_tower.yaml"
NREL = ROOT / "cases" / "nrel5mw_tower.yaml"
F1 = 1.247917**2 / (2 * math.pi)             # Hz, the closed form above (7 digits of b1)


def run(capsys, *argv) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_read_tower_case_takes_a_str_path():
    tower = read_tower_case(str(UNIFORM))
    assert tower.name == "uniform tower" and tower.height == 1.0


def test_read_tower_case_names_an_unnamed_tower_after_its_file(tmp_path):
    path = tmp_path / "my_tower.yaml"
    path.write_text(UNIFORM.read_text().replace("name: uniform tower\n", ""))
    assert read_tower_case(str(path)).name == "my_tower"


def test_one_modes_api_for_blades_and_towers():
    tower = bladefem.read(UNIFORM)
    result = bladefem.modes(tower, n_modes=3, elements=16)
    assert result.kinds[:2] == ["fore-aft", "side-side"]
    assert result.frequencies_hz[0] == pytest.approx(F1, rel=2e-6)      # 16 elements: converged to ~1e-8
    blade = bladefem.read(ROOT / "cases" / "uniform_blade.yaml")
    assert bladefem.modes(blade, rpm=10.0, n_modes=2).kinds[0] == "flap"
    with pytest.raises(ValueError, match="does not rotate"):
        bladefem.modes(tower, rpm=5.0)
    from bladefem.modal import modes as blade_modes
    with pytest.raises(TypeError, match="bladefem.modes takes blades and towers"):
        blade_modes(tower)                                              # not an AttributeError deep inside


@pytest.mark.parametrize(("operating_rpm", "verdict"), [
    ((6.0, 12.0), "soft-stiff"),          # 1P to 0.20 Hz, 3P from 0.30 Hz: f1 = 0.248 Hz between, clear of 10 %
    ((18.0, 20.0), "soft-soft"),          # 1P from 0.30 Hz: f1 below
    ((2.0, 4.0), "stiff-stiff"),          # 3P to 0.20 Hz: f1 above
    ((10.0, 20.0), "resonant"),           # 1P band 0.167-0.333 Hz contains f1
    ((5.0, 13.8), "resonant"),            # 1P to 0.230 Hz: f1 is 7.8 % above it, inside the 10 % margin
])
def test_soft_stiff_classification(operating_rpm, verdict):
    chart = tower_campbell(read_tower_case(UNIFORM), np.linspace(0, 20, 5), n_modes=3, elements=16,
                           operating_rpm=operating_rpm)
    one, passing = chart.bands
    assert (one.low_hz, one.high_hz) == (operating_rpm[0] / 60, operating_rpm[1] / 60)
    assert (passing.low_hz, passing.high_hz) == (3 * operating_rpm[0] / 60, 3 * operating_rpm[1] / 60)
    assert chart.first_bending.frequency_hz == pytest.approx(F1, rel=2e-6)
    assert chart.verdict == verdict and chart.statement().startswith(verdict)
    assert chart.margin == MARGIN


def test_tower_campbell_command_table_json_and_chart(capsys, tmp_path):
    plot = tmp_path / "tower.png"
    code, out, _ = run(capsys, "campbell", UNIFORM, "--rpm", "0:20:5", "--operating-rpm", "6:12", "--n-modes", "3",
                       "--plot", plot)
    assert code == 0 and "# design: soft-stiff" in out and "1P band: 0.1-0.2 Hz" in out
    assert plot.stat().st_size > 10_000
    code, out, _ = run(capsys, "campbell", UNIFORM, "--rpm", "0:20:5", "--operating-rpm", "10:20", "--json")
    data = json.loads(out)
    assert code == 0 and data["structure"] == "tower" and data["verdict"] == "resonant"
    assert data["modes"][0]["bands_hit"] == ["1P"] and data["first_bending_hz"] == pytest.approx(F1, rel=2e-6)


def test_the_chart_margin_is_an_option(capsys):
    """The 5MW tower's first frequency 0.3163 Hz is 8.3 % below the 3P band's 0.345 Hz: resonant within the default
    10 % margin, soft-stiff with 5 % (the margin the shipped design check asks); a blade refuses the option."""
    tower = ROOT / "cases" / "nrel5mw_tower.yaml"
    verdicts = {}
    for margin in (None, "10", "5", "8.4", "8.2"):
        extra = [] if margin is None else ["--margin-percent", margin]
        code, out, _ = run(capsys, "campbell", tower, "--rpm", "0:15:4", "--operating-rpm", "6.9:12.1", "--json",
                           *extra)
        verdicts[margin] = json.loads(out)["verdict"]
    assert verdicts == {None: "resonant", "10": "resonant", "5": "soft-stiff", "8.4": "resonant",
                        "8.2": "soft-stiff"}
    code, _, err = run(capsys, "campbell", ROOT / "cases" / "uniform_blade.yaml", "--rpm", "0:10:2",
                       "--margin-percent", "5")
    assert code == 2 and "field '--margin-percent'" in err


def test_tower_modes_command_refuses_a_rotor_speed_and_the_galerkin_model(capsys):
    code, _, err = run(capsys, "modes", UNIFORM, "--rpm", "5")
    assert code == 2 and "field '--rpm'" in err and "does not rotate" in err
    code, _, err = run(capsys, "modes", UNIFORM, "--method", "galerkin")
    assert code == 2 and "field '--method'" in err


@pytest.mark.parametrize("argv", [["export", NREL, "-o", "{out}", "--png", "--vtk", "--n-modes", "2"],
                                  ["report", NREL, "-o", "{out}", "--n-modes", "2", "--operating-rpm", "6.9:12.1"]])
def test_tower_export_and_report(argv, capsys, tmp_path):
    pytest.importorskip("pyvista")
    code, out, err = run(capsys, *[str(a).format(out=tmp_path) for a in argv])
    assert code == 0, err
    listed = [Path(line) for line in out.splitlines()]
    assert listed and all(path.is_file() for path in listed)
    if argv[0] == "export":
        assert {"mode01.png", "mode02.png", "modes.png", "modes.json", "modes.pvd"} <= {p.name for p in listed}
        sidecar = json.loads((tmp_path / "modes.json").read_text())
        assert sidecar["structure"] == "tower" and sidecar["speeds"][0]["modes"][0]["kind"] == "fore-aft"
    else:
        text = (tmp_path / "report.md").read_text()
        assert "NREL 5MW land tower: modal report" in text and "fore-aft share" in text
        assert "Design: resonant" in text                  # the NREL 5MW tower sits within 10 % of 3P at 6.9 rpm
        assert "tower fore-aft 1" in text                  # ElastoDyn tower coefficients
        assert "modes.png" in text and (tmp_path / "modes.png").is_file()


def test_elastodyn_takes_a_yaml_tower_case(capsys):
    code, out, _ = run(capsys, "elastodyn", UNIFORM)
    assert code == 0 and "TwFAM1Sh(2)" in out and "tower (non-rotating)" in out


def test_a_tower_export_refuses_a_rotor_speed_sweep(capsys, tmp_path):
    code, _, err = run(capsys, "export", UNIFORM, "-o", tmp_path, "--rpm", "0:10:3")
    assert code == 2 and "field '--rpm'" in err
