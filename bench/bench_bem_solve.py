"""Benchmark: residual evaluations per BEM node solve from scratch in the turbine simulation, with Brent's method
started at the Betz rotor's inflow angle (a solve without a previous root) and from the bracket's ends alone
(before). In a run each solve starts from the node's root at the previous right-hand side instead: 3.44 evaluations
a solve over 100 s at 11.4 m/s against 7.0 from scratch (docs/turbine-aero.md#speed).

    python bench/bench_bem_solve.py [SECONDS]

The shipped NREL 5MW deck at 11.4 m/s (torque law, all DOFs free) runs SECONDS (default 20) with the compiled
kernels; at every 20th output row the node inputs of that state are taken (the numpy path of the right-hand
side); a subprocess without numba (``BLADEFEM_NO_NUMBA``, the same kernels as Python) then solves those nodes and
counts the residual evaluations, with the first trial and without (``PREDICTED_FACTOR`` nan), and prints the mean
per node, the histogram and the largest difference of the solutions (phi, rad; the loads fn, ft, relative).
"""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DECK = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"


def node_inputs(seconds: float) -> list:
    """The arguments of :func:`bladefem.aero.bem.solve_nodes` at every 20th output row of the run."""
    from bladefem.builders.turbine_deck import read_turbine_deck
    from bladefem.models.turbine import FreeSystem, TurbineModel
    from bladefem.models.turbine import aero
    from bladefem.models.turbine.simulate import simulate
    deck = read_turbine_deck(DECK, wind_speed=11.4, rpm=12.1, blade_shapes="fe")
    model = TurbineModel(deck.params, aero=deck.aero, generator=deck.generator)
    q, u = np.zeros(model.n), np.zeros(model.n)
    u[5] = 12.1 * np.pi / 30
    free = np.ones(model.n, dtype=bool)
    run = simulate(FreeSystem(model, free, q, u), seconds, method="DP54")
    captured, solve = [], aero.solve_nodes

    def hook(*args):
        captured.append([np.array(a) if isinstance(a, np.ndarray) else a for a in args[:-1]])
        return solve(*args)
    aero.solve_nodes, model._fast = hook, model.equations
    try:
        for k in range(0, len(run.time), 20):
            system = FreeSystem(model, free, run.q[k], run.u[k])
            system(run.time[k], system.initial_state())
    finally:
        aero.solve_nodes, model._fast = solve, None
    return captured


COUNT = """
import pickle, sys
import numpy as np
import bladefem.aero.bem as bem
captured = pickle.load(open(sys.argv[1], "rb"))
residual, calls = bem.framed_residual, [0]
def counted(*args):
    calls[0] += 1
    return residual(*args)
bem.framed_residual = counted
result = {}
for label, factor in (("first trial at the Betz inflow angle", bem.PREDICTED_FACTOR), ("from the ends", float("nan"))):
    bem.PREDICTED_FACTOR = factor
    per, outs = [], []
    for args in captured:
        n = args[0].shape[0]
        for i in range(n):
            before = calls[0]
            outs.append(bem.node_loads(*[a[i] if isinstance(a, np.ndarray) and a.shape == (n,) else a for a in args]))
            per.append(calls[0] - before)
    result[label] = (np.array(per), np.array(outs, dtype=float))
pickle.dump(result, open(sys.argv[1], "wb"))
"""


def main(seconds: float = 20.0) -> None:
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "nodes.pkl"
        path.write_bytes(pickle.dumps(node_inputs(seconds)))
        env = {**os.environ, "BLADEFEM_NO_NUMBA": "1", "PYTHONPATH": str(ROOT)}
        subprocess.run([sys.executable, "-c", COUNT, str(path)], env=env, check=True)
        result = pickle.loads(path.read_bytes())
    print("| Brent's method | node solves | residual evaluations per node (mean) | histogram (0, 1, 2, ...) |")
    print("|---|---|---|---|")
    for label, (per, _) in result.items():
        print(f"| {label} | {len(per)} | {per.mean():.2f} | {np.bincount(per).tolist()} |")
    (_, new), (_, old) = result.values()
    loads = np.abs(new[:, 9:11] - old[:, 9:11]).max() / np.abs(old[:, 9:11]).max()
    print(f"\nlargest difference: phi {np.abs(new[:, 0] - old[:, 0]).max():.1e} rad, fn and ft {loads:.1e} of the "
          "largest")


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 20.0)
