"""Benchmark: real-time factor (simulated seconds per CPU second) of the 16-DOF NREL 5MW model on one core, outputs
included: structural only, and with aerodynamics and the generator's torque law (the aero case).

Run from the repository root::

    python bench/bench_turbine.py [SECONDS]        # structural: default 20 s of simulated time
    python bench/bench_turbine.py --aero [SECONDS] # aero case: default 100 s at rated wind

It pins the process to one core and one BLAS thread. Two 16-DOF models: bladefem's default of the command line
(FE blade shapes at 12.1 rpm, the tower file's polynomials, span nodes at 2 Gauss points per section interval: 96
per blade, 40 on the tower) and the ElastoDyn-compatible one (17 blade and 20 tower nodes).

Structural: integrated for SECONDS from an operating-like deflection at 12.1 rpm, generator free, writing the
output channels every 0.00625 s and every 0.05 s (``simulate``: integration and channels, root moments included),
with the compiled Dormand-Prince 8(5,3) ('DP853', the default) at rtol 1e-6 and 1e-4, the compiled 5(4) ('DP54') at
rtol 1e-6, and fixed-step RK4 at 0.01 s (ElastoDyn's scheme). The error column is the largest deviation of the
blade-1 tip out-of-plane deflection (about 2 m) from a DOP853 run at rtol 1e-10.

Aero case: the shipped OpenFAST deck at its rated wind (11.4 m/s), all 16 DOFs free (the generator on ServoDyn's
torque law), quasi-steady BEM at the deck's 19 AeroDyn nodes x 3 blades, from the undeflected state at 12.1 rpm,
outputs every 0.05 s; DP54 (the default with aerodynamics) at rtol 1e-6 with the command line's absolute tolerance
0.1 rtol and with 0.01 rtol (before), at rtol 1e-5, 1e-4, DP853 at rtol 1e-6, RK4 at
0.01 s; the error against DP853 at rtol 1e-9; and the output channels' share of the DP54 run (the same run writing
only its first and last rows).

CPU (process) times; the numba compilation (first call, cached on disk afterwards) is excluded. Also the CPU time
of one right-hand side, compiled and numpy, and the machine's load average. Prints Markdown tables.
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

from bladefem.builders.turbine_deck import read_turbine_deck  # noqa: E402
from bladefem.builders.turbine_elastodyn import turbine_from_elastodyn  # noqa: E402
from bladefem.models.turbine import FreeSystem, TurbineModel  # noqa: E402
from bladefem.models.turbine.simulate import simulate  # noqa: E402

CASES = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw"
MAIN = CASES / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
DECK = CASES / "NRELOffshrBsline5MW_Onshore.fst"
INTEGRATORS = {"DP853 rtol 1e-6": dict(method="DP853", rtol=1e-6, atol=1e-8),
               "DP853 rtol 1e-4": dict(method="DP853", rtol=1e-4, atol=1e-6),
               "DP54 rtol 1e-6": dict(method="DP54", rtol=1e-6, atol=1e-8),
               "RK4 step 0.01 s": dict(method="RK4", step=0.01)}
OUTPUT_STEPS = (0.00625, 0.05)
AERO_INTEGRATORS = {"DP54 rtol 1e-6, atol 1e-7 (the command line's)": dict(method="DP54", rtol=1e-6, atol=1e-7),
                    "DP54 rtol 1e-6, atol 1e-8 (before)": dict(method="DP54", rtol=1e-6, atol=1e-8),
                    "DP54 rtol 1e-5": dict(method="DP54", rtol=1e-5, atol=1e-7),
                    "DP54 rtol 1e-4": dict(method="DP54", rtol=1e-4, atol=1e-6),
                    "DP853 rtol 1e-6": dict(method="DP853", rtol=1e-6, atol=1e-8),
                    "RK4 step 0.01 s": dict(method="RK4", step=0.01)}


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


def pin() -> None:
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})


def load() -> str:
    return "load average " + " / ".join(f"{x:.1f}" for x in os.getloadavg()) if hasattr(os, "getloadavg") else ""


def main(seconds: float = 20.0) -> str:
    pin()
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
    return load() + "\n\n" + "\n".join(rhs) + "\n\n" + "\n".join(speed)


def aero_models() -> dict[str, TurbineModel]:
    """The deck at rated wind with aerodynamics and the torque law, default and ElastoDyn-compatible."""
    out = {}
    for label, options in (("default (FE blade shapes, 96 + 40 nodes)", {"blade_shapes": "fe"}),
                           ("--elastodyn-compatible (17 + 20 nodes)",
                            {"blade_shapes": "polynomial", "elastodyn_compatible": True, "gauss_points": 1})):
        deck = read_turbine_deck(DECK, wind_speed=11.4, rpm=12.1, **options)
        out[label] = TurbineModel(deck.params, aero=deck.aero, generator=deck.generator)
    return out


def unwatched_reference(free: FreeSystem, seconds: float):
    """DP853 at rtol 1e-9: its first steps from the undeflected blades take more right-hand sides per simulated
    second than the run's watch allows a run (:meth:`.watch.Monitor.steps`), which is switched off for it."""
    from bladefem.models.turbine import watch
    steps = watch.Monitor.steps
    watch.Monitor.steps = staticmethod(lambda *args: None)
    try:
        return simulate(free, seconds, dt_output=0.05, method="DP853", rtol=1e-9, atol=1e-11)
    finally:
        watch.Monitor.steps = staticmethod(steps)


def main_aero(seconds: float = 100.0) -> str:
    pin()
    speed = ["| model | integrator | RHS per simulated s | simulated s per CPU s | tip error [m] | power error [kW] |",
             "|---|---|---|---|---|---|"]
    rhs = ["| model | compiled RHS [ms] | numpy RHS [ms] |", "|---|---|---|"]
    share = ["| model | DP54 rtol 1e-6 atol 1e-7, outputs every 0.05 s [CPU s] | without output rows [CPU s] "
             "| channels' share |",
             "|---|---|---|---|"]
    for label, model in aero_models().items():
        q, u = np.zeros(model.n), np.zeros(model.n)
        u[5] = 12.1 * np.pi / 30
        free = FreeSystem(model, np.ones(model.n, dtype=bool), q, u)
        for method in ("DP54", "DP853"):
            simulate(free, 0.1, method=method)
        warm = simulate(free, 5.0, method="DP54")           # a state along the way for the RHS timing
        x = np.concatenate([warm.q[-1], warm.u[-1]])
        compiled = rhs_time(FreeSystem(model, free.free, warm.q[-1], warm.u[-1]))
        model._fast = model.equations
        numpy_rhs = rhs_time(FreeSystem(model, free.free, x[:model.n], x[model.n:]), 10)
        model._fast = None
        rhs.append(f"| {label} | {1e3 * compiled:.3f} | {1e3 * numpy_rhs:.2f} |")
        reference = unwatched_reference(free, seconds)
        for integrator, settings in AERO_INTEGRATORS.items():
            start = time.process_time()
            result = simulate(free, seconds, dt_output=0.05, **settings)
            cpu = time.process_time() - start
            error = np.abs(result.outputs["OoPDefl1"] - reference.outputs["OoPDefl1"]).max()
            power = np.abs(result.outputs["GenPwr"] - reference.outputs["GenPwr"]).max()
            speed.append(f"| {label} | {integrator} | {result.evaluations / seconds:.0f} | {seconds / cpu:.1f} | "
                         f"{error:.1e} | {power:.1e} |")
        timed = []
        for dt in (0.05, seconds):                          # every 0.05 s, and the first and last rows only
            start = time.process_time()
            simulate(free, seconds, dt_output=dt, **AERO_INTEGRATORS["DP54 rtol 1e-6, atol 1e-7 (the command line's)"])
            timed.append(time.process_time() - start)
        share.append(f"| {label} | {timed[0]:.2f} | {timed[1]:.2f} | {100 * (1 - timed[1] / timed[0]):.0f} % |")
    return "\n\n".join([load(), "\n".join(rhs), "\n".join(speed), "\n".join(share)])


if __name__ == "__main__":
    arguments = sys.argv[1:]
    if arguments[:1] == ["--aero"]:
        print(main_aero(float(arguments[1]) if len(arguments) > 1 else 100.0))
    else:
        print(main(float(arguments[0]) if arguments else 20.0))
