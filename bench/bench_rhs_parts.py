"""Benchmark: where a right-hand side of the turbine simulation spends its time, kernel by kernel.

    python bench/bench_rhs_parts.py [--calls 20000]

The shipped NREL 5MW deck with ROSCO (cases/nrel5mw/NRELOffshrBsline5MW_Onshore_ROSCO.fst, 16 m/s, from 10 deg of
pitch) is built and run for 0.1 s by the command (the kernels compiled or loaded from numba's cache); then, at its
initial state, each part is called ``--calls`` times in a compiled loop (no Python between calls) and its mean time
printed: the state rate with the BEM solved (the first right-hand side of an ABM4 interval) from scratch (each
node's previous solution cleared) and from the nodes' roots at that state (each kept at once: the lower bound of a
run's solve, which searches next to the previous right-hand side's roots), with the BEM's induction held (the
predicted end), with an output row; and its pieces: the structural equations (the Kane model's quadrature points
named: the blades' now enter through their modal integrals), the aerodynamic loads with the BEM solved and held, of
these the aerodynamic nodes' kinematics and wind, the solve of the mass matrix, the pitch set on the BEM's arrays,
the controller library's call. Markdown table; the load average is printed, as the machine may be shared.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DECK = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ROSCO.fst"


def loops():
    """The compiled loops that call each part ``n`` times."""
    from numba import njit

    from bladefem.models.turbine.compiled_control import call_library
    from bladefem.models.turbine.compiled_kernels import equations as structural
    from bladefem.models.turbine.compiled_loads import add_aero
    from bladefem.models.turbine.compiled_node_motion import node_kinematics
    from bladefem.models.turbine.compiled_state import state_rate
    from bladefem.models.turbine.pitching import set_pitch

    @njit
    def rate_loop(n, rate, kernels, x, q0, u0, index, data, work, hub, row, held, cold):
        total = 0.0
        for _ in range(n):
            if cold:
                work[1][6][...] = 0.0                  # no previous solution (as forget_solutions): from scratch
            work[1][13][2] = held
            total += rate(kernels, 1.0, x, q0, u0, index, data, work, hub, row)[0]
            work[1][13][2] = 0.0
        return total

    @njit
    def structure_loop(n, q, u, structure, work):
        total = 0.0
        for _ in range(n):
            total += structural(q, u, structure, work)[1][0]
        return total

    @njit
    def aero_loop(n, q, u, structure, aero, work, held, cold):
        f = np.zeros(q.shape[0])
        for _ in range(n):
            if cold:
                work[1][6][...] = 0.0
            work[1][13][2] = held
            add_aero(f, q, u, structure, aero, work[0], work[1], 1.0)
            work[1][13][2] = 0.0
        return f[0]

    @njit
    def kinematics_loop(n, q, u, structure, aero, work):
        total = 0.0
        for _ in range(n):
            node_kinematics(q, u, structure, aero, work[0], work[1], 1.0)
            total += work[1][5][0, 0, 0]
        return total

    @njit
    def solve_loop(n, x, M, f, index):
        total = 0.0
        for _ in range(n):
            total += state_rate(x, M, f, index)[0]
        return total

    @njit
    def pitch_loop(n, base, references, structure, aero, pitch):
        for i in range(n):
            set_pitch(pitch + 1e-4 * (i % 2), base, references, structure, aero)

    @njit
    def library_loop(n, function, records, buffers):
        total = 0
        for _ in range(n):
            total += call_library(function, records, buffers)
        return total

    return rate_loop, structure_loop, aero_loop, kinematics_loop, solve_loop, pitch_loop, library_loop


def timed(calls: int, loop, *args) -> float:
    """Mean microseconds per call of ``loop``'s part (after a warm-up call that compiles the loop)."""
    loop(2, *args)
    start = time.perf_counter()
    loop(calls, *args)
    return (time.perf_counter() - start) / calls * 1e6


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--calls", type=int, default=20000)
    calls = parser.parse_args().calls
    import bladefem.models.turbine.controlled as controlled
    from bladefem.cli import main as bladefem
    from bladefem.models.turbine.compiled_calls import functions, unwarned
    rows: list[tuple[str, float]] = []
    compiled_loop = controlled.compiled_loop

    def measured(run, controller, times, boundaries, *args, **kwargs):
        result = compiled_loop(run, controller, times, boundaries, *args, **kwargs)
        with unwarned():                               # numba's note on its first-class function types
            parts(run, controller, times)
        return result

    def parts(run, controller, times) -> None:
        rate_loop, structure_loop, aero_loop, kinematics_loop, solve_loop, pitch_loop, library_loop = loops()
        compiled, system = run.compiled, run.system
        x = np.ascontiguousarray(system.initial_state().astype(float))
        index, q0, u0 = (np.ascontiguousarray(a) for a in (system.index, system.q0, system.u0))
        structure, aero, _ = compiled.loaded
        work = compiled.all_work
        rate, kernels = functions(True)
        channels = compiled.outputs(times[:1], x[None], q0, u0, index).shape[1]
        common = (rate, kernels, x, q0, u0, index, compiled.loaded, work, float(compiled.hub_radius))
        rows.append(("state rate, the BEM solved from scratch", timed(calls, rate_loop, *common, np.zeros(0), 0.0,
                                                                     True)))
        rows.append(("state rate, the BEM solved from each node's root at this state",
                     timed(calls, rate_loop, *common, np.zeros(0), 0.0, False)))
        rows.append(("state rate, the BEM's induction held", timed(calls, rate_loop, *common, np.zeros(0), 1.0,
                                                                   False)))
        rows.append(("state rate, the BEM solved from scratch, with an output row",
                     timed(calls, rate_loop, *common, np.zeros(channels), 0.0, True)))
        points = structure[7].shape[0] * structure[10].shape[0] + structure[3].shape[0]
        rows.append((f"structural equations ({structure[10].shape[0]} x {structure[7].shape[0]} blade and "
                     f"{structure[3].shape[0]} tower quadrature points: {points})",
                     timed(calls, structure_loop, q0, u0, structure, work[0])))
        rows.append((f"aerodynamic loads, the BEM solved from scratch ({structure[10].shape[0]} x "
                     f"{aero[2].shape[0]} nodes)", timed(calls, aero_loop, q0, u0, structure, aero, work, 0.0, True)))
        rows.append(("aerodynamic loads, the induction held", timed(calls, aero_loop, q0, u0, structure, aero, work,
                                                                   1.0, False)))
        rows.append(("of these, the aerodynamic nodes' motion, axes and wind",
                     timed(calls, kinematics_loop, q0, u0, structure, aero, work)))
        M, f = compiled(q0, u0)
        rows.append(("the mass matrix solved for the accelerations", timed(calls, solve_loop, x, M, f, index)))
        pitcher = run.pitcher
        rows.append(("the pitch set on the BEM's arrays", timed(calls, pitch_loop, float(pitcher.base),
                                                                pitcher.references, structure, aero,
                                                                float(pitcher.pitch))))
        function, buffers = controller.library.raw()
        rows.append(("the controller library's call (ROSCO)", timed(calls, library_loop, function, controller.records,
                                                                    buffers)))

    controlled.compiled_loop = measured
    try:
        code = bladefem(["turbine", str(DECK), "--simulate", "0.1", "--wind-speed", "16", "--pitch-deg", "10",
                         "--quiet", "--output", str(ROOT / "bench" / "out" / "rhs_parts.csv")])
    finally:
        controlled.compiled_loop = compiled_loop
    if code:
        raise SystemExit(code)
    print(f"load average {os.getloadavg()[0]:.1f}, {calls} calls each\n")
    print("| part | microseconds a call |\n|---|---|")
    for name, micro in rows:
        print(f"| {name} | {micro:.1f} |")


if __name__ == "__main__":
    main()
