"""The YAML tower case reader, the shipped tower cases and the tower path of ``bladefem modes``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from bladefem.cli import main
from bladefem.cli.tower import is_tower_input
from bladefem.errors import InputError
from bladefem.formats.elastodyn_main import read_elastodyn_main
from bladefem.builders.elastodyn_tower import read_elastodyn_tower
from bladefem.builders.tower_case import read_tower_case
from bladefem.builders.tower_elastodyn import elastodyn_top_mass
from bladefem.models.tower import tower_modes

CASES = Path(__file__).parent.parent / "cases"


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "tower.yaml"
    path.write_text(text, encoding="utf-8")
    return path


MINIMAL = """kind: tower
height_m: 10.0
sections:
  columns: [height_fraction, mass_kg_per_m, fore_aft_stiffness_N_m2, side_side_stiffness_N_m2]
  rows:
    - [0.0, 100.0, 1.0e+8, 1.0e+8]
    - [1.0, 100.0, 1.0e+8, 1.0e+8]
"""


def test_uniform_tower_case_matches_its_closed_forms():
    result = tower_modes(read_tower_case(CASES / "uniform_tower.yaml"), 6)
    # bending with tip mass mu = 1 (the b1, b2) and the rod with a tip mass: b tan b = m L / M = 1
    beta = [np.sqrt(2 * np.pi * result.first("fore-aft", n).frequency_hz) for n in (1, 2)]
    assert beta == pytest.approx([1.247917, 4.031139], abs=1e-6)       # the 7 digits given in the case comment
    rod = brentq(lambda b: b * np.tan(b) - 1.0, 0.1, 1.5)
    assert 2 * np.pi * result.first("axial").frequency_hz == pytest.approx(rod * 10.0, rel=1e-8)


def test_nrel5mw_tower_case_is_the_elastodyn_data():
    tower = read_tower_case(CASES / "nrel5mw_tower.yaml")
    shipped = read_elastodyn_tower(CASES / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat")
    assert tower.sections.span == pytest.approx(shipped.fraction * 87.6)
    assert tower.sections.mass == pytest.approx(shipped.mass, rel=1e-6)
    assert tower.sections.flap_stiffness == pytest.approx(shipped.fa_stiffness, rel=1e-6)
    main = read_elastodyn_main(CASES / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat")
    top, _ = elastodyn_top_mass(main)
    # the case stores the derived body rounded to 6 significant digits
    assert tower.top_mass.mass == pytest.approx(top.mass, rel=1e-6)
    assert tower.top_mass.offset == pytest.approx(top.offset, abs=1e-5)
    assert tower.top_mass.inertia == pytest.approx(top.inertia, abs=1e-5 * np.abs(top.inertia).max())


def test_supports_are_read(tmp_path):
    text = MINIMAL + """supports:
  wires: [{count: 3, stiffness_N_per_m: 1.0e+5, angle_deg: 30, height_m: 8.0}]
  soil:
    columns: [height_m, lateral_N_per_m2]
    rows: [[0.0, 1.0e+6], [2.0, 2.0e+6]]
  platform:
    mass_kg: 1.0e+6
    cm_m: [0.0, 0.0, -20.0]
    inertia_kg_m2: [1.0e+9, 1.0e+9, 2.0e+9]
    hydrostatic_SI: [[0,0,0,0,0,0],[0,0,0,0,0,0],[0,0,3.0e+6,0,0,0],[0,0,0,5.0e+8,0,0],[0,0,0,0,5.0e+8,0],
                     [0,0,0,0,0,0]]
    base_height_m: 10.0
"""
    tower = read_tower_case(write(tmp_path, text))
    supports = tower.supports
    assert supports.wires[0].angle == pytest.approx(np.radians(30.0))
    assert supports.soil.embedded_length == 2.0
    assert supports.platform.hydrostatic[2, 2] == 3.0e6
    assert supports.platform.base_height == 10.0


@pytest.mark.parametrize("extra, line, field", [
    ("colour: red\n", 8, "colour"),
    ("gravity_m_s2: -1\n", 8, "gravity_m_s2"),
    ("supports:\n  foundation: {stiffness_SI: [[1, 2], [3, 4]]}\n", 9, "supports.foundation.stiffness_SI"),
    ("top_mass: {mass_kg: 5, cm_offset_m: [1, 2]}\n", 8, "top_mass.cm_offset_m"),
])
def test_errors_name_file_line_and_field(tmp_path, extra, line, field):
    path = write(tmp_path, MINIMAL + extra)
    with pytest.raises(InputError) as caught:
        read_tower_case(path)
    assert caught.value.file == str(path)
    assert caught.value.line == line
    assert caught.value.field == field


def test_unsigned_exponent_is_a_number(tmp_path):
    """YAML 1.2 reads 1e8 (no dot, no exponent sign) as a float, as windIO's tools do."""
    path = write(tmp_path, MINIMAL.replace("1.0e+8, 1.0e+8]\n    - [1.0", "1e8, 1.0e+8]\n    - [1.0"))
    assert read_tower_case(path).sections.flap_stiffness[0] == 1e8


def test_station_error_names_the_row(tmp_path):
    path = write(tmp_path, MINIMAL.replace("[1.0, 100.0", "[1.0, -100.0"))
    with pytest.raises(InputError, match="positive") as caught:
        read_tower_case(path)
    assert caught.value.line == 7 and caught.value.field == "mass"


def test_foundation_and_platform_together_are_refused(tmp_path):
    zeros = "[" + ",".join(["[0,0,0,0,0,0]"] * 6) + "]"
    text = MINIMAL + f"""supports:
  foundation: {{stiffness_SI: {zeros}}}
  platform: {{mass_kg: 1.0, cm_m: [0, 0, 0], inertia_kg_m2: [1, 1, 1]}}
"""
    with pytest.raises(InputError, match="not both") as caught:
        read_tower_case(write(tmp_path, text))
    assert caught.value.line == 8


def test_cli_json_for_a_tower(capsys):
    assert main(["modes", str(CASES / "uniform_tower.yaml"), "--n-modes", "3", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["structure"] == "tower"
    assert [mode["kind"] for mode in data["modes"]] == ["fore-aft", "side-side", "axial"]
    assert data["frequencies_hz"][0] == pytest.approx(1.247917**2 / (2 * np.pi), rel=2e-6)


def test_cli_elastodyn_tower_file_with_coefficients(capsys):
    folder = CASES / "nrel5mw"
    assert main(["modes", str(folder / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"),
                 "--elastodyn-main", str(folder / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"),
                 "--point-top-mass", "--elastodyn-coefficients", "--json", "--n-modes", "2"]) == 0
    data = json.loads(capsys.readouterr().out)
    fits = data["elastodyn_coefficients"]
    assert sorted(fits) == ["fa1", "fa2", "ss1", "ss2"]
    for fit in fits.values():
        assert sum(fit["coefficients"]) == pytest.approx(1.0, abs=1e-12)    # ElastoDyn's tip normalisation


def test_cli_needs_a_height_for_a_bare_elastodyn_tower_file(capsys):
    path = CASES / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"
    assert main(["modes", str(path)]) == 2
    assert "--tower-height" in capsys.readouterr().err


def test_tower_inputs_are_recognised():
    assert is_tower_input(CASES / "uniform_tower.yaml")
    assert is_tower_input(CASES / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat")
    assert not is_tower_input(CASES / "uniform_blade.yaml")
    assert not is_tower_input(CASES / "nrel5mw" / "NRELOffshrBsline5MW_Blade.dat")
