"""Benchmark: the NREL 5MW blade's quadratic eigenproblem with Coriolis coupling (``--coriolis``) on its automatic
mesh, against the symmetric solve on the same mesh. Run: ``python bench/bench_coriolis.py``; median wall time and
smallest CPU time of repeats, BLAS on one thread.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import statistics  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

CASE = Path(__file__).resolve().parent.parent / "cases" / "nrel5mw_blade.yaml"
RPM = np.linspace(0.0, 15.0, 16)


def timed(function: Callable[[], object], repeats: int) -> tuple[float, float]:
    """(median wall time, smallest CPU time), s."""
    walls, cpus = [], []
    for _ in range(repeats):
        wall, cpu = time.perf_counter(), time.process_time()
        function()
        walls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
    return statistics.median(walls), min(cpus)


def main() -> None:
    from bladefem.builders.case import read_case
    from bladefem.modal import campbell_sweep, converged_mesh, solve_modes
    from bladefem.modal.quadratic import solve_quadratic_modes
    from bladefem.modal.quadratic_campbell import quadratic_campbell_sweep

    blade = read_case(CASE)
    matrices = converged_mesh(blade, 6, rpm=15.0).matrices
    _ = matrices.G                                        # assembled once, as in a sweep
    print(f"NREL 5MW blade: {len(matrices.dofs.nodes) - 1} elements, {len(matrices.free)} free DOFs")
    rows = {
        "symmetric solve, 10 modes, 12.1 rpm": lambda: solve_modes(matrices, 12.1, 10),
        "quadratic solve with Coriolis, 10 modes, 12.1 rpm": lambda: solve_quadratic_modes(matrices, 12.1, 10),
        "Campbell sweep, 16 speeds, 6 families": lambda: campbell_sweep(matrices, RPM, 6),
        "Campbell sweep with Coriolis, 16 speeds, 6 families": lambda: quadratic_campbell_sweep(matrices, RPM, 6),
    }
    for label, function in rows.items():
        wall, cpu = timed(lambda solve=function: (matrices.eigenpairs.clear(), solve()), 7)
        print(f"{label:<55} {wall * 1e3:8.1f} ms wall {cpu * 1e3:8.1f} ms CPU")


if __name__ == "__main__":
    main()
