"""Robustness survey: every reference deck shipped with pybmodes (the 22 BModes decks of eleven reference turbines,
a blade and a tower each) and BModes' four CertTest decks (tests/data/bmodes_certtest) through ``bladefem modes``
at default options (the deck's rotor speed and mode count), one process per deck, with its wall time
and how it ended. Run: ``python bench/decks.py`` (needs ``pip install pybmodes``; installs nothing, says so and
stops if pybmodes is absent).
"""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

#: a deck still running after this many seconds counts as a failure
TIMEOUT = 120
CERTTEST = Path(__file__).resolve().parents[1] / "tests" / "data" / "bmodes_certtest"


def reference_decks() -> list[Path]:
    """The pybmodes package's reference-turbine BModes decks, or none if pybmodes is not installed."""
    try:
        import pybmodes
    except ImportError:
        return []
    root = Path(pybmodes.__file__).parent / "_examples" / "sample_inputs" / "reference_turbines"
    return sorted(root.glob("*/*.bmi")) + sorted(CERTTEST.glob("*.bmi"))


def run(deck: Path) -> tuple[str, float, str]:
    command = [sys.executable, "-m", "bladefem", "modes", str(deck)]
    start = time.perf_counter()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return "timeout", TIMEOUT, ""
    seconds = time.perf_counter() - start
    if done.returncode == 0:
        return "ok", seconds, ""
    lines = (done.stderr or done.stdout).strip().splitlines()
    kind = "traceback" if any(line.startswith("Traceback") for line in lines) else f"exit {done.returncode}"
    return kind, seconds, lines[-1][:110] if lines else ""


def main() -> None:
    decks = reference_decks()
    if not decks:
        print("pybmodes is not installed: no reference decks to run (pip install pybmodes)")
        return
    print(f"{'deck':<40} {'result':<10} {'seconds':>8}  message")
    slowest = 0.0
    for deck in decks:
        result, seconds, message = run(deck)
        slowest = max(slowest, seconds)
        print(f"{deck.name:<40} {result:<10} {seconds:8.2f}  {message}")
    print(f"slowest deck: {slowest:.2f} s")


if __name__ == "__main__":
    main()
