"""Benchmark: NREL 5MW blade on its converged mesh — one modal solve, a 16-speed Campbell sweep (0-15 rpm), and
the whole CLI process. Run: ``python bench/bench_blade.py``. Prints the median of repeated runs (wall-clock).

Assembly (once per blade) is timed separately from the sweep, which reuses K0, K2 and M.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from bladefem.io.case import read_case
from bladefem.modal import campbell_sweep, converged_matrices, solve_modes

ROOT = Path(__file__).resolve().parent.parent
CASE = ROOT / "cases" / "nrel5mw_blade.yaml"
RPM = np.linspace(0.0, 15.0, 16)


def median_time(function, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    blade = read_case(CASE)
    matrices = converged_matrices(blade, n_modes=6)
    elements = len(matrices.dofs.nodes) - 1
    print(f"NREL 5MW blade: converged mesh of {elements} elements, {len(matrices.free)} free DOFs")
    rows = [
        ("mesh refinement + assembly of K0, K2, M (once per blade)", median_time(lambda: converged_matrices(blade, 6), 3)),
        ("one modal solve, 10 modes, 12.1 rpm", median_time(lambda: solve_modes(matrices, 12.1, 10), 20)),
        ("Campbell sweep, 16 speeds 0-15 rpm, 6 families", median_time(lambda: campbell_sweep(matrices, RPM, 6), 10)),
    ]
    command = [sys.executable, "-m", "bladefem", "campbell", str(CASE), "--rpm", "0:15:16", "--json"]
    rows.append(("whole CLI process: bladefem campbell --rpm 0:15:16",
                 median_time(lambda: subprocess.run(command, check=True, capture_output=True), 3)))
    for label, seconds in rows:
        print(f"{label:<55} {seconds * 1e3:9.1f} ms")


if __name__ == "__main__":
    main()
