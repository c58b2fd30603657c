"""Benchmark: simulated seconds per CPU second of the 16-DOF structural NREL 5MW model (no aerodynamics) on one
core.

Run from the repository root::

    python bench/bench_turbine.py [SECONDS]        # default 20 s of simulated time

It pins the process to one core and one BLAS thread, builds the 16-DOF model (bladefem FE blade shapes at 12.1 rpm,
ElastoDyn polynomial tower shapes) with span nodes at the files' stations (1 Gauss point per interval: 48 per
blade, 20 on the tower) and a coarser variant (12 blade and 8 tower elements), and integrates 20 s from an
operating-like deflection at 12.1 rpm, generator free. Right-hand sides: the numba-compiled kernel (if numba is
installed) and the numpy assembly. Integrators: the compiled Dormand-Prince 8(5,3) ('DP853', rtol 1e-6 and 1e-4)
and 5(4) ('DP54', rtol 1e-6 and 1e-4), scipy's DOP853 (rtol 1e-6) and fixed-step RK4 (0.02 s). The error column is the largest deviation of the blade-1
tip out-of-plane deflection (about 2 m) from a DOP853 run at rtol 1e-10. CPU (process) times; the first compiled
call (numba compilation, cached on disk afterwards) is excluded. Prints a Markdown table.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from bladefem.io.turbine_elastodyn import turbine_from_elastodyn  # noqa: E402
from bladefem.models.turbine import FreeSystem, TurbineModel  # noqa: E402
from bladefem.models.turbine.simulate import simulate  # noqa: E402

MAIN = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


INTEGRATORS = {"DP853 rtol 1e-6": dict(method="DP853", rtol=1e-6, atol=1e-8),
               "DP853 rtol 1e-4": dict(method="DP853", rtol=1e-4, atol=1e-6),
               "DP54 rtol 1e-6": dict(method="DP54", rtol=1e-6, atol=1e-8),
               "DP54 rtol 1e-4": dict(method="DP54", rtol=1e-4, atol=1e-6),
               "DOP853 rtol 1e-6": dict(method="DOP853", rtol=1e-6, atol=1e-8),
               "RK4 dt 0.02 s": dict(method="RK4", step=0.02)}


def system(model: TurbineModel) -> FreeSystem:
    q, u = np.zeros(model.n), np.zeros(model.n)
    q[0] = 0.3
    q[model.blade_columns[:, 0]] = 2.0
    u[5] = 12.1 * np.pi / 30
    return FreeSystem(model, np.ones(model.n, dtype=bool), q, u)


def rhs_time(free: FreeSystem, repeats: int = 300) -> float:
    """Best-of-5 CPU time of one right-hand side, s."""
    x = free.initial_state()
    best = np.inf
    for _ in range(5):
        start = time.process_time()
        for _ in range(repeats):
            free(0.0, x)
        best = min(best, (time.process_time() - start) / repeats)
    return best


def main(seconds: float = 20.0) -> str:
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})
    rows = ["| span nodes | right-hand side | integrator | RHS [ms] | RHS per simulated s | simulated s per CPU s "
            "| tip error [m] |", "|---|---|---|---|---|---|---|"]
    variants = {"stations (48 + 20), 1 Gauss": dict(gauss_points=1),
                "12/8 elements, 1 Gauss": dict(blade_elements=12, tower_elements=8, gauss_points=1)}
    for label, options in variants.items():
        model = TurbineModel(turbine_from_elastodyn(MAIN, "fe", **options))
        free = system(model)
        if hasattr(model.fast_equations(), "integrate"):
            for method in ("DP54", "DP853"):                # compile (or load) the kernels outside the timing
                simulate(free, 0.1, method=method)
        reference = simulate(free, seconds, dt_output=0.5, method="DOP853", rtol=1e-10, atol=1e-12)
        for backend in ("numba", "numpy"):
            compiled = hasattr(model.fast_equations(), "integrate")
            if backend == "numpy":
                model._fast = model.equations          # the reference numpy assembly
            elif not compiled:
                continue
            per_rhs = rhs_time(free)
            for integrator, settings in INTEGRATORS.items():
                if settings["method"] in ("DP54", "DP853") and backend == "numpy":
                    continue
                start = time.process_time()
                result = simulate(free, seconds, dt_output=0.5, **settings)
                cpu = time.process_time() - start
                error = np.abs(result.outputs["OoPDefl1"] - reference.outputs["OoPDefl1"]).max()
                rows.append(f"| {label} | {backend} | {integrator} | {1e3 * per_rhs:.3f} | "
                            f"{result.evaluations / seconds:.0f} | {seconds / cpu:.1f} | {error:.1e} |")
    return "\n".join(rows)


if __name__ == "__main__":
    print(main(float(sys.argv[1]) if len(sys.argv) > 1 else 20.0))
