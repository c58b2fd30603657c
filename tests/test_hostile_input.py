"""Hostile and absurd input files: each ends in one line naming the file (and its line and field where there is
one), exit code 2, quickly; never a traceback, a hang or a silently wrong answer."""

from __future__ import annotations

import contextlib
import io
import os
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from cpu_watchdog import cpu_limit

from bladefem.cli import main
from bladefem.errors import InputError
from bladefem.builders.case import read_case
from bladefem.formats.windio import read_windio
from bladefem.formats.yamlnodes import MAX_DEPTH, parse_yaml

ROOT = Path(__file__).parent.parent
DATA = Path(__file__).parent / "data"
NREL = ROOT / "cases" / "nrel5mw_blade.yaml"
UNIFORM = ROOT / "cases" / "uniform_blade.yaml"


def cli(*argv: object, cpu: float = 20.0) -> tuple[int, str, str]:
    """Run the command in-process under a CPU watchdog of ``cpu`` seconds; (exit code, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), cpu_limit(cpu):
        code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


def one_line(*argv: object, code: int = 2) -> str:
    """Run the command; assert it fails with one line on stderr and the given exit code; return the line."""
    found, _, err = cli(*argv)
    assert found == code, err
    assert len(err.strip().splitlines()) == 1 and re.match(r"bladefem( \w+)?: error: ", err), err
    return err.strip()


def edited(tmp_path: Path, source: Path, old: str, new: str, name: str | None = None) -> Path:
    text = source.read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / (name or source.name)
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return path


def line_of(path: Path, text: str) -> int:
    return next(i for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if text in line)


# -- YAML ---------------------------------------------------------------------------------------------------------

def test_yaml_numbers_follow_yaml_1_2():
    data, _ = parse_yaml("a: [1e9, 1.0e7, .5, 1., -3E-2, 0x10, 0o17, 7]\nb: [yes, on, 1_000, '1.0', ~, .inf]\n")
    assert data["a"] == [1e9, 1e7, 0.5, 1.0, -0.03, 16, 15, 7]
    assert all(isinstance(value, float) for value in data["a"][:5])
    assert data["b"] == ["yes", "on", "1_000", "1.0", None, float("inf")]


def test_windio_schema_accepts_unsigned_exponents():
    # the test turbine writes K66 as 1.0e7: a float by YAML 1.2, which windIO's schema validation requires
    assert read_windio(DATA / "windio_small.yaml").blade.stiffness["K66"][2] == 1.0e7


def test_case_reads_1e9(tmp_path):
    path = edited(tmp_path, NREL, "1.81100e+10, 1.81136e+10", "1.811e10, 1.81136e+10")
    assert read_case(path).sections.flap_stiffness[0] == 1.811e10


@pytest.mark.parametrize("text,line,message", [
    ("a: 1\nb: " + "9" * 5000 + "\n", 2, "5000 digits"),
    ("a: 1\nb: 1e999\n", 2, "beyond double precision"),
    ("a:\n  b: " + "[" * (MAX_DEPTH + 6) + "]" * (MAX_DEPTH + 6) + "\n", 2, f"deeper than {MAX_DEPTH}"),
    # far deeper: the YAML parser may refuse it before bladefem counts (PyYAML >= 6.0.4 does, in its own words);
    # either way it is one error naming the line
    ("a:\n  b: " + "[" * 1000 + "]" * 1000 + "\n", 2, None),
    ("a: 1\nb: &x [*x]\n", 2, "no complete anchor"),
    ("a: 1\nb: 2\na: 3\n", 3, "duplicate key 'a' (first at line 1)"),
    ("a: !!python/object/apply:os.system [ls]\n", 1, "unsupported tag"),
    ("a: 1\n---\nb: 2\n", 2, "a second YAML document"),
    ("? [1, 2]\n: 3\n", 1, "key must be a plain value"),
    ("a: [1, 2\n", 2, "invalid YAML"),
    ("a: 1\nb: x\x00y\n", 2, "U+0000"),
])
def test_hostile_yaml_is_one_error_with_its_line(text, line, message):
    with cpu_limit(5), pytest.raises(InputError) as caught:
        parse_yaml(text, "f.yaml")
    assert caught.value.line == line and "\n" not in str(caught.value), str(caught.value)
    assert message is None or message in caught.value.message, str(caught.value)


def test_nesting_just_past_the_limit_is_refused_by_bladefem():
    # one level past MAX_DEPTH: far below any YAML parser's own cap, so this is bladefem's check
    depth = MAX_DEPTH + 1
    with pytest.raises(InputError) as caught:
        parse_yaml("a:\n  b: " + "[" * depth + "]" * depth + "\n", "f.yaml")
    assert caught.value.line == 2 and f"deeper than {MAX_DEPTH}" in caught.value.message


def test_alias_bomb_is_refused_quickly(tmp_path):
    # 1 KB that expands to 10^9 values when every alias is followed
    bomb = "a: &a [x, x, x, x, x, x, x, x, x, x]\n" + "".join(
        f"b{k}: &b{k} [{', '.join([f'*b{k - 1}' if k else '*a'] * 10)}]\n" for k in range(8))
    path = tmp_path / "case.yaml"
    path.write_text("kind: blade\n" + bomb)
    with cpu_limit(5):
        assert "refusing the file" in one_line("modes", path)


def test_a_few_aliases_are_fine():
    data, _ = parse_yaml("row: &r [1.0, 2.0]\nrows: [*r, *r]\n")
    assert data["rows"] == [[1.0, 2.0], [1.0, 2.0]]


def test_hostile_yaml_through_the_command(tmp_path):
    path = edited(tmp_path, NREL, "hub_radius_m: 1.5", "hub_radius_m: " + "9" * 5000)
    assert f"{path}:{line_of(path, '99999')}:" in one_line("modes", path)


# -- files that are not what they seem --------------------------------------------------------------------------------

def test_file_problems_say_what_is_wrong(tmp_path):
    loop = tmp_path / "loop.yaml"
    loop.symlink_to(tmp_path / "loop.yaml")
    broken = tmp_path / "broken.yaml"
    broken.symlink_to(tmp_path / "nowhere.yaml")
    empty = tmp_path / "empty.yaml"
    empty.write_bytes(b"")
    comments = tmp_path / "comments.yaml"
    comments.write_text("# nothing here\n\n")
    folder = tmp_path / "folder.yaml"
    folder.mkdir()
    cases = {tmp_path / "missing.yaml": "file not found", loop: "symbolic link loop", broken: "broken symbolic link",
             empty: "file is empty", comments: "no content", folder: "is a folder"}
    for path, message in cases.items():
        err = one_line("modes", path)
        assert f"error: {path}" in err and message in err, err


def test_a_pipe_is_refused_without_hanging(tmp_path):
    pipe = tmp_path / "pipe.dat"
    os.mkfifo(pipe)
    assert "not a regular file" in one_line("modes", pipe)


def test_undecodable_yaml_names_the_line(tmp_path):
    path = tmp_path / "case.yaml"
    path.write_bytes(UNIFORM.read_bytes().replace(b"uniform blade", b"uniform \xe9 blade"))
    err = one_line("modes", path)
    assert f"{path}:{line_of(UNIFORM, 'uniform blade')}:" in err and "not UTF-8" in err and "0xe9" in err


def test_unrecognised_file_says_what_was_looked_for(tmp_path):
    path = tmp_path / "notes.txt"
    path.write_text("hello\nworld\n")
    err = one_line("modes", path)
    assert f"{path}:1:" in err and "NBlInpSt" in err and ".yaml" in err


def test_binary_file_names_the_line(tmp_path):
    path = tmp_path / "blade.dat"
    path.write_bytes(b"NBlInpSt\n\x00\x01")
    assert f"{path}:2:" in one_line("modes", path)


# -- absurd values and geometry -------------------------------------------------------------------------------------

@pytest.mark.parametrize("old,new,field,message", [
    ("- [1.00000", "- [0.50000", "span_fraction", "must be 1"),                       # a blade silently halved
    ("tip_radius_m: 63.0", "tip_radius_m: 1.5000001", "tip_radius_m", "only 1e-07 m beyond"),
    ("precone_deg: -2.5", "precone_deg: 180", "precone_deg", "between -90 and 90"),
    ("1.81100e+10, 1.81136e+10, 3.5420, 0.25000]\n    - [0.01951",
     "1.0e+308, 1.81136e+10, 3.5420, 0.25000]\n    - [0.01951", "flap_stiffness_N_m2", "beyond any real blade"),
    ("- [0.00325, 13.308, 678.935", "- [0.00325, 13.308, 1.0e+31", "mass_kg_per_m", "beyond any real blade"),
])
def test_absurd_case_values_name_line_and_field(tmp_path, old, new, field, message):
    path = edited(tmp_path, NREL, old, new)
    err = one_line("modes", path)
    assert f"{path}:{line_of(path, new.splitlines()[0].strip())}:" in err, err
    assert f"'{field}'" in err and message in err, err


def test_a_stiffness_spike_is_a_unit_slip(tmp_path):
    rows = NREL.read_text().splitlines()
    i = next(k for k, row in enumerate(rows) if row.strip().startswith("- [0.4"))
    values = rows[i].split(", ")
    values[3] = repr(float(values[3]) * 1e9)
    rows[i] = ", ".join(values)
    path = tmp_path / "spike.yaml"
    path.write_text("\n".join(rows) + "\n")
    err = one_line("modes", path)
    assert f"{path}:{i + 1}:" in err and "'flap_stiffness'" in err and "unit slip" in err


def test_elastodyn_precone_out_of_range_names_the_main_file(tmp_path):
    for name in ("NRELOffshrBsline5MW_Onshore_ElastoDyn.dat", "NRELOffshrBsline5MW_Blade.dat",
                 "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"):
        shutil.copy(DATA / name, tmp_path / name)
    main_file = tmp_path / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
    main_file.write_text(main_file.read_text().replace("-2.5   PreCone(1)", "  95   PreCone(1)"))
    err = one_line("modes", main_file, "--elements", "20")
    assert f"{main_file}:{line_of(main_file, 'PreCone(1)')}:" in err and "'PreCone(1)'" in err


def test_windio_cone_angle_out_of_range(tmp_path):
    path = edited(tmp_path, DATA / "windio_small.yaml", "cone_angle: ", "cone_angle: 180 #")
    err = one_line("modes", path)
    assert f"{path}:{line_of(path, 'cone_angle')}:" in err and "cone_angle" in err


@pytest.mark.parametrize("name,first_column,argv", [
    ("NRELOffshrBsline5MW_Blade.dat", "BlFract", ["{main}", "--elements", "20"]),
    ("NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat", "HtFract", ["{path}", "--elastodyn-main", "{main}"]),
])
def test_elastodyn_rows_must_have_exactly_their_columns(tmp_path, name, first_column, argv):
    for other in DATA.glob("NRELOffshrBsline5MW_*"):
        shutil.copy(other, tmp_path / other.name)
    path, main_file = tmp_path / name, tmp_path / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
    lines = path.read_text().splitlines(keepends=True)
    row = next(i for i, line in enumerate(lines) if line.split()[:1] == [first_column]) + 3   # second row
    words = lines[row].split()
    lines[row] = "  ".join(words[:2] + ["400.6"] + words[2:]) + "\n"        # one value too many: columns shift
    path.write_text("".join(lines))
    err = one_line("modes", *(part.format(main=main_file, path=path) for part in argv))
    assert f"{path}:{row + 1}:" in err and f"found {len(words) + 1}" in err, err


TOWER = ROOT / "cases" / "uniform_tower.yaml"


@pytest.mark.parametrize("value,message", [
    (".nan", "finite number"), ("-3", "must be positive"), ("tall", "finite number"), ("2.0", "contradicts"),
])
def test_tower_height_is_validated(tmp_path, value, message):
    path = edited(tmp_path, TOWER, "height_m: 1.0", f"height_m: {value}")
    err = one_line("modes", path)
    assert f"{path}:{line_of(path, 'height_m: ' + value)}:" in err and message in err, err


def test_tower_height_fraction_must_end_at_1(tmp_path):
    path = edited(tmp_path, TOWER, "columns: [height_m,", "columns: [height_fraction,")
    path.write_text(path.read_text().replace("- [1.0, 1.0, 1.0, 1.0, 100.0]", "- [0.5, 1.0, 1.0, 1.0, 100.0]"))
    assert "must be 1" in one_line("modes", path)


# -- options a YAML case used to ignore -----------------------------------------------------------------------------

def frequencies(*argv: object) -> np.ndarray:
    code, out, err = cli("modes", *argv, "--n-modes", "3", "--json")
    assert code == 0, err
    return np.array(__import__("json").loads(out)["frequencies_hz"])


def test_geometry_options_apply_to_a_case(tmp_path):
    base = frequencies(NREL, "--elements", "40")
    with_mass = frequencies(NREL, "--elements", "40", "--tip-mass", "500")
    assert np.all(with_mass < base)                                # a tip mass lowers every bending frequency
    edited_mass = edited(tmp_path, NREL, "root: cantilever", "root: cantilever\ntip_mass: {mass_kg: 500}")
    np.testing.assert_allclose(with_mass, frequencies(edited_mass, "--elements", "40"), rtol=1e-12)
    longer = edited(tmp_path, NREL, "tip_radius_m: 63.0", "tip_radius_m: 70.0", "longer.yaml")
    np.testing.assert_allclose(frequencies(NREL, "--elements", "40", "--tip-radius", "70"),
                               frequencies(longer, "--elements", "40"), rtol=1e-12)
    hub = edited(tmp_path, NREL, "hub_radius_m: 1.5", "hub_radius_m: 3.0", "hub.yaml")
    np.testing.assert_allclose(frequencies(NREL, "--elements", "40", "--hub-radius", "3", "--rpm", "12"),
                               frequencies(hub, "--elements", "40", "--rpm", "12"), rtol=1e-12)


@pytest.mark.parametrize("argv,field", [
    ([UNIFORM, "--tip-radius", "2"], "--tip-radius"),               # span_m fixes the length
    ([NREL, "--hub-radius", "-1"], None),                           # argparse: non-negative
    ([DATA / "windio_small.yaml", "--tip-radius", "80"], "--tip-radius"),
    ([NREL, "--tower-height", "80"], "--tower-height"),
    ([TOWER, "--tip-radius", "2"], "--tip-radius"),
    ([TOWER, "--rpm", "10"], "--rpm"),
    ([NREL, "--elastodyn-main", DATA / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"], "--elastodyn-main"),
])
def test_options_that_do_not_apply_are_refused(argv, field):
    err = one_line("modes", *argv)
    assert field is None or f"'{field}'" in err, err


@pytest.mark.parametrize("source,old,new,key,message", [
    (TOWER, "  mass_kg: 1.0", "  mass_kg: 1.0\n  cm_offset_m: [1e308, 0, 0]", "cm_offset_m", "beyond any real tower"),
    (TOWER, "  mass_kg: 1.0", "  mass_kg: 1.0\n  cm_offset_m: [1e29, 0, 0]", "cm_offset_m", "beam lengths"),
    (UNIFORM, "root: cantilever", "root: cantilever\ntip_mass: {mass_kg: 1, axial_offset_m: 1e6}", "tip_mass",
     "beam lengths"),
    (UNIFORM, "0.01, 1.0e-4, 1.0e-3]\n    - [1.0", "0.01, 1.0e-4, 1.0e+3]\n    - [1.0", "1.0e+3]", "gyration"),
    (NREL, "- [0.00325, 13.308", "- [0.00325, 1.0e+30", "1.0e+30", "half turn"),
])
def test_bodies_offsets_and_ratios_a_beam_cannot_have(tmp_path, source, old, new, key, message):
    path = edited(tmp_path, source, old, new)
    err = one_line("modes", path)
    assert f"{path}:{line_of(path, key)}:" in err and message in err, err


def test_bmodes_precone_out_of_range_names_its_line(tmp_path):
    for other in DATA.glob("bmodes_blade*"):
        shutil.copy(other, tmp_path / other.name)
    deck = tmp_path / "bmodes_blade.bmi"
    deck.write_text(deck.read_text().replace("2.5       precone", "1.0e7     precone", 1))
    err = one_line("modes", deck, "--elements", "20")
    assert f"{deck}:{line_of(deck, 'precone')}:" in err and "between -90 and 90" in err, err


def test_flap_and_edge_stiffness_decades_apart_are_a_slip(tmp_path):
    path = tmp_path / "case.yaml"
    path.write_text(UNIFORM.read_text().replace("1.0, 1.0, 4.0, 0.01", "1.0, 1.0, 4.0e7, 0.01"))
    err = one_line("modes", path)
    assert f"{path}:{line_of(path, '- [0.0, 1.0, 1.0, 4.0e7')}:" in err and "differ by more" in err, err
