"""The ``bladefem elastodyn`` subcommand: report, dry-run diff, in-place update, any input format, user errors."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import Parser
from bladefem.cli import elastodyn as command
from bladefem.errors import InputError
from bladefem.builders.elastodyn_blade import read_elastodyn_blade
from bladefem.builders.elastodyn_tower import read_elastodyn_tower

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
    code, out, _ = run([str(model / NAMES[0]), "--rpm", "12.1", "--write", str(blade), "--force"], capsys)
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
    code, out, _ = run([str(model / NAMES[0]), "--write", str(tower), "--force"], capsys)
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
    from bladefem.builders.detect import detect_format, read_model
    from bladefem.builders.tower import Tower
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


def fit(name: str, fe: float, elastodyn: float):
    from bladefem.modal.elastodyn_fit import ModeFit, PolynomialFit
    return ModeFit(name, PolynomialFit(np.array([1.0, 0, 0, 0, 0]), 0.0, 0.0, 1.0), fe, elastodyn, 1.0)


def coefficients(fresh: dict, shipped: dict):
    from bladefem.modal.elastodyn_fit import ElastoDynCoefficients
    return ElastoDynCoefficients({k: fit(k, *v) for k, v in fresh.items()}, 12.1, 17, False,
                                 {k: fit(k, *v) for k, v in shipped.items()})


def test_worse_is_judged_by_the_elastodyn_frequency_error():
    # flap2: the fresh polynomial gives +5 % against the file's +0.2 % (the NREL 5MW case of the issue): worse;
    # flap1: -0.10 % against +0.15 %: better; edge1: equal errors of opposite sign: not worse
    result = coefficients({"flap1": (0.729, 0.72827), "flap2": (2.0135, 2.1142), "edge1": (1.095, 1.0961)},
                          {"flap1": (0.729, 0.73009), "flap2": (2.0135, 2.0175), "edge1": (1.095, 1.0939)})
    worse = command.worse_modes(result)
    assert len(worse) == 1 and worse[0].startswith("flap2") and "+5.00 %" in worse[0] and "+0.20 %" in worse[0]
    assert command.worse_modes(coefficients({"flap1": (1.0, 1.01)}, {})) == []     # nothing to compare with


def worse_fit(monkeypatch):
    """The fit module made to return a flap-2 polynomial 5 % stiff in ElastoDyn, whatever the fit does today."""
    import bladefem.modal.elastodyn_fit as fit_module
    real = fit_module.blade_coefficients

    def spoiled(*args, **kwargs):
        result = real(*args, **kwargs)
        bad = result.fits["flap2"]
        fits = dict(result.fits, flap2=type(bad)(bad.name, bad.fit, bad.fe_frequency_hz,
                                                 1.05 * bad.fe_frequency_hz, bad.tip_ratio))
        return type(result)(fits, result.rpm, result.nodes, result.tower, result.shipped, result.notes)

    monkeypatch.setattr(fit_module, "blade_coefficients", spoiled)


def test_a_worse_fit_is_refused_without_force(model, capsys, monkeypatch):
    worse_fit(monkeypatch)
    blade = model / NAMES[1]
    before = blade.read_bytes()
    code, _, err = run([str(model / NAMES[0]), "--write", str(blade)], capsys)
    assert code == 2 and "worse than the file's" in err and "flap2" in err and "--force" in err
    assert blade.read_bytes() == before                                   # nothing written
    code, out, _ = run([str(model / NAMES[0]), "--write", str(blade), "--dry-run"], capsys)
    assert code == 0 and "# warning: the fresh fit is worse" in out and blade.read_bytes() == before
    code, _, _ = run([str(model / NAMES[0]), "--write", str(blade), "--force"], capsys)
    assert code == 0 and blade.read_bytes() != before


def test_check_verdict_and_exit_code(model, capsys):
    main = str(model / NAMES[0])
    code, out, _ = run([main, "--check"], capsys)
    # the NREL 5MW blade file's polynomials give ElastoDyn frequencies within 0.2 % of the FE at 12.1 rpm
    assert code == 0 and "# verdict: PASS" in out and out.count(" ok ") == 3
    code, out, _ = run([main, "--check", "--tolerance", "0.1"], capsys)
    assert code == 1 and "# verdict: FAIL" in out and "flap2" in out.split("# verdict:")[1]
    # the tower file's fore-aft 1 is 3 % off the FE tower with the rotor-nacelle as a point mass
    code, out, _ = run([main, "--check", "--part", "tower"], capsys)
    assert code == 1 and "fa1" in out.split("# verdict:")[1]
    code, _, err = run([str(ROOT_CASES / "uniform_blade.yaml"), "--check", "--rpm", "0"], capsys)
    assert code == 2 and "field '--check'" in err


ROOT_CASES = Path(__file__).resolve().parents[1] / "cases"


def test_cli_min_tip_ratio_default_is_the_fits():
    from bladefem.modal.elastodyn_fit import MIN_TIP_RATIO
    assert command.MIN_TIP_RATIO == MIN_TIP_RATIO
