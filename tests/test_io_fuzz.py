"""Parsers never raise an unhandled exception: real input files truncated, corrupted and shuffled by hypothesis
either still read or end in one InputError naming the file, the line and the field (CLI exit code 2)."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bladefem.cli import Parser
from bladefem.cli import elastodyn as command
from bladefem.errors import InputError
from bladefem.io.bmodes import read_bmodes
from bladefem.io.detect import detect_format, read_model
from bladefem.io.elastodyn_blade import read_elastodyn_blade
from bladefem.io.elastodyn_main import read_elastodyn_main
from bladefem.io.elastodyn_tower import read_elastodyn_tower
from bladefem.io.windio import read_windio

DATA = Path(__file__).parent / "data"
READERS = {
    "NRELOffshrBsline5MW_Blade.dat": read_elastodyn_blade,
    "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat": read_elastodyn_tower,
    "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat": read_elastodyn_main,
    "bmodes_blade.bmi": read_bmodes,
    "bmodes_blade_sec_props.dat": lambda path: read_bmodes(Path(path).parent / "bmodes_blade.bmi"),
    "bmodes_tower_platform.bmi": read_bmodes,
    "bmodes_tower_wires.bmi": read_bmodes,
    "windio_small.yaml": read_windio,
}
GARBAGE = ("", "nan", "inf", "-1", "0", "1e999", "abc", "1,2", '"', "'", ":", "- [", "{", "True", "1.5.2", "\t",
           "-0.0", "99999999999999999999", "\x00")


@st.composite
def damaged(draw, name: str) -> str:
    """The text of ``name`` truncated, with tokens replaced, lines deleted, duplicated or shuffled."""
    lines = (DATA / name).read_text().splitlines(keepends=True)
    for _ in range(draw(st.integers(1, 3))):
        if not lines:
            break
        operation = draw(st.sampled_from(("truncate", "corrupt", "delete", "swap", "duplicate", "shuffle")))
        i = draw(st.integers(0, len(lines) - 1))
        if operation == "truncate":
            lines = lines[:i]
        elif operation == "corrupt":
            words = lines[i].split(" ")
            j = draw(st.integers(0, len(words) - 1))
            words[j] = draw(st.sampled_from(GARBAGE) | st.text(max_size=6))
            lines[i] = " ".join(words)
        elif operation == "delete":
            del lines[i]
        elif operation == "swap":
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        elif operation == "duplicate":
            lines.insert(i, lines[i])
        else:
            block = lines[i:i + 8]
            lines[i:i + 8] = draw(st.permutations(block))
    return "".join(lines)


def check_error(error: InputError, path: Path) -> None:
    assert error.file is not None and Path(error.file).name in {path.name, "bmodes_blade_sec_props.dat",
                                                                  "bmodes_tower_sec_props.dat"}
    assert error.line is not None and error.line >= 1
    assert error.field, str(error)
    assert "\n" not in str(error)


FUZZ = settings(max_examples=40, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])


@pytest.mark.parametrize("name", sorted(READERS))
def test_damaged_files_read_or_report(name, tmp_path):
    for other in DATA.iterdir():
        if other.is_file():
            shutil.copy(other, tmp_path / other.name)

    @FUZZ
    @given(text=damaged(name))
    def check(text: str) -> None:
        path = tmp_path / name
        path.write_text(text)
        try:
            READERS[name](path)
        except InputError as error:
            check_error(error, path)

    check()


@FUZZ
@given(text=damaged("NRELOffshrBsline5MW_Blade.dat"))
def test_damaged_blade_through_the_cli_exits_0_or_2(tmp_path_factory, text):
    folder = tmp_path_factory.mktemp("cli")
    for other in DATA.glob("NRELOffshrBsline5MW_*"):
        shutil.copy(other, folder / other.name)
    (folder / "NRELOffshrBsline5MW_Blade.dat").write_text(text)
    parser = Parser(prog="bladefem")
    command.add_parser(parser.add_subparsers(dest="command", required=True, parser_class=Parser))
    args = parser.parse_args(["elastodyn", str(folder / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"),
                              "--elements", "30", "--n-modes", "8"])
    try:
        code = args.run(args)
    except InputError as error:
        print(f"bladefem: error: {error}", file=sys.stderr)
        code = 2
        assert error.file and error.line and error.field, str(error)
    assert code in (0, 2)


@FUZZ
@given(text=damaged("windio_small.yaml"))
def test_damaged_windio_through_read_model(tmp_path_factory, text):
    path = tmp_path_factory.mktemp("model") / "turbine.yaml"
    path.write_text(text)
    windio = detect_format(path) == "windio"      # damage can turn it into something read as a bladefem case
    for part in ("blade", "tower"):
        try:
            read_model(path, part)
        except InputError as error:
            assert error.file and "\n" not in str(error)
            if windio:
                assert error.line and error.field, str(error)
