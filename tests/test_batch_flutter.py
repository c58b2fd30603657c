"""The batch ``flutter`` analysis: each case's row is the onset of ``bladefem flutter`` on its blade (same numbers),
the AeroDyn file and its airfoils travel in the case's bundle, a stiffer torsion moves the Goland wing's flutter
speed up, batch-summary reports the onsets, bad entries name the plan's line, and the shipped example plan reads."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

pytest.importorskip("dask.distributed")
pa = pytest.importorskip("pyarrow")

from bladefem.batch import ResultStore, read_plan, run_case  # noqa: E402
from bladefem.batch.summary import summarize  # noqa: E402
from bladefem.cli import main  # noqa: E402
from bladefem.errors import InputError  # noqa: E402

CASES = Path(__file__).resolve().parents[1] / "cases"
GOLAND = CASES / "goland_wing" / "goland_wing.yaml"
AERODYN = CASES / "goland_wing" / "goland_AeroDyn.dat"
#: a stiffer torsion raises the torsion frequency by sqrt(scale); the flutter speed over (semichord x torsion
#: frequency) grows as the bending-to-torsion frequency ratio falls below the coalescence (the typical section's
#: flutter curve, Bisplinghoff, Ashley and Halfman 1955 ch. 9; Goland's ratio is about 0.5), so the flutter speed
#: rises by more than the torsion frequency does
TORSION_SCALE = 1.2


def plan_text(analysis: str, grid: str = f"{{torsion_stiffness_scale: [1.0, {TORSION_SCALE}]}}") -> str:
    return f"model: {GOLAND}\nanalysis: {{type: flutter, aerodyn: {AERODYN}, {analysis}}}\ngrid: {grid}\n"


GOLAND_SWEEP = "wind_speed_m_s: [120, 170, 51], rpm: 0, blades: 1, n_modes: 4"


@pytest.fixture(scope="module")
def goland_rows(tmp_path_factory):
    folder = tmp_path_factory.mktemp("flutter_batch")
    path = folder / "plan.yaml"
    path.write_text(plan_text(GOLAND_SWEEP))
    plan = read_plan(path)
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("BLADEFEM_BATCH_INPUTS", str(folder / "worker"))
        rows = [run_case(case, plan.bundles[case.bundle]) for case in plan.cases]
    return plan, rows


def test_a_flutter_case_equals_the_command(goland_rows, capsys):
    plan, rows = goland_rows
    names = {Path(p).name for p in plan.bundles[plan.cases[0].bundle].paths}
    assert {AERODYN.name, "flat_plate.dat", "goland_AeroDyn_blade.dat"} <= names        # the airfoils travel too
    assert [len(r) for r in rows] == [1, 1] and all(r[0]["status"] == "ok" for r in rows)
    assert main(["flutter", str(GOLAND), "--aero", str(AERODYN), "--wind-speed", "120:170:51", "--blades", "1",
                 "--n-modes", "4", "--json", "--quiet"]) == 0
    onset = json.loads(capsys.readouterr().out)["onset"]
    row = rows[0][0]
    assert row["swept"] == "wind_speed_m_s" and row["onset"] and row["torsion_stiffness_scale"] == 1.0
    assert (row["onset_rpm"], row["onset_wind_speed_m_s"], row["onset_frequency_hz"], row["onset_mode"]) == (
        onset["rpm"], onset["wind_speed_m_s"], onset["frequency_hz"], onset["mode"])
    assert {name: row[f"{name}_share"] for name in ("flap", "edge", "torsion")} == onset["shares"]
    assert row["least_damping_ratio"] < 0 and row["unconverged_roots"] == 0


def test_stiffer_torsion_flutters_later(goland_rows):
    _, rows = goland_rows
    base, stiff = (r[0] for r in rows)
    assert stiff["onset_wind_speed_m_s"] / base["onset_wind_speed_m_s"] > TORSION_SCALE ** 0.5
    assert stiff["onset_frequency_hz"] > base["onset_frequency_hz"] and stiff["onset_mode"] == base["onset_mode"]


def test_batch_summary_reports_the_onsets(goland_rows):
    _, rows = goland_rows
    summary = summarize(pa.Table.from_pylist([row for case in rows for row in case]))
    quantities = {q.label: q for q in summary.quantities}
    assert set(quantities) == {"flutter onset wind speed", "flutter onset frequency"}
    speed = quantities["flutter onset wind speed"]
    assert speed.unit == "m/s" and list(speed.values) == [r[0]["onset_wind_speed_m_s"] for r in rows]
    assert summary.inputs == ("torsion_stiffness_scale",) and summary.cases == 2 and summary.failed == 0


def test_a_tiny_flutter_batch_on_dask(goland_rows, tmp_path, capsys):
    """`bladefem batch` runs the two cases on a local Dask cluster: the stored rows are the cases' rows, and
    `batch-summary` prints the onsets' statistics and draws them."""
    path = tmp_path / "plan.yaml"
    path.write_text(plan_text(GOLAND_SWEEP))
    assert main(["batch", str(path), "-o", str(tmp_path / "out"), "--workers", "1", "--quiet"]) == 0
    assert "2 run (0 failed)" in capsys.readouterr().out
    stored = sorted(ResultStore(tmp_path / "out").table().to_pylist(), key=lambda row: row["case_index"])
    _, rows = goland_rows
    assert [r["onset_wind_speed_m_s"] for r in stored] == [r[0]["onset_wind_speed_m_s"] for r in rows]
    assert main(["batch-summary", str(tmp_path / "out"), "--plot", str(tmp_path / "plots")]) == 0
    out = capsys.readouterr().out
    assert "flutter onset wind speed" in out and "m/s" in out and "torsion_stiffness_scale" in out
    assert (tmp_path / "plots" / "histograms.png").stat().st_size > 0


@pytest.mark.parametrize("analysis, grid, field", [
    ("wind_speed_m_s: [120, 150, 3]", None, "analysis.aerodyn"),
    ("rpm: [0, 10, 3], wind_speed_m_s: [120, 150, 3]", None, "analysis.rpm"),
    ("rpm: 5, wind_speed_m_s: 10", None, "analysis.type"),
    ("wind_speed_m_s: [150, 120, 3]", None, "analysis.wind_speed_m_s"),
    ("rpm: 5, wind_speed_m_s: [0, 20, 3]", None, "analysis.wind_speed_m_s"),
    ("wind_speed_m_s: [120, 150, 3], yaw_deg: [0, 10, 2]", None, "analysis.yaw_deg"),
    ("wind_speed_m_s: [120, 150, 3]", "{wind_speed_m_s: [10, 20]}", "grid.wind_speed_m_s"),
], ids=["no-aerodyn", "two-sweeps", "no-sweep", "decreasing", "turning-from-still-air", "yaw", "grid-swept"])
def test_bad_flutter_entries_name_the_field(tmp_path, analysis, grid, field):
    path = tmp_path / "plan.yaml"
    text = plan_text(analysis, grid or "{pitch_deg: [85, 90]}")
    path.write_text(text.replace(f"aerodyn: {AERODYN}, ", "") if field == "analysis.aerodyn" else text)
    with pytest.raises(InputError) as error:
        read_plan(path)
    expected = "analysis.type" if field == "analysis.aerodyn" else field      # a missing key: at the analysis
    assert error.value.field == expected and error.value.line == (3 if field.startswith("grid") else 2)


def test_a_wind_speed_sweep_is_refused_by_the_other_analyses(tmp_path):
    path = tmp_path / "plan.yaml"
    path.write_text(f"model: {GOLAND}\nanalysis: {{type: modes, wind_speed_m_s: [1, 2, 3]}}\ngrid: {{pitch_deg: "
                    "[0]}\n")
    with pytest.raises(InputError) as error:
        read_plan(path)
    assert error.value.field == "analysis.wind_speed_m_s" and "one wind speed" in error.value.message


def test_the_shipped_flutter_plan_reads():
    plan = read_plan(CASES / "goland_flutter.yaml")
    assert plan.analysis.type == "flutter" and plan.analysis.wind_sweep == (100.0, 170.0, 36)
    assert [case.inputs["torsion_stiffness_scale"] for case in plan.cases] == [0.8, 0.9, 1.0, 1.1, 1.2]
