"""The batch ``standstill`` analysis: each case's rows are the sweep of ``bladefem standstill`` on its blade (same
numbers), the AeroDyn file and its airfoils travel in the case's bundle, and bad entries name the plan's line."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

pytest.importorskip("dask.distributed")
pytest.importorskip("pyarrow")

from bladefem.batch import read_plan, run_case  # noqa: E402
from bladefem.cli import main  # noqa: E402
from bladefem.errors import InputError  # noqa: E402

CASE = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw"
MAIN = CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
AERODYN = CASE / "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"


def plan_text(analysis: str, grid: str = "{pitch_deg: [85, 90]}") -> str:
    return f"model: {MAIN}\nanalysis: {{type: standstill, aerodyn: {AERODYN}, {analysis}}}\ngrid: {grid}\n"


def test_standstill_cases_equal_the_command(tmp_path, capsys, monkeypatch):
    path = tmp_path / "plan.yaml"
    path.write_text(plan_text("wind_speed_m_s: 50, yaw_deg: [20, 40, 3], n_modes: 3, elements: 24, "
                              "structural_damping_percent: [0.5, 0.5]"))
    plan = read_plan(path)
    assert len(plan.cases) == 2
    names = {Path(p).name for p in plan.bundles[plan.cases[1].bundle].paths}
    assert AERODYN.name in names and "DU40_A17.dat" in names                 # the airfoils travel too
    monkeypatch.setenv("BLADEFEM_BATCH_INPUTS", str(tmp_path / "worker"))
    rows = run_case(plan.cases[1], plan.bundles[plan.cases[1].bundle])
    assert all(row["status"] == "ok" for row in rows) and len(rows) == 3 * 3
    assert main(["standstill", str(MAIN), "--aero", str(AERODYN), "--wind-speed", "50", "--pitch-deg", "90",
                 "--yaw-deg", "20,30,40", "--elements", "24", "--n-modes", "3",
                 "--structural-damping-percent", "0.5,0.5", "--json"]) == 0
    command = json.loads(capsys.readouterr().out)
    expected = [(p["yaw_deg"], m["name"], m["total_damping_ratio"]) for p in command["points"] for m in p["modes"]]
    assert [(r["yaw_deg"], r["name"], r["total_damping_ratio"]) for r in rows] == expected
    assert rows[0]["pitch_deg"] == 90 and not math.isnan(rows[0]["aerodynamic_damping_ratio"])


@pytest.mark.parametrize("analysis, field", [
    ("yaw_deg: [0, 10, 3]", "analysis.type"),
    ("wind_speed_m_s: 50, yaw_deg: [10, 0, 3]", "analysis.yaw_deg"),
    ("wind_speed_m_s: 50, rpm: 5", "analysis.rpm"),
], ids=["no-wind", "decreasing-yaw", "rpm"])
def test_bad_standstill_entries_name_the_field(tmp_path, analysis, field):
    path = tmp_path / "plan.yaml"
    path.write_text(plan_text(analysis))
    with pytest.raises(InputError) as error:
        read_plan(path)
    assert error.value.field == field and error.value.line == 2
