"""Every CLI subcommand on every shipped input file (cases/ and tests/data/): exit 0, or one line 'bladefem: error:'
with exit 2 and never a traceback. Where the outcome is known, it is asserted exactly: a tower goes through every
command that makes sense for it, and the files that lack something (an ElastoDyn blade or tower file without its
main file) say what is missing."""

from __future__ import annotations

import hashlib
from pathlib import Path

import pytest

from bladefem.cli import COMMANDS, main

ROOT = Path(__file__).resolve().parents[1]
INPUT_SUFFIXES = (".yaml", ".yml", ".dat", ".bmi", ".fst")
#: section-property tables that a BModes deck names; they are not inputs on their own
NOT_INPUTS = ("_sec_props.dat",)
MAIN = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


def shipped_inputs() -> list[Path]:
    """Input files in cases/ and tests/data/, each content once (tests/data repeats the NREL 5MW files)."""
    seen, found = set(), []
    for folder in (ROOT / "cases", ROOT / "tests" / "data"):
        for path in sorted(folder.rglob("*")):
            if path.suffix.lower() not in INPUT_SUFFIXES or path.name.endswith(NOT_INPUTS):
                continue
            digest = hashlib.sha256(path.read_bytes()).hexdigest()
            if digest not in seen:
                seen.add(digest)
                found.append(path)
    return found


INPUTS = shipped_inputs()

#: cheap settings: the walk checks that each command runs and ends cleanly, the numbers are tested elsewhere
COMMAND_ARGS: dict[str, list[str]] = {
    "modes": ["--n-modes", "2", "--elements", "12"],
    "campbell": ["--rpm", "0:10:2", "--n-modes", "2", "--elements", "12", "--quiet"],
    "export": ["-o", "{out}", "--n-modes", "2", "--elements", "12", "--quiet"],
    "report": ["-o", "{out}", "--n-modes", "2", "--elements", "12", "--quiet", "--no-pictures", "--sweep", "0:10:2"],
    "elastodyn": ["--elements", "12"],
    "standstill": ["--aero", str(ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"),
                   "--wind-speed", "50", "--yaw-deg", "0", "--n-modes", "2", "--elements", "12"],
    "turbine": ["--linearize", "--dof", "tower1"],
    "check": [],
    "flutter": ["--aero", str(ROOT / "cases" / "goland_wing" / "goland_AeroDyn.dat"), "--wind-speed", "120:140:2",
                "--blades", "1", "--n-modes", "2", "--elements", "12", "--quiet"],
    "batch": ["-o", "{out}"],
    "batch-summary": [],
    "batch-loads": [],
}
MODEL_COMMANDS = ("modes", "campbell", "export", "report", "elastodyn")
#: (file name, command) -> the field the one-line error must name ('' for any); other pairs must succeed
EXPECTED_ERRORS: dict[tuple[str, str], str] = {}
for command in MODEL_COMMANDS:
    EXPECTED_ERRORS["NRELOffshrBsline5MW_Blade.dat", command] = "TipRad"
    EXPECTED_ERRORS["NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat", command] = "TowerHt"
#: the ROSCO deck's controller runs in --simulate only: --linearize is refused naming PCMode (--rpm runs it)
EXPECTED_ERRORS["NRELOffshrBsline5MW_Onshore_ROSCO.fst", "turbine"] = "PCMode"
for command in MODEL_COMMANDS:                                        # a bare ElastoDyn blade file lacks TipRad
    EXPECTED_ERRORS["IEA-15-240-RWT_ElastoDyn_blade.dat", command] = ""
for name in ("uniform_blade.yaml", "nrel5mw_blade.yaml",            # a case file carries no rotor speed, nor
             "IEA-15-240-RWT_BeamDyn.dat", "IEA-15-240-RWT_BeamDyn_blade.dat",   # BeamDyn and windIO files
             "IEA-22-280-RWT_BeamDyn.dat", "IEA-22-280-RWT_BeamDyn_Blade.dat",
             "IEA-15-240-RWT_windio1.yaml", "IEA-15-240-RWT_windio2_blade.yaml",
             "IEA-22-280-RWT_windio2_blade.yaml", "IEA-22MW_blade1_st.dat", "goland_wing.yaml"):
    EXPECTED_ERRORS[name, "elastodyn"] = "--rpm"
SPECS = [path.name for path in INPUTS if path.read_text(errors="replace").count("\nrequirements:")]
PLANS = [path.name for path in INPUTS if path.read_text(errors="replace").count("\nanalysis:")]
def kind(path: Path) -> str:
    """detect_format's kind, "openfast" for a deck (the model commands read its EDFile), "" when not a model."""
    from bladefem.errors import InputError
    from bladefem.builders.detect import detect_format
    try:
        return detect_format(path)
    except InputError as error:
        return "openfast" if error.field == "EDFile" else ""


KINDS = {path: kind(path) for path in INPUTS}
DECK_COPIES = ROOT / "tests" / "data"                    # decks stored without most polars (tests/deck_copies.py)
for path, found in KINDS.items():
    if found in ("elastodyn-blade", "elastodyn-tower") and path.name not in ("NRELOffshrBsline5MW_Blade.dat",
                                                                             "NRELOffshrBsline5MW_Onshore_ElastoDyn_"
                                                                             "Tower.dat"):
        for command in MODEL_COMMANDS:                   # the IEA blade and tower files need their main file
            EXPECTED_ERRORS[path.name, command] = "TipRad" if found == "elastodyn-blade" else "TowerHt"
    if found == "elastodyn-main" and path.name != MAIN.name:
        # the IEA main files switch platform DOFs on: refused naming the first (--foundation rigid runs them)
        from bladefem.formats.elastodyn_main import read_elastodyn_main
        if read_elastodyn_main(path).dofs.get("PtfmSgDOF"):
            EXPECTED_ERRORS[path.name, "turbine"] = "PtfmSgDOF"
    if found == "openfast" and DECK_COPIES in path.parents:
        EXPECTED_ERRORS[path.name, "turbine"] = ""       # unmodelled settings refused, or a polar not stored
for path in INPUTS:
    if KINDS[path] not in ("elastodyn-main", "openfast"):  # the turbine needs an ElastoDyn main or a .fst
        EXPECTED_ERRORS[path.name, "turbine"] = ""
    if path.name not in SPECS:                                        # check takes a spec, and only a spec
        EXPECTED_ERRORS[path.name, "check"] = ""
    EXPECTED_ERRORS[path.name, "batch-summary"] = ""                  # takes a results folder, not a file
    EXPECTED_ERRORS[path.name, "batch-loads"] = ""                    # so does batch-loads
    if path.name not in PLANS:                                        # batch takes a plan
        EXPECTED_ERRORS[path.name, "batch"] = ""
    if not KINDS[path]:                                               # spec, plan, AeroDyn, airfoil...: it says so
        for command in MODEL_COMMANDS:
            EXPECTED_ERRORS[path.name, command] = ""
#: the blades as long as the NREL 5MW's AeroDyn blade (61.5 m) or longer, which standstill runs with it; the rest are
#: towers, shorter blades (BlSpn), files that need their main file, or not models: a one-line error
STANDSTILL_RUNS = {"NRELOffshrBsline5MW_Onshore.fst", "NRELOffshrBsline5MW_Onshore_ROSCO.fst", "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat", "nrel5mw_blade.yaml",
                   "IEA-15-240-RWT-Monopile.fst", "IEA-15-240-RWT-Monopile_ElastoDyn.dat",
                   "IEA-15-240-RWT-UMaineSemi.fst", "IEA-15-240-RWT-UMaineSemi_ElastoDyn.dat",
                   "IEA-15-240-RWT_BeamDyn.dat", "IEA-15-240-RWT_BeamDyn_blade.dat", "IEA-15-240-RWT_windio1.yaml",
                   "IEA-15-240-RWT_windio2_blade.yaml", "IEA-22-280-RWT-Monopile.fst", "IEA-22-280-RWT_ElastoDyn.dat",
                   "IEA-22-280-RWT-Semi.fst", "IEA-22-280-RWT-Semi_ElastoDyn.dat", "IEA-22-280-RWT_BeamDyn.dat",
                   "IEA-22-280-RWT_BeamDyn_Blade.dat", "IEA-22MW_blade1_st.dat", "IEA-22-280-RWT_windio2_blade.yaml",
                   "Main_Onshore.fst", "ElastoDyn.dat", "windio_small.yaml"}
for path in INPUTS:
    if path.name not in STANDSTILL_RUNS:
        EXPECTED_ERRORS[path.name, "standstill"] = ""
#: flutter (with the Goland wing's 6.096 m AeroDyn blade) runs on the blade models at least that long whose first
#: AeroDyn node is off the rotor axis; every other input (a tower, a shorter blade, a blade at radius 0 without
#: --hub-radius, a file that is no model) is one line naming the problem
FLUTTER_RUNS = {"goland_wing.yaml", "NRELOffshrBsline5MW_Onshore.fst", "NRELOffshrBsline5MW_Onshore_ROSCO.fst", "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat",
                "nrel5mw_blade.yaml", "bmodes_blade.bmi", "Test01_nonunif_blade.bmi", "Test02_blade_with_tip_mass.bmi",
                "IEA-15-240-RWT-Monopile.fst", "IEA-15-240-RWT-Monopile_ElastoDyn.dat", "IEA-15-240-RWT-UMaineSemi.fst",
                "IEA-15-240-RWT-UMaineSemi_ElastoDyn.dat", "IEA-15-240-RWT_windio1.yaml",
                "IEA-15-240-RWT_windio2_blade.yaml", "IEA-22-280-RWT-Monopile.fst", "IEA-22-280-RWT_ElastoDyn.dat",
                "IEA-22-280-RWT-Semi.fst", "IEA-22-280-RWT-Semi_ElastoDyn.dat", "IEA-22-280-RWT_windio2_blade.yaml",
                "Main_Onshore.fst", "ElastoDyn.dat"}
#: inputs whose outcome other work changes (BModes platform decks are being modelled; windIO numbers such as
#: 1.0e7 are read as strings by YAML 1.1): exit 0 or a one-line error
EITHER = ("bmodes_tower_platform.bmi", "windio_small.yaml")
for path in INPUTS:
    if path.name not in FLUTTER_RUNS and path.name not in EITHER:
        EXPECTED_ERRORS[path.name, "flutter"] = ""
#: a plan runs its cases on a Dask cluster: tests/test_batch.py runs plans
SKIP = {(name, "batch") for name in PLANS}


def run(argv: list[str], capsys) -> tuple[int, str, str]:
    code = main(argv)
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def check(code: int, err: str, name: str, command: str) -> None:
    if name in EITHER and code == 2 or (name, command) in EXPECTED_ERRORS:
        assert code == 2, f"{name} {command}: expected a one-line error, got exit {code}"
        assert err.startswith("bladefem: error: ") and err.count("\n") == 1, err
        field = EXPECTED_ERRORS.get((name, command))
        if field:
            assert f"field '{field}'" in err, err
    else:
        assert code == 0, f"{name} {command}: exit {code}: {err}"


def test_the_walk_covers_every_command_and_every_kind_of_input():
    assert set(COMMAND_ARGS) | {"verify"} == set(COMMANDS)           # verify takes no input (tests/test_verify.py)
    assert SPECS and PLANS
    names = {path.name for path in INPUTS}
    assert {"uniform_blade.yaml", "nrel5mw_tower.yaml", MAIN.name, "NRELOffshrBsline5MW_Blade.dat",
            "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat", "bmodes_blade.bmi", "bmodes_tower_wires.bmi",
            "windio_small.yaml", "nrel5mw_check.yaml"} <= names


@pytest.mark.slow
@pytest.mark.parametrize("command", list(COMMAND_ARGS))
@pytest.mark.parametrize("path", INPUTS, ids=[path.name for path in INPUTS])
def test_every_command_on_every_input(path, command, tmp_path, capsys):
    if (path.name, command) in SKIP:
        pytest.skip("a batch plan runs on Dask: tests/test_batch.py")
    argv = [command, str(path)] + [a.format(out=tmp_path / "out") for a in COMMAND_ARGS[command]]
    code, _, err = run(argv, capsys)
    check(code, err, path.name, command)


@pytest.mark.slow
@pytest.mark.parametrize("command", MODEL_COMMANDS)
@pytest.mark.parametrize("argv", [
    ["cases/nrel5mw/NRELOffshrBsline5MW_Blade.dat", "--elastodyn-main", str(MAIN)],
    ["cases/nrel5mw/NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat", "--elastodyn-main", str(MAIN)],
    [str(MAIN), "--part", "tower"],
], ids=["blade file with main", "tower file with main", "main file, tower"])
def test_files_that_need_their_main_file_work_with_it(argv, command, tmp_path, capsys):
    argv = [argv[0] if Path(argv[0]).is_absolute() else str(ROOT / argv[0]), *argv[1:]]
    extra = [a.format(out=tmp_path / "out") for a in COMMAND_ARGS[command]]
    code, _, err = run([command, *argv, *extra], capsys)
    assert code == 0, err
