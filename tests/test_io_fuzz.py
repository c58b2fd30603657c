"""Hostile input, fuzzed: every shipped and test input format (YAML blade and tower cases, ElastoDyn main, blade and
tower files, BModes deck and section file, windIO) is damaged by a seeded mutator and run through the readers and
through ``bladefem modes`` in-process, under a CPU watchdog.

A reader either returns what the file says (checked against the text at the lines it reports) or raises one
InputError naming the file. The command either exits 0 with finite, positive frequencies and small residuals, or
prints one line naming the file (with its line where the file has content) and exits 2 (exit 1 only for a solve
whose answer is not a result); never a traceback, never more than :data:`CPU_SECONDS` of CPU per case.

CI runs :data:`CASES` mutants per format; ``BLADEFEM_FUZZ_CASES=5000 python -m pytest tests/test_io_fuzz.py`` runs
more (failing mutants are kept in pytest's temporary folder and named in the failure).
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import json
import math
import os
import random
import re
import shutil
import sys
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from cpu_watchdog import Hang, cpu_limit
import yaml

from bladefem.cli import main
from bladefem.errors import InputError
from bladefem.formats.bmodes import ANGLE_COLUMNS, SECTION_COLUMNS, read_bmodes
from bladefem.builders.elastodyn_blade import read_elastodyn_blade
from bladefem.formats.elastodyn_main import SCALARS, read_elastodyn_main
from bladefem.builders.elastodyn_tower import read_elastodyn_tower
from bladefem.formats.windio import read_windio
from bladefem.modal.results import MAX_RESIDUAL, RIGID_HZ

ROOT = Path(__file__).parent.parent
DATA = Path(__file__).parent / "data"
#: mutants per format in CI (about a minute in all); more with BLADEFEM_FUZZ_CASES
CASES = int(os.environ.get("BLADEFEM_FUZZ_CASES", "24"))
#: CPU seconds a case may take before the watchdog calls it a hang (a sound case takes well under one)
CPU_SECONDS = 10.0
#: errors about the file as a whole, which have no line to name
FILE_LEVEL = ("file not found", "file is empty", "is a folder", "symbolic link", "permission denied",
              "not a regular file", "file too large", "invalid file name")


def watchdog(seconds: float = CPU_SECONDS):
    """Raise :class:`Hang` after ``seconds`` of process CPU time."""
    return cpu_limit(seconds)


# -- the mutator ----------------------------------------------------------------------------------------------------

NUMBERS = ("1e308", "-1e308", "1e-308", "0", "-1", "-0.0", "nan", "inf", "-inf", "1e30", "1e31", "1e999", ".5",
           "1.", "1e9", "1.0e7", "0x10", "99999999999999999999", "9" * 400, "9" * 5000, "1D3", "1,5", "1.5.2")
WORDS = ("", "abc", "True", "'", '"', ":", "- [", "{", "]", "&a", "*a", "!!python/object:os.system", "~", "'1'",
         "\t", "é", "\x00", "\xff")
NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)([eEdD][-+]?\d+)?")


def mutate(text: str, rng: random.Random) -> bytes:
    """``text`` with one to three damages: numbers replaced by absurd ones or scaled by decades, extra values in a
    row, words replaced, lines deleted, duplicated, swapped or truncated, bytes that are not UTF-8, YAML bombs.
    Numbers are picked among all numbers of the file, so most damage lands on values."""
    lines = text.splitlines(keepends=True)
    for _ in range(rng.randint(1, 3)):
        if not lines:
            break
        operation = rng.choice(("number", "number", "number", "scale", "scale", "extra", "word", "delete",
                                "duplicate", "swap", "truncate", "bytes", "yaml"))
        numbers = [(i, match) for i, line in enumerate(lines) for match in NUMBER.finditer(line)]
        i = rng.randrange(len(lines))
        if operation in ("number", "scale", "extra") and numbers:
            i, match = rng.choice(numbers)
            if operation == "number":
                new = rng.choice(NUMBERS)
            elif operation == "scale":
                new = repr(float(match.group().replace("D", "e").replace("d", "e")) * 10.0 ** rng.randint(-12, 12))
            else:
                new = match.group() + rng.choice((" ", ", ")) + rng.choice(("400.6", "0", "1"))
            lines[i] = lines[i][:match.start()] + new + lines[i][match.end():]
        elif operation in ("word", "number", "scale", "extra"):
            words = lines[i].split(" ")
            words[rng.randrange(len(words))] = rng.choice(WORDS)
            lines[i] = " ".join(words)
        elif operation == "delete":
            del lines[i]
        elif operation == "duplicate":
            lines.insert(i, lines[i])
        elif operation == "swap":
            j = rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        elif operation == "truncate":
            lines = lines[:i] + [lines[i][:rng.randrange(len(lines[i]) + 1)]]
        elif operation == "bytes":
            lines[i] = lines[i].replace(" ", rng.choice(("\udcff", "\udce9", "\x00")), 1)
        else:
            lines.insert(i, rng.choice((
                "bomb: &a [x, x, x, x, x, x, x, x, x, x]\n" + "".join(
                    f"b{k}: &a{k} [{', '.join([f'*a{k - 1}' if k else '*a'] * 10)}]\n" for k in range(9)),
                "deep: " + "[" * 1000 + "]" * 1000 + "\n",
                "big: " + "9" * 5000 + "\n",
                "loop: &l [*l]\n")))
    return "".join(lines).encode("utf-8", errors="surrogateescape")


# -- what a run must end in -----------------------------------------------------------------------------------------

def run_cli(argv: list[str]) -> tuple[int, str, str, list[str]]:
    """``bladefem ARGV`` in-process under the watchdog: exit code, stdout, stderr, warnings raised."""
    out, err = io.StringIO(), io.StringIO()
    with warnings.catch_warnings(record=True) as caught, watchdog():
        warnings.simplefilter("always")
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(argv)
    return code, out.getvalue(), err.getvalue(), [str(w.message) for w in caught]


def check_outcome(code: int, out: str, err: str, folder: Path, mutated: Path) -> None:
    if code == 0:
        data = json.loads(out)
        frequencies = np.array(data["frequencies_hz"])
        buckled = any("buckles" in note for note in data.get("notes", []))
        assert np.all(np.isfinite(frequencies)), frequencies
        assert buckled or np.all(frequencies > -RIGID_HZ), frequencies
        for mode in data["modes"]:
            assert abs(mode["frequency_hz"]) < RIGID_HZ or mode["residual"] <= MAX_RESIDUAL, mode
        return
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("bladefem: error: "), err
    assert str(folder) in lines[0], "the error names no input file"
    if code == 1:
        assert "is not a result" in lines[0], err
        return
    assert code == 2, (code, err)
    named = re.match(r"bladefem: error: (.+?)(:(\d+))?: ", lines[0])
    assert named, err
    path = Path(named.group(1))
    has_content = path.is_file() and path.read_bytes().strip()
    if path == mutated and has_content and not any(phrase in lines[0] for phrase in FILE_LEVEL):
        assert named.group(3), f"no line number: {err}"


FORMATS: dict[str, tuple[Path, Path, list[str]]] = {
    # name: (file to mutate, its companions' folder, modes options)
    "case-blade": (ROOT / "cases/nrel5mw_blade.yaml", ROOT / "cases", ["--elements", "30"]),
    "case-uniform-blade": (ROOT / "cases/uniform_blade.yaml", ROOT / "cases", []),
    "case-tower": (ROOT / "cases/nrel5mw_tower.yaml", ROOT / "cases", ["--elements", "30"]),
    "case-uniform-tower": (ROOT / "cases/uniform_tower.yaml", ROOT / "cases", []),
    "elastodyn-main": (DATA / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat", DATA, ["--elements", "30"]),
    "elastodyn-blade": (DATA / "NRELOffshrBsline5MW_Blade.dat", DATA, ["--elements", "30"]),
    "elastodyn-tower": (DATA / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat", DATA, ["--elements", "30"]),
    "bmodes-blade": (DATA / "bmodes_blade.bmi", DATA, ["--elements", "30"]),
    "bmodes-sections": (DATA / "bmodes_blade_sec_props.dat", DATA, ["--elements", "30"]),
    "bmodes-tower": (DATA / "bmodes_tower_platform.bmi", DATA, ["--elements", "30"]),
    "windio": (DATA / "windio_small.yaml", DATA, []),
}
#: the input given to ``modes`` when the mutated file is read through another one
THROUGH = {"elastodyn-blade": "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat", "bmodes-sections": "bmodes_blade.bmi"}
EXTRA = {"elastodyn-tower": ["--elastodyn-main", "{folder}/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"]}


def fuzz(name: str, folder: Path, cases: int, check: Callable[[Path, Path, int], None]) -> None:
    """Run ``check(folder, mutated file, seed)`` on ``cases`` mutants of format ``name``; collect failures."""
    source, companions, _ = FORMATS[name]
    for other in companions.iterdir():
        if other.is_file():
            shutil.copy(other, folder / other.name)
    text = source.read_text(encoding="utf-8", errors="surrogateescape")
    target = folder / source.name
    failures = []
    for seed in range(cases):
        target.write_bytes(mutate(text, random.Random(f"{name}-{seed}")))
        try:
            check(folder, target, seed)
        except (AssertionError, Hang, Exception) as error:       # collect every failure, then report them
            kept = folder.parent / f"failed-{name}-{seed}{source.suffix}"
            shutil.copy(target, kept)
            failures.append(f"seed {seed} ({kept}): {type(error).__name__}: {str(error)[:300]}")
    assert not failures, f"{len(failures)} of {cases} mutants failed:\n" + "\n".join(failures[:10])


@pytest.mark.parametrize("name", sorted(FORMATS))
def test_mutants_through_modes_exit_0_1_or_2_on_one_line(name, tmp_path):
    folder = tmp_path / "inputs"
    folder.mkdir()

    def check(folder: Path, target: Path, seed: int) -> None:
        given = folder / THROUGH.get(name, target.name)
        extra = [part.format(folder=folder) for part in EXTRA.get(name, [])]
        code, out, err, caught = run_cli(["modes", str(given), "--n-modes", "4", "--json", *FORMATS[name][2],
                                          *extra])
        check_outcome(code, out, err, folder, target)

    fuzz(name, folder, CASES, check)


# -- readers: a successful read returns what the file says -----------------------------------------------------------

def numbers_on(line: str) -> list[float]:
    values = []
    for word in line.replace(",", " ").split():
        try:
            values.append(float(word.replace("D", "E").replace("d", "e")))
        except ValueError:
            pass
    return values


def same(value: float, candidates: list[float]) -> bool:
    return any(value == c or abs(value - c) <= 1e-12 * abs(c) for c in candidates)


def header(lines: list[str], first_row: int, first_column: str) -> list[str]:
    """The column names of the table whose first row is line ``first_row``."""
    number = first_row - 1
    while not lines[number - 1].split() or lines[number - 1].split()[0] != first_column:
        number -= 1
    return lines[number - 1].split()


def check_columns(lines: list[str], rows: tuple[int, ...], names: list[str], table: dict[str, np.ndarray]) -> None:
    """Every value of ``table`` (column name -> values) is the number in its column on its row's line."""
    for i, line in enumerate(rows):
        words = numbers_on(lines[line - 1])
        assert len(words) == len(names), (line, words)
        for name, values in table.items():
            assert same(values[i], [words[names.index(name)]]), (line, name, values[i], words)


def check_elastodyn_blade(path: Path) -> None:
    blade = read_elastodyn_blade(path)
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    names = header(lines, blade.station_lines[0], "BlFract")
    check_columns(lines, blade.station_lines, names, {
        "BlFract": blade.fraction, "BMassDen": blade.mass, "FlpStff": blade.flap_stiffness,
        "EdgStff": blade.edge_stiffness, "StrcTwst": np.degrees(blade.twist)})
    assert blade.stations == int(numbers_on(lines[blade.key_lines["NBlInpSt"] - 1])[0])


def check_elastodyn_tower(path: Path) -> None:
    tower = read_elastodyn_tower(path)
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    names = header(lines, tower.station_lines[0], "HtFract")
    check_columns(lines, tower.station_lines, names, {
        "HtFract": tower.fraction, "TMassDen": tower.mass, "TwFAStif": tower.fa_stiffness,
        "TwSSStif": tower.ss_stiffness})
    assert tower.stations == int(numbers_on(lines[tower.key_lines["NTwInpSt"] - 1])[0])


def check_elastodyn_main(path: Path) -> None:
    main_file = read_elastodyn_main(path)
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    for attribute, (key, kind) in SCALARS.items():
        value = getattr(main_file, attribute)
        value = math.degrees(value) if kind == "deg" else value * 30 / math.pi if kind == "rpm" else value
        line = lines[main_file.key_lines[key] - 1]
        assert key in line and same(value, numbers_on(line.split(key)[0])), (key, value, line)


def check_bmodes(path: Path) -> None:
    deck = read_bmodes(path if path.suffix == ".bmi" else path.parent / "bmodes_blade.bmi")
    lines = Path(deck.sections.path).read_text(encoding="utf-8", errors="replace").splitlines()
    columns = {name: np.degrees(values) if name in ANGLE_COLUMNS else values
               for name, values in deck.sections.columns.items()}
    check_columns(lines, deck.sections.station_lines, list(SECTION_COLUMNS), columns)
    if path.suffix == ".bmi":
        main_lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
        for key, value in (("radius", deck.radius), ("hub_rad", deck.hub_rad)):
            assert same(value, numbers_on(main_lines[deck.key_lines[key] - 1])[:1]), key


def check_windio(path: Path) -> None:
    turbine = read_windio(path)
    plain = yaml.safe_load(path.read_text(encoding="utf-8"))    # an independent reader of the same text
    for part, beam in (("blade", turbine.blade), ("tower", turbine.tower)):
        if beam is None:
            continue
        elastic = plain["components"][part]["structure"]["elastic_properties"]
        for name, values in beam.stiffness.items():
            np.testing.assert_array_equal(values, [float(v) for v in elastic["stiffness_matrix"][name]])
        for name, values in beam.inertia.items():
            np.testing.assert_array_equal(values, [float(v) for v in elastic["inertia_matrix"][name]])


READERS = {
    "elastodyn-blade": check_elastodyn_blade,
    "elastodyn-tower": check_elastodyn_tower,
    "elastodyn-main": check_elastodyn_main,
    "bmodes-blade": check_bmodes,
    "bmodes-sections": check_bmodes,
    "windio": check_windio,
}


@pytest.mark.parametrize("name", sorted(READERS))
def test_mutants_read_what_the_file_says_or_one_error(name, tmp_path):
    folder = tmp_path / "inputs"
    folder.mkdir()

    def check(folder: Path, target: Path, seed: int) -> None:
        try:
            with watchdog():
                READERS[name](target)
        except InputError as error:
            assert error.file and Path(error.file).parent == folder and "\n" not in str(error), str(error)

    fuzz(name, folder, 4 * CASES, check)


def _misread(reader: Callable, change: Callable) -> Callable:
    return lambda path: change(reader(path))


@pytest.mark.parametrize("name,attribute,change", [
    ("elastodyn-blade", "read_elastodyn_blade",
     lambda f: dataclasses.replace(f, mass=f.flap_stiffness)),                        # a shifted column
    ("elastodyn-tower", "read_elastodyn_tower", lambda f: dataclasses.replace(f, mass=f.mass[::-1])),
    ("elastodyn-main", "read_elastodyn_main", lambda f: dataclasses.replace(f, tip_radius=f.tip_radius + 1e-9)),
    ("bmodes-blade", "read_bmodes", lambda d: dataclasses.replace(d, sections=dataclasses.replace(
        d.sections, columns={**d.sections.columns, "flp_stff": d.sections.columns["edge_stff"]}))),
    ("windio", "read_windio", lambda t: dataclasses.replace(t, blade=dataclasses.replace(
        t.blade, stiffness={**t.blade.stiffness, "K44": t.blade.stiffness["K44"] * 1.001}))),
])
def test_content_checks_catch_a_reader_that_misreads(name, attribute, change, monkeypatch, tmp_path):
    """The checks above can fail: a reader that returns other values than the file's is caught on the file itself."""
    source, companions, _ = FORMATS[name]
    for other in companions.iterdir():
        if other.is_file():
            shutil.copy(other, tmp_path / other.name)
    READERS[name](tmp_path / source.name)                          # the true reader passes
    monkeypatch.setattr(sys.modules[__name__], attribute, _misread(globals()[attribute], change))
    with pytest.raises(AssertionError):
        READERS[name](tmp_path / source.name)
