"""``bladefem turbine``: linearize, Campbell and simulate from an ElastoDyn main file, checked on content; options an
action would ignore are refused, user mistakes are one-line errors naming the field (exit code 2). The subcommand
is exercised through its own parser registration."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import Parser
from bladefem.cli import turbine as turbine_cli
from bladefem.errors import InputError
from bladefem.builders.turbine_elastodyn import turbine_from_elastodyn
from bladefem.models.turbine import TurbineModel
from bladefem.models.turbine.linearize import linearize

MAIN = str(Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat")
ED = ("--elastodyn-compatible",)


def run(*argv: str) -> int:
    parser = Parser(prog="bladefem")
    turbine_cli.add_parser(parser.add_subparsers(dest="command", required=True, parser_class=Parser))
    args = parser.parse_args(["turbine", *argv])
    return args.run(args)


def test_linearize_prints_the_parked_modes(capsys):
    """The table holds the same modes as the library's parked linearization of the deck with the generator
    locked (GenDOF=off)."""
    assert run(MAIN, *ED, "--linearize", "--rpm", "0", "--dof", "GenDOF=off") == 0
    out = capsys.readouterr().out
    model = TurbineModel(turbine_from_elastodyn(MAIN, "polynomial", elastodyn_compatible=True))
    free = np.ones(model.n, dtype=bool)
    free[model.dofs.index("generator_azimuth")] = False
    assert "parked at azimuth 0 deg" in out and "15 free DOFs" in out
    for mode in linearize(model, free, 0.0).modes:
        line = next(line for line in out.splitlines() if line.startswith(mode.name + " "))
        assert float(line[45:61]) == pytest.approx(mode.frequency_hz, abs=5e-5)
        assert float(line[61:74]) == pytest.approx(100 * mode.damping_ratio, abs=5e-4)


def test_linearize_json_schema(tmp_path):
    path = tmp_path / "modes.json"
    assert run(MAIN, *ED, "--linearize", "--rpm", "0", "--azimuth-deg", "30", "--dof", "tower1", "flap1", "--json",
               "--output", str(path)) == 0
    data = json.loads(path.read_text())
    assert set(data) == {"rpm", "azimuth_deg", "modes"}
    assert data["rpm"] == 0.0 and data["azimuth_deg"] == pytest.approx(30.0)
    assert [m["name"] for m in data["modes"]][:2] == ["1st tower side-side", "1st tower fore-aft"]
    for mode in data["modes"]:
        assert set(mode) == {"name", "frequency_hz", "damping_ratio", "oscillating", "participation"}
        assert 0.98 < sum(mode["participation"].values()) <= 1 + 1e-6
        assert set(mode["participation"]) <= {"tower_fa1", "tower_ss1", "collective_flap1", "cosine_flap1",
                                              "sine_flap1"}


def test_campbell_uses_start_stop_count(tmp_path, capsys):
    """Issue 10, defect 6: 0:12:3 means 3 speeds, 0, 6 and 12 rpm (as ``campbell --rpm``); JSON: one linearization
    per speed, the parked one at the deck's azimuth and the spinning ones averaged (azimuth null)."""
    table = tmp_path / "campbell.csv"
    assert run(MAIN, *ED, "--campbell", "0:12:3", "--dof", "flap1", "--output", str(table)) == 0
    lines = table.read_text().splitlines()
    assert [float(line.split(",")[0]) for line in lines[1:]] == [0.0, 6.0, 12.0]
    header = lines[0].split(",")
    assert "1st blade collective flap [Hz]" in header
    assert "1st blade asymmetric flap (backward whirl) [Hz]" in header
    capsys.readouterr()
    assert run(MAIN, *ED, "--campbell", "0:12:3", "--dof", "flap1", "--json") == 0
    data = json.loads(capsys.readouterr().out)
    assert [d["rpm"] for d in data] == [0.0, 6.0, 12.0]
    assert data[0]["azimuth_deg"] == 0.0 and data[1]["azimuth_deg"] is None
    single = {m["name"]: m["frequency_hz"] for m in data[2]["modes"]}
    backward = single["1st blade asymmetric flap (backward whirl)"]
    forward = single["1st blade asymmetric flap (forward whirl)"]
    assert forward - backward == pytest.approx(2 * 12 / 60, rel=0.05)        # -+ Omega, split by precone/gravity


def test_simulate_writes_a_table_and_a_plot(tmp_path):
    table, figure = tmp_path / "out.csv", tmp_path / "out.png"
    assert run(MAIN, *ED, "--simulate", "1", "--dof", "tower1", "--initial", "TTDspFA=0.2", "--output", str(table),
               "--plot", str(figure)) == 0
    header = table.read_text().splitlines()[0].split(",")
    data = np.loadtxt(table, delimiter=",", skiprows=1)
    assert header[:5] == ["Time_s", "OoPDefl1_m", "IPDefl1_m", "TTDspFA_m", "TTDspSS_m"]
    np.testing.assert_allclose(data[:, 0], np.arange(21) * 0.05, atol=1e-12)          # the output step exactly
    assert data[0, header.index("TTDspFA_m")] == pytest.approx(0.2, rel=1e-12)         # a tip displacement, m
    np.testing.assert_allclose(data[:, header.index("RotSpeed_rpm")], 12.1)             # generator locked
    # the released tower swings back through zero within half a period of its 0.32 Hz mode
    assert data[:, header.index("TTDspFA_m")].min() < 0.05
    assert figure.stat().st_size > 10_000
    assert not list(tmp_path.glob(".tmp-*"))


@pytest.mark.parametrize("dt, rows", [("0.3", [0.0, 0.3, 0.6, 0.9]), ("0.25", [0.0, 0.25, 0.5, 0.75, 1.0])])
def test_output_step_is_honoured(tmp_path, dt, rows):
    """Issue 10, defect 2: rows exactly dt apart, up to the simulated time."""
    table = tmp_path / "out.csv"
    assert run(MAIN, *ED, "--simulate", "1", "--dof", "tower1", "--dt", dt, "--output", str(table)) == 0
    np.testing.assert_allclose(np.loadtxt(table, delimiter=",", skiprows=1)[:, 0], rows, atol=1e-12)


def test_initial_names_are_one_consistent_set(tmp_path):
    """Issue 10, defect 1: every name the error message offers is accepted; angles are NAME_deg."""
    with pytest.raises(InputError) as error:
        run(MAIN, *ED, "--simulate", "1", "--initial", "generator_azimuth=10")
    assert "generator_azimuth_deg" in str(error.value)
    with pytest.raises(InputError) as error:
        run(MAIN, *ED, "--simulate", "1", "--initial", "nonsense=1")
    offered = str(error.value).split("one of ")[1].rstrip(")").split(", ")
    dofs = TurbineModel(turbine_from_elastodyn(MAIN, "polynomial", elastodyn_compatible=True)).dofs
    for name in offered:
        conditions, coordinates = turbine_cli.parse_initial([f"{name}=1"], dofs)
        assert len(conditions) + len(coordinates) == 1, name
    table = tmp_path / "out.csv"
    assert run(MAIN, *ED, "--simulate", "0.1", "--dof", "yaw", "generator", "--initial", "yaw_deg=2",
               "generator_azimuth_deg=30", "--output", str(table)) == 0
    header = table.read_text().splitlines()[0].split(",")
    first = np.loadtxt(table, delimiter=",", skiprows=1)[0]
    assert first[header.index("YawPzn_deg")] == pytest.approx(2.0)
    assert first[header.index("Azimuth_deg")] == pytest.approx(30.0)


def test_rk4_beyond_its_stability_limit_is_refused():
    """Issue 10, defect 3: a fixed step the fastest mode cannot take (the nacelle yaw at 6.1 Hz: RK4 needs
    h < 2.8 / (2 pi 6.1) = 0.073 s) is refused with the limit, not integrated into a blow-up."""
    for step in ("0.1", "0.08"):
        with pytest.raises(InputError) as error:
            run(MAIN, *ED, "--simulate", "5", "--method", "RK4", "--step", step)
        assert error.value.field == "--step" and "unstable" in str(error.value) and "yaw" in str(error.value)


@pytest.mark.parametrize("method", [(), ("--method", "DP54"), ("--method", "auto")])
def test_step_without_rk4_is_refused(method):
    """--step sets only RK4's step: with another method (or none, auto) it would be ignored, so it is refused."""
    with pytest.raises(InputError) as error:
        run(MAIN, *ED, "--simulate", "1", *method, "--step", "0.01")
    assert error.value.field == "--step" and "--method RK4" in str(error.value)


@pytest.mark.parametrize("argv, field", [
    (["--simulate", "-1"], "--simulate"),
    (["--simulate", "1", "--initial", "nonsense=1"], "--initial"),
    (["--simulate", "1", "--initial", "tower_fa1=abc"], "--initial"),
    (["--simulate", "1", "--initial", "yaw=3"], "--initial"),
    (["--simulate", "1", "--dt", "2"], "--dt"),
    (["--simulate", "1", "--json"], "--json"),
    (["--simulate", "1", "--azimuth-deg", "30"], "--azimuth-deg"),
    (["--linearize", "--dof", "rotor"], "--dof"),
    (["--linearize", "--dof", "GenDOF=maybe"], "--dof"),
    (["--linearize", "--plot", "x.png"], "--plot"),
    (["--linearize", "--initial", "TTDspFA=0.1"], "--initial"),
    (["--linearize", "--dt", "0.1"], "--dt"),
    (["--campbell", "0:10:3", "--method", "RK4"], "--method"),
    (["--linearize", "--rpm", "-3"], "--rpm"),
    (["--linearize", "--shapes", "fe"], "--shapes"),
    (["--linearize", "--damping", "rna"], "--damping"),
    (["--simulate", "1e6"], "--simulate"),                          # beyond a day of turbine time
    (["--simulate", "1000", "--dt", "1e-4"], "--dt"),               # 1e7 output rows
    (["--simulate", "1", "--plot", "x.txt"], "--plot"),             # no figure format
])
def test_user_mistakes_name_the_field(argv, field):
    with pytest.raises(InputError) as error:
        run(MAIN, *ED, *argv)
    assert error.value.field == field
    assert "\n" not in str(error.value)


def test_campbell_range_is_checked_by_the_parser(capsys):
    for text in ("5:1:3", "0:15:1.5", "0:15"):
        with pytest.raises(SystemExit) as exit:
            run(MAIN, "--campbell", text)
        assert exit.value.code == 2
    assert "START:STOP:COUNT" in capsys.readouterr().err


def test_campbell_sweep_is_bounded_by_the_parser(capsys):
    with pytest.raises(SystemExit) as exit:
        run(MAIN, "--campbell", "0:15:1001")
    assert exit.value.code == 2 and "COUNT <= 1000" in capsys.readouterr().err


@pytest.mark.parametrize("option", ["--output", "--plot"])
def test_unwritable_outputs_are_refused_before_the_run(tmp_path, monkeypatch, option):
    """A folder where the table or the figure should go is refused before the model is built."""
    monkeypatch.setattr(turbine_cli, "build_model", lambda args: pytest.fail("the model was built"))
    folder = tmp_path / "taken.png"
    folder.mkdir()
    with pytest.raises(InputError) as error:
        run(MAIN, "--simulate", "100", option, str(folder))
    assert "taken.png" in str(error.value) and "folder" in str(error.value)


def test_missing_main_file_is_an_input_error(tmp_path):
    with pytest.raises(InputError) as error:
        run(str(tmp_path / "missing.dat"), "--linearize")
    assert "missing.dat" in str(error.value)


def test_model_reduction_example_runs(tmp_path):
    """The example's pipeline on a short record: both models run from the same state; the reduced model (tower
    first modes and first flap only) keeps the side-side motion's mean and misses part of its fluctuation."""
    import importlib.util
    path = Path(__file__).resolve().parents[1] / "examples" / "model_reduction.py"
    spec = importlib.util.spec_from_file_location("model_reduction", path)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    text = example.main(tmp_path, seconds=3.0)
    assert "RMS of the fluctuation" in text
    assert (tmp_path / "model_reduction.png").stat().st_size > 10_000
    data = np.loadtxt(tmp_path / "tower_side_side.csv", delimiter=",", skiprows=1)
    assert data.shape == (61, 3)
    np.testing.assert_allclose(data[:, 0], np.arange(61) * 0.05, atol=1e-12)
    assert data[0, 1] == data[0, 2] == 0.0                           # the same initial state, no side-side offset
    full, reduced = data[:, 1], data[:, 2]
    assert np.ptp(full) > 1e-3 and np.ptp(reduced) > 1e-4 and not np.allclose(full, reduced, atol=1e-4)
    assert math.isfinite(float(text.split("RMS of the difference between the two histories: ")[1].split(" m")[0]))


def test_the_turbine_command_holds_blas_to_one_thread(monkeypatch):
    """The turbine command's matrices are small, and OpenBLAS's threads only spin on the other core
    (bladefem/cli/threads.py): while it runs, every loaded BLAS library is held to one thread (here from a limit of
    two), and the limit is given back after it."""
    from threadpoolctl import threadpool_info, threadpool_limits
    seen = []

    def build_model(args):
        seen.extend(info["num_threads"] for info in threadpool_info() if info["user_api"] == "blas")
        raise InputError("stopped after the limit was seen")

    monkeypatch.setattr(turbine_cli, "build_model", build_model)
    with threadpool_limits(limits=2, user_api="blas"):
        with pytest.raises(InputError, match="stopped after the limit was seen"):
            run(MAIN, "--linearize")
        after = [info["num_threads"] for info in threadpool_info() if info["user_api"] == "blas"]
    assert seen and set(seen) == {1}
    assert after and set(after) == {2}
