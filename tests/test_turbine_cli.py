"""``bladefem turbine``: linearize, Campbell and simulate from an ElastoDyn main file; user mistakes are one-line
errors naming the field (exit code 2). The subcommand is exercised through its own parser registration."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import Parser
from bladefem.cli import turbine as turbine_cli
from bladefem.errors import InputError

MAIN = str(Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat")


def run(*argv: str) -> int:
    parser = Parser(prog="bladefem")
    turbine_cli.add_parser(parser.add_subparsers(dest="command", required=True, parser_class=Parser))
    args = parser.parse_args(["turbine", *argv])
    return args.run(args)


def test_linearize_prints_named_modes(capsys):
    assert run(MAIN, "--linearize", "--rpm", "0", "--shapes", "polynomial", "--dof", "tower1", "flap1") == 0
    out = capsys.readouterr().out
    for name in ("1st tower fore-aft", "1st tower side-side", "1st blade collective flap"):
        assert name in out


def test_simulate_writes_a_table_and_a_plot(tmp_path):
    table, figure = tmp_path / "out.csv", tmp_path / "out.png"
    assert run(MAIN, "--simulate", "1", "--shapes", "polynomial", "--dof", "tower1", "--initial", "tower_fa1=0.2",
               "--output", str(table), "--plot", str(figure)) == 0
    header = table.read_text().splitlines()[0].split(",")
    data = np.loadtxt(table, delimiter=",", skiprows=1)
    assert header[:5] == ["Time_s", "OoPDefl1_m", "IPDefl1_m", "TTDspFA_m", "TTDspSS_m"]
    assert data[0, header.index("TTDspFA_m")] == pytest.approx(0.2, rel=1e-2)   # polynomial tip sum 1 +- 1e-3
    np.testing.assert_allclose(data[:, header.index("RotSpeed_rpm")], 12.1)     # generator locked
    assert figure.stat().st_size > 10_000
    assert not list(tmp_path.glob(".tmp-*"))


def test_campbell_table(tmp_path):
    table = tmp_path / "campbell.csv"
    assert run(MAIN, "--campbell", "0:12:6", "--shapes", "polynomial", "--dof", "flap1", "--output", str(table)) == 0
    lines = table.read_text().splitlines()
    assert len(lines) == 4 and "1st blade collective flap [Hz]" in lines[0]


@pytest.mark.parametrize("argv, field", [
    (["--simulate", "-1"], "--simulate"),
    (["--simulate", "1", "--initial", "nonsense=1"], "--initial"),
    (["--simulate", "1", "--initial", "tower_fa1=abc"], "--initial"),
    (["--simulate", "1", "--initial", "yaw=3"], "--initial"),
    (["--linearize", "--dof", "rotor"], "dof"),
    (["--campbell", "5:1:1"], "--campbell"),
    (["--linearize", "--rpm", "-3"], "--rpm"),
])
def test_user_mistakes_name_the_field(argv, field):
    with pytest.raises(InputError) as error:
        run(MAIN, "--shapes", "polynomial", *argv)
    assert error.value.field == field
    assert "\n" not in str(error.value)


def test_missing_main_file_is_an_input_error(tmp_path):
    with pytest.raises(InputError) as error:
        run(str(tmp_path / "missing.dat"), "--linearize")
    assert "missing.dat" in str(error.value)


def test_model_reduction_example_runs(tmp_path):
    """The example's pipeline on a short record: both models run, the summary quantifies the side-side response."""
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
