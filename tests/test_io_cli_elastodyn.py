"""The ``bladefem elastodyn`` subcommand: report, dry-run diff, in-place update, any input format, user errors."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import Parser
from bladefem.cli import elastodyn as command
from bladefem.errors import InputError
from bladefem.io.elastodyn_blade import read_elastodyn_blade
from bladefem.io.elastodyn_tower import read_elastodyn_tower

DATA = Path(__file__).parent / "data"
NAMES = ("NRELOffshrBsline5MW_Onshore_ElastoDyn.dat", "NRELOffshrBsline5MW_Blade.dat",
         "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat")


def run(argv: list[str], capsys) -> tuple[int, str, str]:
    """Parse and run like ``bladefem.cli.main``: InputError -> one line on stderr and exit code 2."""
    parser = Parser(prog="bladefem")
    command.add_parser(parser.add_subparsers(dest="command", required=True, parser_class=Parser))
    args = parser.parse_args(["elastodyn", *argv])
    try:
        code = args.run(args)
    except InputError as error:
        print(f"bladefem: error: {error}", file=__import__("sys").stderr)
        code = 2
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture()
def model(tmp_path: Path) -> Path:
    for name in NAMES:
        shutil.copy(DATA / name, tmp_path / name)
    return tmp_path


def test_dry_run_shows_a_diff_and_writes_nothing(model, capsys):
    blade = model / NAMES[1]
    before = blade.read_bytes()
    code, out, _ = run([str(model / NAMES[0]), "--write", str(blade), "--dry-run"], capsys)
    assert code == 0 and blade.read_bytes() == before
    assert "flap1" in out and "ElastoDyn_Hz" in out and f"coefficients in {blade}" in out
    removed = [line for line in out.splitlines() if line.startswith("-") and "Sh(" in line]
    added = [line for line in out.splitlines() if line.startswith("+") and "Sh(" in line]
    assert len(removed) == len(added) == 15 and "+++" in out


def test_write_updates_only_the_coefficient_lines(model, capsys):
    blade = model / NAMES[1]
    before = blade.read_text().splitlines(keepends=True)
    code, out, _ = run([str(model / NAMES[0]), "--rpm", "12.1", "--write", str(blade)], capsys)
    assert code == 0
    after = blade.read_text().splitlines(keepends=True)
    changed = [i + 1 for i, (a, b) in enumerate(zip(before, after)) if a != b]
    assert len(before) == len(after) and changed == list(range(67, 82))
    updated = read_elastodyn_blade(blade)
    printed = [line for line in out.splitlines() if "BldFl1Sh(" in line and " - " in line]
    assert [float(line.split()[0]) for line in printed] == updated.modes["flap1"].tolist()
    # written with 10 decimals: the constraint holds in the file to the last written digit
    assert abs(updated.modes["flap1"].sum() - 1) < 1e-12


def test_tower_coefficients_from_the_main_file(model, capsys):
    tower = model / NAMES[2]
    code, out, _ = run([str(model / NAMES[0]), "--write", str(tower)], capsys)
    assert code == 0 and "fa1" in out and "ss2" in out and "# warning: tower fore-aft 2" in out
    updated = read_elastodyn_tower(tower)
    assert np.allclose(updated.modes["fa1"], updated.modes["ss1"], atol=1e-9)


def test_other_input_formats(capsys):
    code, out, _ = run([str(DATA / "bmodes_blade.bmi")], capsys)
    assert code == 0 and "rotor speed 30 rpm" in out              # the deck's rot_rpm times rpm_mult
    code, out, _ = run([str(DATA / "windio_small.yaml"), "--rpm", "10", "--nodes", "50"], capsys)
    assert code == 0 and "BldEdgSh(6)" in out
    code, out, _ = run([str(DATA / "windio_small.yaml"), "--part", "tower"], capsys)
    assert code == 0 and "TwSSM2Sh(6)" in out
    for deck in ("bmodes_tower_plain.bmi", "bmodes_tower_wires.bmi"):     # towers found from the deck itself
        code, out, _ = run([str(DATA / deck)], capsys)
        assert code == 0 and "TwFAM1Sh(2)" in out and "tower (non-rotating)" in out
    code, _, err = run([str(DATA / "bmodes_tower_plain.bmi"), "--part", "blade"], capsys)
    assert code == 2 and "field '--part'" in err


@pytest.mark.parametrize(("argv", "field"), [
    (["{data}/NRELOffshrBsline5MW_Blade.dat"], "TipRad"),
    (["{data}/NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"], "TowerHt"),
    (["{data}/windio_small.yaml", "--dry-run"], "--dry-run"),
    (["{data}/windio_small.yaml"], "--rpm"),
    (["{data}/windio_small.yaml", "--rpm", "-3"], "--rpm"),
    (["{data}/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat", "--write", "{data}/windio_small.yaml"], "--write"),
    (["{data}/nowhere.dat"], None),
])
def test_user_errors_exit_with_code_2(argv, field, capsys):
    code, out, err = run([a.format(data=DATA) for a in argv], capsys)
    assert code == 2 and err.startswith("bladefem: error: ") and err.count("\n") == 1
    if field:
        assert f"field '{field}'" in err


def test_too_few_modes_is_a_user_error(capsys):
    code, _, err = run([str(DATA / "windio_small.yaml"), "--rpm", "5", "--n-modes", "2"], capsys)
    assert code == 2 and "field '--n-modes'" in err and "only" in err


def test_read_model_dispatches_every_format():
    from bladefem.io.detect import detect_format, read_model
    from bladefem.io.tower import Tower
    from bladefem.sections import Blade
    expected = {"NRELOffshrBsline5MW_Onshore_ElastoDyn.dat": "elastodyn-main",
                "NRELOffshrBsline5MW_Blade.dat": "elastodyn-blade",
                "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat": "elastodyn-tower",
                "bmodes_blade.bmi": "bmodes", "windio_small.yaml": "windio"}
    for name, kind in expected.items():
        assert detect_format(DATA / name) == kind
    assert isinstance(read_model(DATA / NAMES[0]), Blade)
    assert isinstance(read_model(DATA / NAMES[0], "tower"), Tower)
    blade = read_model(DATA / NAMES[1], tip_radius=63.0, hub_radius=1.5)
    assert blade.length == pytest.approx(61.5, rel=1e-15)
    tower = read_model(DATA / NAMES[2], elastodyn_main=DATA / NAMES[0])
    assert tower.height == pytest.approx(87.6, rel=1e-15) and tower.top_mass.mass > 3e5
    from bladefem.sections.tower import Tower as TowerModel                # BModes towers come with their supports
    assert isinstance(read_model(DATA / "bmodes_tower_plain.bmi"), TowerModel)
    assert isinstance(read_model(DATA / "windio_small.yaml", "tower"), Tower)
