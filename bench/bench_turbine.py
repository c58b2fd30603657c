"""Benchmark: real-time factor (simulated seconds per CPU second) of the 16-DOF structural NREL 5MW model (no
aerodynamics) on one core, outputs included.

Run from the repository root::

    python bench/bench_turbine.py [SECONDS]        # default 20 s of simulated time

It pins the process to one core and one BLAS thread and builds two 16-DOF models: bladefem's default of the
command line (FE blade shapes at 12.1 rpm, the tower file's polynomials, span nodes at 2 Gauss points per section
interval: 96 per blade, 40 on the tower) and the ElastoDyn-compatible one (17 blade and 20 tower nodes). Each is
integrated for SECONDS from an operating-like deflection at 12.1 rpm, generator free, writing the output channels
every 0.00625 s and every 0.05 s (``simulate``: integration and channels, root moments included), with the
compiled Dormand-Prince 8(5,3) ('DP853', the default) at rtol 1e-6 and 1e-4, the compiled 5(4) ('DP54') at rtol
1e-6, and fixed-step RK4 at 0.01 s (ElastoDyn's scheme). The error column is the largest deviation of the blade-1
tip out-of-plane deflection (about 2 m) from a DOP853 run at rtol 1e-10. CPU (process) times; the numba
compilation (first call, cached on disk afterwards) is excluded. Also the CPU time of one right-hand side,
compiled and numpy. Prints Markdown tables.
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
               "RK4 step 0.01 s": dict(method="RK4", step=0.01)}
OUTPUT_STEPS = (0.00625, 0.05)


def models() -> dict[str, TurbineModel]:
    return {"default (FE blade shapes, 96 + 40 nodes)": TurbineModel(turbine_from_elastodyn(MAIN, "fe", rpm=12.1)),
            "--elastodyn-compatible (17 + 20 nodes)": TurbineModel(
                turbine_from_elastodyn(MAIN, "polynomial", elastodyn_compatible=True))}


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
    speed = ["| model | integrator | output step [s] | RHS per simulated s | simulated s per CPU s | tip error [m] |",
             "|---|---|---|---|---|---|"]
    rhs = ["| model | compiled RHS [ms] | numpy RHS [ms] |", "|---|---|---|"]
    for label, model in models().items():
        free = system(model)
        for method in ("DP54", "DP853"):                # compile (or load) the kernels outside the timing
            simulate(free, 0.1, method=method)
        compiled = rhs_time(free)
        model._fast = model.equations
        numpy_rhs = rhs_time(free, 30)
        model._fast = None
        rhs.append(f"| {label} | {1e3 * compiled:.3f} | {1e3 * numpy_rhs:.2f} |")
        reference = simulate(free, seconds, dt_output=0.05, method="DOP853", rtol=1e-10, atol=1e-12)
        for integrator, settings in INTEGRATORS.items():
            for dt in OUTPUT_STEPS:
                start = time.process_time()
                result = simulate(free, seconds, dt_output=dt, **settings)
                cpu = time.process_time() - start
                every = int(round(0.05 / dt))
                error = np.abs(result.outputs["OoPDefl1"][::every] - reference.outputs["OoPDefl1"]).max()
                speed.append(f"| {label} | {integrator} | {dt:g} | {result.evaluations / seconds:.0f} | "
                             f"{seconds / cpu:.1f} | {error:.1e} |")
    return "\n".join(rhs) + "\n\n" + "\n".join(speed)


if __name__ == "__main__":
    print(main(float(sys.argv[1]) if len(sys.argv) > 1 else 20.0))
