"""The examples a reader copies are the program's own output: every ``console`` block of the README and docs/ that
shows a ``$ bladefem ...`` command is run here and its printed lines compared with what the command prints today.

Numbers may differ by one unit of their last printed digit (a different BLAS can round the other way); residuals
printed in scientific notation only have to stay small (below 1e-6: they measure the solver, not the model). A line
``...`` in a block skips any number of printed lines. Output paths in the command are sent to a temporary folder.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from bladefem.cli import main

ROOT = Path(__file__).resolve().parents[1]
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
OUTPUT_OPTIONS = ("--junit", "--plot", "-o", "--output", "--vtk")
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
SMALL_RESIDUAL = 1e-6


def console_examples() -> list[tuple[str, str, list[str]]]:
    """(document, command line, shown output lines) of every ``$ bladefem`` command in a console block."""
    examples = []
    for path in DOCUMENTS:
        for block in re.findall(r"```console\n(.*?)```", path.read_text(), flags=re.DOTALL):
            command, shown = None, []
            for line in block.splitlines():
                if line.startswith("$ "):
                    if command:
                        examples.append((path.name, command, shown))
                    command, shown = line[2:], []
                elif command:
                    shown.append(line)
            if command and command.startswith("bladefem "):
                examples.append((path.name, command, shown))
    return examples


def same_number(shown: str, printed: str) -> bool:
    if "e" in shown.lower() and "e" in printed.lower():
        return float(shown) < SMALL_RESIDUAL and float(printed) < SMALL_RESIDUAL or float(shown) == float(printed)
    decimals = len(shown.split(".")[1]) if "." in shown else 0
    return abs(float(shown) - float(printed)) <= 1.01 * 10.0 ** -decimals


def same_line(shown: str, printed: str) -> bool:
    if NUMBER.sub("#", shown).split() != NUMBER.sub("#", printed).split():
        return False
    return all(same_number(a, b) for a, b in zip(NUMBER.findall(shown), NUMBER.findall(printed)))


def matches(shown: list[str], printed: list[str]) -> str | None:
    """None when the shown lines appear in the printed ones in order (``...`` skipping), else the first that doesn't."""
    position, skipping = 0, False
    for line in shown:
        if line.strip() == "...":
            skipping = True
            continue
        while position < len(printed) and not same_line(line, printed[position]):
            if not skipping:
                return f"shown:   {line}\nprinted: {printed[position]}"
            position += 1
        if position == len(printed):
            return f"shown line not printed: {line}"
        position, skipping = position + 1, False
    return None if skipping or position == len(printed) else f"printed but not shown: {printed[position]}"


EXAMPLES = console_examples()


def test_the_documents_have_console_examples():
    assert {document for document, _, _ in EXAMPLES} >= {"README.md", "check.md"}
    assert len(EXAMPLES) >= 3


@pytest.mark.parametrize("document,command,shown", EXAMPLES, ids=[f"{d}:{c}" for d, c, _ in EXAMPLES])
def test_console_example_is_what_the_command_prints(document, command, shown, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    arguments = shlex.split(command)[1:]
    for k, argument in enumerate(arguments[:-1]):
        if argument in OUTPUT_OPTIONS:
            arguments[k + 1] = str(tmp_path / Path(arguments[k + 1]).name)
    code = main(arguments)
    printed = capsys.readouterr().out.rstrip("\n").splitlines()
    assert code == 0
    mismatch = matches(shown, printed)
    assert mismatch is None, f"{document}: {command}\n{mismatch}"


def test_the_comparison_can_fail():
    assert matches(["a 1.25 b"], ["a 1.26 b"]) is None
    assert matches(["a 1.25 b"], ["a 1.27 b"]) is not None
    assert matches(["424 DOFs"], ["496 DOFs"]) is not None
    assert matches(["r 1.2e-08"], ["r 6.8e-08"]) is None
    assert matches(["r 1.2e-08"], ["r 3.0e-03"]) is not None
    assert matches(["x", "...", "z"], ["x", "y", "z"]) is None
    assert matches(["x", "z"], ["x", "y", "z"]) is not None
    assert matches(["x"], ["x", "y"]) is not None
