"""``bladefem turbine DECK.fst --linearize|--campbell --wind-speed ...``: output schema, the plot, the schedule,
the torque law's rotor speed, and one-line errors (exit code 2) for every mistake."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from bladefem.cli import main
from bladefem.errors import InputError
from bladefem.formats.schedule import read_schedule

ROOT = Path(__file__).resolve().parents[1]
CASE = ROOT / "cases" / "nrel5mw"
DECK = CASE / "NRELOffshrBsline5MW_Onshore.fst"
MAIN = CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
SCHEDULE = CASE / "table_7_1_schedule.csv"
FAST = ("--elastodyn-compatible", "--quiet")


def run(capsys, *argv: object) -> tuple[int, str, str]:
    code = main(["turbine", *(str(a) for a in argv)])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_linearize_json_schema(capsys):
    code, out, err = run(capsys, DECK, "--linearize", "--wind-speed", 11.4, "--rpm", 12.1, "--json", *FAST)
    assert code == 0, err
    data = json.loads(out)
    assert {"wind_speed_m_s", "rpm", "pitch_deg", "modes", "operating_point"} <= set(data)
    assert data["wind_speed_m_s"] == 11.4 and data["rpm"] == pytest.approx(12.1) and data["pitch_deg"] == 0.0
    assert data["rotor_speed_trimmed"] is False and data["induction"] == "frozen"
    names = [mode["name"] for mode in data["modes"]]
    assert len(names) == 15 and "1st blade asymmetric edge (backward whirl)" in names
    for mode in data["modes"]:
        assert {"name", "frequency_hz", "damping_ratio", "participation"} <= set(mode)
        assert sum(mode["participation"].values()) == pytest.approx(1.0, abs=0.01)
    tower = next(m for m in data["modes"] if m["name"] == "1st tower fore-aft")
    assert tower["frequency_hz"] == pytest.approx(0.336, rel=0.01) and 0.05 < tower["damping_ratio"] < 0.1
    assert data["operating_point"]["OoPDefl"] == pytest.approx(5.6, rel=0.02)
    assert "generator azimuth is locked" in err                      # the notes go to stderr with --json


def test_linearize_table_and_quasi_steady(capsys):
    code, out, _ = run(capsys, DECK, "--linearize", "--wind-speed", 11.4, "--rpm", 12.1, "--induction",
                       "quasi-steady", *FAST)
    assert code == 0
    assert "quasi-steady induction" in out and "operating point (azimuth-averaged equilibrium)" in out
    assert "1st blade collective flap" in out and "damping [%]" in out


def test_campbell_over_wind_speeds_with_the_schedule(capsys, tmp_path):
    plot = tmp_path / "campbell.png"
    code, out, err = run(capsys, DECK, "--campbell", "--wind-speed", "5,11.4,16", "--schedule", SCHEDULE, "--json",
                         "--plot", plot, *FAST)
    assert code == 0, err
    data = json.loads(out)
    assert [point["wind_speed_m_s"] for point in data] == [5.0, 11.4, 16.0]
    assert [point["rpm"] for point in data] == pytest.approx([7.506, 12.1, 12.1])
    assert [point["pitch_deg"] for point in data] == pytest.approx([0.0, 0.0, 12.06])
    assert plot.stat().st_size > 10_000
    code, out, _ = run(capsys, DECK, "--campbell", "--wind-speed", "5:16:2", "--schedule", SCHEDULE, *FAST)
    header, *rows = [line for line in out.strip().splitlines() if not line.startswith("#")]
    assert header.startswith("wind_speed [m/s],rotor_speed [rpm],pitch [deg],") and "damping [-]" in header
    assert len(rows) == 2 and rows[1].startswith("16,12.1,12.06,")


def test_the_torque_law_sets_the_rotor_speed(capsys):
    """The deck's generator is free with ServoDyn's torque law: the rotor speed is trimmed (OpenFAST's own run with
    that law settles at 9.151 rpm at 8 m/s)."""
    code, out, _ = run(capsys, DECK, "--linearize", "--wind-speed", 8, "--json", *FAST)
    assert code == 0
    data = json.loads(out)
    assert data["rotor_speed_trimmed"] and data["rpm"] == pytest.approx(9.151, rel=0.004)
    assert "1st drivetrain torsion" in [mode["name"] for mode in data["modes"]]


@pytest.mark.parametrize("argv, field", [
    ((MAIN, "--linearize", "--wind-speed", 11.4), "--wind-speed"),
    ((DECK, "--linearize", "--wind-speed", "5:10:3"), "--wind-speed"),
    ((DECK, "--linearize", "--wind-speed", 11.4, "--schedule", SCHEDULE, "--rpm", 12), "--rpm"),
    ((MAIN, "--linearize", "--schedule", SCHEDULE), "--schedule"),
    ((DECK, "--linearize", "--no-aero", "--induction", "frozen"), "--induction"),
    ((DECK, "--campbell"), "--wind-speed"),
    ((MAIN, "--campbell"), "--campbell"),
    ((DECK, "--campbell", "0:12:3", "--wind-speed", 8), "--campbell"),
    ((DECK, "--linearize", "--wind-speed", 30, "--schedule", SCHEDULE), "--wind-speed"),
    ((DECK, "--simulate", 1, "--wind-speed", "5,8"), "--wind-speed"),
    ((DECK, "--linearize", "--wind-speed", 11.4, "--azimuth-deg", 30), "--azimuth-deg"),
    ((DECK, "--linearize", "--wind-speed", 0, "--rpm", 12.1), "--wind-speed"),
    ((DECK, "--linearize", "--wind-speed", 1e6, "--rpm", 12.1, *FAST), "--wind-speed"),
])
def test_mistakes_are_one_line_errors(capsys, argv, field):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and f"field '{field}'" in err


@pytest.mark.parametrize("text", ["abc", "5:3:2", "-1", "4:8:0", "nan", "0:25:100000"])
def test_bad_wind_speeds_are_usage_errors(capsys, text):
    code, _, err = run(capsys, DECK, "--linearize", "--wind-speed", text)
    assert code == 2 and "--wind-speed" in err


def test_schedule_file(tmp_path):
    schedule = read_schedule(SCHEDULE)
    speed, pitch = schedule.at(17.0)
    assert speed == pytest.approx(12.1 * math.pi / 30) and math.degrees(pitch) == pytest.approx((12.06 + 14.92) / 2)
    for text, line in (("3, 6.9, 0\n2, 7, 0\n", 2), ("# c\nU rpm pitch\n3, 6.9\n", 3), ("3 7 0\n4 x 0\n", 2)):
        path = tmp_path / "bad.csv"
        path.write_text(text)
        with pytest.raises(InputError) as error:
            read_schedule(path)
        assert error.value.line == line and error.value.file == str(path)
    with pytest.raises(InputError):
        read_schedule(tmp_path / "missing.csv")


def test_the_damping_document_is_what_its_script_writes(tmp_path):
    """docs/aeroelastic.md is the current output of examples/aeroelastic_damping.py (its numbers to the printed
    0.01 %: rounding may move the last digit)."""
    import re
    import subprocess
    import sys

    written = tmp_path / "aeroelastic.md"
    subprocess.run([sys.executable, str(ROOT / "examples" / "aeroelastic_damping.py"), "--output", str(written)],
                   check=True, cwd=ROOT, capture_output=True)
    numbers = [re.findall(r"-?\d+\.\d+", text) for text in (written.read_text(),
                                                              (ROOT / "docs" / "aeroelastic.md").read_text())]
    assert len(numbers[0]) == len(numbers[1]) > 200
    assert max(abs(float(a) - float(b)) for a, b in zip(*numbers)) <= 0.011


def test_a_deck_with_aerodynamics_linearizes_at_its_wind_speed(capsys):
    """Without --wind-speed the .fst's --linearize is aeroelastic at InflowWind's HWindSpeed (11.4 m/s in the 5MW
    deck); --shear-exp replaces its PLExp (the azimuth-averaged thrust changes)."""
    code, out, _ = run(capsys, DECK, "--linearize", "--rpm", 12.1, "--json", *FAST)
    assert code == 0
    uniform = json.loads(out)
    assert uniform["wind_speed_m_s"] == 11.4 and uniform["modes"]
    code, out, _ = run(capsys, DECK, "--linearize", "--rpm", 12.1, "--shear-exp", 0.2, "--json", *FAST)
    sheared = json.loads(out)["operating_point"]["thrust_N"]
    assert code == 0 and abs(sheared / uniform["operating_point"]["thrust_N"] - 1) > 1e-3
