"""OpenFAST deck readers (.fst, AeroDyn primary/blade/airfoil files, InflowWind, ServoDyn) on the shipped NREL 5MW
deck (OpenFAST 4.2.1 layout), on OpenFAST's own examples of the 3.5 and 5.0 layouts, and on broken inputs (one-line
errors naming file, line and label)."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from bladefem.aero.options import PITT_PETERS_FACTOR
from bladefem.errors import InputError
from bladefem.formats._fast_format import FastText
from bladefem.builders.aerodyn import read_aerodyn_blade
from bladefem.builders.aerodyn_primary import read_aerodyn_primary
from bladefem.builders.airfoil_polars import read_airfoil
from bladefem.builders.inflowwind import read_inflowwind
from bladefem.builders.openfast_fst import read_openfast_deck
from bladefem.builders.servodyn import read_servodyn

ROOT = Path(__file__).resolve().parents[1]
DECK = ROOT / "cases" / "nrel5mw"
FST = "NRELOffshrBsline5MW_Onshore.fst"
AERODYN = "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
SERVODYN = "NRELOffshrBsline5MW_Onshore_ServoDyn.dat"
INFLOW = "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat"
LAYOUTS = ROOT / "tests" / "data" / "openfast_layouts"
RPM = math.pi / 30


@pytest.fixture
def deck_copy(tmp_path) -> Path:
    shutil.copytree(DECK, tmp_path / "deck")
    return tmp_path / "deck"


def edit(path: Path, **values: str) -> None:
    """Replace the values of labels in a file (every other byte kept)."""
    path.write_text(FastText.read(path).replaced(values))


def line_of(path: Path, text: str) -> int:
    return next(i for i, line in enumerate(path.read_text().splitlines(), start=1) if text in line)


def expect_error(call, path: Path, line: int, label: str) -> InputError:
    with pytest.raises(InputError) as info:
        call()
    error = info.value
    assert (Path(error.file).resolve(), error.line, error.field) == (path.resolve(), line, label), str(error)
    assert "\n" not in str(error)
    return error


def test_gravity_of_the_fst_reaches_the_turbine(deck_copy):
    """The .fst's Gravity is the turbine model's (a deck without gravity is run without it)."""
    from bladefem.builders.turbine_deck import read_turbine_deck
    edit(deck_copy / FST, Gravity="0")
    assert read_openfast_deck(deck_copy / FST).gravity == 0.0
    assert read_turbine_deck(deck_copy / FST, blade_shapes="polynomial").params.gravity == 0.0
    edit(deck_copy / FST, Gravity="-9.8")
    expect_error(lambda: read_openfast_deck(deck_copy / FST), deck_copy / FST, line_of(deck_copy / FST, "Gravity"),
                 "Gravity")


def test_shipped_deck():
    deck = read_openfast_deck(DECK / FST)
    assert (deck.t_max, deck.dt, deck.air_density, deck.unmodelled) == (100.0, 0.00625, 1.225, ())
    assert deck.gravity == 9.80665
    assert deck.hub_height == pytest.approx(90.0, abs=1e-5)
    assert deck.pitch == (0.0, 0.0, 0.0) and deck.yaw == 0.0
    options = deck.aerodyn.options()
    assert (options.formulation, options.tip_loss, options.hub_loss, options.tangential_induction) == (2, True, True,
                                                                                                       True)
    assert (options.axial_drag, options.tangential_drag, options.skew_redistribution) == (False, False, True)
    assert (options.skew_factor, options.tolerance, options.max_iterations) == (PITT_PETERS_FACTOR, 5e-10, 100)
    assert [p.name.split()[0] for p in deck.polars] == ["Cylinder1.dat", "Cylinder2.dat", "DU40_A17.dat",
                                                        "DU35_A17.dat", "DU30_A17.dat", "DU25_A17.dat",
                                                        "DU21_A17.dat", "NACA64_A17.dat"]
    blade = deck.blades[0]
    assert len(blade.span) == 19 and blade.span[-1] == 61.4999 and list(blade.airfoil[[0, 3, -1]]) == [1, 2, 8]
    assert blade.sweep[5] == pytest.approx(-5.6986665e-01)
    assert (deck.inflow.speed, deck.inflow.reference_height, deck.inflow.shear_exponent) == (11.4, 90.0, 0.0)
    servo = deck.servodyn
    assert servo.rated_generator_speed == pytest.approx(1161.963 * RPM)
    assert servo.region2_constant == pytest.approx(0.0255764 / RPM ** 2)
    assert (servo.rated_torque, servo.slip, servo.efficiency) == (47402.91, 0.1, pytest.approx(0.944))
    assert (servo.yaw_spring, servo.yaw_damper) == (9.02832e9, 1.916e7)
    rotor = deck.rotor()
    assert (rotor.precone, rotor.shaft_tilt) == (math.radians(-2.5), math.radians(-5.0))


def layout_copy(tmp_path: Path, name: str) -> Path:
    """An example primary file whose airfoil and blade names point at the NREL 5MW files."""
    lines = (LAYOUTS / name).read_text().splitlines(keepends=True)
    first = next(i for i, line in enumerate(lines) if "AFNames" in line)
    count = int(next(line for line in lines if "NumAFfiles" in line).split()[0])
    airfoils = [f'"{DECK / "Airfoils" / "DU40_A17.dat"}"\n'] * count
    lines[first:first + count] = [airfoils[0].rstrip() + "    AFNames   - names\n"] + airfoils[1:]
    text = "".join(lines).replace("Test01_UAE_AeroDyn_blade.dat", str(DECK / "NRELOffshrBsline5MW_AeroDyn_blade.dat"))
    path = tmp_path / name
    path.write_text(text)
    return path


def test_aerodyn_layout_of_openfast_3_5(tmp_path):
    """Legacy labels map as AeroDyn maps them: WakeMod 1 -> BEM without dynamic wake, AFAeroMod 1 -> no unsteady
    aerodynamics, SkewMod 1 -> no skew model; no BEM_Mod -> legacy formulation."""
    primary = read_aerodyn_primary(layout_copy(tmp_path, "aerodyn_primary_v3.5.5.dat"))
    assert (primary.wake_mod, primary.dbemt_mod, primary.ua_mod, primary.skew_mod, primary.bem_mod) == (1, 0, 0, 0, 1)
    options = primary.options()
    assert (options.tip_loss, options.hub_loss, options.axial_drag, options.tangential_drag) == (False, False, True,
                                                                                                 True)
    assert (options.skew_redistribution, options.tolerance, options.formulation) == (False, 1e-5, 1)
    assert len(primary.airfoil_files) == 10 and primary.unmodelled() == []


def test_aerodyn_layout_of_openfast_5(tmp_path):
    """The renamed labels; what the example switches on and bladefem does not model is listed with its line."""
    path = layout_copy(tmp_path, "aerodyn_primary_v5.0.dat")
    primary = read_aerodyn_primary(path)
    assert (primary.wake_mod, primary.dbemt_mod, primary.ua_mod, primary.skew_mod, primary.bem_mod) == (1, 2, 3, 1, 2)
    found = {item.label: item.line for item in primary.unmodelled()}
    assert found == {label: line_of(path, f"  {label} ") for label in ("DBEMT_Mod", "UA_Mod", "TwrPotent",
                                                                         "SkewMomCorr")}


def test_inflowwind_layouts(tmp_path):
    """OpenFAST's InflowWind example (lower-case PLexp): refused for a wind type not modelled (4, Bladed); with its
    TurbSim file missing, refused at FileName_BTS; with WindType 1 its steady-wind entries are read whatever their
    case."""
    path = tmp_path / "inflow.dat"
    shutil.copy(LAYOUTS / "inflowwind_v5.0.dat", path)
    expect_error(lambda: read_inflowwind(path), path, line_of(path, "  Filename  "), "Filename")
    edit(path, WindType="4")
    error = expect_error(lambda: read_inflowwind(path), path, line_of(path, "WindType"), "WindType")
    assert "WindType 4 (Bladed full field wind) is not modelled" in str(error)
    edit(path, WindType="1", HWindSpeed="7.5")
    inflow = read_inflowwind(path)
    assert (inflow.speed, inflow.reference_height, inflow.shear_exponent) == (7.5, 90.0, 0.2)


def test_missing_airfoil_file(deck_copy):
    (deck_copy / "Airfoils" / "DU21_A17.dat").unlink()
    primary = deck_copy / AERODYN
    error = expect_error(lambda: read_openfast_deck(deck_copy / FST), primary, line_of(primary, "DU21_A17.dat"),
                         "AFNames")
    assert "airfoil file 7: file not found" in str(error)


def test_polar_with_non_increasing_angle(deck_copy):
    path = deck_copy / "Airfoils" / "DU25_A17.dat"
    lines = path.read_text().splitlines(keepends=True)
    row = line_of(path, "   -175.00 ")
    lines[row - 1], lines[row] = lines[row], lines[row - 1]
    path.write_text("".join(lines))
    error = expect_error(lambda: read_openfast_deck(deck_copy / FST), path, row + 1, "Alpha")
    assert "must increase strictly" in str(error)
    expect_error(lambda: read_airfoil(path), path, row + 1, "Alpha")


@pytest.mark.parametrize("kind", ["4", "9"])
def test_unknown_wind_type(deck_copy, kind):
    path = deck_copy / INFLOW
    edit(path, WindType=kind)
    expect_error(lambda: read_openfast_deck(deck_copy / FST), path, line_of(path, "WindType"), "WindType")


@pytest.mark.parametrize("label, value", [("PCMode", "5"), ("VSContrl", "5"), ("VSContrl", "0"), ("YCMode", "5")])
def test_unmodelled_control_is_refused(deck_copy, label, value):
    path = deck_copy / SERVODYN
    edit(path, **{label: value})
    error = expect_error(lambda: read_openfast_deck(deck_copy / FST), path, line_of(path, f"  {label} "), label)
    assert "not modelled" in str(error)


def test_timed_events_inside_the_run_are_refused(deck_copy):
    path = deck_copy / SERVODYN
    edit(path, **{"TPitManS(2)": "50"})
    expect_error(lambda: read_openfast_deck(deck_copy / FST), path, line_of(path, "TPitManS(2)"), "TPitManS(2)")
    edit(path, **{"TPitManS(2)": "100"})
    assert read_openfast_deck(deck_copy / FST).unmodelled == ()


def test_unmodelled_aerodynamics_refused_or_kept(deck_copy):
    path = deck_copy / AERODYN
    edit(path, UA_Mod="3", TwrPotent="1")
    expect_error(lambda: read_openfast_deck(deck_copy / FST), path, line_of(path, "  UA_Mod "), "UA_Mod")
    deck = read_openfast_deck(deck_copy / FST, unmodelled="keep")
    assert [item.label for item in deck.unmodelled] == ["UA_Mod", "TwrPotent"]
    assert deck.rotor().options.formulation == 2


def test_legacy_and_new_label_together_is_an_error(deck_copy):
    path = deck_copy / AERODYN
    text = path.read_text().replace("  Wake_Mod ", "  Wake_Mod \n          1   WakeMod   - legacy\n", 1)
    path.write_text(text)
    expect_error(lambda: read_aerodyn_primary(path), path, line_of(path, "  WakeMod "), "WakeMod")


def test_airfoil_number_beyond_the_list(deck_copy):
    path = deck_copy / "NRELOffshrBsline5MW_AeroDyn_blade.dat"
    lines = path.read_text().splitlines(keepends=True)
    row = line_of(path, "4.1000000E+00")
    lines[row - 1] = lines[row - 1].rstrip()[:-1] + "9\n"
    path.write_text("".join(lines))
    expect_error(lambda: read_openfast_deck(deck_copy / FST), path, row, "BlAFID")


def test_servodyn_and_blade_readers_alone():
    servo = read_servodyn(DECK / SERVODYN)
    assert servo.unmodelled(100.0) == [] and servo.yaw_neutral == 0.0
    assert [item.label for item in servo.unmodelled(math.inf)][:2] == ["TPitManS(1)", "TPitManS(2)"]
    blade = read_aerodyn_blade(DECK / "NRELOffshrBsline5MW_AeroDyn_blade.dat")
    assert np.allclose(blade.curve_angle, 0.0) and blade.curve[3] == pytest.approx(-5.9469375e-02)
