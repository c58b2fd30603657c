"""Batch plans found by the larger fuzz: an integer-valued float seed beyond 64 bits, grid values beyond physical
bounds and a plan without its model are one line naming the plan's line and field, exit 2, before any case runs."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from bladefem.batch.plan import GRID_BOUNDS
from bladefem.cli import main

ROOT = Path(__file__).resolve().parents[1]
BASE = "model: nrel5mw_blade.yaml\nanalysis: {type: modes, rpm: 12.1, n_modes: 2}\n"


@pytest.mark.parametrize("body, line, field", [
    ("samples:\n  count: 2\n  seed: 1e31\n  properties:\n    mass: {distribution: uniform, half_width_percent: 5}\n",
     5, "samples.seed"),
    ("grid:\n  mass_scale: [1e-308, 1]\n", 4, "grid.mass_scale.0"),
    ("grid:\n  rpm: [12.1, 1e9]\n", 4, "grid.rpm.1"),
    ("grid:\n  precone_deg: [90]\n", 4, "grid.precone_deg.0"),
])
def test_out_of_bounds_plans_are_one_line(tmp_path, capsys, body, line, field):
    shutil.copy(ROOT / "cases" / "nrel5mw_blade.yaml", tmp_path)
    plan = tmp_path / "plan.yaml"
    plan.write_text(BASE + body)
    code = main(["batch", str(plan), "-o", str(tmp_path / "out"), "--workers", "1"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and "\n" not in err and f"{plan}:{line}: field '{field}'" in err, err
    assert not (tmp_path / "out").exists()


def test_a_plan_without_its_model_names_the_plan(tmp_path, capsys):
    plan = tmp_path / "plan.yaml"
    plan.write_text("analysis: {type: modes, rpm: 12.1}\ngrid:\n  rpm: [0, 12.1]\n")
    assert main(["batch", str(plan), "-o", str(tmp_path / "out")]) == 2
    assert f"{plan}:1: field 'model'" in capsys.readouterr().err


def test_every_grid_name_has_its_bounds():
    assert set(GRID_BOUNDS) >= {"mass_scale", "rpm", "wind_speed_m_s", "pitch_deg", "precone_deg", "tip_mass_kg"}
    assert all(low < high for low, high in GRID_BOUNDS.values())


def test_a_turbine_plan_takes_the_ways_forward_of_a_modern_deck(tmp_path):
    """The IEA-15MW monopile deck (HydroDyn, SubDyn, unsteady aerodynamics, a DISCON controller) in a batch plan:
    refused case by case without the ways forward, linearized parked with foundation: rigid, quasi_steady: true
    and a fixed rotor speed (the command line's --foundation rigid --quasi-steady --rpm)."""
    import pyarrow.dataset as ds
    from deck_copies import deck_copy

    deck = deck_copy("iea15", tmp_path) / "IEA-15-240-RWT-Monopile" / "IEA-15-240-RWT-Monopile.fst"
    plan = tmp_path / "plan.yaml"
    plan.write_text(f"model: {deck}\nanalysis: {{type: turbine_linearize, rpm: 0, wind_speed_m_s: 0, "
                    "foundation: rigid, quasi_steady: true}\ngrid:\n  pitch_deg: [0, 5]\n")
    assert main(["batch", str(plan), "-o", str(tmp_path / "out"), "--workers", "1", "--quiet"]) == 0
    table = ds.dataset(tmp_path / "out", format="parquet").to_table().to_pydict()
    assert set(table["status"]) == {"ok"} and len(set(table["case_index"])) == 2 and len(table["status"]) > 20
    bare = tmp_path / "bare.yaml"
    bare.write_text(f"model: {deck}\nanalysis: {{type: turbine_linearize, rpm: 0, wind_speed_m_s: 0}}\n"
                    "grid:\n  pitch_deg: [0]\n")
    assert main(["batch", str(bare), "-o", str(tmp_path / "bare_out"), "--workers", "1", "--quiet"]) == 1
