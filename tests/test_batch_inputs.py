"""What a batch reads and writes: plan fields that name a device, a FIFO or a huge file are refused before anything
reads them; a results folder that is or holds an input is refused before anything runs or is printed; the files a
case reads are all found and carried to the worker."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("dask.distributed")
pytest.importorskip("pyarrow")

from bladefem.batch import read_plan, run_case  # noqa: E402
from bladefem.batch.bundle import Bundle, materialize, mirrored  # noqa: E402
from bladefem.cli import main  # noqa: E402
from bladefem.files import MAX_INPUT_BYTES  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
DECK_FOLDER = REPO / "cases" / "nrel5mw"
DECK = DECK_FOLDER / "NRELOffshrBsline5MW_Onshore.fst"
UNIFORM = REPO / "cases" / "uniform_blade.yaml"


def write_plan(folder: Path, text: str) -> Path:
    path = folder / "plan.yaml"
    path.write_text(text)
    return path


def one_line_error(capsys) -> str:
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    return lines[0]


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="no /dev/zero here")
def test_a_device_as_the_model_is_refused_before_reading(tmp_path, capsys):
    plan = write_plan(tmp_path, """model: /dev/zero
analysis: {type: turbine_simulate, seconds: 1}
grid: {wind_speed_m_s: [8.0]}
""")
    assert main(["batch", str(plan), "-o", str(tmp_path / "out")]) == 2
    error = one_line_error(capsys)
    assert f"{plan}:1:" in error and "field 'model'" in error and "/dev/zero" in error and "not a regular" in error


def test_a_huge_file_in_a_files_plan_is_refused_before_reading(tmp_path, capsys):
    huge = tmp_path / "huge.yaml"
    with open(huge, "wb") as stream:                       # sparse: no disk used
        stream.truncate(MAX_INPUT_BYTES + 1)
    plan = write_plan(tmp_path, f"""analysis: {{type: modes}}
files:
  - {UNIFORM}
  - huge.yaml
""")
    assert main(["batch", str(plan), "-o", str(tmp_path / "out")]) == 2
    error = one_line_error(capsys)
    assert f"{plan}:4:" in error and "field 'files.1'" in error and "huge.yaml" in error and "too large" in error


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_a_fifo_as_the_model_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "model.fifo"
    os.mkfifo(fifo)
    plan = write_plan(tmp_path, f"""model: {fifo.name}
analysis: {{type: turbine_linearize, wind_speed_m_s: 8}}
grid: {{rpm: [10]}}
""")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in (str(REPO), os.environ.get("PYTHONPATH")) if p)}
    done = subprocess.run([sys.executable, "-m", "bladefem", "batch", str(plan), "-o", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=120, env=env)   # blocked forever before
    assert done.returncode == 2 and done.stdout == ""
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "field 'model'" in lines[0] and "model.fifo" in lines[0]


def test_an_existing_file_as_results_is_one_line_before_any_progress(tmp_path, capsys):
    plan = write_plan(tmp_path, f"""model: {UNIFORM}
analysis: {{type: modes, n_modes: 2, elements: 10}}
grid: {{mass_scale: [1.0]}}
""")
    existing = tmp_path / "results.txt"
    existing.write_text("not results\n")
    assert main(["batch", str(plan), "-o", str(existing)]) == 2                      # no --quiet: a bar would show
    error = one_line_error(capsys)
    assert str(existing) in error and "not a folder" in error
    assert existing.read_text() == "not results\n"


@pytest.mark.parametrize("target", ["plan", "plan folder", "model", "deck folder", "airfoils"])
def test_a_results_folder_that_is_or_holds_an_input_is_refused(tmp_path, capsys, target):
    deck = tmp_path / "deck"
    deck.mkdir()
    for path in DECK_FOLDER.rglob("*"):
        if path.is_file():
            copy = deck / path.relative_to(DECK_FOLDER)
            copy.parent.mkdir(parents=True, exist_ok=True)
            copy.write_bytes(path.read_bytes())
    plan = write_plan(tmp_path, f"""model: deck/{DECK.name}
analysis: {{type: turbine_linearize, rpm: 12.1, pitch_deg: 0}}
grid: {{wind_speed_m_s: [11.4]}}
""")
    output = {"plan": plan, "plan folder": tmp_path, "model": deck / DECK.name, "deck folder": deck,
              "airfoils": deck / "Airfoils"}[target]
    before = {path: path.read_bytes() for path in tmp_path.rglob("*") if path.is_file()}
    assert main(["batch", str(plan), "-o", str(output)]) == 2
    error = one_line_error(capsys)
    assert f"{output}: field '-o':" in error and "an input of the batch" in error
    assert {path: path.read_bytes() for path in tmp_path.rglob("*") if path.is_file()} == before


def test_a_deck_case_carries_every_file_the_deck_references(tmp_path, monkeypatch):
    """The bundle of a deck case holds the .fst and every file it references (ElastoDyn and its blade and tower,
    AeroDyn and its blade and airfoils, InflowWind, ServoDyn), and the worker's copy has the same bytes."""
    plan = read_plan(write_plan(tmp_path, f"""model: {DECK}
analysis: {{type: turbine_linearize, rpm: 12.1, pitch_deg: 0}}
grid: {{wind_speed_m_s: [8, 11.4]}}
"""))
    assert len(plan.bundles) == 1 and {case.bundle for case in plan.cases} == set(plan.bundles)
    bundle = next(iter(plan.bundles.values()))
    referenced = {path for path in DECK_FOLDER.rglob("*") if path.suffix in (".fst", ".dat")
                  and "_ROSCO" not in path.name}                # the ROSCO deck beside it is another deck
    assert set(bundle.paths) == referenced and len(referenced) == 16
    monkeypatch.setenv("BLADEFEM_BATCH_INPUTS", str(tmp_path / "copies"))
    root = materialize(bundle)
    assert root.parent == tmp_path / "copies"
    assert all(mirrored(root, path).read_bytes() == path.read_bytes() for path in referenced)
    assert Bundle.of(mirrored(root, path) for path in referenced).content == bundle.content


def test_a_deck_the_client_cannot_read_fails_its_case_with_the_readers_message(tmp_path, monkeypatch):
    """An empty airfoil file stops the client's reader half way: the bundle holds the files read until then, and
    the case reports the reader's message (not 'not found' for the airfoils the worker never received)."""
    deck = tmp_path / "deck"
    for path in DECK_FOLDER.rglob("*"):
        if path.is_file():
            copy = deck / path.relative_to(DECK_FOLDER)
            copy.parent.mkdir(parents=True, exist_ok=True)
            copy.write_bytes(path.read_bytes())
    (deck / "Airfoils" / "DU21_A17.dat").write_text("")
    plan = read_plan(write_plan(tmp_path, f"""files: [deck/{DECK.name}]
analysis: {{type: turbine_linearize, rpm: 12.1, wind_speed_m_s: 8}}
"""))
    monkeypatch.setenv("BLADEFEM_BATCH_INPUTS", str(tmp_path / "worker"))
    case = plan.cases[0]
    carried = run_case(case, plan.bundles[case.bundle])[0]
    in_place = run_case(case)[0]
    assert carried["status"] == in_place["status"] == "error"
    assert carried["error"] == in_place["error"] == f"InputError: {deck / 'Airfoils' / 'DU21_A17.dat'}: file is empty"


def test_case_hashes_follow_the_bytes_not_the_folder(tmp_path):
    """A project moved to another folder has the same case hashes (--resume finds its cases); a changed byte in a
    file a deck references (an airfoil) changes them."""
    hashes = []
    for name, change in (("here", False), ("moved", False), ("changed", True)):
        deck = tmp_path / name / "deck"
        for path in DECK_FOLDER.rglob("*"):
            if path.is_file():
                copy = deck / path.relative_to(DECK_FOLDER)
                copy.parent.mkdir(parents=True, exist_ok=True)
                copy.write_bytes(path.read_bytes())
        if change:
            polar = deck / "Airfoils" / "DU21_A17.dat"
            polar.write_text(polar.read_text() + "\n")
        plan = read_plan(write_plan(tmp_path / name, f"""model: deck/{DECK.name}
analysis: {{type: turbine_linearize, rpm: 12.1}}
grid: {{wind_speed_m_s: [8, 11.4]}}
"""))
        hashes.append([case.hash for case in plan.cases])
    assert hashes[0] == hashes[1] and len(set(hashes[0])) == 2
    assert not set(hashes[2]) & set(hashes[0])
