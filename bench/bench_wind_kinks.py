"""Where the right-hand sides of a turbulent case go: one case of the shipped DLC 1.2 plan (9.5 m/s, first box),
shortened, simulated in its box as made (``normal``), in the box frozen in time (its time mean at every sample:
only the spatial kinks of the bilinear (y, z) interpolation remain), in the box uniform in space (its spatial mean
at every sample: only the kinks in time remain), and in the box as made with the integration restarted on every
time sample of the box (``aligned``: the steps end on the samples, the remedy for kinks that all points of the rotor
would meet at the same instant).

    python bench/bench_wind_kinks.py [--seconds 40]

Prints per run the right-hand sides (per simulated second), the CPU seconds and the blade-1 root moments' mean,
standard deviation and DEL. The frozen and uniform boxes change the wind, so only their counts are comparable.
"""

from __future__ import annotations

import argparse
import dataclasses
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=40.0)
    args = parser.parse_args()

    import bladefem.aero.turbulence as turbulence
    import bladefem.models.turbine.simulate as simulate
    from bladefem.batch import read_plan
    from bladefem.batch.turbine import simulate_rows
    from bladefem.models.turbine.compiled import CompiledEquations, Integration

    plan = read_plan(ROOT / "cases" / "nrel5mw_dlc12.yaml")
    case = next(c for c in plan.cases if float(c.inputs["wind_speed_m_s"]) == 9.5)
    case = dataclasses.replace(case, analysis=dataclasses.replace(case.analysis, seconds=args.seconds,
                                                                  statistics_from=min(30.0, args.seconds / 2)))
    box_dt = case.analysis.turbulence[3]
    made, integrate, result_of = turbulence.turbulent_grid, CompiledEquations.integrate, simulate.result_of
    state = {"mode": "normal", "evaluations": 0}

    def grid(spec):
        g = made(spec)
        v = g.velocity
        if state["mode"] == "frozen":
            v = np.repeat(v.mean(axis=0, keepdims=True), v.shape[0], axis=0)
        elif state["mode"] == "uniform":
            v = np.broadcast_to(v.mean(axis=(1, 2), keepdims=True), v.shape)
        return dataclasses.replace(g, velocity=np.ascontiguousarray(v, dtype=np.float32))

    def aligned(self, times, x0, rtol, atol, q0, u0, index, order=8, limit=None, watch=None, budget=None,
                first_step=None):
        cuts = np.unique(np.r_[0, np.searchsorted(times, np.arange(box_dt, times[-1], box_dt) - 1e-9), len(times) - 1])
        states, loads, evaluations, x = np.full((len(times), len(x0)), np.nan), None, 0, x0
        for a, b in zip(cuts[:-1], cuts[1:]):
            run = integrate(self, times[a:b + 1], x, rtol, atol, q0, u0, index, order, limit, None, budget,
                            first_step if a == 0 else 0.02)
            loads = np.full((len(times), run.loads.shape[1]), np.nan) if loads is None else loads
            states[a:b + 1], loads[a:b + 1], x = run.states, run.loads, run.states[-1]
            evaluations += run.evaluations - (a > 0)             # the restart's first derivative is not a step's
        return Integration(states, loads, len(times), evaluations, rate=run.rate)

    def counted(system, times, states, loads, evaluations):
        state["evaluations"] = evaluations
        return result_of(system, times, states, loads, evaluations)

    turbulence.turbulent_grid, simulate.result_of = grid, counted
    for mode in ("normal", "frozen", "uniform", "aligned"):
        state["mode"] = mode
        CompiledEquations.integrate = aligned if mode == "aligned" else integrate
        start = time.process_time()
        rows = simulate_rows(case)
        cpu = time.process_time() - start
        n = state["evaluations"]
        moments = " ".join(f"{r['channel']} {r['mean']:.6g} {r['std']:.6g} {r['del']:.6g}" for r in rows
                           if r["channel"] in ("RootMOoP1", "RootMIP1"))
        print(f"{mode:8s} {n:7d} right-hand sides ({n / args.seconds:5.0f}/s), {cpu:5.1f} s CPU; {moments}")


if __name__ == "__main__":
    main()
