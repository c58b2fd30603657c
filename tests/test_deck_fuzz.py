"""Hostile input on the turbine and CI surfaces, fuzzed (issue 24): the OpenFAST deck chain of ``cases/nrel5mw``,
``cases/nrel5mw_check.yaml`` and its baseline, shrunken batch plans, and random option values of ``turbine``.

Each mutant (seeded: the failure message names the seed and keeps the mutant) runs in-process under a CPU
watchdog. A command ends in exit 0 with finite physical outputs, or one line with exit 2 naming the file, line and
field (or the option), or one line with exit 1; never a traceback, a hang past :data:`CPU_SECONDS`, or an input
changed on disk. A batch case ends in result rows, finite where they are ok, or one error row whose message is
bladefem's own (an input, limit or solve error), never a crash of another kind; no case is lost.

CI runs :data:`CASES` mutants per surface (288 runs, under a minute of CPU); ``BLADEFEM_FUZZ_CASES=5000 python -m
pytest tests/test_deck_fuzz.py`` runs more.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import json
import math
import os
import random
import re
import shutil
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np
from cpu_watchdog import Hang, cpu_limit
from test_io_fuzz import FILE_LEVEL, NUMBER, NUMBERS, mutate

from bladefem.batch.plan import read_plan
from bladefem.batch.worker import run_case
from bladefem.cli import main
from bladefem.errors import InputError

ROOT = Path(__file__).parent.parent
#: mutants per surface in CI; BLADEFEM_FUZZ_CASES (mutants per format of test_io_fuzz) scales them up
SCALE = int(os.environ.get("BLADEFEM_FUZZ_CASES", "24"))
CASES = {"deck": 4 * SCALE, "check": 2 * SCALE, "plan": 2 * SCALE, "options": 4 * SCALE}
#: CPU seconds a run may take before the watchdog calls it a hang (a sound run here takes well under two)
CPU_SECONDS = 20.0
FST = "nrel5mw/NRELOffshrBsline5MW_Onshore.fst"
#: the files of the deck chain a mutant damages
CHAIN = ("NRELOffshrBsline5MW_Onshore.fst", "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat",
         "NRELOffshrBsline5MW_Blade.dat", "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat",
         "NRELOffshrBsline5MW_Onshore_AeroDyn.dat", "NRELOffshrBsline5MW_AeroDyn_blade.dat",
         "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat", "NRELOffshrBsline5MW_Onshore_ServoDyn.dat",
         "Airfoils/DU21_A17.dat")
#: the actions run on a mutated deck (cheap: the files' polynomial shapes)
ACTIONS = (["--linearize", "--wind-speed", "11.4", "--elastodyn-compatible", "--json"],
           ["--simulate", "0.2", "--elastodyn-compatible", "--quiet"],
           ["--linearize", "--no-aero", "--elastodyn-compatible", "--json"])
#: bladefem's own errors, as a batch case records them
OWN_ERRORS = ("InputError", "LimitError", "SolveError", "SolverError", "QuadraticSolverError", "DivergenceError",
              "UnstableStep")


def mutate_values(text: str, rng: random.Random) -> bytes:
    """``text`` with one or two of its numbers replaced by absurd ones or scaled by decades (the YAML stays YAML, so
    the values reach the models)."""
    for _ in range(rng.randint(1, 2)):
        matches = list(NUMBER.finditer(text))
        if not matches:
            break
        match = rng.choice(matches)
        new = rng.choice(NUMBERS) if rng.random() < 0.5 else repr(float(match[0]) * 10.0 ** rng.randint(-12, 12))
        text = text[:match.start()] + new + text[match.end():]
    return text.encode()


def damage(text: str, rng: random.Random, seed: int) -> bytes:
    """Every other seed a structural damage (:func:`mutate`), else absurd values (:func:`mutate_values`)."""
    return mutate(text, rng) if seed % 2 else mutate_values(text, rng)


def digests(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file() and not p.is_symlink()}


def run_cli(argv: list[str]) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with warnings.catch_warnings(), cpu_limit(CPU_SECONDS):
        warnings.simplefilter("ignore")
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


def one_line_error(code: int, err: str, folder: Path | None) -> None:
    """Exit 1 or 2 with one line; with ``folder``, an exit-2 line names a file there and, where that file has
    content and the problem is not with the file as a whole, its line."""
    lines = err.strip().splitlines()
    assert code in (1, 2), (code, err)
    assert len(lines) == 1 and re.match(r"bladefem( [\w-]+)?: error: ", lines[0]), err
    if code == 2 and folder is not None and "field '--" not in lines[0] and "argument " not in lines[0]:
        named = re.match(r"bladefem( [\w-]+)?: error: (.+?)(:(\d+))?: ", lines[0])
        assert named and str(folder) in named[2], f"the error names no input file: {err}"
        path = Path(named[2])
        if path.is_file() and path.read_bytes().strip() and not any(p in lines[0] for p in FILE_LEVEL):
            assert named[4], f"no line number: {err}"


def finite_numbers(value) -> bool:
    if isinstance(value, dict):
        return all(finite_numbers(v) for v in value.values())
    if isinstance(value, list):
        return all(finite_numbers(v) for v in value)
    return not isinstance(value, float) or math.isfinite(value)


def run_turbine(argv: list, folder: Path, output: Path) -> None:
    """Run one turbine mutant (a simulation writes ``output``): inputs unchanged on disk, and either a sound output
    or one error line."""
    if "--simulate" in argv:
        argv += ["--output", output]
        output.unlink(missing_ok=True)
    before = digests(folder)
    code, out, err = run_cli(argv)
    assert digests(folder) == before, "an input changed on disk"
    if code == 0:
        check_turbine_output(argv, out, output if "--simulate" in argv else None)
    else:
        one_line_error(code, err, folder)


def check_turbine_output(argv: list[str], out: str, output: Path | None) -> None:
    if "--json" in argv:
        data = json.loads(out)
        assert finite_numbers(data), "non-finite number in the JSON"
        frequencies = [m["frequency_hz"] for p in data.get("points", [data]) for m in p.get("modes", [])]
        assert all(f >= 0 for f in frequencies), frequencies
    else:
        text = output.read_text() if output is not None else out
        rows = [line for line in text.splitlines() if line and not line.startswith("#")]
        table = np.loadtxt(rows[1:], delimiter=",", ndmin=2)
        assert table.size and np.isfinite(table).all(), "non-finite values in the simulation table"


def fuzz(name: str, cases: int, run: Callable[[random.Random, int], None], keep: Callable[[int], list[Path]]) -> None:
    """Call ``run(rng, seed)`` for each seed; collect failures (the mutated files kept beside the folder)."""
    failures = []
    for seed in range(cases):
        try:
            run(random.Random(f"{name}-{seed}"), seed)
        except (AssertionError, Hang, Exception) as error:
            kept = [str(path) for path in keep(seed)]
            failures.append(f"seed {seed} ({', '.join(kept)}): {type(error).__name__}: {str(error)[:300]}")
    assert not failures, f"{len(failures)} of {cases} mutants failed:\n" + "\n".join(failures[:10])


def _keep(source: Path, tmp_path: Path, name: str, seed: int) -> list[Path]:
    kept = tmp_path / f"failed-{name}-{seed}-{source.name}"
    if source.is_file():
        shutil.copy(source, kept)
    return [kept]


# -- the deck chain --------------------------------------------------------------------------------------------------

def test_deck_chain_mutants(tmp_path):
    folder = tmp_path / "cases"
    shutil.copytree(ROOT / "cases" / "nrel5mw", folder / "nrel5mw")
    pristine = {name: (folder / "nrel5mw" / name).read_bytes() for name in CHAIN}
    output = tmp_path / "out" / "table.csv"
    mutated: list[Path] = []

    def run(rng: random.Random, seed: int) -> None:
        for name, data in pristine.items():
            (folder / "nrel5mw" / name).write_bytes(data)
        target = folder / "nrel5mw" / rng.choice(CHAIN)
        mutated[:] = [target]
        target.write_bytes(mutate(pristine[str(target.relative_to(folder / "nrel5mw"))].decode("utf-8", "replace"),
                                  rng))
        argv = ["turbine", folder / FST, *rng.choice(ACTIONS)]
        run_turbine(argv, folder, output)

    fuzz("deck", CASES["deck"], run, lambda seed: _keep(mutated[0], tmp_path, "deck", seed) if mutated else [])


# -- check: the spec and its baseline ----------------------------------------------------------------------------

def test_check_spec_and_baseline_mutants(tmp_path):
    folder = tmp_path / "cases"
    shutil.copytree(ROOT / "cases", folder, ignore=shutil.ignore_patterns("nrel5mw"))
    names = ("nrel5mw_check.yaml", "nrel5mw_check_baseline.json")
    pristine = {name: (folder / name).read_text() for name in names}
    mutated: list[Path] = []

    def run(rng: random.Random, seed: int) -> None:
        for name, text in pristine.items():
            (folder / name).write_text(text)
        target = folder / names[seed // 2 % 2]
        mutated[:] = [target]
        target.write_bytes(damage(pristine[target.name], rng, seed))
        before = digests(folder)
        code, out, err = run_cli(["check", folder / "nrel5mw_check.yaml", "--json"])
        assert digests(folder) == before, "an input changed on disk"
        if code in (0, 1) and out:
            data = json.loads(out)
            assert data["passed"] == (code == 0)
            assert all(math.isfinite(outcome["measured"]) for outcome in data["outcomes"]), data["outcomes"]
        else:
            one_line_error(code, err, folder)

    fuzz("check", CASES["check"], run, lambda seed: _keep(mutated[0], tmp_path, "check", seed) if mutated else [])


# -- batch plans, shrunk to two cheap cases -------------------------------------------------------------------------

PLANS = {
    "samples.yaml": "model: nrel5mw_blade.yaml\nanalysis: {type: modes, rpm: 12.1, n_modes: 2, elements: 20}\n"
                    "samples:\n  count: 2\n  seed: 2026\n  properties:\n"
                    "    mass: {distribution: uniform, half_width_percent: 5}\n"
                    "    flap_stiffness: {distribution: normal, std_percent: 5, correlation_length: 0.3}\n",
    "linearize.yaml": "model: nrel5mw/NRELOffshrBsline5MW_Onshore.fst\nanalysis: {type: turbine_linearize}\n"
                      "grid: {wind_speed_m_s: [8, 11.4]}\n",
    "simulate.yaml": "model: nrel5mw/NRELOffshrBsline5MW_Onshore.fst\n"
                     "analysis: {type: turbine_simulate, seconds: 0.2, dt: 0.1}\n"
                     "grid: {wind_speed_m_s: [11.4], pitch_deg: [0, 1]}\n",
    "check.yaml": "model: nrel5mw_tower.yaml\nanalysis: {type: check, spec: nrel5mw_check.yaml, spec_model: tower, "
                  "n_modes: 4}\ngrid: {mass_scale: [1.0, 1.1]}\n",
}


def check_rows(rows: list[dict]) -> None:
    assert rows, "a case gave no row (lost)"
    errors = [row for row in rows if row["status"] == "error"]
    if errors:
        assert len(rows) == 1, rows
        message = errors[0]["error"]
        assert "\n" not in message.strip() and message.split(":")[0] in OWN_ERRORS, message
        return
    for row in rows:
        assert finite_numbers({k: v for k, v in row.items() if isinstance(v, float)}), row


def test_batch_plan_mutants(tmp_path):
    folder = tmp_path / "cases"
    shutil.copytree(ROOT / "cases", folder)
    names = sorted(PLANS)
    mutated: list[Path] = []

    def run(rng: random.Random, seed: int) -> None:
        target = folder / names[seed // 2 % len(names)]
        mutated[:] = [target]
        target.write_bytes(damage(PLANS[target.name], rng, seed))
        before = digests(folder)
        with cpu_limit(CPU_SECONDS):
            try:
                plan = read_plan(target)
            except InputError as error:
                assert error.file and str(folder) in error.file and "\n" not in str(error), str(error)
                return
            long = (plan.analysis.seconds or 0) > 5       # a legitimately long simulation is no hang: read only
            for case in plan.cases[:0 if long else 2]:
                check_rows(run_case(case))
        assert digests(folder) == before, "an input changed on disk"

    fuzz("plan", CASES["plan"], run, lambda seed: _keep(mutated[0], tmp_path, "plan", seed) if mutated else [])


# -- random option values ------------------------------------------------------------------------------------------

#: option -> values tried (absurd ones from the file mutator, and plausible ones)
OPTIONS = {
    "--rpm": (*NUMBERS, "12.1", "0", "30"), "--wind-speed": (*NUMBERS, "11.4", "3:25:3", "5,8", "0", "100.5"),
    "--dt": (*NUMBERS, "0.05", "0.3"), "--rtol": (*NUMBERS, "1e-6", "1e-3"), "--step": (*NUMBERS, "0.01"),
    "--yaw-stiffness": (*NUMBERS, "1e9"), "--yaw-damping": (*NUMBERS, "1e7"), "--shear-exp": (*NUMBERS, "0.2"),
    "--pitch-deg": (*NUMBERS, "5", "-90", "90"), "--azimuth-deg": (*NUMBERS, "30"),
    "--dof": ("all", "tower", "yaw=off", "GenDOF=on", "nonsense", "flap1", "=", ""),
    "--initial": ("OoPDefl=1", "RotSpeed=1e308", "yaw_deg=nan", "tower_fa1=1e3", "x=1", "Azimuth"),
    "--method": ("auto", "RK4", "DOP853", "RK45", "DP54", "DP853", "nonsense"),
    "--shapes": ("fe", "polynomial", "fe-polynomial", "x"), "--damping": ("elastodyn", "rna", "x"),
}
#: the base actions of option mutants (cheap ones)
BASES = (["--simulate", "0.2", "--elastodyn-compatible", "--quiet"],
         ["--linearize", "--elastodyn-compatible", "--json"],
         ["--linearize", "--no-aero", "--elastodyn-compatible", "--json"],
         ["--simulate", "{simulate}", "--elastodyn-compatible", "--quiet"])


def test_random_option_values(tmp_path):
    folder = tmp_path / "cases"
    shutil.copytree(ROOT / "cases" / "nrel5mw", folder / "nrel5mw")
    output = tmp_path / "out" / "table.csv"

    def run(rng: random.Random, seed: int) -> None:
        base = [part.format(simulate=rng.choice(("0", "-1", "nan", "1e308", "0.1", "1e-9"))) for part in
                rng.choice(BASES)]
        argv = ["turbine", folder / FST, *base]
        for option in rng.sample(sorted(OPTIONS), rng.randint(1, 3)):
            argv += [option, rng.choice(OPTIONS[option])]
        run_turbine(argv, folder, output)

    fuzz("options", CASES["options"], run, lambda seed: [])
