"""An output never replaces an input (issue 24 item 1): an output option that names any file the command reads
(the deck, a file the deck names, the spec, a model or baseline it names; by its own path, a symbolic link or a
hard link) is refused with one line and exit code 2, before anything is computed, and the input is left as it was.
An explicit in-place update (``elastodyn --write``, ``check --update-baseline``) stays allowed."""

from __future__ import annotations

import contextlib
import hashlib
import io
import os
import shutil
from pathlib import Path

import pytest
from cpu_watchdog import cpu_limit

from bladefem.cli import main
from bladefem.errors import InputError
from bladefem.files import check_writable, note_input, recording_inputs, write_atomic

ROOT = Path(__file__).parent.parent
FST = "nrel5mw/NRELOffshrBsline5MW_Onshore.fst"
ELASTODYN = "nrel5mw/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
TOWER = "nrel5mw/NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"
POLAR = "nrel5mw/Airfoils/NACA64_A17.dat"
SCHEDULE = "nrel5mw/table_7_1_schedule.csv"


@pytest.fixture(scope="module")
def cases(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("cases")
    shutil.copytree(ROOT / "cases", folder, dirs_exist_ok=True)
    return folder


def digests(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file() and not p.is_symlink()}


def refused(*argv: object, cpu: float = 20.0) -> str:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), cpu_limit(cpu, "computed before refusing"):
        code = main([str(a) for a in argv])
    assert code == 2, err.getvalue()
    lines = err.getvalue().strip().splitlines()
    assert len(lines) == 1 and "is an input of this command" in lines[0], err.getvalue()
    return lines[0]


@pytest.mark.parametrize("target", [FST, ELASTODYN, TOWER, POLAR])
@pytest.mark.parametrize("action", [["--simulate", "1", "--wind-speed", "11.4"],
                                    ["--linearize", "--wind-speed", "11.4", "--json"],
                                    ["--simulate", "1", "--no-aero"]])
def test_turbine_output_naming_an_input_is_refused(cases, action, target):
    before = digests(cases)
    line = refused("turbine", cases / FST, *action, "--output", cases / target, cpu=15)
    assert "--output" in line and str(cases / target) in line
    assert digests(cases) == before


def test_turbine_plot_naming_a_file_of_the_elastodyn_main_is_refused(cases, tmp_path):
    figure = tmp_path / "figure.png"              # a figure's name, a link to the tower file that the main names
    figure.symlink_to(cases / TOWER)
    before = digests(cases)
    refused("turbine", cases / ELASTODYN, "--simulate", "1", "--plot", figure, cpu=15)
    assert digests(cases) == before


def test_links_to_an_input_are_refused(cases, tmp_path):
    soft, hard = tmp_path / "soft.csv", tmp_path / "hard.csv"
    soft.symlink_to(cases / ELASTODYN)
    os.link(cases / TOWER, hard)
    before = digests(cases)
    for link in (soft, hard):
        assert "the same file as" in refused("turbine", cases / FST, "--simulate", "1", "--output", link, cpu=15)
    assert digests(cases) == before


@pytest.mark.parametrize("target", ["nrel5mw_check.yaml", "nrel5mw_blade.yaml", "nrel5mw_tower.yaml",
                                    "nrel5mw_check_baseline.json"])
def test_check_junit_naming_an_input_is_refused(cases, target):
    before = digests(cases)
    line = refused("check", cases / "nrel5mw_check.yaml", "--junit", cases / target, cpu=10)
    assert "--junit" in line
    assert digests(cases) == before


def test_campbell_plot_naming_its_input_is_refused(cases):
    before = digests(cases)
    refused("campbell", cases / "uniform_blade.yaml", "--rpm", "0:10:3", "--plot", cases / "uniform_blade.yaml", cpu=5)
    assert digests(cases) == before


def test_every_write_refuses_a_recorded_input_but_an_update_in_place(tmp_path):
    source = tmp_path / "input.dat"
    source.write_text("kept\n")
    with recording_inputs():
        note_input(source)
        with pytest.raises(InputError, match="is an input of this command"):
            write_atomic(source, "lost\n")
        assert source.read_text() == "kept\n"
        write_atomic(source, "updated\n", replaces_input=True)
    assert source.read_text() == "updated\n"
    check_writable(source)              # outside a command nothing is recorded: the Python API is unchanged


def test_turbine_output_naming_the_schedule_is_refused(cases):
    before = digests(cases)
    refused("turbine", cases / FST, "--linearize", "--wind-speed", "11.4", "--schedule", cases / SCHEDULE,
            "--output", cases / SCHEDULE, cpu=5)
    assert digests(cases) == before


def test_a_baseline_that_names_a_model_is_refused(tmp_path):
    shutil.copytree(ROOT / "cases", tmp_path, dirs_exist_ok=True)
    spec = tmp_path / "nrel5mw_check.yaml"
    spec.write_text(spec.read_text().replace("file: nrel5mw_check_baseline.json, rpm", "file: nrel5mw_blade.yaml, rpm"))
    before = digests(tmp_path)
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), cpu_limit(5):
        assert main(["check", str(spec), "--update-baseline"]) == 2
    assert "requirements.5.baseline.file" in err.getvalue() and len(err.getvalue().strip().splitlines()) == 1
    assert digests(tmp_path) == before


def test_junit_naming_a_baseline_still_to_be_written_is_refused(tmp_path):
    shutil.copytree(ROOT / "cases", tmp_path, dirs_exist_ok=True)
    (tmp_path / "nrel5mw_check_baseline.json").unlink()
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), cpu_limit(5):
        code = main(["check", str(tmp_path / "nrel5mw_check.yaml"), "--update-baseline", "--junit",
                     str(tmp_path / "nrel5mw_check_baseline.json")])
    assert code == 2 and "is a baseline file of the spec" in err.getvalue(), err.getvalue()
    assert not (tmp_path / "nrel5mw_check_baseline.json").exists()
