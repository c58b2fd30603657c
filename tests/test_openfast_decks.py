"""The OpenFAST decks engineers bring today (issue 25, items 3 and 4): the IEA-15MW and IEA-22MW decks (monopile and
semi-submersible) and openfast_toolbox's copy of OpenFAST's NREL 5MW regression deck, read unmodified; the label
spellings of OpenFAST v3.0 to v5.0; and what bladefem does not model refused with the way forward named, or left
out and said when that way is taken. Data: tests/data/iea15, iea22, nrel5mw_toolbox (README.md beside each)."""

from __future__ import annotations

import math
import shutil

import pytest
from deck_copies import DATA, deck_copy

from bladefem.cli import main
from bladefem.errors import InputError
from bladefem.formats._fast_format import FastText
from bladefem.formats._label_table import spellings
from bladefem.builders.aerodyn_primary import read_aerodyn_primary
from bladefem.builders.detect import read_model
from bladefem.builders.elastodyn_blade import read_elastodyn_blade
from bladefem.formats.elastodyn_main import elastodyn_main_text, read_elastodyn_main
from bladefem.builders.elastodyn_tower import read_elastodyn_tower
from bladefem.builders.openfast_fst import read_openfast_deck
from bladefem.builders.turbine_elastodyn import deck_conditions

IEA15 = DATA / "iea15"
IEA22 = DATA / "iea22"
IEA15_MONOPILE = "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile.fst"
IEA15_SEMI = "IEA-15-240-RWT-UMaineSemi/IEA-15-240-RWT-UMaineSemi.fst"
IEA22_MONOPILE = "IEA-22-280-RWT-Monopile/IEA-22-280-RWT-Monopile.fst"
IEA22_SEMI = "IEA-22-280-RWT-Semi/IEA-22-280-RWT-Semi.fst"


def test_every_spelling_of_an_indexed_label():
    """ElastoDyn reads its per-blade and per-mode entries by position; OpenFAST's templates write BldFile(1), WEIS
    (the IEA decks) BldFile1: both are the same field, whatever their case."""
    assert spellings("BldFile(1)")[:2] == ("BldFile(1)", "BldFile1")
    assert spellings("FlapDOF1") == ("FlapDOF1",)            # a name ending in a digit is not an index
    text = FastText.parse("x", '"a.dat"   BldFile1 - name\n 0.48  bldfldmp2  - damping\n 1.0 FlapDOF1 - flag\n')
    assert text.string("BldFile(1)") == "a.dat" and text.float("BldFlDmp(2)") == 0.48
    assert text.line_of("BldFlDmp(2)") == 2 and text.has("FlapDOF1") and not text.has("BldFile(2)")
    with pytest.raises(InputError, match="also looked for BldFile2") as error:
        text.find("BldFile(2)")
    assert error.value.field == "BldFile(2)"


@pytest.mark.parametrize("main, blade_damping, tip_radius", [
    (IEA15 / "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn.dat", (0.48, 0.48, 0.48), 120.97),
    (IEA15 / "IEA-15-240-RWT-UMaineSemi/IEA-15-240-RWT-UMaineSemi_ElastoDyn.dat", (0.48, 0.48, 0.48), 120.97),
    (IEA22 / "IEA-22-280-RWT-Monopile/IEA-22-280-RWT_ElastoDyn.dat", (0.5, 1.35, 0.5), 142.0),
    (IEA22 / "IEA-22-280-RWT-Semi/IEA-22-280-RWT-Semi_ElastoDyn.dat", (0.5, 1.35, 0.5), 142.0)])
def test_iea_elastodyn_files_read_unmodified(tmp_path, main, blade_damping, tip_radius):
    """The IEA decks' ElastoDyn main, blade and tower files (BldFile1, BldFlDmp1, FlStTunr1 spellings) read with
    their values; the main file written back keeps its own spellings and reads back the same."""
    ed = read_elastodyn_main(main)
    assert ed.num_blades == 3 and ed.tip_radius == pytest.approx(tip_radius, abs=0.5)
    assert all(file.is_file() for file in ed.blade_files) and ed.tower_file.is_file()
    assert ed.dofs["PtfmSgDOF"] in (True, False) and ed.key_lines["BldFile(1)"] == ed.text.line_of("BldFile1")
    blade = read_elastodyn_blade(ed.blade_files[0])
    assert (*blade.flap_damping_percent, blade.edge_damping_percent) == blade_damping
    assert blade.flap_tuners == (1.0, 1.0) and blade.fraction[-1] == 1.0
    tower = read_elastodyn_tower(ed.tower_file)
    assert tower.fraction[0] == 0.0 and tower.fraction[-1] == 1.0
    written = tmp_path / main.name
    written.write_text(elastodyn_main_text(ed, written))
    assert "BldFile1 " in written.read_text() and "BldFile(1)" not in written.read_text()
    again = read_elastodyn_main(written)
    assert again == ed


def test_aerodyn_spellings_of_the_decks(tmp_path):
    """AeroDyn v15 layouts of the decks: IEA-15 (OpenFAST 3.x labels WakeMod 1, AFAeroMod 2 with UAMod 3), IEA-22
    (OpenFAST 3.5's WakeMod 11: BEM with the polar projection, BEM_Mod 2 from v4.0), the toolbox's 5MW (WakeMod 2,
    DBEMT_Mod 2)."""
    iea15 = read_aerodyn_primary(deck_copy("iea15", tmp_path) / "IEA-15-240-RWT-Monopile/"
                                 "IEA-15-240-RWT-Monopile_AeroDyn15.dat")
    assert (iea15.wake_mod, iea15.dbemt_mod, iea15.ua_mod, iea15.bem_mod) == (1, 0, 3, 1)
    iea22 = read_aerodyn_primary(deck_copy("iea22", tmp_path) / "IEA-22-280-RWT-Monopile/IEA-22-280-RWT_AeroDyn15.dat")
    assert (iea22.wake_mod, iea22.dbemt_mod, iea22.ua_mod, iea22.bem_mod) == (1, 0, 4, 2)
    toolbox = read_aerodyn_primary(deck_copy("nrel5mw_toolbox", tmp_path) / "onshore/AeroDyn.dat")
    assert (toolbox.wake_mod, toolbox.dbemt_mod) == (1, 2)


@pytest.mark.parametrize("tree, fst, refusals", [
    ("iea15", IEA15_MONOPILE, [("CompHydro", "--foundation rigid"), ("AFAeroMod", "--quasi-steady"),
                               ("PCMode", "--rpm")]),
    ("iea15", IEA15_SEMI, [("CompHydro", "--foundation rigid"), ("AFAeroMod", "--quasi-steady"),
                           ("PCMode", "--rpm")]),
    ("iea22", IEA22_MONOPILE, [("CompElast", "--elastodyn-blades"), ("CompHydro", "--foundation rigid"),
                               ("AFAeroMod", "--quasi-steady"), ("PCMode", "--rpm")]),
    ("iea22", IEA22_SEMI, [("CompHydro", "--foundation rigid"), ("DBEMT_Mod", "--quasi-steady"),
                           ("PCMode", "--rpm")]),
    ("nrel5mw_toolbox", "Main_Onshore.fst", [("DBEMT_Mod", "--quasi-steady"), ("TimGenOn", "--rpm")])])
def test_each_refusal_names_its_way_forward(tmp_path, tree, fst, refusals):
    """Each thing the deck asks for and bladefem does not model is refused with its file, line and label and the
    option that runs without it; taking that way moves on to the next, and with all of them the deck reads, every
    thing left out named in one line per way."""
    path = deck_copy(tree, tmp_path) / fst
    taken: set[str] = set()
    for label, way in refusals:
        with pytest.raises(InputError) as error:
            read_openfast_deck(path, leave_out=taken)
        assert error.value.field == label and error.value.line is not None and way in str(error.value)
        taken.add(way)
    deck = read_openfast_deck(path, leave_out=taken)
    assert len(deck.left_out) == len({way for _, way in refusals})
    assert all(label in " ".join(deck.left_out) for label, _ in refusals)


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_the_iea15_monopile_runs_parked_and_at_a_wind_speed(tmp_path, capsys):
    """The IEA-15MW monopile deck with --foundation rigid --quasi-steady and a fixed rotor speed: parked and at
    10 m/s, exit 0, the header saying what is left out (foundation, the aerodynamic features, the DISCON
    controller); no mode name repeated."""
    fst = str(deck_copy("iea15", tmp_path) / IEA15_MONOPILE)
    ways = ("--foundation", "rigid", "--quasi-steady", "--quiet")
    for point in (("--rpm", "0", "--wind-speed", "0"), ("--rpm", "7.55", "--wind-speed", "10")):
        code, out, err = run(capsys, "turbine", fst, "--linearize", *ways, *point)
        assert code == 0, err
        assert "# foundation rigid: the tower is clamped at its base" in out and "CompHydro" in out
        assert "PtfmSgDOF" in out and "quasi-steady aerodynamics" in out and "UA_Mod 3" in out
        assert "DISCON" in out and "PCMode" in out
        names = [line[:50].strip() for line in out.splitlines()[out.splitlines().index(next(
            line for line in out.splitlines() if line.startswith("mode "))) + 1:]]
        assert len(names) == len(set(names)) > 10


@pytest.mark.parametrize("tree, fst", [("iea15", IEA15_SEMI), ("iea22", IEA22_MONOPILE), ("iea22", IEA22_SEMI)])
def test_the_other_iea_decks_run_with_their_ways(tmp_path, capsys, tree, fst):
    """The IEA-15 semi and both IEA-22 decks: refused with the way forward (exit 2, one line), then run parked with
    the ways taken (exit 0)."""
    path = str(deck_copy(tree, tmp_path) / fst)
    code, _, err = run(capsys, "turbine", path, "--linearize", "--rpm", "0")
    assert code == 2 and "\n" not in err.strip() and ("--foundation rigid" in err or "--elastodyn-blades" in err)
    code, out, err = run(capsys, "turbine", path, "--linearize", "--rpm", "0", "--wind-speed", "0", "--foundation",
                         "rigid", "--quasi-steady", "--elastodyn-blades", "--quiet")
    assert code == 0, err
    assert "foundation rigid" in out and "1st tower fore-aft" in out
    if fst == IEA22_MONOPILE:
        assert "BeamDyn blades (CompElast 2)" in out


def test_the_toolbox_5mw_deck_runs_quasi_steady(tmp_path, capsys):
    """openfast_toolbox's NREL 5MW (OpenFAST's regression-test deck: DBEMT, unsteady aerodynamics, tower
    aerodynamics, a generator switched on at 5 s): refused naming --quasi-steady, runs with it at a fixed speed."""
    fst = str(deck_copy("nrel5mw_toolbox", tmp_path) / "Main_Onshore.fst")
    code, _, err = run(capsys, "turbine", fst, "--linearize")
    assert code == 2 and "DBEMT_Mod" in err and "--quasi-steady" in err
    code, out, err = run(capsys, "turbine", fst, "--linearize", "--quasi-steady", "--rpm", "9", "--quiet")
    assert code == 0, err
    assert "generator switch-on at 5 s" in out and "1st blade collective flap" in out


def test_platform_dofs_are_refused_with_file_and_line(capsys):
    """Issue 23, item 6: the platform-DOF refusal names the file and line (and the way forward); with --foundation
    rigid the structure alone runs, the header naming the DOFs switched off."""
    main_file = IEA15 / "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn.dat"
    line = FastText.read(main_file).line_of("PtfmSgDOF")
    code, _, err = run(capsys, "turbine", str(main_file), "--linearize", "--rpm", "0")
    assert code == 2 and f"{main_file}:{line}: field 'PtfmSgDOF'" in err and "--foundation rigid" in err
    code, out, err = run(capsys, "turbine", str(main_file), "--linearize", "--rpm", "0", "--foundation", "rigid")
    assert code == 0, err
    assert "left out of IEA-15-240-RWT-Monopile_ElastoDyn.dat: the platform DOFs PtfmSgDOF" in out


def test_blade_and_tower_commands_on_the_iea_files(tmp_path, capsys):
    """modes and export read the IEA ElastoDyn files as they are; a .fst given to modes stands for its ElastoDyn
    main file (said on stderr); read_model names the EDFile."""
    main_file = IEA22 / "IEA-22-280-RWT-Semi/IEA-22-280-RWT-Semi_ElastoDyn.dat"
    code, out, err = run(capsys, "modes", str(main_file))
    assert code == 0, err
    first = next(line.split() for line in out.splitlines() if line.strip().startswith("1 "))
    assert first[2] == "flap" and 0.3 < float(first[1]) < 0.6
    code, out, err = run(capsys, "modes", str(IEA22 / "IEA-22-280-RWT-Semi/IEA-22-280-RWT-Semi_ElastoDyn_tower.dat"),
                         "--elastodyn-main", str(main_file))
    assert code == 0, err
    code, out, err = run(capsys, "export", str(main_file), "-o", str(tmp_path / "out"), "--quiet")
    assert code == 0, err
    fst = IEA22 / IEA22_SEMI
    code, out_fst, err = run(capsys, "modes", str(fst))
    assert code == 0 and "its ElastoDyn main file" in err and "IEA-22-280-RWT-Semi_ElastoDyn.dat (EDFile" in err
    code, out_main, _ = run(capsys, "modes", str(main_file))
    assert out_fst == out_main
    with pytest.raises(InputError) as error:                  # the Python API names the EDFile to give instead
        read_model(fst)
    assert error.value.field == "EDFile" and "IEA-22-280-RWT-Semi_ElastoDyn.dat" in str(error.value)


def test_openfast_5_labels(tmp_path):
    """The .fst and ElastoDyn entries OpenFAST v5.0 adds (docs/source/user/api_change.rst of v5.0.0: ModCoupling,
    NRotors, CompSoil, MirrorRotor, PitchDOF, PBrIner(i), BlPIner(i)) read; those asking for something not modelled
    are refused by label."""
    tree = deck_copy("nrel5mw_toolbox", tmp_path)
    fst = tree / "Main_Onshore.fst"
    text = fst.read_text()
    lines = text.splitlines(keepends=True)
    at = next(i for i, line in enumerate(lines) if "CompElast" in line)
    lines[at:at] = ["          3   ModCoupling  - Module coupling method (switch)\n",
                    "          1   NRotors      - Number of rotors in turbine (-)\n",
                    "          0   CompSoil     - Compute soil-structural dynamics (switch)\n",
                    "          F   MirrorRotor  - Flag to reverse rotor rotation direction\n"]
    fst.write_text("".join(lines))
    ed = tree / "onshore/ElastoDyn.dat"
    ed_lines = ed.read_text().splitlines(keepends=True)
    at = next(i for i, line in enumerate(ed_lines) if "FlapDOF1" in line)
    ed_lines[at:at] = ["False         PitchDOF    - Blade pitch DOF (flag)\n"]
    at = next(i for i, line in enumerate(ed_lines) if "HubMass" in line)
    ed_lines[at:at] = [f"200           PBrIner({i})  - Pitch bearing/actuator inertia, blade {i} (kg m^2)\n"
                       for i in (1, 2, 3)]
    ed.write_text("".join(ed_lines))
    taken = {"--quasi-steady", "--rpm"}
    deck = read_openfast_deck(fst, leave_out=taken)
    assert deck.elastodyn.dofs["PitchDOF"] is False and math.isfinite(deck.elastodyn.hub_mass)
    friction = tmp_path / "friction.dat"
    friction.write_text(ed.read_text().replace("False         PitchDOF", "False         PitchDOF\n"
                                               "1             YawFrctMod  - Yaw-friction model"))
    with pytest.raises(InputError) as error:
        deck_conditions(friction)
    line = next(i for i, text in enumerate(friction.read_text().splitlines(), 1) if "YawFrctMod" in text)
    assert error.value.field == "YawFrctMod" and error.value.line == line
    for label, value in (("NRotors", "2"), ("MirrorRotor", "T"), ("CompSoil", "1")):
        shutil.copyfile(fst, tmp_path / "saved.fst")
        fst.write_text(fst.read_text().replace(
            next(line for line in fst.read_text().splitlines() if f" {label} " in line),
            f"          {value}   {label}  - changed"))
        with pytest.raises(InputError) as error:
            read_openfast_deck(fst, leave_out=taken)
        assert error.value.field == label
        shutil.copyfile(tmp_path / "saved.fst", fst)


def test_tower_concentrated_masses_are_refused(tmp_path):
    """ElastoDyn's optional tower concentrated masses (OpenFAST 4.2 and later, NTwCMass) are refused by line when
    there are any, read when the count is 0."""
    source = DATA / "nrel5mw_toolbox/5MW_Baseline/NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"
    section = ("---------------------- TOWER CONCENTRATED MASSES -----\n{count}   NTwCMass    - Number of tower "
               "concentrated masses (-)\nHtFract  TwCMass\n(-)  (kg)\n0.5  2000.0\n")
    for count in (0, 1):
        path = tmp_path / f"tower_{count}.dat"
        path.write_text(source.read_text() + section.format(count=count))
        if count == 0:
            assert read_elastodyn_tower(path).stations > 2
            continue
        with pytest.raises(InputError) as error:
            read_elastodyn_tower(path)
        line = next(i for i, text in enumerate(path.read_text().splitlines(), 1) if "NTwCMass" in text)
        assert error.value.field == "NTwCMass" and error.value.line == line
