"""``bladefem verify``: the self-check table and its exit code."""

from __future__ import annotations

import argparse
import dataclasses

import pytest

import bladefem.cli.verify as cli_verify
from bladefem.errors import InputError
from bladefem.modal import modes
from bladefem.verify import (
    UNIFORM_BOUND,
    VerifyRow,
    format_table,
    nrel5mw_rows,
    southwell_row,
    torsion_row,
    verification_rows,
)


@pytest.fixture(scope="module")
def rows() -> list[VerifyRow]:
    return verification_rows()


def test_all_checks_hold(rows):
    failed = [row for row in rows if not row.ok]
    assert not failed, format_table(failed)


def test_checks_cover_references_fe_and_galerkin(rows):
    cases = {row.case for row in rows}
    assert {"cantilever at rest", "rotating, lambda=12", "lag, lambda=12", "tip mass mu=1", "torsion, lambda=6",
            "Southwell, lambda->0", "NREL 5MW, 0 rpm", "NREL 5MW, 12.1 rpm"} <= cases
    assert all(row.fe is not None and row.galerkin is not None for row in rows)
    assert sum(row.reference is not None for row in rows) >= 17
    assert sum(row.case.startswith("NREL 5MW") for row in rows) == 8


def test_table_lists_every_row(rows):
    text = format_table(rows)
    lines = text.splitlines()
    assert lines[0].split()[:3] == ["case", "quantity", "reference"]
    assert len(lines) == len(rows) + 4
    assert lines[-1] == f"all {len(rows)} checks within their bounds"


def shifted(factor: float):
    """An FE solver whose frequencies are off by ``factor`` (a deliberately broken solver)."""
    def solver(blade, rpm, n_modes):
        result = modes(blade, rpm, n_modes)
        return dataclasses.replace(result, modes=[dataclasses.replace(mode, frequency_hz=mode.frequency_hz * factor)
                                                  for mode in result.modes])
    return solver


def test_a_solver_error_of_twice_the_bound_is_caught():
    broken = shifted(1 + 2 * UNIFORM_BOUND)
    assert not torsion_row(broken).ok
    assert not southwell_row(broken).ok          # K scales with the square of a frequency error


def test_nrel5mw_bound_catches_a_two_per_mille_error():
    assert not any(row.ok for row in nrel5mw_rows(shifted(1.002), rpm_values=(12.1,)))


def run_cli(monkeypatch, rows: list[VerifyRow], capsys) -> tuple[int, str]:
    monkeypatch.setattr("bladefem.verify.verification_rows", lambda nrel5mw: rows)
    parser = argparse.ArgumentParser()
    cli_verify.add_parser(parser.add_subparsers())
    args = parser.parse_args(["verify"])
    code = args.run(args)
    return code, capsys.readouterr().out


def test_cli_exit_code_follows_the_bounds(monkeypatch, capsys, rows):
    code, out = run_cli(monkeypatch, rows, capsys)
    assert code == 0 and "within their bounds" in out
    broken = rows[:-1] + [dataclasses.replace(rows[-1], fe=rows[-1].fe * 1.01)]
    code, out = run_cli(monkeypatch, broken, capsys)
    assert code == 1 and out.splitlines()[-1] == f"1 of {len(rows)} checks outside their bounds"


def test_missing_nrel5mw_file_is_an_input_error(tmp_path):
    with pytest.raises(InputError) as error:
        nrel5mw_rows(modes, tmp_path / "missing.dat")
    assert error.value.file.endswith("missing.dat") and error.value.field == "--nrel5mw"
