"""``bladefem turbine DECK.fst``: the OpenFAST deck's aerodynamics, generator and yaw spring in the simulation, the
new output channels with OpenFAST's names and units, the aerodynamic options, and bad deck input as one line and
exit code 2."""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import main
from bladefem.formats._fast_format import FastText

ROOT = Path(__file__).resolve().parents[1]
DECK = ROOT / "cases" / "nrel5mw"
FST = "NRELOffshrBsline5MW_Onshore.fst"
MAIN = DECK / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
ED = ("--elastodyn-compatible", "--quiet")
NEW_CHANNELS = ("RotThrust_kN", "RotTorq_kNm", "RotPwr_kW", "GenTq_kNm", "GenPwr_kW", "BldPitch1_deg")
AERO_CHANNELS = ("RtAeroFxh_N", "RtAeroMxh_Nm", "RtAeroPwr_W", "RtTSR_-", "RtAeroCp_-", "RtAeroCt_-")


def table(path: Path) -> dict[str, np.ndarray]:
    lines = path.read_text().splitlines()
    names = lines[0].split(",")
    data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    return {name: data[:, i] for i, name in enumerate(names)}


def one_line_exit_2(capsys, argv: list[str], *expected: str) -> str:
    assert main(["turbine", *argv]) == 2
    error = capsys.readouterr().err.strip()
    assert "\n" not in error and all(text in error for text in expected), error
    return error


@pytest.fixture
def deck_copy(tmp_path) -> Path:
    shutil.copytree(DECK, tmp_path / "deck")
    return tmp_path / "deck"


@pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="simulation with the compiled kernels")
def test_simulate_a_deck_writes_the_aerodynamic_channels(tmp_path):
    """The deck at 11.4 m/s with the rotor held at 12.1 rpm: OpenFAST's channel names and units, the rotor speed
    held, the thrust, torque and power of the right size and sign, Cp below Betz; with --no-aero the aerodynamic
    channels are left out and the shaft carries no aerodynamic torque."""
    out = tmp_path / "out.csv"
    assert main(["turbine", str(DECK / FST), *ED, "--simulate", "2", "--wind-speed", "11.4", "--rpm", "12.1",
                 "--pitch-deg", "1.5", "--output", str(out)]) == 0
    data = table(out)
    assert all(name in data for name in NEW_CHANNELS + AERO_CHANNELS)
    np.testing.assert_allclose(data["LSSGagVxa_rpm"], 12.1, rtol=1e-12)
    np.testing.assert_allclose(data["BldPitch1_deg"], 1.5)
    assert 5e5 < data["RtAeroFxh_N"][-1] < 9e5 and 3e6 < data["RtAeroMxh_Nm"][-1] < 5e6
    assert np.all(data["RtAeroCp_-"] < 16 / 27) and np.all(data["RtTSR_-"] > 6)
    # AeroDyn's rotor speed is the hub's angular velocity along the shaft: the rocking tower top adds up to 1 %
    np.testing.assert_allclose(data["RtAeroPwr_W"], data["RtAeroMxh_Nm"] * 12.1 * np.pi / 30, rtol=0.02)
    np.testing.assert_allclose(data["RotPwr_kW"], data["RotTorq_kNm"] * data["RotSpeed_rpm"] * np.pi / 30,
                               rtol=1e-7)            # the table has 9 digits
    assert main(["turbine", str(DECK / FST), *ED, "--simulate", "1", "--rpm", "12.1", "--no-aero", "--dof", "tower1",
                 "--output", str(out)]) == 0
    data = table(out)
    assert not any(name in data for name in AERO_CHANNELS)
    # three alike blades: gravity gives no shaft torque; what is left is the rocking tower's inertial share
    assert np.abs(data["RotTorq_kNm"]).max() < 0.005 * 4180


@pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="simulation with the compiled kernels")
def test_torque_law_drives_a_free_generator(tmp_path):
    """Without --rpm the deck's GenDOF and torque law act: at 11.4 m/s from 12.1 rpm the rotor slows toward the
    law's 11.9 rpm (region 2.5) and GenTq is the law's torque at the generator speed."""
    out = tmp_path / "out.csv"
    assert main(["turbine", str(DECK / FST), *ED, "--simulate", "3", "--wind-speed", "11.4", "--initial",
                 "RotSpeed=12.1", "--output", str(out)]) == 0
    data = table(out)
    assert data["RotSpeed_rpm"][-1] < 12.1 - 1e-3
    # ServoDyn's law in its own units (rpm, N m, N m/rpm^2): regions 2, 2.5 (the slip line) and 3
    w, sync, rated, k = data["GenSpeed_rpm"], 1161.963 / 1.1, 1161.963, 0.0255764
    slope = 47402.91 / (rated - sync)
    transition = (slope - np.sqrt(slope * (slope - 4 * k * sync))) / (2 * k)
    law = np.where(w >= rated, 47402.91, np.where(w < transition, k * w**2, slope * (w - sync))) / 1e3
    assert (w < transition).any() and (w > transition).any()
    np.testing.assert_allclose(data["GenTq_kNm"], law, rtol=1e-7)
    np.testing.assert_allclose(data["GenPwr_kW"], data["GenTq_kNm"] * w * np.pi / 30 * 0.944, rtol=1e-7)


@pytest.mark.parametrize("damage, expected", [
    ("missing-airfoil", ("NRELOffshrBsline5MW_Onshore_AeroDyn.dat:", "AFNames", "not found")),
    ("polar-order", ("DU25_A17.dat:", "Alpha", "must increase strictly")),
    ("wind-type", ("InflowWind_Steady11p4mps.dat:", "WindType", "WindType 4")),
])
def test_bad_deck_input_is_one_line_and_exit_2(deck_copy, capsys, damage, expected):
    if damage == "missing-airfoil":
        (deck_copy / "Airfoils" / "DU21_A17.dat").unlink()
    elif damage == "polar-order":
        path = deck_copy / "Airfoils" / "DU25_A17.dat"
        lines = path.read_text().splitlines(keepends=True)
        row = next(i for i, line in enumerate(lines) if "   -175.00 " in line)
        lines[row], lines[row + 1] = lines[row + 1], lines[row]
        path.write_text("".join(lines))
    else:
        path = deck_copy / "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat"
        path.write_text(FastText.read(path).replaced({"WindType": "4"}))
    one_line_exit_2(capsys, [str(deck_copy / FST), "--simulate", "1"], *expected)


@pytest.mark.parametrize("argv, expected", [
    ([str(DECK / FST), "--campbell", "0:12:3"], ("--campbell", "--no-aero")),
    ([str(MAIN), "--simulate", "1", "--wind-speed", "8"], ("--wind-speed", ".fst")),
    ([str(DECK / FST), "--simulate", "1", "--no-aero", "--shear-exp", "0.2"], ("--shear-exp", "--no-aero")),
    ([str(DECK / FST), "--simulate", "1", "--wind-speed", "-3"], ("--wind-speed", "non-negative")),
    ([str(DECK / FST), "--simulate", "1", "--pitch-deg", "nan"], ("--pitch-deg",)),
])
def test_aerodynamic_options_are_checked(capsys, argv, expected):
    one_line_exit_2(capsys, argv, *expected)


def test_structural_linearization_of_a_deck_takes_its_yaw_spring(capsys):
    """--no-aero --linearize on the .fst: the ElastoDyn deck's structure with ServoDyn's yaw spring, the same modes
    as the ElastoDyn main file with the NREL 5MW default yaw spring (the deck's value)."""
    assert main(["turbine", str(DECK / FST), *ED, "--no-aero", "--linearize", "--rpm", "0", "--json"]) == 0
    from_deck = json.loads(capsys.readouterr().out)["modes"]
    assert main(["turbine", str(MAIN), *ED, "--linearize", "--rpm", "0", "--json"]) == 0
    from_main = json.loads(capsys.readouterr().out)["modes"]
    # the same but for the generator's torque law, whose slope at rest (zero) enters through central differences
    assert [m["name"] for m in from_deck] == [m["name"] for m in from_main]
    np.testing.assert_allclose([m["frequency_hz"] for m in from_deck], [m["frequency_hz"] for m in from_main],
                               rtol=1e-9)


def test_a_rotor_turned_in_still_air_motors_against_its_drag(tmp_path):
    """12.1 rpm imposed at 0 m/s: the wake is skewed past 90 deg (the rotor's own motion is all the relative wind)
    and the polar formulation's high-thrust curve keeps its clipped a_c = 0.5 there; the run ends (it divided by
    zero before) and the air takes power from the rotor."""
    out = tmp_path / "still.csv"
    assert main(["turbine", str(DECK / FST), "--simulate", "2", "--wind-speed", "0", "--rpm", "12.1", "--output",
                 str(out), *ED]) == 0
    channels = table(out)
    assert np.all(np.isfinite(channels["RtAeroPwr_W"]))
    assert np.mean(channels["RtAeroPwr_W"][-10:]) < 0


def test_the_high_thrust_curve_beyond_a_90_degree_skew():
    from bladefem.aero.induction import empirical_thrust
    for chi0 in (0.0, 0.5, 1.2, 2.4, 3.0):
        ac, c0, c1, c2 = empirical_thrust(chi0, 0.9)
        thrust = c0 + c1 * np.linspace(ac, 1.0, 50) + c2 * np.linspace(ac, 1.0, 50) ** 2
        assert 0.35 <= ac <= 0.5 and np.all(thrust > 0)
        assert c0 + c1 + c2 == pytest.approx(2.0)                          # C_T(1) = 2
        assert c0 + c1 * ac + c2 * ac * ac == pytest.approx(4 * 0.9 * ac * (1 - ac))   # continuous at a_c
