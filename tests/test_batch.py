"""Batch runs on Dask: results equal the serial solver to the last digit, a killed worker loses no case and
duplicates none, an interrupted batch resumes, failures are recorded, Monte Carlo against a closed form."""

from __future__ import annotations

import math
import os
import re
import signal
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("dask.distributed")
pa = pytest.importorskip("pyarrow")

from bladefem.batch import ResultStore, format_summary, read_plan, run_batch, run_case, summarize  # noqa: E402
from bladefem.batch.cases import apply_inputs  # noqa: E402
from bladefem.batch.samples import correlated_normals  # noqa: E402
from bladefem.batch.runner import WORKER_TRIM_THRESHOLD  # noqa: E402
from bladefem.cli import main  # noqa: E402
from bladefem.builders.case import read_case  # noqa: E402
from bladefem.modal import modes  # noqa: E402

CASES = Path(__file__).resolve().parents[1] / "cases"
BLADE = CASES / "nrel5mw_blade.yaml"
UNIFORM = CASES / "uniform_blade.yaml"


def write_plan(folder: Path, text: str) -> Path:
    path = folder / "plan.yaml"
    path.write_text(text)
    return path


def rows_by_case(store: ResultStore) -> dict[int, list[dict]]:
    table = store.table().to_pylist()
    out: dict[int, list[dict]] = {}
    for row in table:
        out.setdefault(row["case_index"], []).append(row)
    return out


def test_results_equal_the_serial_solver_to_the_last_digit(tmp_path):
    plan = read_plan(write_plan(tmp_path, f"""model: {BLADE}
analysis: {{type: modes, rpm: 12.1, n_modes: 4, elements: 60}}
grid: {{flap_stiffness_scale: [0.9, 1.0], tip_mass_kg: [0, 250], rpm: [6.9, 12.1]}}
"""))
    assert len(plan.cases) == 8
    run = run_batch(plan, tmp_path / "out", workers=2)
    assert (run.finished, run.failed) == (8, 0)
    results = rows_by_case(ResultStore(tmp_path / "out"))
    blade = read_case(BLADE)
    for case in plan.cases[::3]:
        inputs = {k: v for k, v in case.inputs.items() if k != "rpm"}
        serial = modes(apply_inputs(blade, inputs), rpm=case.inputs["rpm"], n_modes=4, elements=60)
        rows = sorted(results[case.index], key=lambda row: row["mode"])
        assert [row["frequency_hz"] for row in rows] == list(serial.frequencies_hz)      # bit for bit
        assert [row["kind"] for row in rows] == serial.kinds


def test_a_killed_worker_loses_no_case_and_duplicates_none(tmp_path):
    plan = read_plan(write_plan(tmp_path, f"""model: {BLADE}
analysis: {{type: modes, rpm: 12.1, n_modes: 4, elements: 200}}
grid: {{mass_scale: [0.96, 0.97, 0.98, 0.99, 1.0, 1.01, 1.02, 1.03], edge_stiffness_scale: [0.95, 1.05]}}
"""))
    killed, trim = [], []

    def kill_one_worker(client, case) -> None:
        if not killed:
            trim.extend(client.run(lambda: os.environ.get("MALLOC_TRIM_THRESHOLD_")).values())
            pids = client.run(os.getpid)
            pid = sorted(pids.values())[0]
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)

    run = run_batch(plan, tmp_path / "out", workers=2, on_result=kill_one_worker)
    assert killed and run.finished == 16
    assert trim == [str(WORKER_TRIM_THRESHOLD)] * 2             # the local workers' glibc trim threshold (runner)
    table = ResultStore(tmp_path / "out").table().to_pylist()
    per_case = {}
    for row in table:
        per_case.setdefault(row["case_hash"], []).append(row)
    assert set(per_case) == {case.hash for case in plan.cases}
    assert all(len(rows) == 4 and all(r["status"] == "ok" for r in rows) for rows in per_case.values())


def test_an_interrupted_batch_resumes_without_redoing_work(tmp_path):
    plan = read_plan(write_plan(tmp_path, f"""model: {UNIFORM}
analysis: {{type: modes, rpm: 0, n_modes: 2, elements: 12}}
grid: {{flap_stiffness_scale: [0.8, 0.9, 1.0, 1.1, 1.2, 1.3], tip_mass_kg: [0, 10]}}
"""))

    finished = []

    def interrupt(client, case) -> None:
        finished.append(case)
        if len(finished) == 5:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_batch(plan, tmp_path / "out", workers=2, on_result=interrupt)
    first = ResultStore(tmp_path / "out").done_hashes()
    assert len(first) == 5                                   # what finished before the interruption was written
    assert main(["batch", str(tmp_path / "plan.yaml"), "-o", str(tmp_path / "out"), "--quiet"]) == 2   # no --resume
    run = run_batch(plan, tmp_path / "out", workers=2, resume=True)
    assert (run.skipped, run.finished) == (5, 7)
    rows = ResultStore(tmp_path / "out").table().to_pylist()
    assert sorted(r["case_index"] for r in rows) == sorted(c.index for c in plan.cases for _ in range(2))


def test_a_failing_case_records_its_error_and_the_batch_goes_on(tmp_path, monkeypatch):
    bad = tmp_path / "bad.yaml"
    bad.write_text(UNIFORM.read_text().replace("kind: blade", "kind: blade\nunknown_key: 1"))
    plan = read_plan(write_plan(tmp_path, f"""files: [{UNIFORM}, {bad}]
analysis: {{type: modes, n_modes: 2, elements: 10}}
"""))
    rows = [run_case(case) for case in plan.cases]
    assert rows[0][0]["status"] == "ok" and len(rows[0]) == 2
    assert rows[1] == [{"case_index": 1, "case_hash": plan.cases[1].hash, "file": str(bad), "status": "error",
                        "error": rows[1][0]["error"]}]
    assert "unknown_key" in rows[1][0]["error"] and "bad.yaml" in rows[1][0]["error"]
    monkeypatch.setenv("BLADEFEM_BATCH_INPUTS", str(tmp_path / "worker"))
    carried = [run_case(case, plan.bundles[case.bundle]) for case in plan.cases]   # as on a worker: the same rows,
    assert carried == rows                                                        # messages with the client's paths


def test_monte_carlo_of_a_lognormal_stiffness_matches_the_closed_form(tmp_path):
    """At rest f is proportional to sqrt(EI) exactly (K scales, M does not). With EI x exp(sigma Z), Z standard
    normal, f = f0 exp(sigma Z / 2): mean f0 exp(sigma^2 / 8), std f0 exp(sigma^2 / 8) sqrt(exp(sigma^2 / 4) - 1).
    The sample mean and std must fall within 3.5 standard errors (N = 200)."""
    sigma, count = 0.2, 200
    plan = read_plan(write_plan(tmp_path, f"""model: {UNIFORM}
analysis: {{type: modes, rpm: 0, n_modes: 1, elements: 8}}
samples:
  count: {count}
  seed: 7
  properties: {{stiffness: {{distribution: lognormal, sigma: {sigma}}}}}
"""))
    rows = [run_case(case)[0] for case in plan.cases]
    f = np.array([row["frequency_hz"] for row in rows])
    factor = np.array([row["stiffness_scale"] for row in rows])
    f0 = modes(read_case(UNIFORM), n_modes=1, elements=8).frequencies_hz[0]
    np.testing.assert_allclose(f, f0 * np.sqrt(factor), rtol=1e-9)        # each case: the exact scaling
    mean = f0 * math.exp(sigma**2 / 8)
    std = mean * math.sqrt(math.exp(sigma**2 / 4) - 1)
    assert abs(f.mean() - mean) < 3.5 * std / math.sqrt(count)
    assert abs(f.std(ddof=1) - std) < 3.5 * std / math.sqrt(2 * (count - 1))


def test_correlated_factors_follow_the_exponential_kernel():
    stations = np.linspace(0, 1, 11)
    rng = np.random.default_rng(3)
    z = np.array([correlated_normals(rng, stations, 0.3) for _ in range(4000)])
    expected = np.exp(-np.abs(stations[:, None] - stations[None, :]) / 0.3)
    assert np.max(np.abs(np.corrcoef(z.T) - expected)) < 0.06        # 4000 samples: SE of a correlation < 0.016
    shared = correlated_normals(np.random.default_rng(3), stations, None)
    assert np.all(shared == shared[0])


def test_campbell_and_check_analyses(tmp_path, monkeypatch):
    plan = read_plan(write_plan(tmp_path, f"""model: {BLADE}
analysis: {{type: campbell, rpm: [0, 12, 4], n_modes: 3, elements: 60}}
grid: {{flap_stiffness_scale: [1.0]}}
"""))
    rows = run_case(plan.cases[0])
    assert len(rows) == 12 and {r["rpm"] for r in rows} == {0.0, 4.0, 8.0, 12.0}
    assert [r["name"] for r in rows[:4]] == ["flap 1"] * 4
    spec = tmp_path / "spec.yaml"
    spec.write_text(f"models:\n  blade: {{input: {BLADE}, operating_rpm: [6.9, 12.1]}}\nrequirements:\n"
                    "  - {name: 3P, model: blade, resonance: {modes: [flap 1], harmonics: [3], margin_percent: 15}}\n")
    plan = read_plan(write_plan(tmp_path, f"""model: {BLADE}
analysis: {{type: check, spec: spec.yaml, spec_model: blade}}
grid: {{flap_stiffness_scale: [0.8, 1.0]}}
"""))
    results = [run_case(case)[0] for case in plan.cases]
    assert [row["passed"] for row in results] == [False, True]   # x 0.8: flap 1 within 15 % of 3P (test_check.py)
    assert {row["unit"] for row in results} == {"%"}             # the check's own unit: its margin is in percent
    summary = format_summary(summarize(pa.Table.from_pylist(results)))
    assert re.search(r"^3P / flap 1 vs 3P\s+%\s+2\s", summary, re.MULTILINE), summary
    monkeypatch.setenv("BLADEFEM_BATCH_INPUTS", str(tmp_path / "worker"))
    assert {Path(path).name for path in plan.bundles[plan.cases[0].bundle].paths} == {"spec.yaml", BLADE.name}
    assert [run_case(case, plan.bundles[case.bundle])[0] for case in plan.cases] == results    # the spec carried


def test_cli_batch_and_summary(tmp_path, capsys):
    plan = write_plan(tmp_path, f"""model: {UNIFORM}
analysis: {{type: modes, n_modes: 2, elements: 10}}
samples: {{count: 6, seed: 1, properties: {{mass: {{distribution: normal, std_percent: 5}}}}}}
""")
    assert main(["batch", str(plan), "-o", str(tmp_path / "out"), "--workers", "2", "--quiet"]) == 0
    assert "6 run (0 failed)" in capsys.readouterr().out
    assert main(["batch-summary", str(tmp_path / "out"), "--plot", str(tmp_path / "plots")]) == 0
    out = capsys.readouterr().out
    assert "6 cases, 0 failed" in out and "mass_scale" in out and "-1.000" in out   # f ~ 1/sqrt(m): rank -1
    assert (tmp_path / "plots" / "histograms.png").stat().st_size > 0
    assert (tmp_path / "plots" / "tornado.png").stat().st_size > 0
    summary = summarize(ResultStore(tmp_path / "out").table())
    assert summary.quantities[0].statistics["count"] == 6


def test_plan_errors_name_the_line(tmp_path, capsys):
    plan = write_plan(tmp_path, f"""model: {UNIFORM}
analysis: {{type: modes}}
grid: {{flap_stiffnes_scale: [1.0]}}
""")
    assert main(["batch", str(plan), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and f"{plan}:3:" in err and "flap_stiffnes_scale" in err


def test_a_converged_mesh_case_equals_modes_to_the_last_digit(tmp_path):
    """The default (converged) mesh: the worker takes the same mesh and numbers as ``modes``."""
    plan = read_plan(write_plan(tmp_path, f"""model: {BLADE}
analysis: {{type: modes, rpm: 12.1, n_modes: 4}}
grid: {{edge_stiffness_scale: [1.02]}}
"""))
    rows = run_case(plan.cases[0])
    serial = modes(apply_inputs(read_case(BLADE), {"edge_stiffness_scale": 1.02}), rpm=12.1, n_modes=4)
    assert [row["frequency_hz"] for row in rows] == list(serial.frequencies_hz)


def test_cases_that_share_a_structure_assemble_once_per_worker(tmp_path, monkeypatch):
    """A grid over rpm on a fixed mesh: one assembly for all speeds, and the same numbers as separate solves."""
    import bladefem.modal as modal
    from bladefem.batch import worker
    calls = []
    original = modal.blade_matrices
    monkeypatch.setattr(modal, "blade_matrices", lambda *a, **k: calls.append(a) or original(*a, **k))
    monkeypatch.setattr(worker, "_matrices", {})
    plan = read_plan(write_plan(tmp_path, f"""model: {BLADE}
analysis: {{type: modes, n_modes: 3, elements: 60}}
grid: {{rpm: [0, 6, 12], tip_mass_kg: [0, 100]}}
"""))
    rows = [run_case(case) for case in plan.cases]
    assert len(calls) == 2                                       # one structure per tip mass
    blade = read_case(BLADE)
    for case, found in zip(plan.cases, rows):
        serial = modes(apply_inputs(blade, {"tip_mass_kg": case.inputs["tip_mass_kg"]}), rpm=case.inputs["rpm"],
                       n_modes=3, elements=60)
        assert [row["frequency_hz"] for row in found] == list(serial.frequencies_hz)


def test_a_repeated_case_runs_once_and_the_count_says_so(tmp_path, capsys):
    plan = write_plan(tmp_path, f"""model: {UNIFORM}
analysis: {{type: modes, n_modes: 2, elements: 10}}
grid: {{rpm: [0, 5, 0]}}
""")
    assert main(["batch", str(plan), "-o", str(tmp_path / "out"), "--workers", "1", "--quiet"]) == 0
    assert "3 cases, 1 repeating an earlier case (run once): 0 already in" in capsys.readouterr().out
    rows = ResultStore(tmp_path / "out").table().to_pylist()
    assert sorted((row["case_index"], row["mode"]) for row in rows) == [(0, 1), (0, 2), (1, 1), (1, 2)]


def test_resume_drops_the_failed_rows_and_keeps_the_finished_ones(tmp_path):
    store = ResultStore(tmp_path / "out")
    store.append([{"case_index": 0, "case_hash": "a", "status": "ok", "error": None, "mode": 1},
                  {"case_index": 0, "case_hash": "a", "status": "ok", "error": None, "mode": 2},
                  {"case_index": 1, "case_hash": "b", "status": "error", "error": "InputError: x"}])
    store.append([{"case_index": 2, "case_hash": "c", "status": "error", "error": "KilledWorker: y"}])
    assert store.drop_failed() == 2
    assert len(store.parts()) == 1                               # the part with only a failure is gone
    assert [(row["case_hash"], row["mode"]) for row in store.table().to_pylist()] == [("a", 1), ("a", 2)]
    assert store.done_hashes() == {"a"} and store.drop_failed() == 0
