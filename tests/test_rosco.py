"""The ROSCO controller (ServoDyn's Bladed-style DLL, PCMode and VSContrl 5): the pitch set on the compiled kernels
against models built at that pitch, the controller run against OpenFAST v5 with the same library, the IEA decks run
with their own DISCON settings, and the errors of a bad library, input file or demand.

ROSCO's library comes from its wheel (``pip install --no-deps rosco==2.10.6``, the README's test command)."""

from __future__ import annotations

import json
import math
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.controller import rosco_library
from bladefem.builders.turbine_deck import read_turbine_deck
from bladefem.cli import main
from bladefem.models.turbine import TurbineModel
from bladefem.models.turbine.pitching import CompiledPitch
from deck_copies import deck_copy as iea_copy
from simulation_table import table

ROOT = Path(__file__).resolve().parents[1]
CASE = ROOT / "cases" / "nrel5mw"
DECK = CASE / "NRELOffshrBsline5MW_Onshore_ROSCO.fst"
REFERENCE = ROOT / "tests" / "data" / "openfast" / "rosco" / "steady.json"
TRANSIENT = REFERENCE.with_name("transient.json")

pytestmark = pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="controlled runs need numba")


def run(capsys, *argv: object) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def deck_copy(tmp_path: Path) -> Path:
    """The NREL 5MW ROSCO case in a temporary folder (to edit)."""
    folder = tmp_path / "nrel5mw"
    shutil.copytree(CASE, folder)
    return folder / DECK.name


def replace(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new))


def test_rosco_library_is_found_without_importing_rosco():
    """The installed wheel's library is found by its package's location (ROSCO's own imports need wisdem)."""
    library = rosco_library()
    assert library is not None and library.name.startswith("libdiscon") and library.is_file()


@pytest.mark.parametrize("shapes", ["polynomial", "fe"])
def test_pitch_on_the_kernels_equals_the_model_built_at_that_pitch(shapes):
    """A model built at pitch 0 and pitched to 12 deg on the compiled arrays gives the mass matrix and forcing of
    the model built at 12 deg: to rounding with ElastoDyn's polynomial shapes (the turn is exact); with bladefem's
    FE shapes (solved at the rotor speed with the pitched section stiffness) to 1e-3 of the forcing's largest entry
    (measured 2e-4): the centrifugal softening of the plane of rotation makes the FE modes depend slightly on the
    pitch, which the turn leaves out."""
    options = {"blade_shapes": shapes, "elastodyn_compatible": shapes == "polynomial",
               "gauss_points": 1 if shapes == "polynomial" else 2, "wind_speed": 16.0}
    base = read_turbine_deck(CASE / "NRELOffshrBsline5MW_Onshore.fst", pitch=0.0, **options)
    pitched = read_turbine_deck(CASE / "NRELOffshrBsline5MW_Onshore.fst", pitch=math.radians(12.0), **options)
    model = TurbineModel(base.params, aero=base.aero, generator=base.generator)
    other = TurbineModel(pitched.params, aero=pitched.aero, generator=pitched.generator)
    compiled, reference = model.fast_equations(), other.fast_equations()
    CompiledPitch(model, compiled).set(math.radians(12.0))
    rng = np.random.default_rng(3)
    q, u = 0.05 * rng.standard_normal(model.n), 0.1 * rng.standard_normal(model.n)
    u[5] = 12.1 * math.pi / 30
    M, f = compiled(q, u)
    M_ref, f_ref = reference(q, u)
    tolerance = 1e-9 if shapes == "polynomial" else 1e-3
    assert np.max(np.abs(f - f_ref)) < tolerance * np.max(np.abs(f_ref))
    assert np.max(np.abs(M - M_ref)) < tolerance * np.max(np.abs(M_ref))
    assert np.max(np.abs(f - model.fast_equations()(q, u)[1])) == 0.0


@pytest.fixture(scope="module")
def steady(tmp_path_factory):
    """bladefem's runs of the four OpenFAST cases (150 s each, the same initial rotor speed and pitch)."""
    data = json.loads(REFERENCE.read_text())
    folder = tmp_path_factory.mktemp("rosco")
    tables = {}
    for wind, initial in data["provenance"]["initial"].items():
        out = folder / f"bf_{wind}.csv"
        code = main(["turbine", str(DECK), "--simulate", "150", "--wind-speed", wind, "--initial",
                     f"RotSpeed={initial['RotSpeed_rpm']}", "--pitch-deg", str(initial["BlPitch_deg"]), "--quiet",
                     "-o", str(out)])
        assert code == 0
        tables[wind] = table(out)
    return data, tables, folder


@pytest.mark.parametrize("wind", ["8", "11.4", "16", "20"])
def test_rosco_steady_operation_against_openfast(steady, wind):
    """ROSCO 2.10.6 on the NREL 5MW in steady wind, bladefem against OpenFAST v5.0.0 with the same library, deck
    and start: means over 100-150 s of generator power, rotor speed, rotor thrust and blade-tip out-of-plane
    deflection within 2 %, blade pitch within 0.5 deg (measured figures in docs/turbine-aero.md)."""
    data, tables, _ = steady
    ours, theirs = tables[wind], data["cases"][wind]
    window = ours["Time"] >= data["window_s"][0] - 1e-9
    assert np.mean(ours["BldPitch1"][window]) == pytest.approx(theirs["BldPitch1"]["mean"], abs=0.5)
    for name in ("GenPwr", "RotSpeed", "RotThrust", "OoPDefl1"):
        assert np.mean(ours[name][window]) == pytest.approx(theirs[name]["mean"], rel=0.02), name


@pytest.mark.parametrize("wind", ["8", "11.4", "16", "20"])
def test_rosco_start_transient_follows_openfast(steady, wind):
    """The first 60 s from the schedule's rotor speed and pitch (the controller's filters, wind-speed estimator and
    integrators settling, the rotor and blades swinging up), bladefem against OpenFAST every 0.1 s: rotor speed within
    0.05 rpm, pitch within 0.05 deg, and every channel that moves correlated above 0.99 with OpenFAST's (measured
    at 8-20 m/s: 0.004 to 0.011 rpm; 0.0035, 0.026, 0.009 deg above 8 m/s; correlations 0.997 to 0.99999). The
    pitch bound holds a row at a controller call to the call's new demand, as OpenFAST's rows are: with the demand
    held over the interval before (one interval late) the pitch differed by 0.062 deg at 11.4 m/s."""
    history = json.loads(TRANSIENT.read_text())["cases"][wind]
    ours = steady[1][wind]
    times = np.array(history["Time"])
    for name in ("RotSpeed", "BldPitch1", "GenPwr", "RotThrust", "OoPDefl1"):
        mine, theirs = np.interp(times, ours["Time"], ours[name]), np.array(history[name])
        if name in ("RotSpeed", "BldPitch1"):
            assert np.max(np.abs(mine - theirs)) < 0.05, name
        if np.ptp(theirs) > 0:
            a, b = mine - mine.mean(), theirs - theirs.mean()
            assert a @ b / np.sqrt((a @ a) * (b @ b)) > 0.99, name


def test_the_comparison_example_writes_its_table_and_figure(steady, tmp_path):
    """examples/rosco_against_openfast.py on the runs of the fixture: the table of docs/turbine-aero.md (one row
    per wind speed and channel) and the figure."""
    import subprocess
    import sys
    completed = subprocess.run([sys.executable, str(ROOT / "examples" / "rosco_against_openfast.py"), str(tmp_path),
                                "--tables", str(steady[2])], capture_output=True, text=True, timeout=600,
                               env={**os.environ, "MPLBACKEND": "Agg"})
    assert completed.returncode == 0, completed.stderr
    rows = [line for line in completed.stdout.splitlines() if line.startswith("| ") and "[" in line
            and "channel" not in line]
    assert len(rows) == 20 and (tmp_path / "rosco-transient.png").stat().st_size > 10_000


def test_controller_runs_alone_per_simulation(capsys, tmp_path):
    """Two runs of the same case in one process give the same table: each has its own library instance (ROSCO's
    filters and integrators live in the library's global state)."""
    outputs = []
    for k in range(2):
        out = tmp_path / f"run{k}.csv"
        code, _, _ = run(capsys, "turbine", DECK, "--simulate", "1", "--wind-speed", "16", "--pitch-deg", "10",
                         "--quiet", "-o", out)
        assert code == 0
        outputs.append(out.read_text())
    assert outputs[0] == outputs[1]
    data = table(tmp_path / "run0.csv")
    assert np.ptp(data["BldPitch1"]) > 0 and np.ptp(data["GenTq"]) > 0        # the controller acted


@pytest.mark.parametrize("deck, method", [
    ("iea15/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile.fst", ("--method", "RK4", "--step", "0.005")),
    ("iea22/IEA-22-280-RWT-Monopile/IEA-22-280-RWT-Monopile.fst", ())])
def test_iea_decks_run_with_their_own_rosco_settings(capsys, tmp_path, deck, method):
    """The IEA-15MW and IEA-22MW monopile decks (rigid foundation, quasi-steady, the IEA-22's ElastoDyn blades)
    run 2 s with their DISCON.IN
    (DLL_FileName names a libdiscon.so elsewhere: the installed ROSCO's is taken); the pitch and torque move. The
    IEA-15MW from its undeflected start with ElastoDyn's fixed step (the adaptive step collapses in its start-up
    transient, docs/turbine-aero.md), as the controller's interval allows."""
    fst = iea_copy(Path(deck).parts[0], tmp_path) / Path(*Path(deck).parts[1:])
    out = tmp_path / "out.csv"
    code, _, err = run(capsys, "turbine", fst, "--simulate", "2", "--foundation", "rigid", "--quasi-steady",
                       "--elastodyn-blades", "--wind-speed", "12", "--quiet", "-o", out, *method)
    assert code == 0, err
    data = table(out)
    assert np.ptp(data["GenTq"]) > 0 and np.all(np.isfinite(data["BldPitch1"]))


def test_missing_library_names_the_servodyn_line(capsys, tmp_path):
    """A DLL_FileName that is not there (and not ROSCO's name) is refused with its file, line and the option."""
    fst = deck_copy(tmp_path)
    replace(fst.parent / "NRELOffshrBsline5MW_Onshore_ROSCO_ServoDyn.dat", '"libdiscon.so"', '"mycontroller.so"')
    code, _, err = run(capsys, "turbine", fst, "--simulate", "1", "--quiet")
    assert code == 2 and "mycontroller.so" in err and "DLL_FileName" in err and "--discon-library" in err
    assert "Traceback" not in err


def test_a_file_that_is_no_library_is_refused(capsys, tmp_path):
    """--discon-library pointing at a text file: the library cannot be loaded; exit 2, no traceback."""
    code, _, err = run(capsys, "turbine", DECK, "--simulate", "1", "--quiet", "--discon-library",
                       CASE / "Cp_Ct_Cq.NREL5MW.txt")
    assert code == 2 and "could not be loaded" in err and "Traceback" not in err


def test_bad_discon_input_is_an_input_error(capsys, tmp_path):
    """A DISCON.IN whose performance table is missing: ROSCO fails on its first call (aviFAIL < 0); the message
    names the input file and exit 2."""
    fst = deck_copy(tmp_path)
    (fst.parent / "Cp_Ct_Cq.NREL5MW.txt").unlink()
    code, _, err = run(capsys, "turbine", fst, "--simulate", "1", "--quiet")
    assert code == 2 and "DISCON.IN" in err and "Traceback" not in err


def test_individual_pitch_is_refused_while_running(capsys, tmp_path):
    """ROSCO's individual pitch control on (Ptch_Cntrl 1, IPC_ControlMode 1, an integral gain): in sheared wind,
    as soon as the blades' demands
    differ the run stops, exit 1, naming what is not modelled and keeping the rows so far."""
    fst = deck_copy(tmp_path)
    replace(fst.parent / "NRELOffshrBsline5MW_Onshore_ROSCO_ServoDyn.dat", "          0   Ptch_Cntrl",
            "          1   Ptch_Cntrl")
    discon = fst.parent / "NRELOffshrBsline5MW_Onshore_ROSCO_DISCON.IN"
    replace(discon, "0                   ! IPC_ControlMode", "1                   ! IPC_ControlMode")
    replace(discon, "0.000e+00    0.000e+00    ! IPC_KI", "1.000e-08    0.000e+00    ! IPC_KI")
    out = tmp_path / "out.csv"
    code, _, err = run(capsys, "turbine", fst, "--simulate", "20", "--wind-speed", "16", "--pitch-deg", "10",
                       "--shear-exp", "0.2", "--quiet", "-o", out)
    assert code == 1 and "individual pitch" in err and out.is_file()


def test_dll_ramp_is_refused(capsys, tmp_path):
    """DLL_Ramp True (a linear ramp between calls) is not modelled: refused at its line."""
    fst = deck_copy(tmp_path)
    replace(fst.parent / "NRELOffshrBsline5MW_Onshore_ROSCO_ServoDyn.dat", "False         DLL_Ramp",
            "True          DLL_Ramp")
    code, _, err = run(capsys, "turbine", fst, "--simulate", "1", "--quiet")
    assert code == 2 and "DLL_Ramp" in err


def test_controller_interval_from_the_command_line(capsys, tmp_path):
    """--controller-dt replaces ServoDyn's DLL_DT (a deck whose DLL_DT is 'default' calls the library every DT,
    0.0002 s in the IEA-22MW's monopile deck): the torque demand then changes only at its calls, every 0.02 s
    here, sampled every 0.005 s (a row at a call's time has its new demand); the deck's own interval (DLL_DT
    'default': its DT, 0.00625 s) changes it at nearly every row."""
    held = tmp_path / "held.csv"
    code, _, err = run(capsys, "turbine", DECK, "--simulate", "1", "--wind-speed", "11.4", "--dt", "0.005",
                       "--controller-dt", "0.02", "--quiet", "-o", held)
    assert code == 0, err
    assert "called every 0.02 s (--controller-dt)" in err
    torque = table(held)["GenTq"]
    changes = np.flatnonzero(np.abs(np.diff(torque)) > 1e-6 * np.abs(torque[1:])) + 1     # the demand moved
    assert len(changes) > 10 and np.all(np.mod(changes, 4) == 0)     # at each call (rows 0.02 s apart)
    deck_rows = tmp_path / "deck.csv"
    code, _, err = run(capsys, "turbine", DECK, "--simulate", "1", "--wind-speed", "11.4", "--dt", "0.005",
                       "--quiet", "-o", deck_rows)
    assert code == 0 and "called every 0.00625 s (DLL_DT 'default': the deck's DT" in err
    torque = table(deck_rows)["GenTq"]
    assert np.count_nonzero(np.abs(np.diff(torque)) > 1e-6 * np.abs(torque[1:])) > 2 * len(changes)


@pytest.mark.parametrize("argv", [("--controller-dt", "0"), ("--controller-dt", "-1"), ("--controller-dt", "nan")])
def test_controller_interval_must_be_positive(capsys, argv):
    code, _, err = run(capsys, "turbine", DECK, "--simulate", "1", "--quiet", *argv)
    assert code == 2 and "--controller-dt" in err and "Traceback" not in err


def test_controller_interval_needs_a_controller(capsys):
    """Held at --rpm, the deck runs no controller library: --controller-dt is refused, naming itself."""
    code, _, err = run(capsys, "turbine", DECK, "--simulate", "1", "--rpm", "12.1", "--quiet",
                       "--controller-dt", "0.01")
    assert code == 2 and "--controller-dt" in err and "Bladed-style DLL" in err


def test_the_first_call_check_is_silent_unless_it_fails(capfd, tmp_path):
    """The first call is made first in an isolated twin of the library (a crash there is reported, not suffered):
    what that twin prints is held back (``echo`` False) and shown only when it fails. The twin's process prints
    ROSCO's banner with echo, nothing without; a run whose DISCON.IN names a missing performance table shows the
    twin's Fortran runtime error naming that file, exit 2."""
    from bladefem.builders.controller import controller_setup
    from bladefem.models.turbine.discon import DisconController, Measurements

    setup = controller_setup(read_turbine_deck(DECK, controller=True), None)
    state = Measurements(pitch=np.zeros(3), rotor_speed=1.27, generator_speed=122.9, wind_speed=11.4, azimuth=0.0,
                         shaft_power=5.3e6, generator_torque=4.3e4, electrical_power=5.0e6, root_oop=np.zeros(3),
                         root_ip=np.zeros(3))
    printed = {}
    for echo in (True, False):
        with DisconController(setup, isolated=True, echo=echo) as twin:
            twin.call(0.0, state)
        printed[echo] = capfd.readouterr().err                    # the twin's process has ended: all flushed
    assert printed[True].strip() and not printed[False].strip()
    fst = deck_copy(tmp_path)
    (fst.parent / "Cp_Ct_Cq.NREL5MW.txt").unlink()
    code = main(["turbine", str(fst), "--simulate", "1", "--quiet"])
    err = capfd.readouterr().err
    assert code == 2 and "Cp_Ct_Cq.NREL5MW.txt" in err and "Traceback" not in err


def test_the_table_on_stdout_is_the_table_alone(tmp_path):
    """A run writing its table to stdout: what the library prints (ROSCO's banner, through gfortran's buffered
    units and C's stdio) goes to stderr while it is loaded and is flushed there before stdout is given back, so the
    table is whole and alone; before, the buffered prints were written at the process's end, onto the table."""
    import subprocess
    import sys
    redirected = tmp_path / "table.csv"                    # stdout to a file, as `> table.csv` does
    with redirected.open("w") as stdout:
        done = subprocess.run([sys.executable, "-m", "bladefem", "turbine", str(DECK), "--simulate", "0.2",
                               "--wind-speed", "11.4", "--quiet"], stdout=stdout, stderr=subprocess.PIPE,
                              text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    lines = [line for line in redirected.read_text().splitlines() if not line.startswith("#")]  # notes aside
    columns = lines[0].count(",")
    assert len(lines) == 6 and all(line.count(",") == columns for line in lines)   # header and rows 0-0.2 s
    assert len(done.stderr.splitlines()) > 3                                      # the library's prints are there
