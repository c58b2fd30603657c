"""Benchmark: cost of the quasi-steady BEM (Ning's method) at one blade node and for a 17-node x 3-blade rotor.

Run from the repository root::

    python bench/bench_aero.py

NREL 5MW deck (cases/nrel5mw), 11.4 m/s, 12.1 rpm, pitch 0, AeroDyn's settings of the deck (polar formulation, tip
and hub loss, tangential induction, skewed wake). Cases:

- one node (mid-span, DU25 airfoil) called N times from a compiled loop: cold (no previous solution: Ning's
  bracket [0+, pi/2]) and warm (the previous solution as guess with the inflow changed by 0.1 %, as between two
  right-hand sides of a time integration); and its loads with the induction factors held (``section_loads``);
- ``solve_nodes`` on the 17 interior nodes of each of the 3 blades, called from Python (includes the call
  overhead): cold, warm with the inflow changed by 0.1 % since the previous call, warm with the same inflow;
- ``rotor_performance`` (numpy kinematics, solve, sums) with 1 and 16 azimuths.

CPU (process) times on one core, best of 5; the first compiled call (numba compilation, cached on disk afterwards)
is excluded. Prints a Markdown table.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import math  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from bladefem.aero import Rotor, rotor_performance  # noqa: E402
from bladefem.aero._jit import COMPILED, kernel  # noqa: E402
from bladefem.aero.bem import NODE_OUTPUTS, node_loads, plane_geometry, solve_nodes  # noqa: E402
from bladefem.aero.section import section_loads  # noqa: E402
from bladefem.aero.kinematics import rigid_rotor  # noqa: E402
from bladefem.aero.polars import pack_polars  # noqa: E402
from bladefem.builders.openfast_fst import read_openfast_deck  # noqa: E402

DECK = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"


@kernel
def repeat_node(count, vx, vy, r, chord, theta, tip_c, hub_c, tip_ratio, chi0, skew_cos, airfoil, knots, values,
                coefs, start, count_af, options, rho, warm):
    """``count`` node solves; warm: each with the previous solution as guess and the inflow changed by 0.1 %."""
    guess, total = math.nan, 0.0
    for i in range(count):
        scale = 1.0 + 1e-3 * (i % 2)
        out = node_loads(vx * scale, vy, r, chord, theta, tip_c, hub_c, 3.0, tip_ratio, chi0, skew_cos, 1.0,
                         airfoil, knots, values, coefs, start, count_af, options, rho, guess, 0.0, 0.0, 1.0)
        total += out[9]
        if warm:
            guess = out[0]
    return total


@kernel
def repeat_section(count, vx, vy, a, ap, chord, theta, airfoil, knots, values, coefs, start, count_af, options, rho):
    """``count`` section-load evaluations with the induction held (inflow changed by 0.1 % every other call)."""
    total = 0.0
    for i in range(count):
        out = section_loads(vx * (1.0 + 1e-3 * (i % 2)), vy, a, ap, chord, theta, airfoil, knots, values, coefs,
                            start, count_af, options, rho, 0.0, 0.0)
        total += out[6]
    return total


def best(function, repeats: int) -> float:
    """Best-of-5 CPU time of one call, s."""
    function()
    times = []
    for _ in range(5):
        start = time.process_time()
        for _ in range(repeats):
            function()
        times.append((time.process_time() - start) / repeats)
    return min(times)


def main() -> None:
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    deck = read_openfast_deck(DECK)
    full = deck.rotor()
    inner = slice(1, -1)
    rotor = Rotor(**{**full.__dict__, "span": full.span[inner], "chord": full.chord[inner],
                     "twist": full.twist[inner], "airfoil": full.airfoil[inner], "curve": full.curve[inner],
                     "sweep": full.sweep[inner],
                     "curve_angle": None if full.curve_angle is None else full.curve_angle[inner]})
    kin = rigid_rotor(rotor, deck.inflow, 12.1 * math.pi / 30, np.zeros(1))
    table, options = pack_polars(rotor.polars), rotor.options.vector()
    n = 9                                                   # mid-span node of blade 1
    node = (float(kin.vx[0, 0, n]), float(kin.vy[0, 0, n]), float(kin.r_local[0, 0, n]), float(rotor.chord[n]),
            float(rotor.twist[n]), float(kin.tip_constant[0, 0, n]), float(kin.hub_constant[0, 0, n]),
            float(kin.tip_ratio[0, 0, n]), float(kin.chi0[0]), float(kin.skew_cos[0, 0, n]), int(rotor.airfoil[n]))
    calls = 20000
    rows = []
    for warm in (False, True):
        seconds = best(lambda w=warm: repeat_node(calls, *node, *table.arrays, options, rotor.air_density, w), 3)
        rows.append((f"one node, {'warm' if warm else 'cold'} (compiled loop)", seconds / calls))
    solution = node_loads(*node[:7], 3.0, *node[7:10], 1.0, node[10], *table.arrays, options, rotor.air_density,
                          math.nan, 0.0, 0.0, 1.0)
    held = (node[0], node[1], solution[1], solution[2], node[3], node[4], node[10])
    seconds = best(lambda: repeat_section(calls, *held, *table.arrays, options, rotor.air_density), 3)
    rows.append(("one node, loads with the induction held (section_loads)", seconds / calls))
    flat = {name: np.ascontiguousarray(np.broadcast_to(value, kin.vx.shape[1:]).ravel()) for name, value in (
        ("vx", kin.vx[0]), ("vy", kin.vy[0]), ("r", kin.r_local[0]), ("chord", rotor.chord),
        ("theta", rotor.twist), ("tip", kin.tip_constant[0]), ("hub", kin.hub_constant[0]),
        ("ratio", kin.tip_ratio[0]), ("chi0", np.full(kin.vx.shape[1:], kin.chi0[0])),
        ("skew", kin.skew_cos[0]), ("airfoil", rotor.airfoil))}
    out = np.empty((flat["vx"].size, NODE_OUTPUTS))

    inflows = (flat["vx"], flat["vx"] * 1.001)
    calls = [0]

    def solve(guess, vx=None):
        if vx is None:                                      # alternate between two inflows 0.1 % apart
            calls[0] += 1
            vx = inflows[calls[0] % 2]
        solve_nodes(vx, flat["vy"], flat["r"], flat["chord"], flat["theta"], flat["tip"], flat["hub"], 3.0,
                    flat["ratio"], flat["chi0"], flat["skew"], 1.0, flat["airfoil"], *table.arrays, options,
                    rotor.air_density, guess, *plane_geometry(out.shape[0]), out)

    cold = np.full(flat["vx"].size, np.nan)
    solve(cold, flat["vx"])
    same = out[:, 0].copy()

    def warm():
        solve(out[:, 0].copy())

    rows.append(("17 nodes x 3 blades, cold (solve_nodes)", best(lambda: solve(cold), 200)))
    rows.append(("17 nodes x 3 blades, warm: inflow changed by 0.1 % (solve_nodes)", best(warm, 200)))
    rows.append(("17 nodes x 3 blades, warm: same inflow (solve_nodes)",
                 best(lambda: solve(same, flat["vx"]), 200)))
    for azimuths in (1, 16):
        rows.append((f"rotor_performance, {azimuths} azimuth{'s' if azimuths > 1 else ''} (19 nodes x 3 blades)",
                     best(lambda n=azimuths: rotor_performance(deck, 11.4, 12.1, 0.0, azimuths=n), 20)))
    print(f"NREL 5MW, 11.4 m/s, 12.1 rpm; numba {'on' if COMPILED else 'off'}\n")
    print("| case | time per call |\n|---|---|")
    for name, seconds in rows:
        print(f"| {name} | {seconds * 1e6:.2f} µs |")


if __name__ == "__main__":
    main()
