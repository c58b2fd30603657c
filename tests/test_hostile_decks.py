"""Hostile OpenFAST decks, check baselines and option values (issue 24 items 2, 3, 4, 8, 9; issue 23 item 10): each
ends in one line naming the file, line and field (exit 2), or the option; never a traceback, a hang on a pipe or an
answer changed by an absurd value."""

from __future__ import annotations

import json
import math
import os
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from cpu_watchdog import wall_limit
from test_hostile_input import one_line

from bladefem.errors import InputError, SolveError
from bladefem.formats.bmodes import read_bmodes_sections
from bladefem.models.turbine.linearize import modes_of

ROOT = Path(__file__).parent.parent
DATA = Path(__file__).parent / "data"
FST = "NRELOffshrBsline5MW_Onshore.fst"
ELASTODYN = "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
AERODYN = "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
SERVODYN = "NRELOffshrBsline5MW_Onshore_ServoDyn.dat"
INFLOW = "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat"
LINEARIZE = ("--linearize", "--wind-speed", "11.4")


def at(path: Path, label: str, message: str = "") -> str:
    """``file:line: field 'label':`` of the line of ``path`` that holds ``label`` (for asserting the location)."""
    line = next(i for i, text in enumerate(path.read_text().splitlines(), 1) if re.search(rf"\s{label}\s", text))
    return f"{path}:{line}: field '{label}': {message}"


@pytest.fixture
def deck(tmp_path) -> Path:
    shutil.copytree(ROOT / "cases" / "nrel5mw", tmp_path / "nrel5mw")
    return tmp_path / "nrel5mw"


def set_value(path: Path, label: str, value: str) -> None:
    """Replace the value in front of ``label`` (the rest of the line kept)."""
    text = path.read_text()
    new, count = re.subn(rf"(?m)^(\s*)\S+(\s+{re.escape(label)}\s)", lambda m: m[1] + value + m[2], text, count=1)
    assert count == 1, label
    path.write_text(new)


# -- item 2: the baseline of `check` is an input ------------------------------------------------------------------

def _short(data):
    data["entries"][0]["modes"][0]["shape"]["flap"].pop()


def _zero(data):
    data["entries"][0]["modes"][0]["shape"]["edge"] = 0


def _empty(data):
    data["entries"][0]["modes"][0]["shape"]["edge"][3] = []


def _nan(data):
    data["entries"][0]["modes"][1]["frequency_hz"] = math.nan


@pytest.mark.parametrize("damage,field", [
    (_short, "entries[0].modes[0].shape.flap"), (_zero, "entries[0].modes[0].shape.edge"),
    (_empty, "entries[0].modes[0].shape.edge[3]"), (_nan, "entries[0].modes[1].frequency_hz")])
def test_damaged_baseline_names_file_line_and_field(tmp_path, damage, field):
    shutil.copytree(ROOT / "cases", tmp_path, dirs_exist_ok=True)
    baseline = tmp_path / "nrel5mw_check_baseline.json"
    data = json.loads(baseline.read_text())
    damage(data)
    baseline.write_text(json.dumps(data, indent=1))
    line = one_line("check", tmp_path / "nrel5mw_check.yaml")
    assert re.search(rf"{re.escape(str(baseline))}:\d+: field '{re.escape(field)}'", line), line


def test_baseline_with_a_5000_digit_number_names_its_line(tmp_path):
    shutil.copytree(ROOT / "cases", tmp_path, dirs_exist_ok=True)
    baseline = tmp_path / "nrel5mw_check_baseline.json"
    text = baseline.read_text()
    number = re.search(r'"frequency_hz": (\S+),', text)[1]
    baseline.write_text(text.replace(number, "7" * 5000, 1))
    line_number = text[:text.index(number)].count("\n") + 1
    assert f"{baseline}:{line_number}:" in one_line("check", tmp_path / "nrel5mw_check.yaml")


def test_nan_tolerance_in_a_spec_is_refused(tmp_path):
    shutil.copytree(ROOT / "cases", tmp_path, dirs_exist_ok=True)
    spec = tmp_path / "nrel5mw_check.yaml"
    spec.write_text(spec.read_text().replace("tolerance_percent: 1,", "tolerance_percent: .nan,", 1))
    assert "field 'requirements.5.baseline.tolerance_percent': must be a finite number" in one_line("check", spec)


# -- item 3: airfoil table columns ---------------------------------------------------------------------------------

@pytest.mark.parametrize("column", ["-1000", "-1", "0", "101"])
def test_polar_column_out_of_range(deck, column):
    set_value(deck / AERODYN, "InCol_Cl", column)
    assert at(deck / AERODYN, "InCol_Cl", "a column number") in one_line("turbine", deck / FST, *LINEARIZE)


def test_polar_columns_must_differ(deck):
    set_value(deck / AERODYN, "InCol_Cd", "2")
    assert "must name different columns" in one_line("turbine", deck / FST, *LINEARIZE)


def test_no_moment_column_is_still_allowed(deck):
    from bladefem.builders.aerodyn_primary import read_aerodyn_primary
    set_value(deck / AERODYN, "InCol_Cm", "0")
    set_value(deck / AERODYN, "UseBlCm", "False")
    assert read_aerodyn_primary(deck / AERODYN).columns.cm == 0


# -- item 4: infinite matrices -------------------------------------------------------------------------------------

@pytest.mark.parametrize("main_file", [FST, ELASTODYN])
@pytest.mark.parametrize("option", [["--yaw-stiffness", "1e308"], ["--yaw-stiffness", "1e308", "--no-damping"],
                                    ["--yaw-damping", "1e308"]])
def test_absurd_yaw_options_are_refused(deck, main_file, option):
    action = LINEARIZE if main_file == FST else ("--linearize",)
    assert f"field '{option[0]}': must be at most" in one_line("turbine", deck / main_file, *action, *option)


@pytest.mark.parametrize("label", ["YawSpr", "YawDamp"])
def test_absurd_servodyn_yaw_values_are_refused(deck, label):
    set_value(deck / SERVODYN, label, "1e29")
    assert at(deck / SERVODYN, label, "must be at most") in one_line("turbine", deck / FST, *LINEARIZE)


def test_non_finite_state_matrix_is_a_solve_error():
    with pytest.raises(SolveError, match="infinite or undefined"):
        modes_of(np.array([[0.0, 1.0], [-np.inf, 0.0]]), ["yaw"], np.ones(1), np.ones(1), spinning=False)


# -- item 8: absurd values that changed the answer ----------------------------------------------------------------

@pytest.mark.parametrize("path,label,value", [
    (AERODYN, "MaxIter", "9223372036854775807"), (AERODYN, "MaxIter", "0"), (INFLOW, "VFlowAng", "1e15"),
    (INFLOW, "PropagationDir", "1e15"), (INFLOW, "HWindSpeed", "1e9"), (INFLOW, "PLExp", "40")])
def test_absurd_deck_values_are_refused(deck, path, label, value):
    set_value(deck / path, label, value)
    assert at(deck / path, label) in one_line("turbine", deck / FST, "--linearize")


@pytest.mark.parametrize("option", [["--rtol", "1e308"], ["--rtol", "1e-300"], ["--shear-exp", "1e9"]])
def test_absurd_simulation_options_are_refused(deck, option):
    assert f"field '{option[0]}': must lie between" in one_line("turbine", deck / FST, "--simulate", "1", *option)


def test_absurd_wind_speed_option_is_refused(deck):
    line = one_line("turbine", deck / FST, "--linearize", "--wind-speed", "1e300")
    assert "field '--wind-speed': at most 100 m/s" in line


def test_a_value_line_with_an_extra_value_is_refused(deck):
    set_value(deck / AERODYN, "TwrPotent", "1 2")
    expected = at(deck / AERODYN, "TwrPotent", "expected one value before TwrPotent, found 2")
    assert expected in one_line("turbine", deck / FST, *LINEARIZE)


def test_a_comment_after_the_label_and_lists_stay_accepted():
    from bladefem.formats._fast_format import FastText
    text = FastText.parse("f.dat", "  0   TwrPotent   - comment 1 2 TwrShadow\n0.0 0.0 0.0   RotorApexOffsetPos - m\n")
    assert text.has("TwrPotent") and not text.has("TwrShadow")
    with pytest.raises(InputError, match="expected one value before RotorApexOffsetPos, found 3"):
        text.has("RotorApexOffsetPos")       # a list where one value is asked for


# -- item 9: messages that name the right thing ------------------------------------------------------------------

def test_truncated_fst_names_its_missing_label(deck):
    fst = deck / FST
    fst.write_text("".join(fst.read_text().splitlines(keepends=True)[:3]))
    line = one_line("turbine", fst, *LINEARIZE)
    assert line.startswith(f"bladefem: error: {fst}:") and "--wind-speed" not in line


def test_absurd_tower_height_is_blamed_on_towerht(deck):
    set_value(deck / ELASTODYN, "TowerHt", str(2 ** 31))
    assert at(deck / ELASTODYN, "TowerHt", "must be at most") in one_line("turbine", deck / FST, *LINEARIZE)


def test_nacelle_yaw_inertia_is_located(deck):
    set_value(deck / ELASTODYN, "NacYIner", "0")
    assert at(deck / ELASTODYN, "NacYIner") in one_line("turbine", deck / ELASTODYN, "--linearize",
                                                        "--elastodyn-compatible")


@pytest.mark.parametrize("kind,words", [("folder", "is a folder"), ("loop", "symbolic link loop"),
                                        ("fifo", "not a regular file")])
@pytest.mark.parametrize("name", [SERVODYN, "Airfoils/DU21_A17.dat", "NRELOffshrBsline5MW_AeroDyn_blade.dat",
                                  "NRELOffshrBsline5MW_Blade.dat", "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"])
def test_referenced_file_that_is_not_a_file_says_what_it_is(deck, kind, words, name):
    path = deck / name
    path.unlink()
    {"folder": path.mkdir, "loop": lambda: path.symlink_to(path.name), "fifo": lambda: os.mkfifo(path)}[kind]()
    with wall_limit(30):
        line = one_line("turbine", deck / FST, *LINEARIZE)
    assert words in line and str(path) in line and "file not found" not in line, line
    assert re.match(rf"bladefem: error: {re.escape(str(deck))}/[^:]+:\d+: field ", line), line    # the naming line


# -- issue 23 item 10: BModes section counts ------------------------------------------------------------------------

@pytest.mark.parametrize("count", ["99999999999999999999", "9" * 400, "9" * 5000])
def test_bmodes_section_count_beyond_the_file(tmp_path, count):
    path = tmp_path / "sections.dat"
    set_value_text = re.sub(r"(?m)^(\s*)\S+(\s+n_secs)", lambda m: m[1] + count + m[2],
                            (DATA / "bmodes_blade_sec_props.dat").read_text(), count=1)
    path.write_text(set_value_text)
    with pytest.raises(InputError) as caught:
        read_bmodes_sections(path)
    assert caught.value.file == str(path) and caught.value.line is not None and "\n" not in str(caught.value)


def test_absurd_rotor_speed_in_a_spec_names_its_line(tmp_path):
    shutil.copytree(ROOT / "cases", tmp_path, dirs_exist_ok=True)
    spec = tmp_path / "nrel5mw_check.yaml"
    spec.write_text(spec.read_text().replace("hz: [0.70, 0.80], rpm: 12.1", "hz: [0.70, 0.80], rpm: 1.21e11"))
    line = one_line("check", spec)
    assert f"{spec}:15: field 'requirements.0.window.rpm'" in line, line
