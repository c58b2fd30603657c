"""Turbine analyses in batch plans: an OpenFAST deck simulated per case (wind speed, rotor speed, pitch from a
grid), each output channel summarised over a window; the same numbers as ``bladefem turbine --simulate``."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pyarrow")
pytest.importorskip("numba")

from bladefem.batch import read_plan, run_case, summarize  # noqa: E402
from bladefem.cli import main  # noqa: E402

DECK = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"


def write_plan(folder: Path, text: str) -> Path:
    path = folder / "plan.yaml"
    path.write_text(text)
    return path


def test_a_simulated_case_equals_the_command_line_run(tmp_path, capsys):
    plan = read_plan(write_plan(tmp_path, f"""model: {DECK}
analysis: {{type: turbine_simulate, seconds: 4, dt: 0.05, statistics_from_s: 2, rpm: 12.1, pitch_deg: 0}}
grid: {{wind_speed_m_s: [8.0, 11.4]}}
"""))
    rows = run_case(plan.cases[1])
    assert all(row["status"] == "ok" for row in rows) and rows[0]["wind_speed_m_s"] == 11.4
    by_channel = {row["channel"]: row for row in rows}
    output = tmp_path / "run.csv"
    assert main(["turbine", str(DECK), "--simulate", "4", "--dt", "0.05", "--rpm", "12.1", "--pitch-deg", "0",
                 "--wind-speed", "11.4", "--output", str(output), "--quiet"]) == 0
    capsys.readouterr()
    table = list(csv.reader(io.StringIO(output.read_text())))
    header, data = table[0], np.array(table[1:], dtype=float)
    window = data[:, 0] >= 2 - 1e-9
    for column, label in enumerate(header[1:], 1):
        channel, unit = label.rsplit("_", 1)
        assert by_channel[channel]["unit"].replace(" ", "") == unit
        # the CSV holds 9 significant digits
        assert by_channel[channel]["mean"] == pytest.approx(np.mean(data[window, column]), rel=1e-8, abs=1e-9)
        assert by_channel[channel]["max"] == pytest.approx(np.max(data[window, column]), rel=1e-8, abs=1e-9)
    assert set(by_channel) == {label.rsplit("_", 1)[0] for label in header[1:]}
    thrust = [run_case(plan.cases[0]), rows]
    means = [{row["channel"]: row["mean"] for row in case}["RtAeroFxh"] for case in thrust]
    assert means[0] < means[1]                       # more wind below rated, more thrust


def test_a_linearized_case_equals_the_command_line_linearization(tmp_path, capsys):
    plan = read_plan(write_plan(tmp_path, f"""model: {DECK}
analysis: {{type: turbine_linearize, rpm: 12.1, pitch_deg: 0}}
grid: {{wind_speed_m_s: [11.4]}}
"""))
    rows = run_case(plan.cases[0])
    assert all(row["status"] == "ok" for row in rows), rows[0].get("error")
    assert main(["turbine", str(DECK), "--linearize", "--wind-speed", "11.4", "--rpm", "12.1", "--pitch-deg", "0",
                 "--json"]) == 0
    expected = json.loads(capsys.readouterr().out)
    assert [row["name"] for row in rows] == [mode["name"] for mode in expected["modes"]]
    for row, mode in zip(rows, expected["modes"]):
        assert row["frequency_hz"] == pytest.approx(mode["frequency_hz"], rel=1e-12)
        assert row["damping_ratio"] == pytest.approx(mode["damping_ratio"], rel=1e-9, abs=1e-12)
        assert row["rpm"] == pytest.approx(12.1) and row["wind_speed_m_s"] == 11.4
    flap = next(row for row in rows if row["name"] == "1st blade collective flap")
    assert flap["damping_ratio"] > 0.3                    # aerodynamic damping of the flap family


def test_summary_of_turbine_cases_is_per_channel():
    import pyarrow as pa

    rows = [{"case_index": i, "case_hash": str(i), "status": "ok", "error": None, "wind_speed_m_s": u,
             "channel": channel, "unit": unit, "mean": value, "std": 0.0, "min": value, "max": value}
            for i, u in enumerate((8.0, 10.0, 12.0))
            for channel, unit, value in (("RotPwr", "kW", 100 * u), ("TTDspFA", "m", 0.5 - 0.01 * u))]
    summary = summarize(pa.Table.from_pylist(rows))
    assert summary.inputs == ("wind_speed_m_s",)
    power = {q.label: q for q in summary.quantities}["RotPwr mean"]
    assert power.unit == "kW" and power.statistics["mean"] == pytest.approx(1000.0)
    assert power.correlation["wind_speed_m_s"] == pytest.approx(1.0)
    assert {q.label: q for q in summary.quantities}["TTDspFA mean"].correlation["wind_speed_m_s"] == pytest.approx(-1)


@pytest.mark.parametrize("analysis, grid, field", [
    ("{type: turbine_simulate, rpm: 12.1}", "{wind_speed_m_s: [8.0]}", "analysis.type"),
    ("{type: turbine_simulate, seconds: 10, n_modes: 4}", "{wind_speed_m_s: [8.0]}", "analysis.n_modes"),
    ("{type: turbine_simulate, seconds: 10, statistics_from_s: 10}", "{rpm: [12.1]}", "analysis.statistics_from_s"),
    ("{type: turbine_simulate, seconds: 10, rpm: [0, 1, 2]}", "{pitch_deg: [0]}", "analysis.rpm"),
    ("{type: modes, wind_speed_m_s: 8}", "{rpm: [12.1]}", "analysis.wind_speed_m_s"),
    ("{type: modes}", "{wind_speed_m_s: [8.0]}", "grid.wind_speed_m_s"),
    ("{type: turbine_linearize, seconds: 10}", "{wind_speed_m_s: [8.0]}", "analysis.seconds"),
    ("{type: turbine_simulate, seconds: 10, induction: frozen}", "{rpm: [12.1]}", "analysis.induction"),
])
def test_turbine_plan_mistakes_name_line_and_field(tmp_path, capsys, analysis, grid, field):
    plan = write_plan(tmp_path, f"model: {DECK}\nanalysis: {analysis}\ngrid: {grid}\n")
    assert main(["batch", str(plan), "-o", str(tmp_path / "out")]) == 2
    error = capsys.readouterr().err.strip()
    assert "\n" not in error and str(plan) in error and field in error


def test_blade_inputs_on_a_turbine_case_are_refused(tmp_path):
    plan = read_plan(write_plan(tmp_path, f"""model: {DECK}
analysis: {{type: turbine_simulate, seconds: 1}}
grid: {{mass_scale: [1.1]}}
"""))
    rows = run_case(plan.cases[0])
    assert rows[0]["status"] == "error" and "mass_scale" in rows[0]["error"]


def test_a_deck_case_runs_on_the_worker_from_its_carried_files_alone(tmp_path, monkeypatch):
    """A worker with none of the deck's files (the copy it was read from is gone) runs the case from the bundle the
    client carried, with the same modes as the deck read in place (without the bundle: file not found)."""
    import shutil
    shutil.copytree(DECK.parent, tmp_path / "deck")
    plan = read_plan(write_plan(tmp_path, f"""model: deck/{DECK.name}
analysis: {{type: turbine_linearize, rpm: 12.1, pitch_deg: 0}}
grid: {{wind_speed_m_s: [11.4]}}
"""))
    shutil.rmtree(tmp_path / "deck")
    monkeypatch.setenv("BLADEFEM_BATCH_INPUTS", str(tmp_path / "worker"))
    case = plan.cases[0]
    carried = run_case(case, plan.bundles[case.bundle])
    assert all(row["status"] == "ok" for row in carried), carried[0].get("error")
    in_place = run_case(read_plan(write_plan(tmp_path, f"""model: {DECK}
analysis: {{type: turbine_linearize, rpm: 12.1, pitch_deg: 0}}
grid: {{wind_speed_m_s: [11.4]}}
""")).cases[0])
    assert [(r["name"], r["frequency_hz"], r["damping_ratio"]) for r in carried] == \
        [(r["name"], r["frequency_hz"], r["damping_ratio"]) for r in in_place]
    assert run_case(case)[0]["error"].count(str(tmp_path / "deck" / DECK.name)) == 1     # without it: not found
